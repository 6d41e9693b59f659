#pragma once
// The largest hole a fabric's yarn leaves, seen from the front (issue 24: "eyelets: each hole's largest empty
// disc at least 3 times stockinette's"): bench/open_area.py's measure for yarn in memory, with distances taken to
// the spline's samples (open_area.py: to the segments between them; within 0.01 mm on an eyelet preview). On a
// periodic patch the middle half of its extent lies inside the ring of copies around the real repeat.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "relax/yarn_curves.hpp"

namespace skein::testing {

/// The diameter [mm] of the largest disc in the xy plane that no yarn tube covers, its centre on a grid `step` mm
/// apart inside the middle half of the yarn's extent in x and in y. Each curve is the Catmull-Rom spline through
/// its points (ends doubled), sampled 8 times a segment; a tube covers what lies within `yarn.radius` of the
/// centreline's projection. `points` replaces yarn.points (a relaxed state).
inline double largest_open_disc(const relax::YarnCurves& yarn, const Eigen::Matrix3Xd& points, double step) {
  std::vector<Eigen::Vector2d> samples;
  for (int c = 0; c < yarn.curves(); ++c) {
    const int first = yarn.curve_start[c], n = yarn.curve_size(c);
    if (n == 0) continue;
    const auto at = [&](int i) -> Eigen::Vector2d { return points.col(first + std::clamp(i, 0, n - 1)).head<2>(); };
    for (int i = 0; i + 1 < n; ++i)
      for (int k = 0; k < 8; ++k) {
        const double t = k / 8.0, t2 = t * t, t3 = t2 * t;
        const Eigen::Vector2d a = at(i - 1), b = at(i), d = at(i + 1), e = at(i + 2);
        samples.push_back(0.5 * (2 * b + (d - a) * t + (2 * a - 5 * b + 4 * d - e) * t2 + (3 * b - a - 3 * d + e) * t3));
      }
    samples.push_back(at(n - 1));
  }
  Eigen::Vector2d lo = samples.front(), hi = samples.front();
  for (const auto& s : samples) lo = lo.cwiseMin(s), hi = hi.cwiseMax(s);
  // Samples bucketed in square cells; a centre's nearest sample is searched ring by ring outwards.
  const double cell = 1.0;
  const int nx = static_cast<int>((hi.x() - lo.x()) / cell) + 1, ny = static_cast<int>((hi.y() - lo.y()) / cell) + 1;
  std::vector<std::vector<int>> buckets(static_cast<size_t>(nx) * ny);
  const auto bucket_of = [&](const Eigen::Vector2d& p) {
    return Eigen::Vector2i(std::clamp(static_cast<int>((p.x() - lo.x()) / cell), 0, nx - 1), std::clamp(static_cast<int>((p.y() - lo.y()) / cell), 0, ny - 1));
  };
  for (int i = 0; i < static_cast<int>(samples.size()); ++i) {
    const auto b = bucket_of(samples[i]);
    buckets[static_cast<size_t>(b.y()) * nx + b.x()].push_back(i);
  }
  const auto nearest = [&](const Eigen::Vector2d& p) {
    const auto b = bucket_of(p);
    double best = std::numeric_limits<double>::infinity();
    for (int ring = 0; ring <= std::max(nx, ny); ++ring) {
      if ((ring - 1) * cell > best) break;  // every sample further out is at least (ring - 1) cells away
      for (int y = b.y() - ring; y <= b.y() + ring; ++y)
        for (int x = b.x() - ring; x <= b.x() + ring; ++x) {
          if (x < 0 || y < 0 || x >= nx || y >= ny || std::max(std::abs(x - b.x()), std::abs(y - b.y())) != ring) continue;
          for (int i : buckets[static_cast<size_t>(y) * nx + x]) best = std::min(best, (samples[i] - p).norm());
        }
    }
    return best;
  };
  double largest = 0;
  const Eigen::Vector2d size = hi - lo;
  for (double y = lo.y() + 0.25 * size.y(); y <= hi.y() - 0.25 * size.y(); y += step)
    for (double x = lo.x() + 0.25 * size.x(); x <= hi.x() - 0.25 * size.x(); x += step)
      largest = std::max(largest, nearest({x, y}) - yarn.radius);
  return 2 * largest;
}

}  // namespace skein::testing
