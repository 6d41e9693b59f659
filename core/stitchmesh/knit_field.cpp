#include "stitchmesh/knit_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include <CGAL/Heat_method_3/Surface_mesh_geodesic_distances_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>

#include "common/error.hpp"

namespace skein::mesh {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Surface = CGAL::Surface_mesh<Kernel::Point_3>;
using SurfaceVertex = Surface::Vertex_index;

std::string where(const Eigen::Vector3d& p) {
  char text[96];
  std::snprintf(text, sizeof text, "near (%.4g, %.4g, %.4g)", p.x(), p.y(), p.z());
  return text;
}

/// Fans each polygon into triangles (InputMesh keeps polygons as drawn; the heat method needs triangles).
std::vector<std::array<int, 3>> triangles(const InputMesh& surface) {
  std::vector<std::array<int, 3>> tris;
  for (const auto& f : surface.faces())
    for (std::size_t k = 1; k + 1 < f.size(); ++k) tris.push_back({f[0], f[k], f[k + 1]});
  return tris;
}

/// Vertices of each connected piece, as a piece id per vertex.
std::vector<int> pieces(const InputMesh& surface, int& count) {
  std::vector<int> parent(surface.num_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& f : surface.faces())
    for (int v : f) parent[find(v)] = find(f[0]);
  std::vector<int> id(surface.num_vertices(), -1);
  std::map<int, int> root_id;
  for (int v = 0; v < surface.num_vertices(); ++v) id[v] = root_id.try_emplace(find(v), static_cast<int>(root_id.size())).first->second;
  count = static_cast<int>(root_id.size());
  return id;
}

/// Geodesic distance from the sources to every vertex (CGAL's heat method on the intrinsic Delaunay
/// triangulation, which stays accurate on the long thin triangles artists' meshes have).
std::vector<double> geodesic_distance(const InputMesh& surface, const std::vector<int>& sources) {
  Surface tm;
  std::vector<SurfaceVertex> vertex;
  vertex.reserve(surface.num_vertices());
  for (const auto& p : surface.points()) vertex.push_back(tm.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
  for (const auto& t : triangles(surface))
    if (tm.add_face(vertex[t[0]], vertex[t[1]], vertex[t[2]]) == Surface::null_face())
      throw Error(surface.source(), "face with vertex " + std::to_string(t[0]), "cannot be triangulated for the knitting field");
  auto distance = tm.add_property_map<SurfaceVertex, double>("v:knit_distance", 0).first;
  CGAL::Heat_method_3::Surface_mesh_geodesic_distances_3<Surface, CGAL::Heat_method_3::Intrinsic_Delaunay> heat(tm);
  for (int v : sources) heat.add_source(vertex[v]);
  heat.estimate_geodesic_distances(distance);
  std::vector<double> t(surface.num_vertices());
  for (int v = 0; v < surface.num_vertices(); ++v) t[v] = distance[vertex[v]];
  return t;
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
std::vector<Polyline> isolines(const InputMesh& surface, const std::vector<std::array<int, 3>>& tris,
                               const std::vector<double>& t, double level) {
  std::map<std::pair<int, int>, int> crossing_of;  // undirected edge -> crossing id
  std::vector<Eigen::Vector3d> crossing;
  const auto crossing_id = [&](int u, int v) {
    const auto key = std::minmax(u, v);
    auto [it, added] = crossing_of.try_emplace({key.first, key.second}, static_cast<int>(crossing.size()));
    if (added) {
      const double s = (level - t[u]) / (t[v] - t[u]);
      crossing.push_back(surface.point(u) + s * (surface.point(v) - surface.point(u)));
    }
    return it->second;
  };
  std::vector<std::pair<int, int>> pieces;  // from, to
  for (const auto& tri : tris) {
    int down = -1, up = -1;
    for (int k = 0; k < 3; ++k) {
      const int u = tri[k], v = tri[(k + 1) % 3];
      const bool above_u = t[u] >= level, above_v = t[v] >= level;
      if (above_u && !above_v) down = crossing_id(u, v);
      if (!above_u && above_v) up = crossing_id(u, v);
    }
    if (down >= 0 && up >= 0) pieces.push_back({down, up});
  }
  std::vector<int> next(crossing.size(), -1), prev(crossing.size(), -1);
  for (auto [a, b] : pieces) {
    next[a] = b;
    prev[b] = a;
  }
  std::vector<Polyline> lines;
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
  return lines;
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
  // Sources: the start run's vertices, or the vertex nearest the start point.
  std::vector<int> sources;
  if (start.point) {
    int best = 0;
    for (int v = 1; v < surface.num_vertices(); ++v)
      if ((surface.point(v) - *start.point).squaredNorm() < (surface.point(best) - *start.point).squaredNorm()) best = v;
    sources.push_back(best);
  } else {
    for (int e : field_start_run(surface, start.border_edge)) {
      const auto [a, b] = surface.edge_vertices(e);
      sources.push_back(a);
      sources.push_back(b);
    }
  }
  int piece_count = 0;
  const std::vector<int> piece = pieces(surface, piece_count);
  if (piece_count > 1) {
    std::vector<char> reached(piece_count, 0);
    for (int v : sources) reached[piece[v]] = 1;
    for (int v = 0; v < surface.num_vertices(); ++v)
      if (!reached[piece[v]])
        throw Error(name, "vertex " + std::to_string(v) + " " + where(surface.point(v)),
                    "lies on a piece of the surface the knitting start does not reach (" + std::to_string(piece_count) +
                        " pieces); trace each piece from its own start");
  }
  std::vector<double> t = geodesic_distance(surface, sources);
  for (int v = 0; v < surface.num_vertices(); ++v)
    if (!std::isfinite(t[v])) throw Error(name, "vertex " + std::to_string(v) + " " + where(surface.point(v)), "the heat method gave no knitting distance here");
  for (int v : sources) t[v] = 0;  // the heat method's estimate leaves them near, not at, zero
  const double lowest = *std::min_element(t.begin(), t.end());
  for (double& x : t) x -= lowest;
  const double field_max = *std::max_element(t.begin(), t.end());

  // Levels one stitch height apart: from just off the start border, or from a ring one stitch width round the
  // start point (six stitches, as a crown is cast on), to short of the farthest point.
  const double first = start.point ? size.width : 0.05 * size.height;
  const auto tris = triangles(surface);
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> faces;
  struct FaceRows { int bottom, top; };
  std::vector<FaceRows> face_rows;  // bottom and top course edge counts of each face
  std::vector<int> face_row;
  std::vector<PlacedRow> below;
  int rows = 0, levels = 0, starts = 0, ends = 0;
  const double golden = 0.6180339887498949;
  for (int k = 0;; ++k) {
    const double level = first + k * size.height;
    if (level > field_max - 0.3 * size.height) break;
    ++levels;
    std::vector<Polyline> lines;
    for (auto& line : isolines(surface, tris, t, level)) {
      const double l = line.length();
      if (line.points.size() < 2 || (line.closed ? l < 2 * size.width : l < 0.5 * size.width)) continue;  // a tip
      lines.push_back(std::move(line));
    }
    // Each line's row below: the nearest one, no more than two stitch heights off.
    std::vector<int> match(lines.size(), -1), taken(below.size(), 0);
    const auto refuse = [&](const Eigen::Vector3d& p, const std::string& rule) {
      throw Error(name, "knitting distance " + std::to_string(level) + " " + where(p), rule);
    };
    const std::string branch = "the rows split or merge here (the surface branches); knitting one piece across a branch needs short "
                               "rows and joins skein does not make: cut the mesh at the branch, or label it by hand";
    for (std::size_t i = 0; i < lines.size(); ++i) {
      double best = 2 * size.height;
      for (std::size_t j = 0; j < below.size(); ++j) {
        const double gap = mean_gap(below[j].line, lines[i]);
        if (gap < best) best = gap, match[i] = static_cast<int>(j);
      }
      if (match[i] < 0) continue;
      if (taken[match[i]]++) refuse(lines[i].points.front(), branch);
      if (below[match[i]].line.closed != lines[i].closed)
        refuse(lines[i].points.front(), std::string("the rows ") + (lines[i].closed ? "leave" : "reach") +
                                            " a border unevenly here (a ring becomes a row with ends); start from that border instead");
    }
    for (std::size_t j = 0; j < below.size(); ++j) {
      if (taken[j]) continue;
      for (const auto& line : lines)  // a row below that ends where another row goes on: a merge
        if (mean_gap(line, below[j].line) < size.height) refuse(below[j].line.points.front(), branch);
      ++ends;
    }
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
    throw Error(name, "", "no row fits: the surface is " + std::to_string(field_max) + " across from the start, less than two stitch heights (" +
                              std::to_string(size.height) + ")");
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
