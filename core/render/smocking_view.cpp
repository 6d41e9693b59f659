#include "render/smocking_view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/sketch.hpp"

namespace skein::render {
namespace {

const Eigen::Vector3f kFabric(0.72f, 0.72f, 0.74f), kStitchPoint(0.95f, 0.5f, 0.08f), kFront(0.2f, 0.62f, 0.25f), kBack(0.55f, 0.3f, 0.7f),
    kPleat(0.55f, 0.55f, 0.58f), kPaper(1, 1, 1), kInk(0.15f, 0.15f, 0.2f), kGoal(0.8f, 0.25f, 0.2f), kBead(0.15f, 0.35f, 0.75f);

/// A dashed line (a back stitch, as patterns draw them).
void dashes(Sketch& s, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double width, double dash, const Eigen::Vector3f& color, double z) {
  const double length = (b - a).norm();
  const int n = std::max(1, static_cast<int>(std::round(length / (2 * dash))));
  for (int k = 0; k < n; ++k) s.stroke(a + (b - a) * (2.0 * k / (2 * n - 1)), a + (b - a) * ((2.0 * k + 1) / (2 * n - 1)), width, color, z);
}

/// One panel: the fabric springs and threads at `x`, on a sheet the flat fabric's size so every panel has one scale.
Image panel(const smocking::Embedding& e, const Eigen::Matrix2Xd& x, bool as_drawn, double spacing, int pixels) {
  Sketch s;
  const double line = 0.06 * spacing, dot = 0.12 * spacing;
  for (const auto& f : e.fabric) s.stroke(x.col(f.a), x.col(f.b), 0.5 * line, kFabric, 0.01);
  std::vector<char> stitched(x.cols(), 0);
  for (const auto& st : e.stitches) {
    stitched[st.a] = stitched[st.b] = 1;
    const Eigen::Vector2d a = x.col(st.a), b = x.col(st.b);
    if (st.front) s.stroke(a, b, line, kFront, 0.03);
    else if (as_drawn) dashes(s, a, b, line, 0.15 * spacing, kBack, 0.02);
    else s.stroke(a, b, line, kBack, 0.02);
    if (!as_drawn) s.dot(0.5 * (a + b), 0.7 * dot, st.front ? kFront : kBack, 0.04);
    if (st.bead > 0) s.ring(0.5 * (a + b), 0.5 * st.bead, 0.4 * line, kBead, 0.06);
  }
  for (int p = 0; p < x.cols(); ++p)
    if (stitched[p]) s.dot(x.col(p), dot, kStitchPoint, 0.05);
    else s.dot(x.col(p), 0.45 * dot, kPleat, 0.02);
  // The sheet: the flat fabric's extent and a margin, centred on this panel's drawing.
  const Eigen::Vector2d lo = e.rest.rowwise().minCoeff(), hi = e.rest.rowwise().maxCoeff(), half = 0.5 * (hi - lo) + Eigen::Vector2d::Constant(spacing);
  const Eigen::Vector2d centre = 0.5 * (x.rowwise().minCoeff() + x.rowwise().maxCoeff());
  const double side = std::max(half.x(), half.y());
  s.box(centre.x() - side, centre.y() - side, centre.x() + side, centre.y() + side, kPaper, 0);
  return draw_flat(s, pixels);
}

}  // namespace

Image draw_smocking(const smocking::SmockingPattern& pattern, const smocking::Embedding& e, int pixels) {
  std::vector<Image> panels{panel(e, e.rest, true, pattern.spacing, pixels)};
  for (const auto& [fraction, x] : e.snapshots)
    if (fraction < 1) panels.push_back(panel(e, x, false, pattern.spacing, pixels));
  panels.push_back(panel(e, e.positions, false, pattern.spacing, pixels));
  // Wide or tall patterns: the blank rows above and below every panel's drawing go.
  int top = pixels, bottom = 0;
  for (const auto& im : panels)
    for (int y = 0; y < im.height; ++y)
      if (std::any_of(&im.rgb[static_cast<size_t>(y) * im.width * 3], &im.rgb[static_cast<size_t>(y + 1) * im.width * 3], [](std::uint8_t c) { return c < 250; }))
        top = std::min(top, y), bottom = std::max(bottom, y);
  const int margin = pixels / 40;
  top = std::max(0, top - margin), bottom = std::min(pixels - 1, bottom + margin);
  for (auto& im : panels) {
    Image cropped(im.width, std::max(1, bottom - top + 1));
    std::copy(im.rgb.begin() + static_cast<size_t>(top) * im.width * 3, im.rgb.begin() + static_cast<size_t>(top + cropped.height) * im.width * 3, cropped.rgb.begin());
    im = std::move(cropped);
  }
  return side_by_side(panels);
}

Image draw_shrinkage_chart(const smocking::Embedding& e, double gamma, int pixels) {
  Sketch s;
  // Plot area 0..1.6 across (the iterations), 0..1 up (D/D̄).
  const double w = 1.6, text = 0.045;
  const double last = std::max(1.0, e.history.back().x());
  for (size_t k = 1; k < e.history.size(); ++k)
    s.stroke({w * e.history[k - 1].x() / last, e.history[k - 1].y()}, {w * e.history[k].x() / last, e.history[k].y()}, 0.008, kFront, 0.03);
  for (int k = 0; k < 20; ++k) s.stroke({w * k / 20.0, gamma}, {w * (k + 0.5) / 20.0, gamma}, 0.004, kGoal, 0.02);
  s.stroke({0, 0}, {w, 0}, 0.004, kInk);
  s.stroke({0, 0}, {0, 1}, 0.004, kInk);
  for (double f : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    s.stroke({-0.015, f}, {0, f}, 0.004, kInk);
    char label[16];
    std::snprintf(label, sizeof label, "%.2f", f);
    s.figures(label, -0.2, f - text / 2, text, kInk);
  }
  s.figures(std::to_string(static_cast<long>(last)), w - 0.2, -0.09, text, kInk);
  s.figures("0", 0, -0.09, text, kInk);
  s.box(-0.25, -0.15, w + 0.05, 1.05, kPaper, 0);
  return draw_flat(s, pixels);
}

Image draw_smocked_fabric(const smocking::Cloth& cloth, int pixels) {
  std::vector<Polygon> polygons;
  for (const auto& t : cloth.triangles) {
    Polygon p;
    for (int v : t) p.points.push_back(cloth.positions.col(v));
    p.color = {0.78f, 0.70f, 0.86f};
    polygons.push_back(std::move(p));
  }
  View view;
  view.directions = {{0.3, -0.45, -1.0}, {1.0, -0.6, -0.35}};
  view.outlines = false;
  view.panel = pixels;
  return draw(polygons, view);
}

}  // namespace skein::render
