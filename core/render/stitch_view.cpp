#include "render/stitch_view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/atomic_file.hpp"
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
  if (t->bottom > 1 && t->top > 1) return {0.45f, 0.85f, 0.9f};  // lace: ys 2u y3y
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

Eigen::Vector3f linear_color(const std::array<double, 3>& srgb) {
  Eigen::Vector3f out;
  for (int k = 0; k < 3; ++k) out[k] = linear_of_byte(static_cast<unsigned>(std::lround(std::clamp(srgb[k], 0.0, 1.0) * 255)));
  return out;
}

std::vector<Polygon> stitch_polygons(const mesh::StitchMesh& mesh, ColorBy color) {
  std::vector<Polygon> out;
  out.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces) {
    Polygon p;
    for (int v : f.vertices) p.points.push_back(mesh.vertices[v]);
    if (color == ColorBy::Colour && !mesh.palette.empty()) p.color = linear_color(mesh.palette.at(static_cast<size_t>(f.colour)).srgb);
    else p.color = color == ColorBy::Row ? row_color(f.row) : stitch_color(f.type);
    out.push_back(std::move(p));
  }
  return out;
}

Eigen::Vector3f strain_color(double strain, double range) {
  const float t = static_cast<float>(std::clamp(strain / range, -1.0, 1.0));
  const Eigen::Vector3f white(0.97f, 0.97f, 0.97f), red(0.8f, 0.1f, 0.1f), blue(0.15f, 0.3f, 0.85f);
  return t >= 0 ? Eigen::Vector3f(white + t * (red - white)) : Eigen::Vector3f(white - t * (blue - white));
}

std::vector<Polygon> stitch_polygons(const mesh::StitchMesh& mesh, const std::vector<Eigen::Vector3f>& face_colors) {
  std::vector<Polygon> out;
  out.reserve(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    Polygon p;
    for (int v : mesh.faces[f].vertices) p.points.push_back(mesh.vertices[v]);
    p.color = face_colors.at(f);
    out.push_back(std::move(p));
  }
  return out;
}

void write_ply(const mesh::StitchMesh& mesh, const std::vector<Eigen::Vector3f>& face_colors,
               const std::vector<std::pair<std::string, std::vector<double>>>& face_values, const std::filesystem::path& path) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "ply\nformat ascii 1.0\ncomment skein stitch mesh\nelement vertex " << mesh.vertices.size()
        << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << mesh.faces.size()
        << "\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n";
    for (const auto& [name, values] : face_values) out << "property float " << name << "\n";
    out << "end_header\n";
    char buf[128];
    for (const auto& v : mesh.vertices) {
      std::snprintf(buf, sizeof buf, "%.9g %.9g %.9g\n", v.x(), v.y(), v.z());
      out << buf;
    }
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
      out << mesh.faces[f].vertices.size();
      for (int v : mesh.faces[f].vertices) out << ' ' << v;
      for (int c = 0; c < 3; ++c) out << ' ' << std::clamp(static_cast<int>(std::lround(face_colors[f][c] * 255)), 0, 255);
      for (const auto& [name, values] : face_values) {
        std::snprintf(buf, sizeof buf, " %.6g", values[f]);
        out << buf;
      }
      out << '\n';
    }
  });
}

}  // namespace skein::render
