#include <gtest/gtest.h>

#include <random>

#include "common/error.hpp"
#include "garments.hpp"
#include "stitchmesh/edits.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/tessellation.hpp"
#include "stitch_fixtures.hpp"
#include "testing.hpp"

using namespace skein;
using skein::testing::all_faces;
using skein::testing::error_of;

namespace {
mesh::StitchMesh stitched(const mesh::InputMesh& m) {
  const auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  return mesh::tessellate(m, l, mesh::initial_values(m, l, {}));
}
/// A face in the middle of the swatch (neighbours on all four sides).
int middle_face(const mesh::StitchMesh& s) {
  Eigen::Vector3d centre(60, 50, 0);
  int best = 0;
  double best_d = 1e9;
  for (int f = 0; f < static_cast<int>(s.faces.size()); ++f) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int v : s.faces[f].vertices) c += s.vertices[v] / s.faces[f].size();
    if ((c - centre).norm() < best_d) best_d = (c - centre).norm(), best = f;
  }
  return best;
}
}  // namespace

TEST(Edits, SetStitchTypeChecksTheShape) {
  const auto s = stitched(models::swatch());
  const auto p = mesh::set_stitch_type(s, {0, 1, 2}, "p");
  EXPECT_EQ(p.faces[1].type, "p");
  EXPECT_EQ(s.faces[1].type, "k");  // the input is untouched
  const std::string msg = error_of([&] { mesh::set_stitch_type(s, {3}, "kp"); });
  EXPECT_NE(msg.find("face 3"), std::string::npos) << msg;
  EXPECT_NE(msg.find("needs 1 bottom and 2 top"), std::string::npos) << msg;
  EXPECT_THROW(mesh::set_stitch_type(s, {0}, "knit"), Error);
  EXPECT_THROW(mesh::set_stitch_type(s, {123456}, "k"), Error);
}

TEST(Edits, SplitThenCollapseACourseEdgeRoundTrips) {
  const auto s = stitched(models::swatch());
  const auto& f = s.faces[middle_face(s)];
  const int u = f.vertex(f.bottom + 1), v = f.vertex(f.bottom + 2);  // its top edge
  const auto split = mesh::split_course_edge(s, u, v);
  ASSERT_TRUE(mesh::validate(split).valid());
  const auto stats = mesh::stitch_stats(split);
  EXPECT_EQ(stats.increases, 1);
  EXPECT_EQ(stats.decreases, 1);
  EXPECT_EQ(stats.stitch_types.at("kp"), 1);
  EXPECT_EQ(stats.stitch_types.at("d12k"), 1);
  const int m = static_cast<int>(split.vertices.size()) - 1;
  EXPECT_TRUE(mesh::collapse_course_edge(split, u, m) == s);
}

TEST(Edits, CollapseRefusesAnEdgeBetweenWaleEdges) {
  const auto s = stitched(models::swatch());
  const auto& f = s.faces[middle_face(s)];
  const std::string msg = error_of([&] { mesh::collapse_course_edge(s, f.vertex(0), f.vertex(1)); });
  EXPECT_NE(msg.find("wale edge meets each end"), std::string::npos) << msg;
  EXPECT_THROW(mesh::split_course_edge(s, f.vertex(f.bottom), f.vertex(f.bottom + 1)), Error);  // a wale edge
  EXPECT_THROW(mesh::split_course_edge(s, 0, 999999), Error);
}

TEST(Edits, AddThenRemoveAWaleEdgeRoundTrips) {
  const auto s = stitched(models::swatch());
  const int f = middle_face(s);
  const auto added = mesh::add_wale_edge(s, f);
  ASSERT_TRUE(mesh::validate(added).valid()) << mesh::validate(added).summary();
  EXPECT_EQ(added.faces.size(), s.faces.size() + 1);
  const auto stats = mesh::stitch_stats(added);
  EXPECT_EQ(stats.increases, 1);  // the stitch below now feeds two
  EXPECT_EQ(stats.decreases, 1);  // the stitch above now takes two
  const auto& left = added.faces[f];
  const auto removed = mesh::remove_wale_edge(added, left.vertex(left.bottom), left.vertex(left.bottom + 1));
  EXPECT_TRUE(removed == s);
}

TEST(Edits, RemovingAWaleEdgeBetweenPlainStitchesMakesALaceStitch) {
  const auto s = stitched(models::swatch());
  const int m = middle_face(s);
  const auto& f = s.faces[m];
  // Two plain stitches merge into one of two loops below and two above: Leaf's lace shape, yarn-over + ssk.
  const auto merged = mesh::remove_wale_edge(s, f.vertex(f.bottom), f.vertex(f.bottom + 1));
  EXPECT_TRUE(mesh::validate(merged).valid());
  EXPECT_EQ(merged.faces.size(), s.faces.size() - 1);
  EXPECT_EQ(mesh::stitch_stats(merged).stitch_types.at("ys"), 1);
  // An increase beside a plain stitch would merge into 2 below and 3 above, which no stitch has.
  const auto split = mesh::split_course_edge(s, f.vertex(f.bottom + 1), f.vertex(f.bottom + 2));
  const auto& g = split.faces[m];
  const std::string msg = error_of([&] { mesh::remove_wale_edge(split, g.vertex(g.bottom), g.vertex(g.bottom + 1)); });
  EXPECT_NE(msg.find("refused"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no stitch has that shape"), std::string::npos) << msg;
}

TEST(Edits, ShiftAWaleEdgeAndBack) {
  const auto s = stitched(models::swatch());
  const int f = middle_face(s);
  // Make a stitch with two top edges first, then hand one of them across its right wale edge and back.
  const auto& face = s.faces[f];
  const auto split = mesh::split_course_edge(s, face.vertex(face.bottom + 1), face.vertex(face.bottom + 2));
  const auto& g = split.faces[f];
  ASSERT_EQ(g.top(), 2);
  const int u = g.vertex(g.bottom), v = g.vertex(g.bottom + 1);
  const auto shifted = mesh::shift_wale_edge(split, u, v, mesh::WaleEnd::Top, -1);
  ASSERT_TRUE(mesh::validate(shifted).valid());
  EXPECT_EQ(shifted.faces[f].top(), 1);
  const auto& h = shifted.faces[f];
  const auto back = mesh::shift_wale_edge(shifted, h.vertex(h.bottom), h.vertex(h.bottom + 1), mesh::WaleEnd::Top, +1);
  EXPECT_TRUE(back == split);
  const std::string msg = error_of([&] { mesh::shift_wale_edge(s, face.vertex(face.bottom), face.vertex(face.bottom + 1), mesh::WaleEnd::Top, -1); });
  EXPECT_NE(msg.find("single course edge"), std::string::npos) << msg;
}

TEST(Edits, CableMarksNeedACourseRunBetweenTwoRows) {
  const auto s = stitched(models::swatch());
  const auto path = mesh::top_edge_path(s, 4, 8, 11);  // three neighbouring stitches of row 4
  const auto marked = mesh::mark_cable(s, path, 1, 1);
  EXPECT_EQ(marked.cables.size(), 3u);
  EXPECT_TRUE(mesh::validate(marked).valid());
  EXPECT_TRUE(mesh::unmark_cable(marked, path) == s);
  EXPECT_THROW(mesh::mark_cable(s, path, 0, 1), Error);
  EXPECT_THROW(mesh::mark_cable(s, path, 3, 1), Error);
  EXPECT_THROW(mesh::mark_cable(s, path, 1, 0), Error);
  EXPECT_THROW(mesh::mark_cable(s, {path[0], path[1]}, 1, 1), Error);
  // A split cannot take a cable edge apart.
  EXPECT_THROW(mesh::split_course_edge(marked, path[0], path[1]), Error);
}

TEST(Edits, RibFillMakesAlignedColumns) {
  const auto s = stitched(models::swatch());
  const auto all = all_faces(s);
  const auto rib = mesh::fill(s, all, mesh::parse_fill("rib2x2"));
  for (const auto& row : mesh::faces_by_row(rib))
    for (size_t i = 0; i < row.size(); ++i) EXPECT_EQ(rib.faces[row[i]].type, i % 4 < 2 ? "k" : "p");
  const auto garter = mesh::fill(s, all, mesh::parse_fill("garter"));
  for (const auto& f : garter.faces) EXPECT_EQ(f.type, f.row % 2 == 0 ? "k" : "p");
  const auto seed = mesh::fill(s, all, mesh::parse_fill("seed"));
  for (const auto& row : mesh::faces_by_row(seed))
    for (size_t i = 0; i < row.size(); ++i) EXPECT_EQ(seed.faces[row[i]].type, (seed.faces[row[i]].row + i) % 2 == 0 ? "k" : "p");
  EXPECT_THROW(mesh::parse_fill("rib0x2"), Error);
  EXPECT_THROW(mesh::parse_fill("cables"), Error);
}

TEST(Edits, FillsKeepIncreasesAndDecreases) {
  const auto s = stitched(models::beanie());
  const auto all = all_faces(s);
  const auto moss = mesh::fill(s, all, mesh::parse_fill("moss"));
  EXPECT_TRUE(mesh::validate(moss).valid());
  EXPECT_EQ(mesh::stitch_stats(moss).decreases, mesh::stitch_stats(s).decreases);
}

TEST(Edits, EveryAcceptedEditKeepsTheMeshValid) {
  auto s = stitched(models::tube());
  std::mt19937 rng(2012);
  int accepted = 0, refused = 0;
  for (int step = 0; step < 300; ++step) {
    const int f = std::uniform_int_distribution<int>(0, static_cast<int>(s.faces.size()) - 1)(rng);
    const auto& face = s.faces[f];
    const int k = std::uniform_int_distribution<int>(0, face.size() - 1)(rng);
    const int u = face.vertex(k), v = face.vertex(k + 1);
    try {
      switch (std::uniform_int_distribution<int>(0, 5)(rng)) {
        case 0: s = mesh::split_course_edge(s, u, v); break;
        case 1: s = mesh::collapse_course_edge(s, u, v); break;
        case 2: s = mesh::add_wale_edge(s, f); break;
        case 3: s = mesh::remove_wale_edge(s, u, v); break;
        case 4: s = mesh::shift_wale_edge(s, u, v, rng() % 2 ? mesh::WaleEnd::Top : mesh::WaleEnd::Bottom, rng() % 2 ? 1 : -1); break;
        case 5: s = mesh::set_stitch_type(s, {f}, face.bottom == 1 && face.top() == 1 ? "p" : "x"); break;
      }
      ++accepted;
    } catch (const Error&) {
      ++refused;
    }
    ASSERT_TRUE(mesh::validate(s).valid()) << "after step " << step << "\n" << mesh::validate(s).summary();
  }
  EXPECT_GT(accepted, 30);
  EXPECT_GT(refused, 30);
}

TEST(Edits, FacesNearTheBorderAreTheHemAndTheTop) {
  const auto s = stitched(models::swatch());  // 20 stitch rows of 20
  const auto near = mesh::faces_near_border(s, 3);
  EXPECT_EQ(near.size(), 2u * 3 * 20);  // three rows at the bottom, three at the top
  for (int f : near) EXPECT_TRUE(s.faces[f].row < 3 || s.faces[f].row >= 17) << f;
  EXPECT_TRUE(mesh::faces_near_border(s, 0).empty());
  EXPECT_THROW(mesh::faces_near_border(s, -1), Error);
}
