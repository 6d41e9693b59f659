#include "stitchmesh/knit_field.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include <CGAL/Heat_method_3/Surface_mesh_geodesic_distances_3.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include "common/error.hpp"

namespace skein::mesh {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Surface = CGAL::Surface_mesh<Kernel::Point_3>;
using SurfaceVertex = Surface::Vertex_index;

std::string mm(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g mm", x);
  return text;
}

std::string where(const Eigen::Vector3d& p) {
  char text[96];
  std::snprintf(text, sizeof text, "near (%.4g, %.4g, %.4g)", p.x(), p.y(), p.z());
  return text;
}

/// The connected piece of each vertex; `count` gets how many there are.
std::vector<int> pieces(const InputMesh& surface, int& count) {
  std::vector<int> parent(static_cast<std::size_t>(surface.num_vertices()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int v) {
    while (parent[static_cast<std::size_t>(v)] != v) v = parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
    return v;
  };
  for (const auto& f : surface.faces())
    for (int v : f) parent[static_cast<std::size_t>(find(v))] = find(f[0]);
  std::vector<int> id(static_cast<std::size_t>(surface.num_vertices()));
  std::map<int, int> root_id;
  for (int v = 0; v < surface.num_vertices(); ++v)
    id[static_cast<std::size_t>(v)] = root_id.try_emplace(find(v), static_cast<int>(root_id.size())).first->second;
  count = static_cast<int>(root_id.size());
  return id;
}

/// The surface the field lives on: the input's polygons fanned into triangles (the heat method needs them)
/// and their long edges split until none is longer than half a stitch, so that the field and its isolines are
/// as fine as the rows, however coarse the artist's mesh.
struct FieldSurface {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> tris;
  std::vector<double> t;      ///< the knitting distance at each point
  std::vector<double> slope;  ///< the length of its gradient on each triangle (1 for an exact distance)
};

/// The longest edge the field's triangles keep: half the smaller stitch side, or coarser where that would
/// pass kFieldMaxTriangles on this surface's area.
constexpr double kFieldMaxTriangles = 4e6;

/// Builds the field surface and the geodesic distance from `sources` (CGAL's heat method, directly on the
/// isotropically remeshed triangles, whose good shapes the cotangent weights want). `sources` picks the
/// refined surface's source vertices from their positions and whether they lie on the border; `end_sources`,
/// when given, picks where knitting ends, and the field becomes the start's share of the two distances.
using SourcePicker = std::function<std::vector<int>(const std::vector<Eigen::Vector3d>&, const std::vector<char>&)>;
FieldSurface knitting_distance(const InputMesh& surface, double max_edge, const SourcePicker& sources, const SourcePicker* end_sources) {
  Surface tm;
  std::vector<SurfaceVertex> vertex;
  vertex.reserve(surface.num_vertices());
  for (const auto& p : surface.points()) vertex.push_back(tm.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
  double area = 0;
  for (int f = 0; f < surface.num_faces(); ++f) {
    const auto& loop = surface.face(f);
    for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
      const auto& a = surface.point(loop[0]);
      area += 0.5 * (surface.point(loop[k]) - a).cross(surface.point(loop[k + 1]) - a).norm();
      if (tm.add_face(vertex[loop[0]], vertex[loop[k]], vertex[loop[k + 1]]) == Surface::null_face())
        throw Error(surface.source(), "face " + std::to_string(f), "cannot be triangulated for the knitting field");
    }
  }
  max_edge = std::max(max_edge, std::sqrt(4 * area / (std::sqrt(3.0) * kFieldMaxTriangles)));
  // Isotropic remeshing, not only split edges: the heat method's cotangent weights want well-shaped triangles
  // (split edges alone leave the fans' slivers, and a 100 mm square's far border came out 3 to 6 % short).
  CGAL::Polygon_mesh_processing::isotropic_remeshing(faces(tm), max_edge, tm, CGAL::parameters::number_of_iterations(3));
  tm.collect_garbage();
  FieldSurface field;
  std::vector<char> on_border;
  for (auto v : tm.vertices()) {
    const auto& p = tm.point(v);
    field.points.emplace_back(p.x(), p.y(), p.z());
    on_border.push_back(tm.is_border(v) ? 1 : 0);
  }
  for (auto f : tm.faces()) {
    std::array<int, 3> tri{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(tm.halfedge(f), tm)) tri[static_cast<std::size_t>(k++)] = static_cast<int>(v);
    field.tris.push_back(tri);
  }
  const std::vector<int> from = sources(field.points, on_border);
  if (from.empty()) throw Error(surface.source(), "", "the knitting start lies on no point of the remeshed surface");
  auto distance = tm.add_property_map<SurfaceVertex, double>("v:knit_distance", 0).first;
  CGAL::Heat_method_3::Surface_mesh_geodesic_distances_3<Surface, CGAL::Heat_method_3::Direct> heat(tm);
  for (int v : from) heat.add_source(SurfaceVertex(static_cast<Surface::size_type>(v)));
  heat.estimate_geodesic_distances(distance);
  for (auto v : tm.vertices()) field.t.push_back(distance[v]);
  for (int v : from) field.t[static_cast<std::size_t>(v)] = 0;  // the heat method's estimate leaves them near, not at, zero
  if (end_sources) {
    // Where knitting ends (AutoKnit's and Stitch Meshing's second constraint): with d_s and d_e the distances
    // from the start and from the end, the field d_s / (d_s + d_e) is 0 on the start and 1 on the end, so the
    // rows turn from the start's shape to the end's and the last row lies along it. Scaled by the mean of
    // d_s + d_e (the start-to-end length), so that it is a distance again before the gradient scaling below.
    const std::vector<int> to = (*end_sources)(field.points, on_border);
    if (to.empty()) throw Error(surface.source(), "", "the knitting end lies on no point of the remeshed surface");
    for (int v : to)
      if (std::find(from.begin(), from.end(), v) != from.end())
        throw Error(surface.source(), "", "the knitting end touches the start: give an end away from it");
    heat.clear_sources();
    for (int v : to) heat.add_source(SurfaceVertex(static_cast<Surface::size_type>(v)));
    heat.estimate_geodesic_distances(distance);
    std::vector<double> to_end;
    for (auto v : tm.vertices()) to_end.push_back(distance[v]);
    for (int v : to) to_end[static_cast<std::size_t>(v)] = 0;
    double span = 0;
    for (std::size_t v = 0; v < to_end.size(); ++v) span += field.t[v] + to_end[v];
    span /= static_cast<double>(to_end.size());
    for (std::size_t v = 0; v < to_end.size(); ++v) {
      const double sum = field.t[v] + to_end[v];
      field.t[v] = sum > 0 ? span * field.t[v] / sum : 0;
    }
  }
  // A distance has a gradient of length 1 (the eikonal equation). The heat method's smoothing shortens it,
  // most near the start (a 100 mm square's far border came out at 97.3 mm): the field is divided by its
  // area-weighted mean gradient length, and each triangle's own length is kept for spacing the rows.
  const auto gradient_length = [&](const std::array<int, 3>& tri, double& twice_area) {
    const Eigen::Vector3d& pa = field.points[static_cast<std::size_t>(tri[0])];
    const Eigen::Vector3d e1 = field.points[static_cast<std::size_t>(tri[1])] - pa, e2 = field.points[static_cast<std::size_t>(tri[2])] - pa;
    const Eigen::Vector3d n = e1.cross(e2);
    twice_area = n.norm();
    if (!(twice_area > 0)) return 1.0;
    // The gradient of the linear interpolant: ((t_b - t_a) n x e2 + (t_c - t_a) e1 x n) / |n|^2.
    const double ta = field.t[static_cast<std::size_t>(tri[0])];
    const Eigen::Vector3d grad = ((field.t[static_cast<std::size_t>(tri[1])] - ta) * n.cross(e2) + (field.t[static_cast<std::size_t>(tri[2])] - ta) * e1.cross(n)) /
                                 (twice_area * twice_area);
    return grad.norm();
  };
  double weighted = 0, total_area = 0;
  for (const auto& tri : field.tris) {
    double twice_area = 0;
    weighted += gradient_length(tri, twice_area) * twice_area;
    total_area += twice_area;
  }
  if (weighted > 0)
    for (double& x : field.t) x *= total_area / weighted;
  for (const auto& tri : field.tris) {
    double twice_area = 0;
    field.slope.push_back(gradient_length(tri, twice_area));
  }
  return field;
}

/// One isoline of the field, or one row once sampled: points along the row from left to right (the field
/// rising to their left, seen from outside), closed when it goes round.
struct Polyline {
  std::vector<Eigen::Vector3d> points;
  bool closed = false;
  double length() const {
    double l = 0;
    for (std::size_t i = 0; i + 1 < points.size(); ++i) l += (points[i + 1] - points[i]).norm();
    if (closed && points.size() > 1) l += (points.front() - points.back()).norm();
    return l;
  }
};

/// The isolines of `t` at `level` by marching triangles. A triangle's crossing runs from the edge where its
/// loop (counter-clockwise) goes from above the level to below, to the edge where it goes back above: so the
/// higher field lies to the left of each piece and the pieces of neighbouring triangles chain head to tail.
struct Isolines {
  std::vector<Polyline> lines;
  double slope = 1;  ///< the field's gradient length along them, weighted by length
};
Isolines isolines(const FieldSurface& field, double level) {
  const auto& t = field.t;
  std::map<std::pair<int, int>, int> crossing_of;  // undirected edge -> crossing id
  std::vector<Eigen::Vector3d> crossing;
  const auto crossing_id = [&](int u, int v) {
    const auto key = std::minmax(u, v);
    auto [it, added] = crossing_of.try_emplace({key.first, key.second}, static_cast<int>(crossing.size()));
    if (added) {
      const double s = (level - t[u]) / (t[v] - t[u]);
      crossing.push_back(field.points[u] + s * (field.points[v] - field.points[u]));
    }
    return it->second;
  };
  std::vector<std::pair<int, int>> pieces;  // from, to
  double slope_sum = 0, length_sum = 0;
  for (std::size_t f = 0; f < field.tris.size(); ++f) {
    const auto& tri = field.tris[f];
    int down = -1, up = -1;
    for (int k = 0; k < 3; ++k) {
      const int u = tri[k], v = tri[(k + 1) % 3];
      const bool above_u = t[u] >= level, above_v = t[v] >= level;
      if (above_u && !above_v) down = crossing_id(u, v);
      if (!above_u && above_v) up = crossing_id(u, v);
    }
    if (down >= 0 && up >= 0) {
      pieces.push_back({down, up});
      const double l = (crossing[static_cast<std::size_t>(up)] - crossing[static_cast<std::size_t>(down)]).norm();
      slope_sum += field.slope[f] * l;
      length_sum += l;
    }
  }
  std::vector<int> next(crossing.size(), -1), prev(crossing.size(), -1);
  for (auto [a, b] : pieces) {
    next[a] = b;
    prev[b] = a;
  }
  Isolines found;
  if (length_sum > 0) found.slope = slope_sum / length_sum;
  auto& lines = found.lines;
  std::vector<char> used(crossing.size(), 0);
  const auto follow = [&](int c, bool closed) {
    Polyline line{{}, closed};
    while (c >= 0 && !used[c]) {
      used[c] = 1;
      line.points.push_back(crossing[c]);
      c = next[c];
    }
    lines.push_back(std::move(line));
  };
  for (std::size_t c = 0; c < crossing.size(); ++c)
    if (prev[c] < 0 && next[c] >= 0) follow(static_cast<int>(c), false);  // from a border edge
  for (std::size_t c = 0; c < crossing.size(); ++c)
    if (!used[c] && next[c] >= 0) follow(static_cast<int>(c), true);
  return found;
}

/// `edges` stitches along the line: edges + 1 points evenly by arclength (edges points when closed).
Polyline resample(const Polyline& line, int edges) {
  std::vector<Eigen::Vector3d> pts = line.points;
  if (line.closed) pts.push_back(pts.front());
  std::vector<double> at(pts.size(), 0);
  for (std::size_t i = 1; i < pts.size(); ++i) at[i] = at[i - 1] + (pts[i] - pts[i - 1]).norm();
  const double total = at.back();
  Polyline out{{}, line.closed};
  const int count = line.closed ? edges : edges + 1;
  std::size_t seg = 0;
  for (int i = 0; i < count; ++i) {
    const double s = total * i / edges;
    while (seg + 2 < pts.size() && at[seg + 1] < s) ++seg;
    const double span = at[seg + 1] - at[seg];
    const double f = span > 0 ? std::clamp((s - at[seg]) / span, 0.0, 1.0) : 0.0;
    out.points.push_back(pts[seg] + f * (pts[seg + 1] - pts[seg]));
  }
  return out;
}

/// The ring begun at its point nearest to p, so that its stitches start across from the ring below's first.
Polyline begun_near(const Polyline& ring, const Eigen::Vector3d& p) {
  const std::size_t n = ring.points.size();
  std::size_t best_segment = 0;
  Eigen::Vector3d best_point = ring.points[0];
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& a = ring.points[i];
    const Eigen::Vector3d d = ring.points[(i + 1) % n] - a;
    const double s = d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    const Eigen::Vector3d q = a + s * d;
    if ((q - p).squaredNorm() < best) best = (q - p).squaredNorm(), best_point = q, best_segment = i;
  }
  Polyline out{{best_point}, true};
  for (std::size_t k = 1; k <= n; ++k) out.points.push_back(ring.points[(best_segment + k) % n]);
  return out;
}

/// The share of b's points that lie within `reach` of a point of a.
double near_share(const Polyline& a, const Polyline& b, double reach) {
  int near = 0;
  for (const auto& p : b.points)
    for (const auto& q : a.points)
      if ((p - q).squaredNorm() <= reach * reach) {
        ++near;
        break;
      }
  return static_cast<double>(near) / static_cast<double>(b.points.size());
}

/// A sampled row placed in the traced mesh: its vertex ids, left to right.
struct PlacedRow {
  Polyline line;
  std::vector<int> ids;
  int edges() const { return line.closed ? static_cast<int>(ids.size()) : static_cast<int>(ids.size()) - 1; }
};

/// The first of face f's share of `big` edges among m faces: floor(f big / m + phase), the last face's end at big.
int share_start(int f, int m, int big, double phase) {
  return f >= m ? big : static_cast<int>(std::floor(static_cast<double>(f) * big / m + phase));
}

/// Turning angle of the border at v between the directions in and out [degrees].
double turn_degrees(const Eigen::Vector3d& in, const Eigen::Vector3d& out) {
  const double c = in.normalized().dot(out.normalized());
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace

std::vector<int> field_start_run(const InputMesh& surface, int border_edge) {
  if (border_edge < 0 || border_edge >= surface.num_edges() || !surface.is_border(border_edge))
    throw Error(surface.source(), "edge " + std::to_string(border_edge), "is not a border edge; knitting starts on a border or at a point (--start-point)");
  // The border edges in the direction their face runs them (the surface to their left).
  const auto directed = [&](int e) {
    const EdgeUse use = surface.edge_uses(e)[0];
    const auto& f = surface.face(use.face);
    return std::pair{f[use.local], f[(use.local + 1) % f.size()]};
  };
  std::map<int, int> leaving;  // border vertex -> the border edge leaving it
  for (int e = 0; e < surface.num_edges(); ++e)
    if (surface.is_border(e)) leaving[directed(e).first] = e;
  const auto direction = [&](int e) {
    const auto [a, b] = directed(e);
    return Eigen::Vector3d(surface.point(b) - surface.point(a));
  };
  std::vector<int> run{border_edge};
  // Forward while the border runs straight on.
  for (int e = border_edge;;) {
    const int n = leaving.at(directed(e).second);
    if (n == border_edge) return run;  // round the whole loop without a corner
    if (turn_degrees(direction(e), direction(n)) > kFieldCornerDegrees) break;
    run.push_back(n);
    e = n;
  }
  std::map<int, int> arriving;
  for (auto [v, e] : leaving) arriving[directed(e).second] = e;
  for (int e = border_edge;;) {
    const int p = arriving.at(directed(e).first);
    if (turn_degrees(direction(p), direction(e)) > kFieldCornerDegrees) break;
    run.insert(run.begin(), p);
    e = p;
  }
  return run;
}

/// The input's vertices a start or end names (the run of border edges, or the vertex nearest the point), and a
/// picker of the refined field surface's vertices that lie on them. `what` is "start" or "end", for errors.
struct FieldEnds {
  std::vector<int> vertices;
  SourcePicker picker;
};
FieldEnds field_ends(const InputMesh& surface, const KnitStart& at, const std::string& what) {
  const std::string& name = surface.source();
  FieldEnds ends;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> run_segments;
  if (at.point) {
    int best = 0;
    for (int v = 1; v < surface.num_vertices(); ++v)
      if ((surface.point(v) - *at.point).squaredNorm() < (surface.point(best) - *at.point).squaredNorm()) best = v;
    ends.vertices.push_back(best);
  } else {
    int border_edge = at.border_edge;
    if (border_edge < 0) {  // the lowest border edge; a closed surface has none
      bool has_border = false;
      for (int e = 0; e < surface.num_edges() && !has_border; ++e) has_border = surface.is_border(e);
      if (!has_border) throw Error(name, "", "a closed surface has no border to " + what + " from: give --" + what + "-point X,Y,Z");
      border_edge = default_start_edge(surface);
    }
    if (what == "end" && (border_edge >= surface.num_edges() || !surface.is_border(border_edge)))
      throw Error(name, "edge " + std::to_string(border_edge), "is not a border edge; knitting ends on a border or at a point (--end-point)");
    for (int e : field_start_run(surface, border_edge)) {
      const auto [a, b] = surface.edge_vertices(e);
      ends.vertices.push_back(a);
      run_segments.push_back({surface.point(a), surface.point(b)});
    }
  }
  const double tolerance = 1e-9 * surface.bounding_diagonal();
  const std::optional<Eigen::Vector3d> point = at.point;
  ends.picker = [point, run_segments, tolerance](const std::vector<Eigen::Vector3d>& points, const std::vector<char>& on_border) {
    std::vector<int> from;
    if (point) {  // the remeshing moves inner points: the nearest of the refined surface's
      int best = 0;
      for (int v = 1; v < static_cast<int>(points.size()); ++v)
        if ((points[static_cast<std::size_t>(v)] - *point).squaredNorm() < (points[static_cast<std::size_t>(best)] - *point).squaredNorm()) best = v;
      return std::vector<int>{best};
    }
    for (int v = 0; v < static_cast<int>(points.size()); ++v) {
      const Eigen::Vector3d& p = points[static_cast<std::size_t>(v)];
      if (!on_border[static_cast<std::size_t>(v)]) continue;
      for (const auto& [a, b] : run_segments) {  // on a run edge (split or not)
        const Eigen::Vector3d d = b - a;
        const double s = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
        if ((a + s * d - p).norm() <= tolerance) {
          from.push_back(v);
          break;
        }
      }
    }
    return from;
  };
  return ends;
}

TracedRows trace_stitch_mesh(const InputMesh& surface, const KnitStart& start, const StitchSize& size, const std::optional<KnitStart>& end) {
  size.validate();
  const std::string& name = surface.source();
  const FieldEnds from = field_ends(surface, start, "start");
  std::optional<FieldEnds> to;
  if (end) to = field_ends(surface, *end, "end");
  int piece_count = 0;
  const std::vector<int> piece = pieces(surface, piece_count);
  if (piece_count > 1) {
    std::vector<char> reached(piece_count, 0);
    for (int v : from.vertices) reached[piece[v]] = 1;
    for (int v = 0; v < surface.num_vertices(); ++v)
      if (!reached[piece[v]])
        throw Error(name, "vertex " + std::to_string(v) + " " + where(surface.point(v)),
                    "lies on a piece of the surface the knitting start does not reach (" + std::to_string(piece_count) +
                        " pieces); trace each piece from its own start");
  }
  FieldSurface field = knitting_distance(surface, 0.5 * std::min(size.width, size.height), from.picker, to ? &to->picker : nullptr);
  for (std::size_t v = 0; v < field.t.size(); ++v)
    if (!std::isfinite(field.t[v])) throw Error(name, where(field.points[v]), "the heat method gave no knitting distance here");
  const double lowest = *std::min_element(field.t.begin(), field.t.end());
  for (double& x : field.t) x -= lowest;
  const double field_max = *std::max_element(field.t.begin(), field.t.end());

  // Levels one stitch height apart: from just off the start border, or from a ring one stitch width round the
  // start point (six stitches, as a crown is cast on), to short of the farthest point.
  const double first = start.point ? size.width : 0.05 * size.height;
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> faces;
  struct FaceRows { int bottom, top; };
  std::vector<FaceRows> face_rows;  // bottom and top course edge counts of each face
  std::vector<int> face_row;
  std::vector<PlacedRow> below;
  int rows = 0, levels = 0, starts = 0, ends = 0;
  const double golden = 0.6180339887498949;
  const double reach = 1.6 * size.height;  // a row and a half, and the distance between a row's samples
  double level = first;
  const auto refuse_at = [&](const Eigen::Vector3d& p, const std::string& rule) {
    throw Error(name, "knitting distance " + mm(level) + " " + where(p), rule);
  };
  // A stretch of a row: `edges` edges from index `from` on (round a ring as far as it goes).
  const auto path = [](const PlacedRow& row, int from, int edges) {
    std::vector<int> ids;
    const int n = static_cast<int>(row.ids.size());
    for (int i = 0; i <= edges; ++i) ids.push_back(row.ids[static_cast<std::size_t>(row.line.closed ? (from + i) % n : from + i)]);
    return ids;
  };
  // Joins a stretch of the row below (a) to one of the row above (b), both left to right: min(na, nb) faces,
  // the longer one's edges shared out evenly from `phase` on, so that increases and decreases spread along
  // the row (the phase moves on by the golden ratio each row, so that they do not stack in a column).
  const auto add_strip = [&](const std::vector<int>& a, const std::vector<int>& b, double phase) {
    const int na = static_cast<int>(a.size()) - 1, nb = static_cast<int>(b.size()) - 1;
    if (na < 1 || nb < 1) return;
    const int m = std::min(na, nb), big = std::max(na, nb);
    if (big > 3 * m) refuse_at(points[static_cast<std::size_t>(a.front())], "the rows change length more than threefold here (no stitch has more than three top or bottom edges)");
    for (int f = 0; f < m; ++f) {
      const int s0 = share_start(f, m, big, phase), s1 = share_start(f + 1, m, big, phase);
      const int a0 = na >= nb ? s0 : f, a1 = na >= nb ? s1 : f + 1;
      const int b0 = nb > na ? s0 : f, b1 = nb > na ? s1 : f + 1;
      std::vector<int> loop;
      for (int i = a0; i <= a1; ++i) loop.push_back(a[static_cast<std::size_t>(i)]);
      for (int i = b1; i >= b0; --i) loop.push_back(b[static_cast<std::size_t>(i)]);
      faces.push_back(std::move(loop));
      face_rows.push_back({a1 - a0, b1 - b0});
      face_row.push_back(rows);
    }
    ++rows;
  };
  // Where a row meets several (a split above it, or a merge below): each edge of `whole` goes with the
  // nearest of `partners` within reach (runs of fewer than three edges join the run before them), and each
  // run is joined to the stretch of its partner across from it. Edges with no partner in reach, and what a
  // partner keeps of its own, are borders there: cast on above a split (a crotch, an underarm), closed off
  // below a merge or under a slot.
  const auto join_runs = [&](const PlacedRow& whole, const std::vector<int>& partners, const std::vector<PlacedRow>& others, bool whole_above, double phase) {
    const int n = whole.edges(), count = static_cast<int>(whole.line.points.size());
    const auto point = [&](int i) { return whole.line.points[static_cast<std::size_t>(i % count)]; };
    const auto nearest_in = [](const PlacedRow& row, const Eigen::Vector3d& p) {
      int best = 0;
      for (int i = 1; i < static_cast<int>(row.line.points.size()); ++i)
        if ((row.line.points[static_cast<std::size_t>(i)] - p).squaredNorm() < (row.line.points[static_cast<std::size_t>(best)] - p).squaredNorm()) best = i;
      return best;
    };
    std::vector<int> label(static_cast<std::size_t>(n), -1);  // -1: no partner within reach (closed off / cast on)
    for (int e = 0; e < n; ++e) {
      const Eigen::Vector3d mid = 0.5 * (point(e) + point(e + 1));
      double best = reach * reach;
      for (int p : partners)
        for (const auto& q : others[static_cast<std::size_t>(p)].line.points)
          if ((q - mid).squaredNorm() < best) best = (q - mid).squaredNorm(), label[static_cast<std::size_t>(e)] = p;
    }
    struct Run { int partner, from, edges; };
    std::vector<Run> runs;
    for (bool changed = true; changed;) {
      runs.clear();
      for (int e = 0; e < n; ++e) {
        if (runs.empty() || runs.back().partner != label[static_cast<std::size_t>(e)]) runs.push_back({label[static_cast<std::size_t>(e)], e, 0});
        ++runs.back().edges;
      }
      if (whole.line.closed && runs.size() > 1 && runs.front().partner == runs.back().partner) {  // a ring's run across its start
        runs.front().from = runs.back().from;
        runs.front().edges += runs.back().edges;
        runs.pop_back();
      }
      changed = false;
      for (std::size_t r = 0; r < runs.size() && runs.size() > 1; ++r)
        if (runs[r].edges < 3) {  // into the run before it (the one after it, at an open row's start)
          const bool first_of_open = r == 0 && !whole.line.closed;
          const int into = runs[first_of_open ? 1 : (r + runs.size() - 1) % runs.size()].partner;
          for (int e = 0; e < runs[r].edges; ++e) label[static_cast<std::size_t>((runs[r].from + e) % n)] = into;
          changed = true;  // a neighbour's partner always differs from the run's: the runs become fewer
          break;
        }
    }
    // Runs of two partners side by side would share their end point with no face between them (two fans
    // meeting at a point): the first gives up its last edge, closed off (or cast on) there.
    for (std::size_t r = 0; r < runs.size(); ++r) {
      const bool last = r + 1 == runs.size();
      if (last && !whole.line.closed) break;
      const Run& next = runs[last ? 0 : r + 1];
      if (&next != &runs[r] && runs[r].partner >= 0 && next.partner >= 0 && runs[r].edges > 1) --runs[r].edges;
    }
    std::map<int, std::vector<char>> covered;  // partner -> its edges joined so far (a partner may meet several runs)
    std::map<int, std::set<int>> ends;         // partner -> its points that end a stretch joined so far
    for (const Run& run : runs) {
      if (run.partner < 0) continue;
      // The partner's stretch across from the run: each point of the run's nearest on the partner, followed
      // round the partner by its shortest steps (so a run the partner meets only at its ends, as at a crotch,
      // still spans the partner's side that faces it).
      const PlacedRow& other = others[static_cast<std::size_t>(run.partner)];
      const int m = other.edges();
      int from = nearest_in(other, point(run.from));
      int edges = 0;
      for (int v = 1, previous = from; v <= run.edges; ++v) {
        const int at = nearest_in(other, point(run.from + v));
        int step = at - previous;
        if (other.line.closed) step = ((step % m) + m + m / 2) % m - m / 2;
        edges += step;
        previous = at;
      }
      // A run over part of its row takes less than all of a ring: a whole ring would start and end its
      // stretch at one point, two fans meeting there.
      edges = std::min(edges, other.line.closed && !(whole.line.closed && run.edges == n) ? m - 1 : m);
      // Nor may two stretches of one partner meet at a point: a stretch stops an edge short of another's end.
      int first = from;
      auto& taken_ends = ends[run.partner];
      const auto wrap = [&](int i) { return other.line.closed ? ((i % m) + m) % m : i; };
      if (taken_ends.count(wrap(first))) ++first, --edges;
      if (edges > 0 && taken_ends.count(wrap(first + edges))) --edges;
      if (edges < 1) continue;
      from = wrap(first);
      taken_ends.insert(from);
      taken_ends.insert(wrap(from + edges));
      auto& used = covered.try_emplace(run.partner, static_cast<std::size_t>(m), 0).first->second;
      for (int e = 0; e < edges; ++e) {
        char& edge = used[static_cast<std::size_t>(other.line.closed ? (from + e) % m : from + e)];
        if (edge) refuse_at(point(run.from), "the rows split or merge unevenly here (two stretches of a row meet one stretch of another); cut the mesh at the branch, or label it by hand");
        edge = 1;
      }
      const auto mine = path(whole, run.from, run.edges), theirs = path(other, from, edges);
      if (whole_above) add_strip(theirs, mine, phase);
      else add_strip(mine, theirs, phase);
    }
  };
  double next_level = first;
  for (int k = 0;; ++k) {
    level = next_level;
    if (level > field_max - 0.3 * size.height) break;
    ++levels;
    Isolines found = isolines(field, level);
    // The next row one stitch height on: the field rises by the height times its gradient length, averaged
    // between here and the predicted next row (Heun's rule; the length changes fastest near the start).
    // Clamped: a distance's gradient is 1, and a stray one must neither stall the rows nor skip them.
    const auto clamped = [](double slope) { return std::clamp(slope, 0.5, 2.0); };
    next_level = level + size.height * 0.5 * (clamped(found.slope) + clamped(isolines(field, level + size.height * clamped(found.slope)).slope));
    std::vector<Polyline> lines;
    for (auto& line : found.lines) {
      const double l = line.length();
      if (line.points.size() < 2 || (line.closed ? l < 2 * size.width : l < 0.5 * size.width)) continue;  // a tip
      lines.push_back(std::move(line));
    }
    // Each line's row below: the one most of its points lie next to (within `reach`), if a quarter of them
    // do; at a branch a line runs next to the row below only on its outer side.
    std::vector<int> match(lines.size(), -1);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      double best = kFieldSliver;
      for (std::size_t j = 0; j < below.size(); ++j) {
        const double share = near_share(below[j].line, lines[i], reach);
        if (share >= best) best = share, match[i] = static_cast<int>(j);
      }
    }
    // Pieces of a row's continuation under a quarter of its longest are slivers the field's error cut off at a
    // border (dropped); pieces that together are under half the row below are its end running into a far
    // border, as the field's error frays it (all dropped).
    std::vector<char> dropped(lines.size(), 0);
    for (std::size_t j = 0; j < below.size(); ++j) {
      double longest = 0, going_on = 0;
      int count = 0;
      for (std::size_t i = 0; i < lines.size(); ++i)
        if (match[i] == static_cast<int>(j)) longest = std::max(longest, lines[i].length()), going_on += lines[i].length(), ++count;
      for (std::size_t i = 0; i < lines.size(); ++i)
        if (match[i] == static_cast<int>(j) && count > 1 && (going_on < 0.5 * below[j].line.length() || lines[i].length() < kFieldSliver * longest))
          dropped[i] = 1;
    }
    {
      std::vector<Polyline> kept;
      std::vector<int> kept_match;
      for (std::size_t i = 0; i < lines.size(); ++i)
        if (!dropped[i]) kept.push_back(std::move(lines[i])), kept_match.push_back(match[i]);
      lines = std::move(kept);
      match = std::move(kept_match);
    }
    // Branches: a row below that goes on as several lines splits (ups), a line that a second row below ends
    // beside is where rows merge (downs). A row below with no line ends (closed off); a line with none starts.
    std::vector<std::vector<int>> ups(below.size()), downs(lines.size());
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (match[i] >= 0) ups[static_cast<std::size_t>(match[i])].push_back(static_cast<int>(i)), downs[i].push_back(match[i]);
    for (std::size_t j = 0; j < below.size(); ++j) {
      if (!ups[j].empty()) continue;
      int beside = -1;
      double best = kFieldSliver;
      for (std::size_t i = 0; i < lines.size(); ++i) {
        const double share = near_share(lines[i], below[j].line, reach);
        if (share >= best) best = share, beside = static_cast<int>(i);
      }
      if (beside >= 0) {
        downs[static_cast<std::size_t>(beside)].push_back(static_cast<int>(j));
        ups[j].push_back(beside);
      } else {
        ++ends;
      }
    }
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (downs[i].size() < 2) continue;
      for (int j : downs[i])
        if (ups[static_cast<std::size_t>(j)].size() > 1)
          refuse_at(lines[i].points.front(), "the rows split and merge at once here; cut the mesh at the branch, or label it by hand");
    }
    // A line that goes on from one row alone, both rings or both rows with ends: joined stitch for stitch. A ring
    // that runs into a border unevenly (a sleeve's slanted cuff) goes on as a row with ends: joined as at a
    // branch, the rest of the ring closed off (or, the other way round, cast on).
    const auto one_to_one = [&](std::size_t i) {
      return downs[i].size() == 1 && ups[static_cast<std::size_t>(downs[i][0])].size() == 1 &&
             below[static_cast<std::size_t>(downs[i][0])].line.closed == lines[i].closed;
    };
    const auto ring_to_row = [&](std::size_t i) {
      return downs[i].size() == 1 && ups[static_cast<std::size_t>(downs[i][0])].size() == 1 && !one_to_one(i);
    };
    // Sample every line at the stitch width; a row continuing one row below changes its count at most by a
    // doubling or a halving (Yuksel Table 1's increases and decreases).
    std::vector<PlacedRow> placed;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const double l = lines[i].length();
      int edges = std::max(lines[i].closed ? 3 : 1, static_cast<int>(std::lround(l / size.width)));
      if (downs[i].empty()) ++starts;
      if (one_to_one(i)) {
        const PlacedRow& a = below[static_cast<std::size_t>(downs[i][0])];
        const int n = a.edges();
        // The row keeps the count below unless its length is more than 3/4 of a stitch off it: no increase and
        // decrease in turn where a tube's length hovers about a half stitch (a knitter keeps the count).
        if (std::abs(l / size.width - n) < 0.75) edges = n;
        edges = std::clamp(edges, (n + 1) / 2, 2 * n);
        if (lines[i].closed) edges = std::max(edges, 3);
        if (lines[i].closed) lines[i] = begun_near(lines[i], a.line.points.front());
      }
      PlacedRow row{resample(lines[i], edges), {}};
      for (const auto& p : row.line.points) {
        row.ids.push_back(static_cast<int>(points.size()));
        points.push_back(p);
      }
      placed.push_back(std::move(row));
    }
    const double phase = std::fmod(k * golden, 1.0);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (!one_to_one(i)) continue;
      PlacedRow& b = placed[i];
      const PlacedRow& a = below[static_cast<std::size_t>(downs[i][0])];
      if (b.line.closed) {  // turn the ring so that its wale edges are as short as they can be (no twist)
        const int na = a.edges(), nb = b.edges(), m = std::min(na, nb), big = std::max(na, nb);
        int best_turn = 0;
        double best = std::numeric_limits<double>::infinity();
        for (int turn = 0; turn < nb; ++turn) {
          double cost = 0;
          for (int f = 0; f < m && cost < best; ++f) {
            const int share = share_start(f, m, big, phase);
            const int ia = na >= nb ? share : f, ib = nb > na ? share : f;
            cost += (a.line.points[static_cast<std::size_t>(ia % na)] - b.line.points[static_cast<std::size_t>((ib + turn) % nb)]).squaredNorm();
          }
          if (cost < best) best = cost, best_turn = turn;
        }
        std::rotate(b.ids.begin(), b.ids.begin() + best_turn, b.ids.end());
        std::rotate(b.line.points.begin(), b.line.points.begin() + best_turn, b.line.points.end());
      }
      add_strip(path(a, 0, a.edges()), path(b, 0, b.edges()), b.line.closed ? phase : 0.0);
    }
    // Splits: each edge of the row below goes on into the nearest of its lines; each run of edges so shared
    // is joined to the stretch of its line across from it, and the rest of that line starts there (cast on,
    // as a crotch or an underarm is). Merges the other way round: the rest of a row below is closed off.
    for (std::size_t j = 0; j < below.size(); ++j)
      if (ups[j].size() > 1) join_runs(below[j], ups[j], placed, false, phase);
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (downs[i].size() > 1 || ring_to_row(i)) join_runs(placed[i], downs[i], below, true, phase);
    below = std::move(placed);
  }
  ends += static_cast<int>(below.size());
  if (faces.empty())
    throw Error(name, "", "no row fits: the surface reaches " + mm(field_max) + " from the start, less than two stitch heights (" +
                              mm(size.height) + ")");
  // Points no face uses (rows with nothing above or below them alone) are dropped.
  std::optional<InputMesh> built;
  try {
    built.emplace(with_used_points(points, faces, name + " (traced rows)"));
  } catch (const Error& e) {  // a branch joined in a way the mesh's rules refuse: say so in the user's terms
    std::string place = e.place();
    int vertex = -1;
    if (std::sscanf(place.c_str(), "vertex %d", &vertex) == 1) {  // the traced vertex's position, numbered by first use
      std::vector<int> seen(points.size(), -1);
      int next = 0;
      for (const auto& f : faces)
        for (int v : f)
          if (seen[static_cast<std::size_t>(v)] < 0 && (seen[static_cast<std::size_t>(v)] = next++) == vertex) place = where(points[static_cast<std::size_t>(v)]);
    }
    const std::string rule = e.rule().find("non-manifold") != std::string::npos ? "two fans of stitches meet only at a point" : e.rule();
    throw Error(name, place, "the traced rows break a rule of meshes at a branch (" + rule + "); cut the mesh at the branch, or label it by hand");
  }
  InputMesh traced = std::move(*built);
  Labeling labels(traced);
  labels.rows = rows;
  for (int f = 0; f < traced.num_faces(); ++f) {
    const int bottom = face_rows[f].bottom, n = static_cast<int>(traced.face(f).size());
    labels.faces[f] = {face_row[f], n - 1, bottom};
    for (int k = 0; k < n; ++k)
      labels.edges[traced.face_edge(f, k)] = (k == n - 1 || k == bottom) ? EdgeLabel::Wale : EdgeLabel::Course;
  }
  const LabelReport report = validate_labels(traced, labels);
  if (!report.valid())
    throw Error(name, "traced face " + std::to_string(report.face_problems.front().first), "the traced rows do not label: " + report.face_problems.front().second);
  TessellationValues values{std::vector<int>(traced.num_edges(), 1), std::vector<char>(traced.num_edges(), 0)};
  return TracedRows{std::move(traced), std::move(labels), std::move(values), levels, field_max, starts, ends};
}

}  // namespace skein::mesh
