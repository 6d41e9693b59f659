#include "render/stitch_view.hpp"

#include <cmath>

#include "stitchmesh/stitch_types.hpp"

namespace skein::render {
namespace {
/// Pieces that belong to no stitch type: cables teal, bind-off slate, turns pale.
Eigen::Vector3f border_color(const std::string& piece) {
  if (piece.rfind("cable", 0) == 0) return {0.2f, 0.75f, 0.8f};
  if (piece == "bind-off") return {0.55f, 0.55f, 0.6f};
  return {0.75f, 0.75f, 0.8f};
}
}  // namespace

Eigen::Vector3f row_color(int row) {
  const double hue = std::fmod(row * 0.618033988749895, 1.0) * 6.0;
  const double s = row % 2 == 0 ? 0.65 : 0.45, v = 0.95;
  const int i = static_cast<int>(hue);
  const double f = hue - i, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  const double rgb[6][3] = {{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}};
  return {static_cast<float>(rgb[i % 6][0]), static_cast<float>(rgb[i % 6][1]), static_cast<float>(rgb[i % 6][2])};
}

Eigen::Vector3f stitch_color(const std::string& type) {
  const mesh::StitchType* t = mesh::find_stitch_type(type);
  if (!t) return border_color(type);
  if (t->top == 2) return {0.35f, 0.75f, 0.35f};
  if (t->top == 3) return {0.15f, 0.5f, 0.2f};
  if (t->bottom == 2) return {0.85f, 0.3f, 0.25f};
  if (t->bottom == 3) return {0.55f, 0.1f, 0.1f};
  if (type == "k") return {0.93f, 0.88f, 0.76f};
  if (type == "p") return {0.45f, 0.3f, 0.55f};
  if (type == "y") return {0.95f, 0.8f, 0.2f};
  if (type[0] == 'k' || type[0] == 'p' || type[0] == 'y') return {0.95f, 0.55f, 0.2f};  // twisted tops
  return {0.3f, 0.55f, 0.9f};                                                          // x, s, sk
}

std::vector<Polygon> stitch_polygons(const mesh::StitchMesh& mesh, ColorBy color) {
  std::vector<Polygon> out;
  out.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces) {
    Polygon p;
    for (int v : f.vertices) p.points.push_back(mesh.vertices[v]);
    p.color = color == ColorBy::Row ? row_color(f.row) : stitch_color(f.type);
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace skein::render
