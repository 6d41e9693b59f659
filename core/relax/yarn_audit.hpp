#pragma once
#include <vector>

#include <Eigen/Core>

#include "relax/yarn_system.hpp"
#include "stitchmesh/yarn_curves.hpp"

namespace skein::relax {

/// The topology auditor, independent of the pull-through guard (it shares none of its geometry): the yarn
/// centrelines as polylines and a continuous test of every pair of polyline edges while all control points
/// move on straight lines from one state to the next; a meeting is confirmed on polylines of 64 points per
/// segment for the two segments involved. Each segment gets as many polyline edges as its curvature needs to
/// stay within `deviation` r of its curve in both states and all the way between them (issue 10's adaptive
/// resolution): m = ceil(sqrt(max |y''| / 8 deviation r)), from the chord error bound h² max |y''| / 8.
class TopologyAuditor {
public:
  explicit TopologyAuditor(const YarnSystem& system, double deviation = 0.1);
  /// A centreline crossing: two segments whose polyline edges met during the move, and where (at the start).
  struct Crossing {
    int segment_a = 0, segment_b = 0;
    Eigen::Vector3d where = Eigen::Vector3d::Zero();
  };
  /// Centreline crossings during the straight-line move from `before` to `after`: edges that meet, of
  /// segments that are not one piece of yarn (YarnSystem::adjacent).
  std::vector<Crossing> crossings(const Eigen::Matrix3Xd& before, const Eigen::Matrix3Xd& after) const;
  /// Per segment: the largest |y''| [mm] over it and over the move from `before` to `after` (a polyline of m
  /// edges stays within |y''| / 8 m² of the curve).
  std::vector<double> second_derivative_bounds(const Eigen::Matrix3Xd& before, const Eigen::Matrix3Xd& after) const;
  /// Per segment: the polyline edges that keep it within the deviation over the move from `before` to `after`.
  std::vector<int> edges_per_segment(const Eigen::Matrix3Xd& before, const Eigen::Matrix3Xd& after) const;

private:
  Eigen::Vector3d curve_point(const Eigen::Matrix3Xd& points, int segment, double t) const;
  /// The same test on 64 points per segment, for one pair of segments.
  bool segments_meet_finely(int a, int b, const Eigen::Matrix3Xd& before, const Eigen::Matrix3Xd& after, double tolerance) const;
  const YarnSystem& m_system;
  double m_deviation;  ///< [mm]
};

/// Does the edge a0-a1 meet the edge b0-b1 at some time while all four ends move linearly from their *0
/// positions (t = 0) to their *1 positions (t = 1)? Edges closer than `tolerance` count as meeting.
bool edges_meet_during(const Eigen::Vector3d a0[2], const Eigen::Vector3d a1[2], const Eigen::Vector3d b0[2],
                       const Eigen::Vector3d b1[2], double tolerance);

/// Gauss linking number of two closed polylines (exact for polylines: the solid angle of each pair of edges,
/// Klenin & Langowski 2000); an integer up to rounding when the curves do not meet.
double linking_number(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b);

/// Linking numbers between every two closed curves of `yarn` whose bounding boxes overlap (curves with
/// apart boxes have linking number 0). Each curve is sampled finely enough to stay within `deviation` r of
/// itself (at least 4 samples a segment), and each pair more finely until neither polyline strays from its
/// curve by half the gap between them, so that the polylines' linking number is the curves' (up to
/// kMaxLinkingSamples a segment: curves closer than that resolves are as good as touching).
struct Linking {
  int a = 0, b = 0;
  long number = 0;
};
inline constexpr int kMaxLinkingSamples = 1024;
std::vector<Linking> linking_numbers(const mesh::YarnCurves& yarn, double deviation = 0.1);

}  // namespace skein::relax
