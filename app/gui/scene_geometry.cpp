#include "scene_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/stitch_view.hpp"
#include "render/yarn_view.hpp"
#include "stitchmesh/labeling.hpp"
#include "surface/mesh_relax.hpp"
#include "workflow/yarn_io.hpp"

namespace skein::gui {
namespace {

using Vec3 = Eigen::Vector3d;
using Color = Eigen::Vector3f;

const Color kCourse(0.12f, 0.12f, 0.12f), kUnlabeledEdge(0.55f, 0.55f, 0.55f), kUnlabeledFace(0.72f, 0.72f, 0.72f);
const Color kProblem(0.9f, 0.12f, 0.1f), kMarked(1.0f, 0.55f, 0.0f), kSelected(1.0f, 0.85f, 0.0f), kCable(0.0f, 0.6f, 0.6f);

Color mix(const Color& a, const Color& b, float t) { return (1 - t) * a + t * b; }

/// Newell's normal of a polygon loop (unit; zero for a degenerate loop).
Vec3 loop_normal(const std::vector<Vec3>& points, const std::vector<int>& loop) {
  Vec3 n = Vec3::Zero();
  for (size_t k = 0; k < loop.size(); ++k) {
    const Vec3& a = points[loop[k]];
    const Vec3& b = points[loop[(k + 1) % loop.size()]];
    n += Vec3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()), (a.x() - b.x()) * (a.y() + b.y()));
  }
  const double len = n.norm();
  return len > 0 ? Vec3(n / len) : Vec3::Zero();
}

void add_polygon(Geometry& g, const std::vector<Vec3>& points, const std::vector<int>& loop, const Color& color) {
  const Eigen::Vector3f n = loop_normal(points, loop).cast<float>();
  for (size_t k = 1; k + 1 < loop.size(); ++k)
    for (int v : {loop[0], loop[k], loop[k + 1]}) g.triangles.push_back({points[v].cast<float>(), n, color});
}

void add_line(Geometry& g, const Vec3& a, const Vec3& b, const Color& color) {
  g.lines.push_back({a.cast<float>(), Eigen::Vector3f::Zero(), color});
  g.lines.push_back({b.cast<float>(), Eigen::Vector3f::Zero(), color});
}

/// Pickable faces and bounds from the loops drawn.
void set_pick(Geometry& g, const std::vector<Vec3>& points, const std::vector<std::vector<int>>& loops) {
  g.pick_points = points;
  g.pick_faces = loops;
  for (const auto& p : points) g.bounds.extend(p);
}

Vec3 centroid(const std::vector<Vec3>& points, const std::vector<int>& loop) {
  Vec3 c = Vec3::Zero();
  for (int v : loop) c += points[v];
  return c / static_cast<double>(loop.size());
}

/// An arrow from a to b drawn as three lines, its head in the plane with normal n.
void add_arrow(Geometry& g, const Vec3& a, const Vec3& b, const Vec3& n, const Color& color) {
  const Vec3 d = b - a;
  const Vec3 side = n.cross(d) * 0.35;
  add_line(g, a, b, color);
  add_line(g, b, b - 0.35 * d + side, color);
  add_line(g, b, b - 0.35 * d - side, color);
}

}  // namespace

Geometry input_geometry(const mesh::InputMesh& input, const std::optional<mesh::Labeling>& labels,
                        const std::optional<mesh::TessellationValues>& values) {
  Geometry g;
  const auto& points = input.points();
  set_pick(g, points, input.faces());
  std::vector<char> problem(input.num_faces(), 0);
  if (labels)
    for (const auto& [face, reason] : mesh::validate_labels(input, *labels).face_problems) problem[face] = 1;
  const double lift = 2e-3 * input.bounding_diagonal();
  for (int f = 0; f < input.num_faces(); ++f) {
    const auto& loop = input.face(f);
    const mesh::FaceLabel label = labels ? labels->faces[f] : mesh::FaceLabel{};
    Color color = label.labeled() ? mix(render::row_color(label.row), Color::Ones(), 0.45f) : kUnlabeledFace;
    if (problem[f]) color = kProblem;
    add_polygon(g, points, loop, color);
    if (!label.labeled()) continue;
    // The wale direction: from the middle of the bottom edges to the middle of the top edges.
    const auto mid = [&](const std::vector<int>& edges) {
      Vec3 m = Vec3::Zero();
      for (int k : edges) m += 0.5 * (points[loop[k]] + points[loop[(k + 1) % loop.size()]]);
      return Vec3(m / static_cast<double>(edges.size()));
    };
    const Vec3 bottom = mid(mesh::bottom_edges(input, label, f)), top = mid(mesh::top_edges(input, label, f));
    const Vec3 n = loop_normal(points, loop);
    const Vec3 c = centroid(points, loop) + lift * n;
    add_arrow(g, c - 0.25 * (top - bottom), c + 0.25 * (top - bottom), n, render::row_color(label.row) * 0.45f);
  }
  for (int e = 0; e < input.num_edges(); ++e) {
    const auto [u, v] = input.edge_vertices(e);
    Color color = kUnlabeledEdge;
    if (labels && labels->edges[e] == mesh::EdgeLabel::Course) color = kCourse;
    if (labels && labels->edges[e] == mesh::EdgeLabel::Wale) {
      const int row = labels->faces[input.edge_uses(e).front().face].row;
      color = row >= 0 ? Color(render::row_color(row) * 0.6f) : kUnlabeledEdge;
      if (values && values->marked[e]) color = kMarked;
    }
    add_line(g, points[u], points[v], color);
  }
  return g;
}

namespace {
Eigen::Vector3f stitch_srgb(const std::array<double, 3>& srgb) { return {static_cast<float>(srgb[0]), static_cast<float>(srgb[1]), static_cast<float>(srgb[2])}; }
}  // namespace

std::vector<Eigen::Vector3f> face_colors(const mesh::StitchMesh& stitch, Coloring coloring, const std::optional<RestSize>& rest) {
  std::vector<double> strain;
  if (coloring == Coloring::Stretch && rest) strain = surface::face_stretch(stitch, rest->r_course, rest->r_wale).area_strain;
  std::vector<Eigen::Vector3f> colors(stitch.faces.size(), kUnlabeledFace);
  for (size_t f = 0; f < stitch.faces.size(); ++f) {
    if (coloring == Coloring::StitchType) colors[f] = render::stitch_color(stitch.faces[f].type);
    if (coloring == Coloring::Row) colors[f] = render::row_color(stitch.faces[f].row);
    if (coloring == Coloring::YarnColour)  // the view shows colours as given, not gamma-encoded: a palette's sRGB as it is
      colors[f] = stitch.palette.empty() ? render::stitch_color(stitch.faces[f].type)
                                         : stitch_srgb(stitch.palette.at(static_cast<size_t>(stitch.faces[f].colour)).srgb);
    if (!strain.empty()) colors[f] = render::strain_color(strain[f]);
  }
  return colors;
}

Geometry stitch_geometry(const mesh::StitchMesh& stitch, Coloring coloring, const std::optional<RestSize>& rest,
                         const std::vector<char>& selected) {
  Geometry g;
  std::vector<std::vector<int>> loops;
  loops.reserve(stitch.faces.size());
  for (const auto& f : stitch.faces) loops.push_back(f.vertices);
  set_pick(g, stitch.vertices, loops);
  const auto colors = face_colors(stitch, coloring, rest);
  for (size_t f = 0; f < stitch.faces.size(); ++f) {
    const auto& face = stitch.faces[f];
    Color color = colors[f];
    if (f < selected.size() && selected[f]) color = mix(color, kSelected, 0.6f);
    add_polygon(g, stitch.vertices, face.vertices, color);
    for (int k = 0; k < face.size(); ++k) add_line(g, stitch.vertices[face.vertex(k)], stitch.vertices[face.vertex(k + 1)], Color::Constant(0.1f));
  }
  for (const auto& [edge, mark] : stitch.cables) add_line(g, stitch.vertices[edge.first], stitch.vertices[edge.second], kCable);
  return g;
}

Geometry yarn_geometry(const relax::YarnCurves& yarn, YarnDetail detail, int max_tube_points) {
  Geometry g;
  if (static_cast<int>(yarn.points.size()) <= max_tube_points) {
    const bool full = detail == YarnDetail::Full;
    const auto color = yarn.point_colour.empty() ? render::YarnColor::StitchType : render::YarnColor::Colour;  // yarn in colours shows them
    for (const auto& polygon : render::yarn_polygons(yarn, color, full ? 6 : 4, full ? 2 : 1)) {
      std::vector<int> loop(polygon.points.size());
      for (size_t k = 0; k < loop.size(); ++k) loop[k] = static_cast<int>(k);
      // The rasterizer's colours are linear; the view shows colours as given, so the yarn's own go back to sRGB.
      Color shown = polygon.color;
      if (color == render::YarnColor::Colour)
        for (int k = 0; k < 3; ++k) shown[k] = render::display_byte(polygon.color[k]) / 255.0f;
      add_polygon(g, polygon.points, loop, shown);
    }
  } else {
    const auto curves = workflow::sample_curves(yarn, 2);
    for (int c = 0; c < static_cast<int>(curves.size()); ++c)
      for (size_t i = 0; i + 1 < curves[c].size(); ++i) add_line(g, curves[c][i], curves[c][i + 1], render::row_color(c));
  }
  for (const auto& p : yarn.points) g.bounds.extend(p);
  return g;
}

std::optional<Hit> pick(const Geometry& g, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
  std::optional<Hit> best;
  double best_t = std::numeric_limits<double>::infinity();
  for (int f = 0; f < static_cast<int>(g.pick_faces.size()); ++f) {
    const auto& loop = g.pick_faces[f];
    for (size_t k = 1; k + 1 < loop.size(); ++k) {
      // Möller–Trumbore ray/triangle intersection, both sides.
      const Vec3& a = g.pick_points[loop[0]];
      const Vec3 e1 = g.pick_points[loop[k]] - a, e2 = g.pick_points[loop[k + 1]] - a;
      const Vec3 p = direction.cross(e2);
      const double det = e1.dot(p);
      if (std::abs(det) < 1e-14) continue;
      const Vec3 s = origin - a;
      const double u = s.dot(p) / det;
      if (u < 0 || u > 1) continue;
      const Vec3 q = s.cross(e1);
      const double v = direction.dot(q) / det;
      if (v < 0 || u + v > 1) continue;
      const double t = e2.dot(q) / det;
      if (t <= 0 || t >= best_t) continue;
      best_t = t;
      best = Hit{f, -1, 0, origin + t * direction};
    }
  }
  if (!best) return best;
  // The loop edge nearest to the hit point.
  const auto& loop = g.pick_faces[best->face];
  best->edge_distance = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < loop.size(); ++k) {
    const Vec3& a = g.pick_points[loop[k]];
    const Vec3 ab = g.pick_points[loop[(k + 1) % loop.size()]] - a;
    const double t = std::clamp((best->point - a).dot(ab) / std::max(ab.squaredNorm(), 1e-30), 0.0, 1.0);
    const double d = (a + t * ab - best->point).norm();
    if (d < best->edge_distance) {
      best->edge_distance = d;
      best->local_edge = static_cast<int>(k);
    }
  }
  return best;
}

}  // namespace skein::gui
