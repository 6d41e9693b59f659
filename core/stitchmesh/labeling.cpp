#include "stitchmesh/labeling.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <unordered_set>

#include "common/error.hpp"

namespace skein::mesh {
namespace {

int wrap(int k, int n) { return ((k % n) + n) % n; }

/// Local index of edge e in face f.
int local_of(const InputMesh& mesh, int f, int e) {
  const auto& fe = mesh.face_edges(f);
  return static_cast<int>(std::find(fe.begin(), fe.end(), e) - fe.begin());
}

/// The use of edge e by a face other than f, or {-1,-1}.
EdgeUse across(const InputMesh& mesh, int e, int f) {
  for (const auto& use : mesh.edge_uses(e))
    if (use.face != f) return use;
  return {};
}

Eigen::Vector3d edge_direction(const InputMesh& mesh, int f, int k) {
  const auto& loop = mesh.face(f);
  return (mesh.point(loop[(k + 1) % loop.size()]) - mesh.point(loop[k])).normalized();
}

/// Grows rows through wale edges: one face at a time, each face's wale edges lead to its neighbours in
/// the row, whose other wale edge is found by other_wale().
class RowGrower {
public:
  RowGrower(const InputMesh& mesh, Labeling& labels) : m_mesh(mesh), m_labels(labels) {}

  /// Whether face f can take wale edges (left, right) without contradicting labels already set.
  bool can_assign(int f, int left, int right) const {
    const int n = static_cast<int>(m_mesh.face(f).size());
    if (left < 0 || right < 0 || left == right) return false;
    if (wrap(right - left, n) < 2 || wrap(left - right, n) < 2) return false;  // a side without course edges
    for (int k = 0; k < n; ++k) {
      const EdgeLabel want = (k == left || k == right) ? EdgeLabel::Wale : EdgeLabel::Course;
      const EdgeLabel have = m_labels.edges[m_mesh.face_edge(f, k)];
      if (have != EdgeLabel::None && have != want) return false;
    }
    return true;
  }

  void assign(int f, int left, int right, int row) {
    m_labels.faces[f] = {row, left, right};
    const int n = static_cast<int>(m_mesh.face(f).size());
    for (int k = 0; k < n; ++k)
      m_labels.edges[m_mesh.face_edge(f, k)] = (k == left || k == right) ? EdgeLabel::Wale : EdgeLabel::Course;
  }

  /// Labels face f as a new row with the given course chain (local edges first..last) as its bottom or
  /// top, then grows the row. Returns the row id, or -1 when the face cannot take that labeling.
  int seed(int f, int first, int last, bool chain_is_bottom) {
    const int n = static_cast<int>(m_mesh.face(f).size());
    // Counter-clockwise: left wale, bottom chain, right wale, top chain.
    const int before = wrap(first - 1, n), after = wrap(last + 1, n);
    const int left = chain_is_bottom ? before : after;
    const int right = chain_is_bottom ? after : before;
    if (!can_assign(f, left, right)) return -1;
    const int row = m_labels.rows++;
    assign(f, left, right, row);
    grow(f);
    return row;
  }

  /// Breadth-first through wale edges from a labeled face.
  void grow(int start) {
    std::deque<int> queue{start};
    while (!queue.empty()) {
      const int f = queue.front();
      queue.pop_front();
      const FaceLabel fl = m_labels.faces[f];
      for (const bool through_right : {true, false}) {
        const int e = m_mesh.face_edge(f, through_right ? fl.right : fl.left);
        const EdgeUse g = across(m_mesh, e, f);
        if (g.face < 0 || m_labels.faces[g.face].labeled()) continue;
        const int other = other_wale(g.face, g.local);
        if (other < 0) continue;
        // Across f's right wale lies the neighbour's left wale, and the other way round.
        const int left = through_right ? g.local : other;
        const int right = through_right ? other : g.local;
        if (!can_assign(g.face, left, right)) continue;
        assign(g.face, left, right, fl.row);
        queue.push_back(g.face);
      }
    }
  }

private:
  /// The wale edge opposite entry edge k of face g: an edge already labeled wale if there is one,
  /// otherwise the unlabeled non-adjacent edge most parallel to the entry edge (the opposite one on a quad).
  int other_wale(int g, int k) const {
    const int n = static_cast<int>(m_mesh.face(g).size());
    if (n < 4) return -1;  // a triangle cannot carry a row through: one side would have no course edge
    std::vector<int> candidates, wale;
    for (int j = 0; j < n; ++j) {
      if (j == k || j == wrap(k - 1, n) || j == wrap(k + 1, n)) continue;
      const EdgeLabel have = m_labels.edges[m_mesh.face_edge(g, j)];
      if (have == EdgeLabel::Wale) wale.push_back(j);
      if (have == EdgeLabel::None) candidates.push_back(j);
    }
    if (wale.size() == 1) return wale[0];
    if (!wale.empty() || candidates.empty()) return -1;
    const Eigen::Vector3d dk = edge_direction(m_mesh, g, k);
    int best = -1;
    double best_score = -1;
    for (int j : candidates) {
      // Parallel first; on a tie the edge closest to half-way round the loop.
      const double score = std::abs(dk.dot(edge_direction(m_mesh, g, j))) - 1e-6 * std::abs(wrap(j - k, n) - n / 2.0);
      if (score > best_score) best_score = score, best = j;
    }
    return best;
  }

  const InputMesh& m_mesh;
  Labeling& m_labels;
};

/// The maximal run of consecutive local edges of face f around local edge k that satisfy `in_chain`.
template <class Pred>
std::pair<int, int> chain_around(const InputMesh& mesh, int f, int k, Pred in_chain) {
  const int n = static_cast<int>(mesh.face(f).size());
  int first = k, last = k, len = 1;
  while (len < n && in_chain(wrap(first - 1, n))) first = wrap(first - 1, n), ++len;
  while (len < n && in_chain(wrap(last + 1, n))) last = wrap(last + 1, n), ++len;
  return {first, last};
}

bool is_top(const InputMesh& mesh, const FaceLabel& label, int f, int k) {
  const int n = static_cast<int>(mesh.face(f).size());
  const int after_right = wrap(k - label.right, n);  // top edges lie strictly between the right and the left wale
  return after_right > 0 && after_right < wrap(label.left - label.right, n);
}

/// Seeds the unlabeled face across course edge e of labeled face f; -1 when it cannot be labeled.
int seed_across(const InputMesh& mesh, Labeling& labels, RowGrower& grower, int f, int e) {
  const EdgeUse g = across(mesh, e, f);
  if (g.face < 0 || labels.faces[g.face].labeled()) return -1;
  const bool from_top = is_top(mesh, labels.faces[f], f, local_of(mesh, f, e));
  // The chain in g: consecutive course edges shared with labeled faces on the same side as e.
  const auto in_chain = [&](int j) {
    const int ej = mesh.face_edge(g.face, j);
    if (labels.edges[ej] != EdgeLabel::Course) return false;
    const EdgeUse h = across(mesh, ej, g.face);
    if (h.face < 0 || !labels.faces[h.face].labeled()) return false;
    return is_top(mesh, labels.faces[h.face], h.face, h.local) == from_top;
  };
  const auto [first, last] = chain_around(mesh, g.face, g.local, in_chain);
  return grower.seed(g.face, first, last, from_top);
}

}  // namespace

std::vector<int> bottom_edges(const InputMesh& mesh, const FaceLabel& label, int face) {
  const int n = static_cast<int>(mesh.face(face).size());
  std::vector<int> out;
  for (int k = wrap(label.left + 1, n); k != label.right; k = wrap(k + 1, n)) out.push_back(k);
  return out;
}

std::vector<int> top_edges(const InputMesh& mesh, const FaceLabel& label, int face) {
  const int n = static_cast<int>(mesh.face(face).size());
  std::vector<int> out;
  for (int k = wrap(label.right + 1, n); k != label.left; k = wrap(k + 1, n)) out.push_back(k);
  return out;
}

std::vector<int> border_run(const InputMesh& mesh, int border_edge) {
  if (border_edge < 0 || border_edge >= mesh.num_edges() || !mesh.is_border(border_edge))
    throw Error(mesh.source(), "edge " + std::to_string(border_edge), "is not a border edge");
  const PolyMesh& pm = mesh.poly();
  const auto [a, b] = mesh.edge_vertices(border_edge);
  auto h0 = pm.find_halfedge(pm.vertex_handle(a), pm.vertex_handle(b));
  if (!pm.is_boundary(h0)) h0 = pm.opposite_halfedge_handle(h0);
  const auto edge_id = [&](PolyMesh::HalfedgeHandle h) {
    return mesh.find_edge(pm.from_vertex_handle(h).idx(), pm.to_vertex_handle(h).idx());
  };
  const auto straight = [&](PolyMesh::VertexHandle v) { return pm.valence(v) == 3; };

  std::deque<int> run{border_edge};
  auto h = h0;
  while (straight(pm.to_vertex_handle(h))) {
    h = pm.next_halfedge_handle(h);
    if (h == h0) return {run.begin(), run.end()};  // a closed loop: the whole border
    run.push_back(edge_id(h));
  }
  h = h0;
  while (straight(pm.from_vertex_handle(h))) {
    h = pm.prev_halfedge_handle(h);
    run.push_front(edge_id(h));
  }
  return {run.begin(), run.end()};
}

std::vector<int> label_first_row(const InputMesh& mesh, Labeling& labels, int border_edge) {
  const std::vector<int> run = border_run(mesh, border_edge);
  const std::unordered_set<int> in_run(run.begin(), run.end());
  for (int e : run)
    if (labels.edges[e] == EdgeLabel::Wale)
      throw Error(mesh.source(), "edge " + std::to_string(e), "is already a wale edge; it cannot start a row");
  for (int e : run) labels.edges[e] = EdgeLabel::Course;
  RowGrower grower(mesh, labels);
  std::vector<int> rows;
  for (int e : run) {
    const EdgeUse use = mesh.edge_uses(e)[0];
    if (labels.faces[use.face].labeled()) continue;
    const auto in_chain = [&](int j) { return in_run.count(mesh.face_edge(use.face, j)) > 0; };
    const auto [first, last] = chain_around(mesh, use.face, use.local, in_chain);
    const int row = grower.seed(use.face, first, last, true);
    if (row >= 0) rows.push_back(row);
  }
  return rows;
}

int label_next_row(const InputMesh& mesh, Labeling& labels, int course_edge) {
  const auto fail = [&](const std::string& rule) { throw Error(mesh.source(), "edge " + std::to_string(course_edge), rule); };
  if (course_edge < 0 || course_edge >= mesh.num_edges()) fail("does not exist");
  if (labels.edges[course_edge] != EdgeLabel::Course) fail("is not a course edge");
  int labeled = -1, unlabeled = -1;
  for (const auto& use : mesh.edge_uses(course_edge)) (labels.faces[use.face].labeled() ? labeled : unlabeled) = use.face;
  if (labeled < 0 || unlabeled < 0) fail("must lie between a labeled and an unlabeled face");
  RowGrower grower(mesh, labels);
  const int row = seed_across(mesh, labels, grower, labeled, course_edge);
  if (row < 0) fail("face " + std::to_string(unlabeled) + " cannot continue the row: its edges contradict the labels around it");
  return row;
}

void flip_row(Labeling& labels, int row) {
  for (auto& f : labels.faces)
    if (f.row == row) std::swap(f.left, f.right);
}

int default_start_edge(const InputMesh& mesh) {
  int best = -1;
  double best_y = 0;
  for (int e = 0; e < mesh.num_edges(); ++e) {
    if (!mesh.is_border(e)) continue;
    const auto [a, b] = mesh.edge_vertices(e);
    const double y = 0.5 * (mesh.point(a).y() + mesh.point(b).y());
    if (best < 0 || y < best_y - 1e-9) best = e, best_y = y;
  }
  if (best < 0) throw Error(mesh.source(), "", "the mesh has no border edge to start labeling from (a closed surface needs a cut)");
  return best;
}

namespace {
/// Flips rows so that rows sharing course edges agree on the wale direction wherever they can. Rows are
/// oriented one at a time, heaviest connection to the oriented rows first (a maximum spanning tree), each
/// agreeing with the weighted majority of its oriented neighbours; the first row of each piece is fixed.
void orient_rows(const InputMesh& mesh, Labeling& labels, const std::vector<int>& fixed_rows) {
  // agreement[a][b]: course edges where rows a and b agree minus those where they disagree.
  std::vector<std::map<int, int>> agreement(labels.rows);
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const auto& uses = mesh.edge_uses(e);
    if (uses.size() != 2 || labels.edges[e] != EdgeLabel::Course) continue;
    const FaceLabel &fa = labels.faces[uses[0].face], &fb = labels.faces[uses[1].face];
    if (!fa.labeled() || !fb.labeled() || fa.row == fb.row) continue;
    const bool agree = is_top(mesh, fa, uses[0].face, uses[0].local) != is_top(mesh, fb, uses[1].face, uses[1].local);
    agreement[fa.row][fb.row] += agree ? 1 : -1;
    agreement[fb.row][fa.row] += agree ? 1 : -1;
  }
  std::vector<int> sign(labels.rows, 1);
  std::vector<char> done(labels.rows, 0);
  std::vector<double> pull(labels.rows, 0);  // connection weight to oriented rows
  const auto settle = [&](int r) {
    done[r] = 1;
    for (const auto& [b, w] : agreement[r])
      if (!done[b]) pull[b] += std::abs(w);
  };
  for (int r : fixed_rows) settle(r);
  for (;;) {
    int next = -1;
    for (int r = 0; r < labels.rows; ++r)
      if (!done[r] && pull[r] > 0 && (next < 0 || pull[r] > pull[next])) next = r;
    if (next < 0) break;
    long vote = 0;
    for (const auto& [b, w] : agreement[next])
      if (done[b]) vote += static_cast<long>(sign[b]) * w;
    if (vote < 0) {
      sign[next] = -1;
      flip_row(labels, next);
    }
    settle(next);
  }
}
}  // namespace

Labeling auto_label(const InputMesh& mesh, int border_edge) {
  Labeling labels(mesh);
  RowGrower grower(mesh, labels);
  std::vector<int> fixed_rows;
  std::vector<char> tried_start(mesh.num_edges(), 0);
  int start = border_edge;
  while (start >= 0) {
    tried_start[start] = 1;
    std::vector<int> first;
    try {
      first = label_first_row(mesh, labels, start);
    } catch (const Error&) {
      // Its border run meets a wale edge of a row labeled already: try the next start instead.
    }
    fixed_rows.insert(fixed_rows.end(), first.begin(), first.end());
    // Rows in labeling order; each row seeds the rows across its course edges, above and below.
    for (int r = first.empty() ? labels.rows : first.front(); r < labels.rows; ++r) {
      for (int f = 0; f < mesh.num_faces(); ++f) {
        if (labels.faces[f].row != r) continue;
        for (int e : mesh.face_edges(f))
          if (labels.edges[e] == EdgeLabel::Course) seed_across(mesh, labels, grower, f, e);
      }
    }
    // A piece not reached yet starts again from its lowest border edge.
    start = -1;
    double best_y = 0;
    for (int e = 0; e < mesh.num_edges(); ++e) {
      if (!mesh.is_border(e) || tried_start[e] || labels.faces[mesh.edge_uses(e)[0].face].labeled()) continue;
      if (labels.edges[e] == EdgeLabel::Wale) continue;
      const auto [a, b] = mesh.edge_vertices(e);
      const double y = 0.5 * (mesh.point(a).y() + mesh.point(b).y());
      if (start < 0 || y < best_y) start = e, best_y = y;
    }
  }
  orient_rows(mesh, labels, fixed_rows);
  return labels;
}

LabelReport validate_labels(const InputMesh& mesh, const Labeling& labels) {
  LabelReport report;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const FaceLabel& fl = labels.faces[f];
    const int n = static_cast<int>(mesh.face(f).size());
    int wale = 0;
    for (int e : mesh.face_edges(f)) wale += labels.edges[e] == EdgeLabel::Wale;
    if (!fl.labeled()) {
      report.face_problems.emplace_back(f, "is not labeled (no labeled row reaches it, or its edges contradict the labels around it)");
    } else if (wale != 2) {
      report.face_problems.emplace_back(f, "has " + std::to_string(wale) + " wale edges; a face needs exactly 2");
    } else if (fl.left < 0 || fl.left >= n || fl.right < 0 || fl.right >= n ||
               labels.edges[mesh.face_edge(f, fl.left)] != EdgeLabel::Wale || labels.edges[mesh.face_edge(f, fl.right)] != EdgeLabel::Wale) {
      report.face_problems.emplace_back(f, "its recorded wale edges are not its wale edges");
    } else if (bottom_edges(mesh, fl, f).empty() || top_edges(mesh, fl, f).empty()) {
      report.face_problems.emplace_back(f, std::string("has no ") + (bottom_edges(mesh, fl, f).empty() ? "bottom" : "top") +
                                               " course edge between its two wale edges");
    }
  }
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const auto& uses = mesh.edge_uses(e);
    if (uses.size() != 2 || labels.edges[e] == EdgeLabel::None) continue;
    const FaceLabel &fa = labels.faces[uses[0].face], &fb = labels.faces[uses[1].face];
    if (!fa.labeled() || !fb.labeled()) continue;
    const std::string faces = "faces " + std::to_string(uses[0].face) + " and " + std::to_string(uses[1].face);
    if (labels.edges[e] == EdgeLabel::Course) {
      const bool ta = is_top(mesh, fa, uses[0].face, uses[0].local), tb = is_top(mesh, fb, uses[1].face, uses[1].local);
      if (ta == tb) report.mismatches.emplace_back(e, faces + " both have it as a " + (ta ? "top" : "bottom") + " edge (opposite wale directions)");
    } else {
      const bool ra = uses[0].local == fa.right, rb = uses[1].local == fb.right;
      if (ra == rb) report.mismatches.emplace_back(e, faces + " both have it as their " + (ra ? "right" : "left") + " wale edge (opposite wale directions)");
    }
  }
  return report;
}

}  // namespace skein::mesh
