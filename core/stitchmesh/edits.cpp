#include "stitchmesh/edits.hpp"

#include <algorithm>
#include <set>

#include "common/error.hpp"
#include "stitchmesh/stitch_types.hpp"

namespace skein::mesh {
namespace {

std::string edge_name(int u, int v) { return "edge " + std::to_string(u) + "-" + std::to_string(v); }

struct Use {
  int face, local;
};

/// The faces using edge u-v (at most two in a valid mesh).
std::vector<Use> uses_of(const StitchMesh& mesh, int u, int v) {
  std::vector<Use> uses;
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f) {
    const auto& face = mesh.faces[f];
    for (int k = 0; k < face.size(); ++k)
      if (edge_key(face.vertex(k), face.vertex(k + 1)) == edge_key(u, v)) uses.push_back({f, k});
  }
  return uses;
}

std::vector<Use> course_uses(const StitchMesh& mesh, int u, int v) {
  const auto uses = uses_of(mesh, u, v);
  if (uses.empty()) throw Error("", edge_name(u, v), "no such edge in the stitch mesh");
  for (const auto& use : uses)
    if (mesh.faces[use.face].is_wale(use.local)) throw Error("", edge_name(u, v), "is a wale edge; this edit works on course edges");
  return uses;
}

/// Gives faces whose type no longer fits their shape the default type of the new shape.
void refit_type(StitchFace& face) {
  const StitchType* type = find_stitch_type(face.type);
  if (!type || type->bottom != face.bottom || type->top != face.top()) face.type = default_stitch_type(face.bottom, face.top());
}

/// Refuses an edit whose result breaks a rule, naming what the edit was and the first rule broken.
StitchMesh checked(StitchMesh out, const std::string& what) {
  for (auto& face : out.faces)
    if (face.type.empty()) face.type = "?";
  const StitchReport report = validate(out);
  if (!report.valid()) throw Error("", what, "refused: it would leave " + report.summary(1).substr(0, report.summary(1).size() - 1));
  return out;
}

bool on_cable(const StitchMesh& mesh, int w) {
  for (const auto& [edge, mark] : mesh.cables)
    if (edge.first == w || edge.second == w) return true;
  return false;
}

/// Inserts a new vertex in the middle of course edge u-v in every face using it.
void split_unchecked(StitchMesh& out, int u, int v) {
  const auto uses = course_uses(out, u, v);
  if (out.cables.count(std::minmax(u, v))) throw Error("", edge_name(u, v), "is a cable edge; unmark it first");
  const int m = static_cast<int>(out.vertices.size());
  out.vertices.push_back(0.5 * (out.vertices[u] + out.vertices[v]));
  for (const auto& use : uses) {
    auto& face = out.faces[use.face];
    const bool bottom = face.is_bottom(use.local);
    face.vertices.insert(face.vertices.begin() + use.local + 1, m);
    if (bottom) ++face.bottom;
    refit_type(face);
  }
}

/// Whether w meets exactly two edges, both course edges: then it can be merged away.
bool is_free(const StitchMesh& mesh, int w) {
  std::set<int> neighbours;
  for (const auto& face : mesh.faces)
    for (int k = 0; k < face.size(); ++k) {
      if (face.vertices[k] != w) continue;
      if (face.is_wale(k) || face.is_wale((k + face.size() - 1) % face.size())) return false;
      neighbours.insert(face.vertex(k + 1));
      neighbours.insert(face.vertex(k + face.size() - 1));
    }
  return neighbours.size() == 2;
}

/// Removes vertex w (interior to course chains) from the faces and the vertex list.
void remove_free_vertex(StitchMesh& out, int w) {
  for (auto& face : out.faces) {
    const auto it = std::find(face.vertices.begin(), face.vertices.end(), w);
    if (it == face.vertices.end()) continue;
    const int k = static_cast<int>(it - face.vertices.begin());
    face.vertices.erase(it);
    if (k > 0 && k < face.bottom) --face.bottom;
    refit_type(face);
  }
  out.vertices.erase(out.vertices.begin() + w);
  for (auto& face : out.faces)
    for (int& v : face.vertices)
      if (v > w) --v;
  std::map<std::pair<int, int>, CableMark> cables;
  for (const auto& [edge, mark] : out.cables) cables[{edge.first - (edge.first > w), edge.second - (edge.second > w)}] = mark;
  out.cables = std::move(cables);
}

/// The two stitches on either side of wale edge u-v: the one it is the right wale edge of, then the other.
std::pair<int, int> stitches_beside(const StitchMesh& mesh, int u, int v) {
  const auto uses = uses_of(mesh, u, v);
  int a = -1, b = -1;
  for (const auto& use : uses) {
    const auto& face = mesh.faces[use.face];
    if (use.local == face.right_wale()) a = use.face;
    if (use.local == face.left_wale()) b = use.face;
  }
  if (uses.size() != 2 || a < 0 || b < 0 || a == b)
    throw Error("", edge_name(u, v), "is not a wale edge between two stitches of one row");
  return {a, b};
}

}  // namespace

StitchMesh set_stitch_type(const StitchMesh& mesh, const std::vector<int>& faces, const std::string& type) {
  const StitchType* t = find_stitch_type(type);
  if (!t) throw Error("", "stitch type '" + type + "'", "is not a known stitch type");
  StitchMesh out = mesh;
  for (int f : faces) {
    if (f < 0 || f >= static_cast<int>(mesh.faces.size())) throw Error("", "face " + std::to_string(f), "does not exist");
    auto& face = out.faces[f];
    if (face.bottom != t->bottom || face.top() != t->top)
      throw Error("", "face " + std::to_string(f),
                  "'" + type + "' needs " + std::to_string(t->bottom) + " bottom and " + std::to_string(t->top) + " top edges, the face has " +
                      std::to_string(face.bottom) + " and " + std::to_string(face.top()));
    face.type = type;
  }
  return out;
}

StitchMesh split_course_edge(const StitchMesh& mesh, int u, int v) {
  StitchMesh out = mesh;
  split_unchecked(out, u, v);
  return checked(std::move(out), "splitting " + edge_name(u, v));
}

StitchMesh collapse_course_edge(const StitchMesh& mesh, int u, int v) {
  course_uses(mesh, u, v);
  const int w = is_free(mesh, v) ? v : is_free(mesh, u) ? u : -1;
  if (w < 0)
    throw Error("", edge_name(u, v), "cannot collapse: a wale edge meets each end (collapsing would take a stitch's wale edge away)");
  if (on_cable(mesh, w)) throw Error("", edge_name(u, v), "cannot collapse a cable edge; unmark it first");
  StitchMesh out = mesh;
  remove_free_vertex(out, w);
  return checked(std::move(out), "collapsing " + edge_name(u, v));
}

StitchMesh add_wale_edge(const StitchMesh& mesh, int f) {
  if (f < 0 || f >= static_cast<int>(mesh.faces.size())) throw Error("", "face " + std::to_string(f), "does not exist");
  StitchMesh out = mesh;
  if (out.faces[f].bottom == 1) split_unchecked(out, out.faces[f].vertex(0), out.faces[f].vertex(1));
  if (out.faces[f].top() == 1) {
    const auto& face = out.faces[f];
    split_unchecked(out, face.vertex(face.bottom + 1), face.vertex(face.bottom + 2));
  }
  const StitchFace face = out.faces[f];
  const int bi = face.bottom / 2, ti = face.bottom + 1 + face.top() / 2;
  StitchFace left = face, right = face;
  left.vertices.assign(face.vertices.begin(), face.vertices.begin() + bi + 1);
  left.vertices.insert(left.vertices.end(), face.vertices.begin() + ti, face.vertices.end());
  left.bottom = bi;
  right.vertices.assign(face.vertices.begin() + bi, face.vertices.begin() + ti + 1);
  right.bottom = face.bottom - bi;
  refit_type(left);
  refit_type(right);
  right.input_face = left.input_face;
  out.faces[f] = std::move(left);
  out.faces.push_back(std::move(right));
  return checked(std::move(out), "adding a wale edge through face " + std::to_string(f));
}

StitchMesh remove_wale_edge(const StitchMesh& mesh, int u, int v) {
  const auto [a, b] = stitches_beside(mesh, u, v);
  const StitchFace &A = mesh.faces[a], &B = mesh.faces[b];
  const int bottom_end = A.vertex(A.bottom), top_end = A.vertex(A.bottom + 1);
  StitchFace merged = A;
  merged.vertices.assign(A.vertices.begin(), A.vertices.begin() + A.bottom + 1);
  merged.vertices.insert(merged.vertices.end(), B.vertices.begin() + 1, B.vertices.end());
  merged.vertices.insert(merged.vertices.end(), A.vertices.begin() + A.bottom + 2, A.vertices.end());
  merged.bottom = A.bottom + B.bottom;
  StitchMesh out = mesh;
  out.faces[a] = std::move(merged);
  out.faces.erase(out.faces.begin() + b);
  // Collapse the ends the removed edge leaves free, higher id first so the lower id stays valid.
  std::vector<int> ends;
  for (int w : {top_end, bottom_end})
    if (is_free(out, w) && !on_cable(out, w)) ends.push_back(w);
  std::sort(ends.rbegin(), ends.rend());
  for (int w : ends) remove_free_vertex(out, w);
  for (auto& face : out.faces) refit_type(face);
  return checked(std::move(out), "removing wale " + edge_name(u, v));
}

StitchMesh shift_wale_edge(const StitchMesh& mesh, int u, int v, WaleEnd end, int direction) {
  if (direction != 1 && direction != -1) throw Error("", edge_name(u, v), "a wale edge shifts by +1 or -1");
  const auto [a, b] = stitches_beside(mesh, u, v);
  StitchMesh out = mesh;
  auto &A = out.faces[a].vertices, &B = out.faces[b].vertices;
  int& nbA = out.faces[a].bottom;
  int& nbB = out.faces[b].bottom;
  const auto refuse = [&](const char* side) {
    throw Error("", edge_name(u, v), std::string("cannot shift: the stitch on the ") + side + " has a single course edge on that side");
  };
  if (end == WaleEnd::Top && direction > 0) {  // B hands its rightmost top edge to A
    if (out.faces[b].top() < 2) refuse("right");
    A.insert(A.begin() + nbA + 1, B[B.size() - 2]);
    B.pop_back();
  } else if (end == WaleEnd::Top) {  // A hands its rightmost top edge to B
    if (out.faces[a].top() < 2) refuse("left");
    B.push_back(A[nbA + 2]);
    A.erase(A.begin() + nbA + 1);
  } else if (direction > 0) {  // B hands its leftmost bottom edge to A
    if (nbB < 2) refuse("right");
    A.insert(A.begin() + nbA + 1, B[1]);
    ++nbA;
    B.erase(B.begin());
    --nbB;
  } else {  // A hands its rightmost bottom edge to B
    if (nbA < 2) refuse("left");
    B.insert(B.begin(), A[nbA - 1]);
    ++nbB;
    A.erase(A.begin() + nbA);
    --nbA;
  }
  refit_type(out.faces[a]);
  refit_type(out.faces[b]);
  return checked(std::move(out), "shifting wale " + edge_name(u, v));
}

StitchMesh mark_cable(const StitchMesh& mesh, const std::vector<int>& path, int shift, int order) {
  const std::string what = "cable along " + std::to_string(path.size()) + " vertices";
  if (path.size() < 3) throw Error("", what, "a cable crosses at least two course edges (1 over 1)");
  const int edges = static_cast<int>(path.size()) - 1;
  if (shift == 0 || std::abs(shift) >= edges)
    throw Error("", what, "shift must be between 1 and " + std::to_string(edges - 1) + " stitches either way, got " + std::to_string(shift));
  if (order != 1 && order != -1) throw Error("", what, "order must be +1 (crossing in front) or -1 (behind)");
  StitchMesh out = mesh;
  std::pair<int, int> rows{-1, -1};
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const int u = path[i], v = path[i + 1];
    const auto uses = course_uses(mesh, u, v);
    if (uses.size() != 2) throw Error("", edge_name(u, v), "a cable edge must lie between two rows");
    const auto& f0 = mesh.faces[uses[0].face];
    const auto& f1 = mesh.faces[uses[1].face];
    const std::pair<int, int> here = f0.is_top(uses[0].local) ? std::pair{f0.row, f1.row} : std::pair{f1.row, f0.row};
    if (rows.first >= 0 && here != rows) throw Error("", edge_name(u, v), "all edges of a cable must lie between the same two rows");
    rows = here;
    out.cables[std::minmax(u, v)] = {shift, order};
  }
  return checked(std::move(out), what);
}

StitchMesh unmark_cable(const StitchMesh& mesh, const std::vector<int>& path) {
  StitchMesh out = mesh;
  for (size_t i = 0; i + 1 < path.size(); ++i)
    if (!out.cables.erase(std::minmax(path[i], path[i + 1])))
      throw Error("", edge_name(path[i], path[i + 1]), "is not marked as a cable edge");
  return out;
}

Fill parse_fill(const std::string& text) {
  if (text == "stockinette") return {FillKind::Stockinette};
  if (text == "reverse") return {FillKind::ReverseStockinette};
  if (text == "garter") return {FillKind::Garter};
  if (text == "seed") return {FillKind::Seed};
  if (text == "moss") return {FillKind::Moss};
  if (text == "rib") return {FillKind::Rib, 1, 1};
  int k = 0, p = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "rib%dx%d%c", &k, &p, &tail) == 2 && k >= 1 && p >= 1 && k <= 64 && p <= 64) return {FillKind::Rib, k, p};
  throw Error("", "fill '" + text + "'", "expected stockinette, reverse, garter, seed, moss, rib or ribKxP (e.g. rib2x2)");
}

StitchGrid stitch_grid(const StitchMesh& mesh) {
  const auto rows = faces_by_row(mesh);
  const EdgeTable table = edge_table(mesh);
  const auto below = [&](int f) { return stitch_below(mesh, table, f); };
  // Rows bottom-up, so that each row lines its columns up with the stitches it is worked into.
  const RowOrder ordered = row_order(mesh, rows, table);
  StitchGrid grid;
  grid.column.assign(mesh.faces.size(), 0);
  grid.level.assign(mesh.faces.size(), 0);
  std::vector<char> placed(mesh.faces.size(), 0);
  for (int r : ordered.order) {
    const auto& row = rows[r];
    // Each stitch takes the column of the stitch below it; the second stitch above an increase (same stitch
    // below) takes the next column. Stitches with nothing placed below continue from their left neighbour.
    size_t first_anchored = row.size();
    for (size_t i = 0; i < row.size() && first_anchored == row.size(); ++i)
      if (const int b = below(row[i]); b >= 0 && placed[b]) first_anchored = i;
    long col = first_anchored < row.size() ? grid.column[below(row[first_anchored])] - static_cast<long>(first_anchored) : 0;
    for (size_t i = 0; i < row.size(); ++i) {
      const int f = row[i], b = below(f);
      const bool anchored = b >= 0 && placed[b] && (i == 0 || b != below(row[i - 1]));
      col = anchored ? grid.column[b] : (i == 0 ? col : col + 1);
      grid.column[f] = col;
      grid.level[f] = ordered.level[r];
    }
    for (int f : row) placed[f] = 1;
  }
  return grid;
}

int lowest_left(const StitchMesh& mesh, const std::vector<int>& faces) {
  if (faces.empty()) throw Error("", "stitches", "none chosen");
  const auto grid = stitch_grid(mesh);
  return *std::min_element(faces.begin(), faces.end(), [&](int a, int b) {
    return std::pair(grid.level[a], grid.column[a]) < std::pair(grid.level[b], grid.column[b]);
  });
}

StitchMesh fill(const StitchMesh& mesh, const std::vector<int>& faces, const Fill& pattern) {
  const std::set<int> chosen(faces.begin(), faces.end());
  for (int f : chosen)
    if (f < 0 || f >= static_cast<int>(mesh.faces.size())) throw Error("", "face " + std::to_string(f), "does not exist");
  const StitchGrid grid = stitch_grid(mesh);
  StitchMesh out = mesh;
  const auto mod = [](long a, long m) { return ((a % m) + m) % m; };
  for (int f : chosen) {
    auto& face = out.faces[f];
    if (face.bottom != 1 || face.top() != 1) continue;
    const long row = grid.level[f], col = grid.column[f];
    bool knit = true;
    switch (pattern.kind) {
      case FillKind::Stockinette: knit = true; break;
      case FillKind::ReverseStockinette: knit = false; break;
      case FillKind::Rib: knit = mod(col, pattern.knits + pattern.purls) < pattern.knits; break;
      case FillKind::Garter: knit = mod(row, 2) == 0; break;
      case FillKind::Seed: knit = mod(row + col, 2) == 0; break;
      case FillKind::Moss: knit = mod(row / 2 + col, 2) == 0; break;
    }
    face.type = knit ? "k" : "p";
  }
  return out;
}

std::vector<int> faces_near_border(const StitchMesh& mesh, int rows) {
  if (rows < 0) throw Error("", "border rows", "must be 0 or more, got " + std::to_string(rows));
  const EdgeTable table = edge_table(mesh);
  const int nf = static_cast<int>(mesh.faces.size());
  std::vector<int> distance(nf, -1), frontier;
  for (int f = 0; f < nf; ++f) {
    const auto& face = mesh.faces[f];
    for (int k = 0; k < face.size(); ++k)
      if (!face.is_wale(k) && table.at(edge_key(face.vertex(k), face.vertex(k + 1))).count == 1) {
        distance[f] = 0;
        frontier.push_back(f);
        break;
      }
  }
  // Breadth-first across course edges, one stitch row per step.
  for (int d = 1; d < rows && !frontier.empty(); ++d) {
    std::vector<int> next;
    for (int f : frontier) {
      const auto& face = mesh.faces[f];
      for (int k = 0; k < face.size(); ++k) {
        if (face.is_wale(k)) continue;
        const auto& uses = table.at(edge_key(face.vertex(k), face.vertex(k + 1)));
        if (uses.count != 2) continue;
        const int g = uses.use[0].face == f ? uses.use[1].face : uses.use[0].face;
        if (distance[g] < 0) distance[g] = d, next.push_back(g);
      }
    }
    frontier = std::move(next);
  }
  std::vector<int> out;
  for (int f = 0; f < nf; ++f)
    if (distance[f] >= 0 && distance[f] < rows) out.push_back(f);
  return out;
}

}  // namespace skein::mesh
