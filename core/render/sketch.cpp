#include "render/sketch.hpp"

#include <algorithm>
#include <cmath>

namespace skein::render {

void Sketch::quad(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, const Eigen::Vector2d& d, const Eigen::Vector3f& color,
                  double z) {
  Polygon p;
  for (const auto& v : {a, b, c, d}) p.points.emplace_back(v.x(), v.y(), z);
  p.color = color;
  polygons.push_back(std::move(p));
}

void Sketch::stroke(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double width, const Eigen::Vector3f& color, double z) {
  const Eigen::Vector2d d = (b - a).normalized(), n(-d.y() * width / 2, d.x() * width / 2);
  quad(a - n, b - n, b + n, a + n, color, z);
}

void Sketch::dot(const Eigen::Vector2d& c, double r, const Eigen::Vector3f& color, double z) {
  Polygon p;
  for (int k = 0; k < 16; ++k) p.points.emplace_back(c.x() + r * std::cos(k * M_PI / 8), c.y() + r * std::sin(k * M_PI / 8), z);
  p.color = color;
  polygons.push_back(std::move(p));
}

void Sketch::ring(const Eigen::Vector2d& c, double r, double width, const Eigen::Vector3f& color, double z) {
  for (int k = 0; k < 20; ++k) {
    const double a0 = k * M_PI / 10, a1 = (k + 1) * M_PI / 10;
    stroke(c + r * Eigen::Vector2d(std::cos(a0), std::sin(a0)), c + r * Eigen::Vector2d(std::cos(a1), std::sin(a1)), width, color, z);
  }
}

double Sketch::figures(const std::string& text, double x, double y, double height, const Eigen::Vector3f& color) {
  // Segments a (top), b (upper right), c (lower right), d (bottom), e (lower left), f (upper left), g (middle).
  static const char* const kDigits[] = {"abcdef", "bc", "abged", "abgcd", "fgbc", "afgcd", "afgedc", "abc", "abcdefg", "abcdfg"};
  // Each segment's two ends, a to g: (column 0 or 1, height 0, 1 or 2 halves) and the same for the other end.
  static const int kEnds[7][4] = {{0, 2, 1, 2}, {1, 2, 1, 1}, {1, 1, 1, 0}, {0, 0, 1, 0}, {0, 1, 0, 0}, {0, 2, 0, 1}, {0, 1, 1, 1}};
  const double w = 0.55 * height, line = 0.16 * height, advance = w + 0.35 * height;
  double x0 = x;
  for (char ch : text) {
    if (ch == '.') {
      dot({x0 + line, y + line / 2}, line * 0.7, color);
      x0 += 3 * line;
      continue;
    }
    const char* segments = ch == '-' ? "g" : (ch >= '0' && ch <= '9') ? kDigits[ch - '0'] : "";
    const double x1 = x0 + w, xs[2] = {x0, x1}, ys[3] = {y, y + height / 2, y + height};
    for (const char* seg = segments; *seg; ++seg) {
      const int* e = kEnds[*seg - 'a'];
      const Eigen::Vector2d a(xs[e[0]], ys[e[1]]), b(xs[e[2]], ys[e[3]]);
      const Eigen::Vector2d along = (b - a).normalized() * (line / 2);
      stroke(a - along, b + along, line, color);
    }
    x0 += advance;
  }
  return x0 - x;
}

Image draw_flat(const Sketch& sketch, int pixels) {
  View view;
  view.directions = {{0, 0, -1}};
  view.outlines = false;
  view.panel = pixels;
  return draw(sketch.polygons, view);
}

Image side_by_side(const std::vector<Image>& images) {
  int width = 0, height = 0;
  for (const auto& im : images) width += im.width, height = std::max(height, im.height);
  Image out(width, height);
  int x0 = 0;
  for (const auto& im : images) {
    for (int y = 0; y < im.height; ++y)
      std::copy_n(&im.rgb[static_cast<size_t>(y) * im.width * 3], static_cast<size_t>(im.width) * 3, &out.rgb[(static_cast<size_t>(y) * width + x0) * 3]);
    x0 += im.width;
  }
  return out;
}

}  // namespace skein::render
