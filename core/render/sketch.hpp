#pragma once
// Flat drawings (charts, smocking patterns) as polygons for the rasterizer: x across, y up, each layer a little
// nearer the eye (z) than the one below it; draw them with a View looking down -z.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "render/raster.hpp"

namespace skein::render {

struct Sketch {
  std::vector<Polygon> polygons;
  void quad(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, const Eigen::Vector2d& d, const Eigen::Vector3f& color,
            double z);
  void box(double x0, double y0, double x1, double y1, const Eigen::Vector3f& color, double z) { quad({x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, color, z); }
  /// A line `width` wide from a to b.
  void stroke(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double width, const Eigen::Vector3f& color, double z = 0.03);
  void dot(const Eigen::Vector2d& c, double r, const Eigen::Vector3f& color, double z = 0.03);
  void ring(const Eigen::Vector2d& c, double r, double width, const Eigen::Vector3f& color, double z = 0.03);
  /// `text` (digits, '.' and '-') as seven-segment figures `height` tall, the lower left corner at (x, y); returns
  /// the width it took.
  double figures(const std::string& text, double x, double y, double height, const Eigen::Vector3f& color);
  double number(int n, double x, double y, double height, const Eigen::Vector3f& color) { return figures(std::to_string(n), x, y, height, color); }
};

/// The sketch seen from the front (down -z), `pixels` on its longer side, no outlines.
Image draw_flat(const Sketch& sketch, int pixels);

/// Images side by side, their tops aligned, on white.
Image side_by_side(const std::vector<Image>& images);

}  // namespace skein::render
