#include "stitchmesh/tessellation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include <Eigen/Geometry>

#include "common/error.hpp"
#include "stitchmesh/mean_value.hpp"
#include "stitchmesh/stitch_types.hpp"

namespace skein::mesh {
namespace {

int wrap(int k, int n) { return ((k % n) + n) % n; }

/// Stitches on each line j = 0..n of a face whose bottom carries B and top T stitches (Yuksel §5.2:
/// interpolated between the two sides).
std::vector<int> line_counts(int bottom, int top, int rows) {
  std::vector<int> m(rows + 1);
  for (int j = 0; j <= rows; ++j) m[j] = bottom + static_cast<int>(std::lround(static_cast<double>(top - bottom) * j / rows));
  return m;
}

/// Largest ratio between the stitch counts of consecutive lines.
double worst_step(const std::vector<int>& m) {
  double worst = 1;
  for (size_t j = 0; j + 1 < m.size(); ++j)
    worst = std::max(worst, static_cast<double>(std::max(m[j], m[j + 1])) / std::min(m[j], m[j + 1]));
  return worst;
}

int side_total(const InputMesh& mesh, const TessellationValues& values, int f, const std::vector<int>& locals) {
  int total = 0;
  for (int k : locals) total += values.edge[mesh.face_edge(f, k)];
  return total;
}

/// Union-find over stitch faces, to number stitch rows as the components joined by wale edges.
struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(int a, int b) { parent[find(a)] = find(b); }
};

/// Builds the stitch mesh one input face at a time, sharing the vertices on input vertices and edges.
class Tessellator {
public:
  Tessellator(const InputMesh& mesh, const Labeling& labels, const TessellationValues& values)
      : m_mesh(mesh), m_labels(labels), m_values(values), m_corner(mesh.num_vertices(), -1), m_edge_first(mesh.num_edges(), -1) {}

  StitchMesh run() {
    // Rows are numbered in input-row order, then bottom to top inside each row.
    std::vector<int> row_rows(m_labels.rows, 0);
    for (int f = 0; f < m_mesh.num_faces(); ++f)
      row_rows[m_labels.faces[f].row] = m_values.edge[m_mesh.face_edge(f, m_labels.faces[f].left)];
    m_row_base.assign(m_labels.rows + 1, 0);
    for (int r = 0; r < m_labels.rows; ++r) m_row_base[r + 1] = m_row_base[r] + row_rows[r];
    for (int f = 0; f < m_mesh.num_faces(); ++f) tessellate_face(f);
    number_rows();
    return std::move(m_out);
  }

private:
  int corner(int v) {
    if (m_corner[v] < 0) {
      m_corner[v] = static_cast<int>(m_out.vertices.size());
      m_out.vertices.push_back(m_mesh.point(v));
    }
    return m_corner[v];
  }

  /// Point i of n+1 along edge e from its lower-id end.
  int edge_point(int e, int i) {
    const auto [a, b] = m_mesh.edge_vertices(e);
    const int n = m_values.edge[e];
    if (i == 0) return corner(a);
    if (i == n) return corner(b);
    if (m_edge_first[e] < 0) {
      m_edge_first[e] = static_cast<int>(m_out.vertices.size());
      for (int k = 1; k < n; ++k) {
        const double t = static_cast<double>(k) / n;
        m_out.vertices.push_back((1 - t) * m_mesh.point(a) + t * m_mesh.point(b));
      }
    }
    return m_edge_first[e] + i - 1;
  }

  /// The points along local edge k of face f, in the face's direction (both ends included).
  std::vector<int> points_along(int f, int k) {
    const int e = m_mesh.face_edge(f, k);
    const int n = m_values.edge[e];
    const bool forward = m_mesh.face(f)[k] == m_mesh.edge_vertices(e).first;
    std::vector<int> out(n + 1);
    for (int i = 0; i <= n; ++i) out[i] = edge_point(e, forward ? i : n - i);
    return out;
  }

  /// Points along a chain of local edges, in loop order, shared corners once.
  std::vector<int> points_along_chain(int f, const std::vector<int>& chain) {
    std::vector<int> out;
    for (int k : chain) {
      auto pts = points_along(f, k);
      out.insert(out.end(), pts.begin() + (out.empty() ? 0 : 1), pts.end());
    }
    return out;
  }

  void tessellate_face(int f) {
    const FaceLabel& fl = m_labels.faces[f];
    const auto& loop = m_mesh.face(f);
    const int n = static_cast<int>(loop.size());
    const std::vector<int> bottom_chain = bottom_edges(m_mesh, fl, f), top_chain = top_edges(m_mesh, fl, f);
    const int rows = m_values.edge[m_mesh.face_edge(f, fl.left)];
    const int B = side_total(m_mesh, m_values, f, bottom_chain), T = side_total(m_mesh, m_values, f, top_chain);
    const std::vector<int> m = line_counts(B, T, rows);
    if (worst_step(m) > 3.0)
      throw Error(m_mesh.source(), "face " + std::to_string(f),
                  "its bottom carries " + std::to_string(B) + " stitches and its top " + std::to_string(T) + " over " + std::to_string(rows) +
                      " stitch rows; a stitch row can change its count at most 3x (raise row " + std::to_string(fl.row) + "'s wale value)");

    // The canonical polygon (Yuksel §5.2 with Floater's mean value coordinates): bottom corners on y = 0,
    // top corners on y = 1, spaced by their stitch counts; the wale edges are x = 0 and x = 1.
    std::vector<Eigen::Vector2d> canonical(n);
    std::vector<Eigen::Vector3d> corners(n);
    {
      int along = 0;
      canonical[wrap(fl.left + 1, n)] = {0, 0};
      for (int k : bottom_chain) {
        along += m_values.edge[m_mesh.face_edge(f, k)];
        canonical[wrap(k + 1, n)] = {static_cast<double>(along) / B, 0};
      }
      along = 0;
      canonical[wrap(fl.right + 1, n)] = {1, 1};
      for (int k : top_chain) {
        along += m_values.edge[m_mesh.face_edge(f, k)];
        canonical[wrap(k + 1, n)] = {1 - static_cast<double>(along) / T, 1};
      }
      for (int i = 0; i < n; ++i) corners[i] = m_mesh.point(loop[i]);
    }
    const auto map_to_face = [&](const Eigen::Vector2d& p) {
      const Eigen::VectorXd w = mean_value_coordinates(canonical, p);
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (int i = 0; i < n; ++i) x += w[i] * corners[i];
      return x;
    };

    std::vector<int> left = points_along(f, fl.left), right = points_along(f, fl.right);
    std::reverse(left.begin(), left.end());  // the left wale runs top to bottom in the loop
    std::vector<std::vector<int>> lines(rows + 1);
    lines[0] = points_along_chain(f, bottom_chain);
    lines[rows] = points_along_chain(f, top_chain);
    std::reverse(lines[rows].begin(), lines[rows].end());  // left to right
    for (int j = 1; j < rows; ++j) {
      auto& line = lines[j];
      line.push_back(left[j]);
      for (int i = 1; i < m[j]; ++i) {
        line.push_back(static_cast<int>(m_out.vertices.size()));
        m_out.vertices.push_back(map_to_face({static_cast<double>(i) / m[j], static_cast<double>(j) / rows}));
      }
      line.push_back(right[j]);
    }

    const int marked = m_values.marked[m_mesh.face_edge(f, fl.left)] ? -1 : m_values.marked[m_mesh.face_edge(f, fl.right)] ? 1 : 0;
    for (int j = 0; j < rows; ++j) stitch_row(f, fl.row, j, lines[j], lines[j + 1], marked);
  }

  /// Faces between two lines; the extra edges of the longer line go to faces next to the wale edges.
  void stitch_row(int f, int input_row, int j, const std::vector<int>& below, const std::vector<int>& above, int marked) {
    const int mb = static_cast<int>(below.size()) - 1, mt = static_cast<int>(above.size()) - 1;
    const int slots = std::min(mb, mt), extra = std::abs(mt - mb);
    std::vector<int> share(slots, 1);
    std::vector<int> order;  // which slots take the extras first
    for (int i = 0; i < slots; ++i) {
      if (marked < 0) order.push_back(i);
      else if (marked > 0) order.push_back(slots - 1 - i);
      else order.push_back(i % 2 == 0 ? i / 2 : slots - 1 - i / 2);
    }
    for (int x = 0; x < extra; ++x) ++share[order[x % slots]];

    int b = 0, t = 0;
    for (int s = 0; s < slots; ++s) {
      const int nb = mt >= mb ? 1 : share[s], nt = mt >= mb ? share[s] : 1;
      StitchFace face;
      face.bottom = nb;
      for (int i = 0; i <= nb; ++i) face.vertices.push_back(below[b + i]);
      for (int i = nt; i >= 0; --i) face.vertices.push_back(above[t + i]);
      face.type = default_stitch_type(nb, nt);
      face.row = m_row_base[input_row] + j;
      face.input_face = f;
      m_out.faces.push_back(std::move(face));
      b += nb;
      t += nt;
    }
  }

  /// Stitch rows are the faces joined by wale edges; each takes the smallest provisional number in it.
  void number_rows() {
    const int nf = static_cast<int>(m_out.faces.size());
    DisjointSets sets(nf);
    for (const auto& [key, uses] : edge_table(m_out))
      if (uses.count == 2 && m_out.faces[uses.use[0].face].is_wale(uses.use[0].local)) sets.join(uses.use[0].face, uses.use[1].face);
    std::vector<int> smallest(nf, INT32_MAX);
    for (int f = 0; f < nf; ++f) smallest[sets.find(f)] = std::min(smallest[sets.find(f)], m_out.faces[f].row);
    std::vector<int> keys;
    for (int f = 0; f < nf; ++f)
      if (sets.find(f) == f) keys.push_back(smallest[f]);
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    for (int f = 0; f < nf; ++f)
      m_out.faces[f].row = static_cast<int>(std::lower_bound(keys.begin(), keys.end(), smallest[sets.find(f)]) - keys.begin());
  }

  const InputMesh& m_mesh;
  const Labeling& m_labels;
  const TessellationValues& m_values;
  std::vector<int> m_corner, m_edge_first, m_row_base;
  StitchMesh m_out;
};

}  // namespace

void StitchSize::validate() const {
  if (!(std::isfinite(width) && width > 0)) throw Error("", "stitch size", "width must be a positive number of mm, got " + std::to_string(width));
  if (!(std::isfinite(height) && height > 0)) throw Error("", "stitch size", "height must be a positive number of mm, got " + std::to_string(height));
}

double estimated_stitches(const InputMesh& mesh, const StitchSize& size) {
  size.validate();
  double area = 0;
  for (const auto& face : mesh.faces()) {
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // Newell: twice the polygon's vector area
    for (size_t i = 0; i < face.size(); ++i) normal += mesh.point(face[i]).cross(mesh.point(face[(i + 1) % face.size()]));
    area += 0.5 * normal.norm();
  }
  return area / (size.width * size.height);
}

void check_stitch_count(const InputMesh& mesh, const StitchSize& size, double max_stitches) {
  const double n = estimated_stitches(mesh, size);
  if (!(n <= max_stitches)) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "would make about %.3g stitches of %g x %g mm (its surface is %.3g m²), more than the limit of %.3g (--max-stitches): "
                  "check the mesh's units, or use larger stitches",
                  n, size.width, size.height, n * size.width * size.height * 1e-6, max_stitches);
    throw Error(mesh.source(), "", text);
  }
}

TessellationValues initial_values(const InputMesh& mesh, const Labeling& labels, const StitchSize& size) {
  size.validate();
  TessellationValues values;
  values.edge.assign(mesh.num_edges(), 1);
  values.marked.assign(mesh.num_edges(), 0);
  std::vector<double> wale_length(labels.rows, 0);
  std::vector<int> wale_count(labels.rows, 0);
  for (int e = 0; e < mesh.num_edges(); ++e) {
    if (labels.edges[e] == EdgeLabel::Wale) {
      const int row = labels.faces[mesh.edge_uses(e)[0].face].row;
      if (row < 0) continue;
      wale_length[row] += mesh.edge_length(e);
      ++wale_count[row];
    } else {
      values.edge[e] = std::max(1, static_cast<int>(std::lround(mesh.edge_length(e) / size.width)));
    }
  }
  std::vector<int> row_value(labels.rows, 1);
  for (int r = 0; r < labels.rows; ++r)
    if (wale_count[r] > 0) row_value[r] = std::max(1, static_cast<int>(std::lround(wale_length[r] / wale_count[r] / size.height)));
  // Enough stitch rows that each stitch row at most doubles or halves the stitch count.
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const FaceLabel& fl = labels.faces[f];
    if (!fl.labeled()) continue;
    const int B = side_total(mesh, values, f, bottom_edges(mesh, fl, f)), T = side_total(mesh, values, f, top_edges(mesh, fl, f));
    if (B == 0 || T == 0) continue;
    while (worst_step(line_counts(B, T, row_value[fl.row])) > 2.0) ++row_value[fl.row];
  }
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (labels.edges[e] == EdgeLabel::Wale) {
      const int row = labels.faces[mesh.edge_uses(e)[0].face].row;
      if (row >= 0) values.edge[e] = row_value[row];
    }
  return values;
}

void set_course_value(const InputMesh& mesh, const Labeling& labels, TessellationValues& values, int edge, int n) {
  const std::string place = "edge " + std::to_string(edge);
  if (edge < 0 || edge >= mesh.num_edges()) throw Error(mesh.source(), place, "does not exist");
  if (labels.edges[edge] != EdgeLabel::Course) throw Error(mesh.source(), place, "is not a course edge (wale edges take their row's value)");
  if (n < 1) throw Error(mesh.source(), place, "a tessellation value must be at least 1, got " + std::to_string(n));
  values.edge[edge] = n;
}

void set_row_value(const InputMesh& mesh, const Labeling& labels, TessellationValues& values, int row, int n) {
  const std::string place = "row " + std::to_string(row);
  if (row < 0 || row >= labels.rows) throw Error(mesh.source(), place, "does not exist");
  if (n < 1) throw Error(mesh.source(), place, "a tessellation value must be at least 1, got " + std::to_string(n));
  for (int e = 0; e < mesh.num_edges(); ++e)
    if (labels.edges[e] == EdgeLabel::Wale && labels.faces[mesh.edge_uses(e)[0].face].row == row) values.edge[e] = n;
}

void mark_wale_edge(const InputMesh& mesh, const Labeling& labels, TessellationValues& values, int edge, bool marked) {
  if (edge < 0 || edge >= mesh.num_edges() || labels.edges[edge] != EdgeLabel::Wale)
    throw Error(mesh.source(), "edge " + std::to_string(edge), "only a wale edge can be marked for increases and decreases");
  values.marked[edge] = marked;
}

StitchMesh tessellate(const InputMesh& mesh, const Labeling& labels, const TessellationValues& values) {
  const LabelReport report = validate_labels(mesh, labels);
  if (!report.valid()) {
    std::string rule = "the labeling is not complete: " + std::to_string(report.face_problems.size()) + " faces break the rules (first: face " +
                       std::to_string(report.face_problems[0].first) + " " + report.face_problems[0].second + ")";
    throw Error(mesh.source(), "face " + std::to_string(report.face_problems[0].first), rule);
  }
  if (static_cast<int>(values.edge.size()) != mesh.num_edges() || static_cast<int>(values.marked.size()) != mesh.num_edges())
    throw Error(mesh.source(), "", "tessellation values do not match the mesh's edges");
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const FaceLabel& fl = labels.faces[f];
    if (values.edge[mesh.face_edge(f, fl.left)] != values.edge[mesh.face_edge(f, fl.right)])
      throw Error(mesh.source(), "face " + std::to_string(f), "its two wale edges have different tessellation values");
  }
  return Tessellator(mesh, labels, values).run();
}

}  // namespace skein::mesh
