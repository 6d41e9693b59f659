#include "render/raster.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include <Eigen/Geometry>
#include <png.h>

#include "common/atomic_file.hpp"
#include "common/error.hpp"

namespace skein::render {
namespace {

struct Frame {
  Eigen::Vector3d right, up, forward;
};

Frame frame_for(const Eigen::Vector3d& direction, const Eigen::Vector3d& up_hint) {
  Frame f;
  f.forward = direction.normalized();
  f.right = f.forward.cross(up_hint).normalized();
  f.up = f.right.cross(f.forward);
  return f;
}

/// One panel at `scale` pixels per mm, supersampled by `ss`; writes into `out` at column offset `x0`.
void draw_panel(const std::vector<Polygon>& polygons, const Frame& fr, double scale, const Eigen::Vector2d& centre, int size,
                bool outlines, Image& out, int x0) {
  constexpr int ss = 2;
  const int n = size * ss;
  std::vector<float> depth(static_cast<size_t>(n) * n, std::numeric_limits<float>::infinity());
  std::vector<Eigen::Vector3f> color(static_cast<size_t>(n) * n, Eigen::Vector3f(1, 1, 1));
  const auto project = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector3d((p.dot(fr.right) - centre.x()) * scale * ss + n / 2.0, (centre.y() - p.dot(fr.up)) * scale * ss + n / 2.0,
                           p.dot(fr.forward));
  };

  double edge_px = 0;
  size_t edges = 0;
  std::vector<Eigen::Vector3d> q;
  for (const auto& poly : polygons) {
    const size_t m = poly.points.size();
    if (m < 3) continue;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < m; ++i) normal += poly.points[i].cross(poly.points[(i + 1) % m]);
    const double len = normal.norm();
    const double light = len > 0 ? 0.3 + 0.7 * std::abs(normal.dot(fr.forward)) / len : 0.3;
    const Eigen::Vector3f shaded = poly.color * static_cast<float>(light);
    q.clear();
    for (const auto& p : poly.points) q.push_back(project(p));
    for (size_t i = 0; i < m; ++i) edge_px += (q[i] - q[(i + 1) % m]).head<2>().norm(), ++edges;
    for (size_t i = 1; i + 1 < m; ++i) {
      const Eigen::Vector3d &a = q[0], &b = q[i], &c = q[i + 1];
      const double area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
      if (std::abs(area) < 1e-12) continue;
      const int xmin = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
      const int xmax = std::min(n - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
      const int ymin = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
      const int ymax = std::min(n - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
      for (int y = ymin; y <= ymax; ++y)
        for (int x = xmin; x <= xmax; ++x) {
          const double px = x + 0.5, py = y + 0.5;
          const double w0 = ((b.x() - px) * (c.y() - py) - (b.y() - py) * (c.x() - px)) / area;
          const double w1 = ((c.x() - px) * (a.y() - py) - (c.y() - py) * (a.x() - px)) / area;
          const double w2 = 1 - w0 - w1;
          if (w0 < 0 || w1 < 0 || w2 < 0) continue;
          const float z = static_cast<float>(w0 * a.z() + w1 * b.z() + w2 * c.z());
          const size_t k = static_cast<size_t>(y) * n + x;
          if (z < depth[k]) depth[k] = z, color[k] = shaded;
        }
    }
  }

  // Outlines only where a polygon edge spans enough pixels to read as structure rather than noise.
  const double bias = 1e-3 * (1.0 / scale);
  if (outlines && edges > 0 && edge_px / edges > 6.0 * ss) {
    for (const auto& poly : polygons) {
      const size_t m = poly.points.size();
      for (size_t i = 0; i < m; ++i) {
        const Eigen::Vector3d a = project(poly.points[i]), b = project(poly.points[(i + 1) % m]);
        const int steps = static_cast<int>(std::ceil((b - a).head<2>().norm())) + 1;
        for (int s = 0; s <= steps; ++s) {
          const Eigen::Vector3d p = a + (b - a) * (static_cast<double>(s) / steps);
          const int x = static_cast<int>(p.x()), y = static_cast<int>(p.y());
          if (x < 0 || y < 0 || x >= n || y >= n) continue;
          const size_t k = static_cast<size_t>(y) * n + x;
          if (p.z() <= depth[k] + bias * 50) color[k] = poly.color * 0.25f;
        }
      }
    }
  }

  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      Eigen::Vector3f sum = Eigen::Vector3f::Zero();
      for (int dy = 0; dy < ss; ++dy)
        for (int dx = 0; dx < ss; ++dx) sum += color[static_cast<size_t>(y * ss + dy) * n + x * ss + dx];
      sum /= ss * ss;
      const size_t o = (static_cast<size_t>(y) * out.width + x0 + x) * 3;
      for (int c = 0; c < 3; ++c) out.rgb[o + c] = display_byte(sum[c]);
    }
}

}  // namespace

std::uint8_t display_byte(float linear) {
  return static_cast<std::uint8_t>(std::clamp(std::lround(std::pow(std::max(linear, 0.0f), 1 / 2.2f) * 255.0f), 0L, 255L));
}

float linear_of_byte(unsigned byte) { return std::pow(static_cast<float>(byte) / 255.0f, 2.2f); }

Image draw(const std::vector<Polygon>& polygons, const View& view) {
  const int panels = static_cast<int>(view.directions.size());
  Image image(view.panel * panels, view.panel);
  // One scale for all panels: the largest projected extent fills 90% of a panel.
  double extent = 1e-9;
  std::vector<Eigen::Vector2d> centres;
  for (const auto& d : view.directions) {
    const Frame fr = frame_for(d, view.up);
    Eigen::AlignedBox2d box;
    for (const auto& poly : polygons)
      for (const auto& p : poly.points) box.extend(Eigen::Vector2d(p.dot(fr.right), p.dot(fr.up)));
    if (box.isEmpty()) box.extend(Eigen::Vector2d::Zero());
    extent = std::max(extent, box.sizes().maxCoeff());
    centres.push_back(box.center());
  }
  const double scale = 0.9 * view.panel / extent;
  for (int i = 0; i < panels; ++i)
    draw_panel(polygons, frame_for(view.directions[i], view.up), scale, centres[i], view.panel, view.outlines, image, i * view.panel);
  return image;
}

void write_png(const Image& image, const std::filesystem::path& path) {
  write_file_atomically(
      path,
      [&](std::ostream& out) {
        png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
        png_infop info = png ? png_create_info_struct(png) : nullptr;
        if (!png || !info) throw Error(path.string(), "", "libpng could not start");
        if (setjmp(png_jmpbuf(png))) {
          png_destroy_write_struct(&png, &info);
          throw Error(path.string(), "", "libpng failed while writing");
        }
        png_set_write_fn(
            png, &out, [](png_structp p, png_bytep data, png_size_t len) { static_cast<std::ostream*>(png_get_io_ptr(p))->write(reinterpret_cast<const char*>(data), len); },
            [](png_structp p) { static_cast<std::ostream*>(png_get_io_ptr(p))->flush(); });
        png_set_IHDR(png, info, image.width, image.height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                     PNG_FILTER_TYPE_DEFAULT);
        png_write_info(png, info);
        for (int y = 0; y < image.height; ++y) png_write_row(png, const_cast<png_bytep>(&image.rgb[static_cast<size_t>(y) * image.width * 3]));
        png_write_end(png, nullptr);
        png_destroy_write_struct(&png, &info);
      },
      true);
}

Image read_png(const std::filesystem::path& path) {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path.c_str())) throw Error(path.string(), "", std::string("cannot read PNG: ") + img.message);
  img.format = PNG_FORMAT_RGB;
  Image out(static_cast<int>(img.width), static_cast<int>(img.height));
  if (!png_image_finish_read(&img, nullptr, out.rgb.data(), 0, nullptr)) throw Error(path.string(), "", std::string("cannot read PNG: ") + img.message);
  return out;
}

}  // namespace skein::render
