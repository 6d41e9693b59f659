#pragma once
// Small geometric queries shared by the yarn statistics and the topology auditor.
#include <Eigen/Core>

#include "common/closest_points.hpp"

namespace skein::relax {

/// Closest distance between the segments p0-p1 and q0-q1 (clamped closest points, Ericson, Real-Time
/// Collision Detection §5.1.9).
inline double segment_distance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  const auto [s, t] = closest_on_segments(p0, p1, q0, q1);
  return (p0 + (p1 - p0) * s - (q0 + (q1 - q0) * t)).norm();
}

}  // namespace skein::relax
