#include "stitchmesh/stitch_mesh.hpp"

#include <algorithm>
#include <set>

#include "common/error.hpp"
#include "stitchmesh/stitch_types.hpp"

namespace skein::mesh {

EdgeTable edge_table(const StitchMesh& mesh) {
  EdgeTable table;
  table.reserve(mesh.faces.size() * 3);
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f) {
    const auto& face = mesh.faces[f];
    for (int k = 0; k < face.size(); ++k) {
      auto& uses = table[edge_key(face.vertex(k), face.vertex(k + 1))];
      if (uses.count < 2) uses.use[uses.count] = {f, k};
      ++uses.count;
    }
  }
  return table;
}

int StitchReport::invalid_faces() const {
  std::set<int> faces;
  for (const auto& [f, why] : face_problems) faces.insert(f);
  return static_cast<int>(faces.size());
}

std::string StitchReport::summary(size_t max_lines) const {
  std::string s;
  size_t lines = 0;
  for (const auto& [f, why] : face_problems)
    if (lines++ < max_lines) s += "face " + std::to_string(f) + ": " + why + "\n";
  for (const auto& why : other_problems)
    if (lines++ < max_lines) s += why + "\n";
  if (lines > max_lines) s += "... and " + std::to_string(lines - max_lines) + " more\n";
  return s;
}

StitchReport validate(const StitchMesh& mesh) {
  StitchReport report;
  const int nv = static_cast<int>(mesh.vertices.size());
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f) {
    const auto& face = mesh.faces[f];
    const auto bad = [&](std::string why) { report.face_problems.emplace_back(f, std::move(why)); };
    bool indices_ok = true;
    for (int v : face.vertices)
      if (v < 0 || v >= nv) indices_ok = false;
    if (!indices_ok) {
      bad("refers to a vertex that does not exist");
      continue;
    }
    std::vector<int> sorted = face.vertices;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) bad("uses a vertex twice");
    if (face.bottom < 1 || face.top() < 1) {
      bad("has " + std::to_string(face.bottom) + " bottom and " + std::to_string(face.top()) +
          " top edges; a stitch needs at least one of each between its two wale edges");
      continue;
    }
    if (default_stitch_type(face.bottom, face.top()).empty()) {
      bad("has " + std::to_string(face.bottom) + " bottom and " + std::to_string(face.top()) +
          " top edges; no stitch has that shape (1 bottom with 1-3 top, 2-3 bottom with 1 top, or lace: 2 with 2, 3 with 3)");
      continue;
    }
    const StitchType* type = find_stitch_type(face.type);
    if (!type)
      bad("stitch type '" + face.type + "' is not a known stitch type");
    else if (type->bottom != face.bottom || type->top != face.top())
      bad("stitch type '" + face.type + "' needs " + std::to_string(type->bottom) + " bottom and " + std::to_string(type->top) +
          " top edges, the face has " + std::to_string(face.bottom) + " and " + std::to_string(face.top()));
    if (face.row < 0) bad("has no row");
  }
  if (!report.face_problems.empty()) return report;  // edge checks need sound faces

  const EdgeTable table = edge_table(mesh);
  for (const auto& [key, uses] : table) {
    const int u = static_cast<int>(key >> 32), v = static_cast<int>(key & 0xffffffffu);
    const std::string edge = "edge " + std::to_string(u) + "-" + std::to_string(v);
    if (uses.count > 2) {
      report.other_problems.push_back(edge + ": shared by " + std::to_string(uses.count) + " faces; at most 2");
      continue;
    }
    if (uses.count == 2) {
      const auto [fa, ka] = uses.use[0];
      const auto [fb, kb] = uses.use[1];
      const auto &a = mesh.faces[fa], &b = mesh.faces[fb];
      if (a.vertex(ka) == b.vertex(kb))
        report.face_problems.emplace_back(fb, edge + " runs the same way as in face " + std::to_string(fa) + " (inconsistent orientation)");
      if (a.is_wale(ka) != b.is_wale(kb))
        report.face_problems.emplace_back(fb, edge + " is " + (b.is_wale(kb) ? "a wale" : "a course") + " edge here but " +
                                                  (a.is_wale(ka) ? "a wale" : "a course") + " edge in face " + std::to_string(fa));
    }
  }
  for (const auto& [edge, mark] : mesh.cables) {
    const std::string where = "cable edge " + std::to_string(edge.first) + "-" + std::to_string(edge.second);
    const auto it = table.find(edge_key(edge.first, edge.second));
    if (it == table.end()) {
      report.other_problems.push_back(where + ": no such edge");
      continue;
    }
    const auto& uses = it->second;
    if (uses.count != 2 || mesh.faces[uses.use[0].face].is_wale(uses.use[0].local))
      report.other_problems.push_back(where + ": a cable edge must be a course edge between two rows");
    if (mark.shift == 0 || (mark.order != 1 && mark.order != -1))
      report.other_problems.push_back(where + ": shift must be non-zero and order +1 or -1");
  }
  return report;
}

std::vector<std::vector<int>> faces_by_row(const StitchMesh& mesh) {
  int rows = 0;
  for (const auto& f : mesh.faces) rows = std::max(rows, f.row + 1);
  std::vector<std::vector<int>> by_row(rows);
  const EdgeTable table = edge_table(mesh);
  const auto neighbour = [&](int f, int k) {
    const auto& face = mesh.faces[f];
    const auto it = table.find(edge_key(face.vertex(k), face.vertex(k + 1)));
    if (it == table.end() || it->second.count != 2) return -1;
    const auto& u = it->second.use;
    return u[0].face == f ? u[1].face : u[0].face;
  };
  std::vector<char> placed(mesh.faces.size(), 0);
  std::vector<std::vector<int>> members(rows);
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f)
    if (mesh.faces[f].row >= 0) members[mesh.faces[f].row].push_back(f);
  for (int r = 0; r < rows; ++r) {
    for (int start : members[r]) {
      if (placed[start]) continue;
      // Walk left to the row's first face (or once round a ring), then right.
      int first = start;
      for (int steps = 0; steps < static_cast<int>(members[r].size()); ++steps) {
        const int left = neighbour(first, mesh.faces[first].left_wale());
        if (left < 0 || left == start || placed[left] || mesh.faces[left].row != r) break;
        first = left;
      }
      for (int f = first; f >= 0 && !placed[f] && mesh.faces[f].row == r; f = neighbour(f, mesh.faces[f].right_wale())) {
        placed[f] = 1;
        by_row[r].push_back(f);
      }
    }
  }
  return by_row;
}

std::vector<int> top_edge_path(const StitchMesh& mesh, int row, int from, int to) {
  const auto rows = faces_by_row(mesh);
  if (row < 0 || row >= static_cast<int>(rows.size()) || from < 0 || to > static_cast<int>(rows[row].size()) || from >= to)
    throw Error("", "row " + std::to_string(row), "has no stitches " + std::to_string(from) + " to " + std::to_string(to - 1));
  std::vector<int> path;
  for (int i = from; i < to; ++i) {
    const auto& f = mesh.faces[rows[row][i]];
    if (path.empty()) path.push_back(f.vertex(f.size() - 1));
    path.push_back(f.vertex(f.bottom + 1));
  }
  return path;
}

int stitch_below(const StitchMesh& mesh, const EdgeTable& table, int f) {
  const auto& face = mesh.faces[f];
  const auto& uses = table.at(edge_key(face.vertex(0), face.vertex(1)));
  if (uses.count != 2) return -1;
  const auto& other = uses.use[0].face == f ? uses.use[1] : uses.use[0];
  return mesh.faces[other.face].is_top(other.local) ? other.face : -1;
}

namespace {

/// The face across local edge `k` of face f, where that edge is local edge `want(other)` of it; -1 if none.
template <class Want>
int across(const StitchMesh& mesh, const EdgeTable& table, int f, int k, Want want) {
  const auto& face = mesh.faces[f];
  const auto& uses = table.at(edge_key(face.vertex(k), face.vertex(k + 1)));
  if (uses.count != 2) return -1;
  const auto& other = uses.use[0].face == f && uses.use[0].local == k ? uses.use[1] : uses.use[0];
  return other.face != f && want(mesh.faces[other.face], other.local) ? other.face : -1;
}

}  // namespace

int step(const StitchMesh& mesh, const EdgeTable& table, int f, Step s) {
  if (f < 0 || !is_plain(mesh.faces[f])) return -1;
  int g = -1;
  switch (s) {
    case Step::Right: g = across(mesh, table, f, 1, [](const StitchFace& o, int k) { return k == o.left_wale(); }); break;
    case Step::Left: g = across(mesh, table, f, 3, [](const StitchFace& o, int k) { return k == o.right_wale(); }); break;
    case Step::Up: g = across(mesh, table, f, 2, [](const StitchFace& o, int k) { return o.is_bottom(k); }); break;
    case Step::Down: g = across(mesh, table, f, 0, [](const StitchFace& o, int k) { return o.is_top(k); }); break;
  }
  return g >= 0 && is_plain(mesh.faces[g]) ? g : -1;
}

int steps(const StitchMesh& mesh, const EdgeTable& table, int f, Step s, int n) {
  for (int i = 0; i < n && f >= 0; ++i) f = step(mesh, table, f, s);
  return f;
}

RowOrder row_order(const StitchMesh& mesh, const std::vector<std::vector<int>>& rows, const EdgeTable& table) {
  // Kahn's order over "row below".
  const int nrows = static_cast<int>(rows.size());
  std::vector<std::set<int>> rows_above(nrows);
  std::vector<int> waiting(nrows, 0);
  for (int r = 0; r < nrows; ++r) {
    std::set<int> under;
    for (int f : rows[r])
      if (const int b = stitch_below(mesh, table, f); b >= 0 && mesh.faces[b].row != r) under.insert(mesh.faces[b].row);
    waiting[r] = static_cast<int>(under.size());
    for (int u : under) rows_above[u].insert(r);
  }
  RowOrder out;
  for (int r = 0; r < nrows; ++r)
    if (waiting[r] == 0) out.order.push_back(r);
  for (size_t i = 0; i < out.order.size(); ++i)
    for (int a : rows_above[out.order[i]])
      if (--waiting[a] == 0) out.order.push_back(a);
  for (int r = 0; r < nrows; ++r)
    if (waiting[r] > 0) out.order.push_back(r);
  out.level.assign(nrows, 0);
  for (int r : out.order)
    for (int f : rows[r])
      if (const int b = stitch_below(mesh, table, f); b >= 0 && mesh.faces[b].row != r)
        out.level[r] = std::max(out.level[r], out.level[mesh.faces[b].row] + 1);
  return out;
}

StitchStats stitch_stats(const StitchMesh& mesh) {
  StitchStats s;
  s.faces = static_cast<int>(mesh.faces.size());
  s.vertices = static_cast<int>(mesh.vertices.size());
  std::set<int> rows;
  for (const auto& f : mesh.faces) {
    rows.insert(f.row);
    s.increases += f.top() > f.bottom;
    s.decreases += f.bottom > f.top();
    ++s.stitch_types[f.type];
  }
  s.rows = static_cast<int>(rows.size());
  s.cable_edges = static_cast<int>(mesh.cables.size());
  const StitchReport report = validate(mesh);
  s.invalid_faces = report.invalid_faces();
  s.valid = report.valid();
  return s;
}

}  // namespace skein::mesh
