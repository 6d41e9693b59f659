#include "render/yarn_view.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "render/stitch_view.hpp"
#include "workflow/yarn_io.hpp"

namespace skein::render {

std::vector<Polygon> yarn_polygons(const relax::YarnCurves& yarn, YarnColor color, int sides, int samples_per_segment) {
  const auto curves = workflow::sample_curves(yarn, samples_per_segment);
  std::vector<Polygon> out;
  for (int c = 0; c < static_cast<int>(curves.size()); ++c) {
    const auto& pts = curves[c];
    if (pts.size() < 2) continue;
    const int n = yarn.curve_size(c), first = yarn.curve_start[c];
    const auto rings = workflow::tube_rings(pts, yarn.radius, sides);
    for (size_t i = 0; i + 1 < rings.size(); ++i) {
      Eigen::Vector3f rgb;
      const int point = first + std::min(n - 1, static_cast<int>(i) / samples_per_segment);  // where this stretch starts
      if (color == YarnColor::Colour && yarn.point_colour.size() == yarn.points.size()) {
        rgb = linear_color(yarn.colours.at(static_cast<size_t>(yarn.point_colour[point])).srgb);
      } else if (color == YarnColor::Yarn || yarn.point_type.empty() || yarn.point_type[first] < 0) {
        rgb = row_color(c);
      } else {  // the type of the control point this stretch starts from
        const int type = yarn.point_type[point];
        rgb = type >= 0 && type < static_cast<int>(yarn.type_names.size()) ? stitch_color(yarn.type_names[type]) : Eigen::Vector3f(0.6f, 0.6f, 0.6f);
      }
      for (int k = 0; k < sides; ++k) {
        Polygon p;
        p.points = {rings[i][k], rings[i][(k + 1) % sides], rings[i + 1][(k + 1) % sides], rings[i + 1][k]};
        p.color = rgb;
        out.push_back(std::move(p));
      }
    }
  }
  return out;
}

}  // namespace skein::render
