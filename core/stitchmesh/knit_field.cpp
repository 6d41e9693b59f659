#include "stitchmesh/knit_field.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>

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

/// Builds the field surface and the geodesic distance from `sources` (CGAL's heat method on the intrinsic
/// Delaunay triangulation, which stays accurate on the long thin triangles artists' meshes have). `sources`
/// picks the refined surface's source vertices from their positions and whether they lie on the border.
FieldSurface knitting_distance(const InputMesh& surface, double max_edge,
                               const std::function<std::vector<int>(const std::vector<Eigen::Vector3d>&, const std::vector<char>&)>& sources) {
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

/// Mean distance from b's points to their nearest points of a.
double mean_gap(const Polyline& a, const Polyline& b) {
  double sum = 0;
  for (const auto& p : b.points) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& q : a.points) best = std::min(best, (p - q).squaredNorm());
    sum += std::sqrt(best);
  }
  return sum / static_cast<double>(b.points.size());
}

/// A sampled row placed in the traced mesh: its vertex ids, left to right.
struct PlacedRow {
  Polyline line;
  std::vector<int> ids;
  int edges() const { return line.closed ? static_cast<int>(ids.size()) : static_cast<int>(ids.size()) - 1; }
};

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

TracedRows trace_stitch_mesh(const InputMesh& surface, const KnitStart& start, const StitchSize& size) {
  size.validate();
  const std::string& name = surface.source();
  // Sources: the points of the start run, or the point nearest the start.
  std::vector<int> start_vertices;
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> run_segments;
  if (start.point) {
    int best = 0;
    for (int v = 1; v < surface.num_vertices(); ++v)
      if ((surface.point(v) - *start.point).squaredNorm() < (surface.point(best) - *start.point).squaredNorm()) best = v;
    start_vertices.push_back(best);
  } else {
    for (int e : field_start_run(surface, start.border_edge)) {
      const auto [a, b] = surface.edge_vertices(e);
      start_vertices.push_back(a);
      run_segments.push_back({surface.point(a), surface.point(b)});
    }
  }
  int piece_count = 0;
  const std::vector<int> piece = pieces(surface, piece_count);
  if (piece_count > 1) {
    std::vector<char> reached(piece_count, 0);
    for (int v : start_vertices) reached[piece[v]] = 1;
    for (int v = 0; v < surface.num_vertices(); ++v)
      if (!reached[piece[v]])
        throw Error(name, "vertex " + std::to_string(v) + " " + where(surface.point(v)),
                    "lies on a piece of the surface the knitting start does not reach (" + std::to_string(piece_count) +
                        " pieces); trace each piece from its own start");
  }
  const double tolerance = 1e-9 * surface.bounding_diagonal();
  const auto sources = [&](const std::vector<Eigen::Vector3d>& points, const std::vector<char>& on_border) {
    std::vector<int> from;
    if (start.point) {  // the remeshing moves inner points: the nearest of the refined surface's
      int best = 0;
      for (int v = 1; v < static_cast<int>(points.size()); ++v)
        if ((points[static_cast<std::size_t>(v)] - *start.point).squaredNorm() < (points[static_cast<std::size_t>(best)] - *start.point).squaredNorm()) best = v;
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
  FieldSurface field = knitting_distance(surface, 0.5 * std::min(size.width, size.height), sources);
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
  double next_level = first;
  for (int k = 0;; ++k) {
    const double level = next_level;
    if (level > field_max - 0.3 * size.height) break;
    ++levels;
    Isolines found = isolines(field, level);
    // The next row one stitch height on: the field rises by the height times its gradient length, averaged
    // between here and the predicted next row (Heun's rule; the length changes fastest near the start).
    next_level = level + size.height * 0.5 * (found.slope + isolines(field, level + size.height * found.slope).slope);
    std::vector<Polyline> lines;
    for (auto& line : found.lines) {
      const double l = line.length();
      if (line.points.size() < 2 || (line.closed ? l < 2 * size.width : l < 0.5 * size.width)) continue;  // a tip
      lines.push_back(std::move(line));
    }
    // Each line's row below: the nearest one, no more than two stitch heights off.
    std::vector<int> match(lines.size(), -1), taken(below.size(), 0);
    const auto refuse = [&](const Eigen::Vector3d& p, const std::string& rule) {
      throw Error(name, "knitting distance " + mm(level) + " " + where(p), rule);
    };
    const std::string branch = "the rows split or merge here (the surface branches); knitting one piece across a branch needs short "
                               "rows and joins skein does not make: cut the mesh at the branch, or label it by hand";
    for (std::size_t i = 0; i < lines.size(); ++i) {
      double best = 2 * size.height;
      for (std::size_t j = 0; j < below.size(); ++j) {
        const double gap = mean_gap(below[j].line, lines[i]);
        if (gap < best) best = gap, match[i] = static_cast<int>(j);
      }
    }
    // A row that goes on as two lines: the longer goes on; the other is a sliver the field's error cut off at a
    // border (dropped) when it is under a quarter of it, else the surface branches. Pieces that together are
    // under half the row below are its end running into a far border, as the field's error frays it.
    std::vector<char> dropped(lines.size(), 0);
    for (std::size_t j = 0; j < below.size(); ++j) {
      int longest = -1;
      for (std::size_t i = 0; i < lines.size(); ++i)
        if (match[i] == static_cast<int>(j) && (longest < 0 || lines[i].length() > lines[static_cast<std::size_t>(longest)].length())) longest = static_cast<int>(i);
      double going_on = 0;
      int count = 0;
      for (std::size_t i = 0; i < lines.size(); ++i)
        if (match[i] == static_cast<int>(j)) going_on += lines[i].length(), ++count;
      if (count > 1 && going_on < 0.5 * below[j].line.length()) {  // the row runs into a far border in pieces: it ends
        for (std::size_t i = 0; i < lines.size(); ++i)
          if (match[i] == static_cast<int>(j)) dropped[i] = 1;
        continue;
      }
      for (std::size_t i = 0; i < lines.size(); ++i) {
        if (match[i] != static_cast<int>(j) || static_cast<int>(i) == longest) continue;
        if (lines[i].length() >= kFieldSliver * lines[static_cast<std::size_t>(longest)].length()) refuse(lines[i].points.front(), branch);
        dropped[i] = 1;
      }
      if (longest >= 0) {
        taken[j] = 1;
        const Polyline& line = lines[static_cast<std::size_t>(longest)];
        if (below[j].line.closed != line.closed)
          refuse(line.points.front(), std::string("the rows ") + (line.closed ? "leave" : "reach") +
                                          " a border unevenly here (a ring becomes a row with ends); start from that border instead");
      }
    }
    for (std::size_t j = 0; j < below.size(); ++j) {
      if (taken[j]) continue;
      for (std::size_t i = 0; i < lines.size(); ++i)  // a row that ends where another goes on beside it: a merge
        if (!dropped[i] && mean_gap(lines[i], below[j].line) < size.height && below[j].line.length() >= kFieldSliver * lines[i].length())
          refuse(below[j].line.points.front(), branch);
      ++ends;
    }
    std::vector<Polyline> kept;
    std::vector<int> kept_match;
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (!dropped[i]) kept.push_back(std::move(lines[i])), kept_match.push_back(match[i]);
    lines = std::move(kept);
    match = std::move(kept_match);
    std::vector<PlacedRow> placed;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const double l = lines[i].length();
      int edges = std::max(lines[i].closed ? 3 : 1, static_cast<int>(std::lround(l / size.width)));
      if (match[i] >= 0) {  // at most a doubling or a halving per row (Yuksel Table 1's increases and decreases)
        const int n = below[match[i]].edges();
        edges = std::clamp(edges, (n + 1) / 2, 2 * n);
        if (lines[i].closed) edges = std::max(edges, 3);
      } else {
        ++starts;
      }
      if (match[i] >= 0 && lines[i].closed) lines[i] = begun_near(lines[i], below[match[i]].line.points.front());
      PlacedRow row{resample(lines[i], edges), {}};
      for (const auto& p : row.line.points) {
        row.ids.push_back(static_cast<int>(points.size()));
        points.push_back(p);
      }
      if (match[i] >= 0) {
        // Join the row below (a) to this one (b): min(na, nb) faces, the longer row's edges shared out evenly,
        // the share's phase moving on by the golden ratio each row so that increases do not stack in a column.
        const PlacedRow& a = below[match[i]];
        const int na = a.edges(), nb = row.edges(), m = std::min(na, nb), big = std::max(na, nb);
        const double phase = row.line.closed ? std::fmod(k * golden, 1.0) : 0.0;
        const auto split = [&](int f) { return static_cast<int>(std::floor(static_cast<double>(f) * big / m + (f == m ? 0 : phase))); };
        const auto at = [](const PlacedRow& r, int i) { return r.ids[static_cast<std::size_t>(r.line.closed ? i % static_cast<int>(r.ids.size()) : i)]; };
        const auto ends_of = [&](int f) {  // face f's first bottom and first top point
          const int share = f == m ? big : split(f);
          return std::pair{na >= nb ? share : f, nb > na ? share : f};
        };
        if (row.line.closed) {  // turn the ring so that its wale edges are as short as they can be (no twist)
          const int n = static_cast<int>(row.line.points.size());
          int best_turn = 0;
          double best = std::numeric_limits<double>::infinity();
          for (int turn = 0; turn < n; ++turn) {
            double cost = 0;
            for (int f = 0; f < m && cost < best; ++f) {
              const auto [ia, ib] = ends_of(f);
              cost += (a.line.points[static_cast<std::size_t>(ia % na)] - row.line.points[static_cast<std::size_t>((ib + turn) % n)]).squaredNorm();
            }
            if (cost < best) best = cost, best_turn = turn;
          }
          std::rotate(row.ids.begin(), row.ids.begin() + best_turn, row.ids.end());
          std::rotate(row.line.points.begin(), row.line.points.begin() + best_turn, row.line.points.end());
        }
        for (int f = 0; f < m; ++f) {
          const auto [a0, b0] = ends_of(f);
          const auto [a1, b1] = ends_of(f + 1);
          std::vector<int> loop;
          for (int i = a0; i <= a1; ++i) loop.push_back(at(a, i));
          for (int i = b1; i >= b0; --i) loop.push_back(at(row, i));
          faces.push_back(std::move(loop));
          face_rows.push_back({a1 - a0, b1 - b0});
          face_row.push_back(rows);
        }
        ++rows;
      }
      placed.push_back(std::move(row));
    }
    below = std::move(placed);
  }
  ends += static_cast<int>(below.size());
  if (faces.empty())
    throw Error(name, "", "no row fits: the surface reaches " + mm(field_max) + " from the start, less than two stitch heights (" +
                              mm(size.height) + ")");
  // Points no face uses (rows with nothing above or below them alone) are dropped.
  std::vector<int> remap(points.size(), -1);
  std::vector<Eigen::Vector3d> used;
  for (auto& f : faces)
    for (int& v : f) {
      if (remap[v] < 0) remap[v] = static_cast<int>(used.size()), used.push_back(points[v]);
      v = remap[v];
    }
  InputMesh traced(std::move(used), faces, name + " (traced rows)");
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
