#pragma once
#include <vector>

#include <Eigen/Core>

namespace skein::mesh {

/// Mean value coordinates (Floater 2003) of a point strictly inside a counter-clockwise 2D polygon:
/// weights w_i >= 0 (for convex polygons) with sum w_i = 1 and sum w_i v_i = p. Collinear vertices are fine.
/// w_i ∝ (tan(α_{i-1}/2) + tan(α_i/2)) / |v_i - p|, α_i the angle at p subtended by edge (v_i, v_{i+1}).
inline Eigen::VectorXd mean_value_coordinates(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
  const int n = static_cast<int>(polygon.size());
  std::vector<Eigen::Vector2d> s(n);
  std::vector<double> r(n), tan_half(n);
  for (int i = 0; i < n; ++i) {
    s[i] = polygon[i] - p;
    r[i] = s[i].norm();
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const double cross = s[i].x() * s[j].y() - s[i].y() * s[j].x();  // 2 × signed area
    const double dot = s[i].dot(s[j]);
    tan_half[i] = cross / (r[i] * r[j] + dot);  // tan(α/2) = sin α / (1 + cos α)
  }
  Eigen::VectorXd w(n);
  for (int i = 0; i < n; ++i) w[i] = (tan_half[(i + n - 1) % n] + tan_half[i]) / r[i];
  return w / w.sum();
}

}  // namespace skein::mesh
