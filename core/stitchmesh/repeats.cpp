#include "stitchmesh/repeats.hpp"

#include <algorithm>
#include <array>
#include <deque>
#include <map>
#include <set>
#include <tuple>

#include "common/error.hpp"

namespace skein::mesh {
namespace {

int wrap(int a, int m) { return ((a % m) + m) % m; }

/// The stitch grid around plain stitches: per face its neighbours right, left, up and down (mesh::step) and a
/// type id, -1 for stitches in no repeat (not plain, or on a cable mark).
struct Grid {
  std::vector<std::array<int, 4>> next;  ///< indexed by Step
  std::vector<int> id;
  std::vector<std::string> names;        ///< per type id

  int at(int f, Step s) const { return f < 0 ? -1 : next[f][static_cast<int>(s)]; }
  /// The stitch `a` along the row and `b` up the wale from f, the row first (or the wale first, which meets it
  /// where the grid is regular); -1 when the walk leaves the grid.
  int walk(int f, int a, int b, bool wale_first = false) const {
    const auto go = [&](int n, Step plus, Step minus) {
      for (; n != 0 && f >= 0; n += n > 0 ? -1 : 1) f = at(f, n > 0 ? plus : minus);
    };
    if (wale_first) go(b, Step::Up, Step::Down);
    go(a, Step::Right, Step::Left);
    if (!wale_first) go(b, Step::Up, Step::Down);
    return f;
  }
  int type(int f) const { return f < 0 ? -1 : id[f]; }
};

Grid stitch_grid_of(const StitchMesh& mesh) {
  const int n = static_cast<int>(mesh.faces.size());
  const EdgeTable table = edge_table(mesh);
  Grid grid;
  grid.next.resize(n);
  grid.id.assign(n, -1);
  std::map<std::string, int> ids;
  for (int f = 0; f < n; ++f) {
    const auto& face = mesh.faces[f];
    for (Step s : {Step::Right, Step::Left, Step::Up, Step::Down}) grid.next[f][static_cast<int>(s)] = step(mesh, table, f, s);
    if (!is_plain(face) || mesh.cables.count(std::minmax(face.vertex(0), face.vertex(1))) ||
        mesh.cables.count(std::minmax(face.vertex(2), face.vertex(3))))
      continue;
    const auto [it, added] = ids.emplace(face.type, static_cast<int>(grid.names.size()));
    if (added) grid.names.push_back(face.type);
    grid.id[f] = it->second;
  }
  return grid;
}

/// Type ids of the P x Q stitches from f (tile[b * P + a]: a along the row, b up the wale); empty when one is missing.
std::vector<int> tile_from(const Grid& grid, int f, int P, int Q) {
  std::vector<int> tile(P * Q);
  for (int b = 0; b < Q; ++b)
    for (int a = 0; a < P; ++a)
      if ((tile[b * P + a] = grid.type(grid.walk(f, a, b))) < 0) return {};
  return tile;
}

/// Whether the stitch types from f repeat with period P x Q over the window [-m, P + m) x [-n, Q + n), with
/// m = max(P, 2) and n = max(Q, 2): at least two stitches each way, so that the middle of a 3 x 3 rib's knit
/// column is no stockinette.
bool repeats_with(const Grid& grid, int f, int P, int Q) {
  const auto tile = tile_from(grid, f, P, Q);
  if (tile.empty()) return false;
  const int m = std::max(P, 2), n = std::max(Q, 2);
  for (int b = -n; b < Q + n; ++b) {
    int g = grid.walk(f, -m, b);
    for (int a = -m; a < P + m; ++a, g = grid.at(g, Step::Right))
      if (grid.type(g) < 0 || grid.type(g) != tile[wrap(b, Q) * P + wrap(a, P)]) return false;
  }
  return true;
}

/// The smallest period (area, then width) the types from f repeat with, or {0, 0}.
std::pair<int, int> smallest_period(const Grid& grid, int f, int max_period) {
  if (grid.type(f) < 0) return {0, 0};
  for (int area = 1; area <= max_period * max_period; ++area)
    for (int P = 1; P <= std::min(area, max_period); ++P)
      if (area % P == 0 && area / P <= max_period && repeats_with(grid, f, P, area / P)) return {P, area / P};
  return {0, 0};
}

/// Whether f's 3 x 3 neighbourhood is a regular grid with the repeat's types around (column, row).
bool fits(const Grid& grid, const std::vector<std::vector<int>>& rows, int f, int column, int row) {
  const int P = static_cast<int>(rows[0].size()), Q = static_cast<int>(rows.size());
  for (int b = -1; b <= 1; ++b)
    for (int a = -1; a <= 1; ++a) {
      const int g = grid.walk(f, a, b);
      if (g < 0 || g != grid.walk(f, a, b, true) || grid.type(g) != rows[wrap(row + b, Q)][wrap(column + a, P)]) return false;
    }
  return true;
}

/// Per face and local edge: the face across that edge and the edge's local index there; {-1, -1} at a border.
std::vector<std::vector<std::pair<int, int>>> faces_across(const StitchMesh& mesh) {
  const EdgeTable table = edge_table(mesh);
  std::vector<std::vector<std::pair<int, int>>> out(mesh.faces.size());
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f) {
    const auto& face = mesh.faces[f];
    out[f].assign(face.size(), {-1, -1});
    for (int k = 0; k < face.size(); ++k) {
      const auto& uses = table.at(edge_key(face.vertex(k), face.vertex(k + 1)));
      if (uses.count != 2) continue;
      const auto& other = uses.use[0].face == f && uses.use[0].local == k ? uses.use[1] : uses.use[0];
      out[f][k] = {other.face, other.local};
    }
  }
  return out;
}

/// Whether face f of `a` and face g of `b` are the same stitch: type, shape and the cable marks on each edge.
bool same_stitch(const StitchMesh& a, int f, const StitchMesh& b, int g) {
  const auto &x = a.faces[f], &y = b.faces[g];
  if (x.type != y.type || x.bottom != y.bottom || x.size() != y.size()) return false;
  for (int k = 0; k < x.size(); ++k) {
    const auto i = a.cables.find(std::minmax(x.vertex(k), x.vertex(k + 1)));
    const auto j = b.cables.find(std::minmax(y.vertex(k), y.vertex(k + 1)));
    if ((i == a.cables.end()) != (j == b.cables.end()) || (i != a.cables.end() && i->second != j->second)) return false;
  }
  return true;
}

}  // namespace

TiledRepeats find_tiled_repeats(const StitchMesh& mesh, const std::vector<Pattern>& patterns) {
  const int n = static_cast<int>(mesh.faces.size());
  TiledRepeats out;
  out.pattern.assign(n, -1);
  out.place.assign(n, -1);
  const auto next = faces_across(mesh);
  for (const Pattern& pattern : patterns) {
    if (pattern.format == PatternFormat::Woven) throw Error("", "pattern " + pattern.name, "is woven: a stitch mesh holds no repeat of it");
    if (!remeshes(pattern)) continue;
    const int index = static_cast<int>(out.patterns.size());
    out.patterns.push_back(pattern);
    out.repeats.push_back(0);
    // The repeat in the middle of a 3 x 3 tiling: every edge of it joined as in a larger piece of the fabric.
    const StitchMesh tiles = pattern_stitch_mesh(pattern, 3, 3);
    const auto tiles_next = faces_across(tiles);
    const int faces = pattern.stitches();
    std::vector<int> place_of(tiles.faces.size(), -1), face_at(faces);
    for (int q = 0; q < faces; ++q) place_of[face_at[q] = repeat_face(pattern, 3, 1, 1, q)] = q;
    // A repeat is matched from the place that the fewest of the mesh's faces could take.
    std::vector<std::vector<int>> could(faces);
#pragma omp parallel for schedule(static)
    for (int q = 0; q < faces; ++q)
      for (int g = 0; g < n; ++g)
        if (same_stitch(tiles, face_at[q], mesh, g)) could[q].push_back(g);
    const int anchor = static_cast<int>(std::min_element(could.begin(), could.end(), [](const auto& a, const auto& b) { return a.size() < b.size(); }) - could.begin());
    std::vector<int> image(faces);
    for (int start : could[anchor]) {
      if (out.pattern[start] >= 0) continue;
      std::fill(image.begin(), image.end(), -1);
      image[anchor] = start;
      std::vector<int> queue{anchor};
      std::set<int> taken{start};
      bool matches = true;
      while (matches && !queue.empty()) {
        const int q = queue.back();
        queue.pop_back();
        const int t = face_at[q], g = image[q];
        for (int k = 0; matches && k < tiles.faces[t].size(); ++k) {
          const auto [t2, k2] = tiles_next[t][k];
          if (t2 < 0 || place_of[t2] < 0) continue;  // an edge of the repeat
          const auto [g2, l2] = next[g][k];
          const int q2 = place_of[t2];
          if (g2 < 0 || l2 != k2 || out.pattern[g2] >= 0 || !same_stitch(tiles, t2, mesh, g2)) matches = false;
          else if (image[q2] < 0) {
            matches = taken.insert(g2).second;
            image[q2] = g2;
            queue.push_back(q2);
          } else matches = image[q2] == g2;
        }
      }
      if (!matches || std::count(image.begin(), image.end(), -1)) continue;
      for (int q = 0; q < faces; ++q) out.pattern[image[q]] = index, out.place[image[q]] = q;
      ++out.repeats[index];
    }
  }
  return out;
}

int RepeatRegions::faces_of(int r) const { return static_cast<int>(std::count(repeat.begin(), repeat.end(), r)); }

RepeatRegions find_repeats(const StitchMesh& mesh, int max_period, int reach) {
  if (max_period < 1 || max_period > 16)
    throw Error("", "repeats", "the longest period must be 1 to 16 stitches, found " + std::to_string(max_period));
  if (reach < 0) throw Error("", "repeats", "the rings beyond a region must be 0 or more, found " + std::to_string(reach));
  const int n = static_cast<int>(mesh.faces.size());
  const Grid grid = stitch_grid_of(mesh);
  std::vector<std::pair<int, int>> period(n);
#pragma omp parallel for schedule(dynamic, 64)
  for (int f = 0; f < n; ++f) period[f] = smallest_period(grid, f, max_period);
  // Regions start from the stitches with the smallest periods, so that a stitch between two patterns goes to
  // the simpler one.
  std::vector<int> starts;
  for (int f = 0; f < n; ++f)
    if (period[f].first > 0) starts.push_back(f);
  std::stable_sort(starts.begin(), starts.end(),
                   [&](int a, int b) { return period[a].first * period[a].second < period[b].first * period[b].second; });

  RepeatRegions out;
  out.repeat.assign(n, -1);
  out.column.assign(n, -1);
  out.row.assign(n, -1);
  std::map<std::vector<std::vector<int>>, int> known;  // a repeat's rows of type ids, canonical phase
  std::vector<std::vector<std::vector<int>>> id_rows;  // per repeat
  for (int start : starts) {
    if (out.repeat[start] >= 0) continue;
    const auto [P, Q] = period[start];
    const auto tile = tile_from(grid, start, P, Q);
    // The canonical phase: the roll (c, d) of the tile whose rows of type names come first.
    std::vector<std::vector<std::string>> best;
    std::vector<std::vector<int>> best_ids;
    int column = 0, row = 0;
    for (int d = 0; d < Q; ++d)
      for (int c = 0; c < P; ++c) {
        std::vector<std::vector<std::string>> names(Q, std::vector<std::string>(P));
        std::vector<std::vector<int>> ids(Q, std::vector<int>(P));
        for (int b = 0; b < Q; ++b)
          for (int a = 0; a < P; ++a) names[b][a] = grid.names[ids[b][a] = tile[((b + d) % Q) * P + (a + c) % P]];
        if (best.empty() || names < best) best = names, best_ids = ids, column = wrap(-c, P), row = wrap(-d, Q);
      }
    if (!fits(grid, best_ids, start, column, row)) continue;
    auto [it, added] = known.emplace(best_ids, static_cast<int>(out.repeats.size()));
    if (added) {
      Pattern pattern;
      pattern.format = PatternFormat::Knit;
      pattern.rows = best;
      pattern.name = repeat_text(pattern);
      out.repeats.push_back(pattern);
      id_rows.push_back(best_ids);
    }
    const int r = it->second;
    // Grow the region along rows and wales.
    std::deque<int> queue{start};
    out.repeat[start] = r, out.column[start] = column, out.row[start] = row;
    while (!queue.empty()) {
      const int f = queue.front();
      queue.pop_front();
      for (const auto& [s, da, db] : {std::tuple{Step::Right, 1, 0}, {Step::Left, -1, 0}, {Step::Up, 0, 1}, {Step::Down, 0, -1}}) {
        const int g = grid.at(f, s);
        // A stitch whose own surroundings repeat with another period belongs to that pattern's region.
        if (g < 0 || out.repeat[g] >= 0 || (period[g].first > 0 && period[g] != period[start])) continue;
        const int c = wrap(out.column[f] + da, P), w = wrap(out.row[f] + db, Q);
        if (!fits(grid, id_rows[r], g, c, w)) continue;
        out.repeat[g] = r, out.column[g] = c, out.row[g] = w;
        queue.push_back(g);
      }
    }
  }
  // The rings beyond: a plain stitch next to a region joins it when its own type is the pattern's at its place,
  // one ring at a time, each from the stitches the last one reached.
  for (int ring = 0; ring < reach; ++ring) {
    std::vector<std::array<int, 4>> joins;  // face, repeat, column, row
    for (int g = 0; g < n; ++g) {
      if (out.repeat[g] >= 0 || grid.type(g) < 0) continue;
      for (const auto& [s, da, db] : {std::tuple{Step::Left, 1, 0}, {Step::Right, -1, 0}, {Step::Down, 0, 1}, {Step::Up, 0, -1}}) {
        const int f = grid.at(g, s), r = f < 0 ? -1 : out.repeat[f];
        if (r < 0) continue;
        const auto& rows = id_rows[r];
        const int c = wrap(out.column[f] + da, static_cast<int>(rows[0].size())), w = wrap(out.row[f] + db, static_cast<int>(rows.size()));
        if (rows[w][c] != grid.type(g)) continue;
        joins.push_back({g, r, c, w});
        break;
      }
    }
    for (const auto& [g, r, c, w] : joins) out.repeat[g] = r, out.column[g] = c, out.row[g] = w;
  }
  return out;
}

std::string repeat_text(const Pattern& repeat) {
  std::string text;
  for (auto row = repeat.rows.rbegin(); row != repeat.rows.rend(); ++row) {
    if (!text.empty()) text += " / ";
    for (size_t i = 0; i < row->size(); ++i) text += (i ? " " : "") + (*row)[i];
  }
  return text;
}

}  // namespace skein::mesh
