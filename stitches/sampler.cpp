// skein-sampler: writes two stitch-mesh projects for looking at the stitch library:
//   sampler.skein  every stitch type of the library on one swatch (bands of the 1-1 stitches, then pairs of
//                  increases and decreases made by splitting course edges, each pair typed in turn);
//   cable.skein    a cable panel: purl background, 2-over-2 cables crossing every sixth row.
#include <cstdio>
#include <filesystem>
#include <map>

#include "common/error.hpp"
#include "garments.hpp"
#include "stitchmesh/edits.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/project.hpp"
#include "stitchmesh/stitch_types.hpp"
#include "stitchmesh/tessellation.hpp"

using namespace skein::mesh;

namespace {

Project swatch(double stitch) {
  Project p;
  p.stitch_size = {stitch, stitch * 5.0 / 6.0};
  p.input = skein::models::swatch();
  p.labels = auto_label(*p.input, default_start_edge(*p.input));
  p.values = initial_values(*p.input, *p.labels, p.stitch_size);
  p.stitch = tessellate(*p.input, *p.labels, *p.values);
  return p;
}

Project sampler() {
  Project p = swatch(6);  // 20 stitches by 20 rows
  StitchMesh& s = *p.stitch;
  // Types by shape: plain (1-1), increases 1-2 and 1-3, decreases 2-1 and 3-1.
  std::map<std::pair<int, int>, std::vector<std::string>> by_shape;
  for (const auto& t : stitch_types()) by_shape[{t.bottom, t.top}].push_back(t.name);
  // Rows 1..12: one plain type per row (row 0 is the cast-on).
  const auto& plain = by_shape[{1, 1}];
  for (size_t i = 0; i < plain.size(); ++i) s = set_stitch_type(s, faces_by_row(s)[i + 1], plain[i]);
  // Rows 13, 15, 17: split top edges (once or twice) to make increase/decrease pairs, each typed in turn.
  auto& inc2 = by_shape[{1, 2}], &inc3 = by_shape[{1, 3}], &dec2 = by_shape[{2, 1}], &dec3 = by_shape[{3, 1}];
  for (int row = 13; row <= 17 && (!inc2.empty() || !inc3.empty() || !dec2.empty() || !dec3.empty()); row += 2)
    for (int col = 1; col + 1 < static_cast<int>(faces_by_row(s)[row].size()); col += 2) {
      const bool triple = !inc3.empty() || !dec3.empty();
      if (!triple && inc2.empty() && dec2.empty()) break;
      const int f = faces_by_row(s)[row][col];
      for (int k = 0; k < (triple ? 2 : 1); ++k) {
        const auto& face = s.faces[f];
        s = split_course_edge(s, face.vertex(face.bottom + 1), face.vertex(face.bottom + 2));
      }
      const auto take = [&](std::vector<std::string>& names, int face) {
        if (names.empty()) return;
        s = set_stitch_type(s, {face}, names.front());
        names.erase(names.begin());
      };
      take(triple ? inc3 : inc2, f);
      take(triple ? dec3 : dec2, faces_by_row(s)[row + 1][col]);
    }
  return p;
}

Project cable_panel() {
  Project p = swatch(7.5);
  StitchMesh& s = *p.stitch;
  // p2, k4, p2 ... across; the k4 columns cross 2 over 2 every sixth row.
  std::vector<int> all(s.faces.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  s = fill(s, all, parse_fill("rib4x2"));
  const auto rows = faces_by_row(s);
  for (size_t r = 3; r + 2 < rows.size(); r += 6)
    for (int col = 0; col + 4 <= static_cast<int>(rows[r].size()); col += 6)
      if (s.faces[rows[r][col]].type == "k") s = mark_cable(s, top_edge_path(s, static_cast<int>(r), col, col + 4), 2, 1);
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path out = argc > 1 ? argv[1] : ".";
  try {
    write_project(sampler(), out / "sampler.skein");
    write_project(cable_panel(), out / "cable.skein");
  } catch (const skein::Error& e) {
    std::fprintf(stderr, "skein-sampler: %s\n", e.what());
    return 1;
  }
  std::printf("wrote %s and %s\n", (out / "sampler.skein").c_str(), (out / "cable.skein").c_str());
}
