#pragma once
#include <vector>

#include <Eigen/Core>

#include "relax/yarn_system.hpp"

namespace skein::relax {

/// A sphere holding a whole segment: about the centroid of its Bezier control points.
struct SegmentSphere {
  Eigen::Vector3d center;
  double radius = 0;
};
std::vector<SegmentSphere> segment_spheres(const YarnSystem& system, const Eigen::Matrix3Xd& points);

/// Candidate contact pairs (Leaf 2018 Algorithm 1's contactPairSet, per segment pair as Yuksel §6.3): two
/// segments that do not share a control-point end and whose bounding spheres are less than 2r + margin apart.
/// They feel contact (samples less than 2r apart along one yarn excepted) and the pull-through guard watches them. Kept both ways, as a CSR
/// from each segment to its partners in increasing order, so forces can be gathered per segment without
/// write conflicts.
struct ContactPairs {
  std::vector<int> start{0};  ///< segment s's partners are partner[start[s] .. start[s+1])
  std::vector<int> partner;
  /// Unordered pairs (each counted once).
  long pairs() const { return static_cast<long>(partner.size()) / 2; }
};

/// The pairs found with a uniform grid over the segment spheres.
ContactPairs find_contact_pairs(const YarnSystem& system, const Eigen::Matrix3Xd& points, double margin);
/// The same pairs by testing every pair of segments: the reference the grid is checked against.
ContactPairs find_contact_pairs_brute_force(const YarnSystem& system, const Eigen::Matrix3Xd& points, double margin);

}  // namespace skein::relax
