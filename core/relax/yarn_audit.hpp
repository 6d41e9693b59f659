#pragma once
#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "relax/yarn_curves.hpp"
#include "relax/yarn_system.hpp"

namespace skein::relax {

/// The topology auditor, independent of the pull-through guard (it shares none of its geometry): while all
/// control points move on straight lines from one state to the next, does any centreline touch another? Each
/// pair of Catmull-Rom segments whose swept Bezier hulls overlap is tested exactly (issue 27): their difference
/// y_a(s, t) − y_b(u, t) is a polynomial of degree 3 × 3 × 1 in (s, u, t), whose values lie in the convex hull
/// of its Bernstein coefficients; pieces whose hull a plane separates from the origin are proved apart, the
/// others are halved (de Casteljau) until proved apart or smaller than `tolerance`, which is a meeting. No
/// crossing is missed at any separation: centrelines that come within the tolerance count as meeting.
class TopologyAuditor {
public:
  /// `tolerance`: centrelines closer than this × r count as touching (far below any yarn's gap; rounding in
  /// the coefficients is about 1e-14 mm).
  explicit TopologyAuditor(const YarnSystem& system, double tolerance = 1e-9);
  /// A centreline crossing: two segments that met during the move, and where (at the start). `resolved` is false
  /// when the pair stayed closer than the test could settle in kMaxAuditPieces pieces: counted as a meeting.
  struct Crossing {
    int segment_a = 0, segment_b = 0;
    Eigen::Vector3d where = Eigen::Vector3d::Zero();
    bool resolved = true;
  };
  /// Centreline crossings during the straight-line move from `before` to `after`, of segments that are not one
  /// piece of yarn (YarnSystem::adjacent); pairs of segments that both stay put are not tested. Not to be called
  /// from two threads at once on one auditor (it keeps its buffers).
  std::vector<Crossing> crossings(const Eigen::Matrix3Xd& before, const Eigen::Matrix3Xd& after) const;
  /// Only pairs with at least one segment marked here are tested (a periodic patch's periodic_tested_segments:
  /// the patch's other segments are translated copies that move alike, so one copy of each pair is tested);
  /// empty: every pair.
  void restrict_to(std::vector<char> segments);

private:
  const YarnSystem& m_system;
  double m_tolerance;  ///< [mm]
  std::vector<char> m_tested;  ///< per segment, or empty (restrict_to)
  /// Per-call buffers, kept so that each step does not allocate them again: one call at a time per auditor.
  struct Scratch {
    std::vector<std::array<Eigen::Vector3d, 8>> bezier;
    std::vector<Eigen::AlignedBox3d> boxes;
    std::vector<char> moving;
  };
  mutable Scratch m_scratch;
};

/// The most pieces the exact test splits one pair into before it counts the pair as meeting (unresolved).
inline constexpr int kMaxAuditPieces = 1 << 16;

/// The exact continuous test of two cubic Bezier curves (control points a0, b0 at the start, a1, b1 at the end;
/// every control point moves on a straight line): do they come within `tolerance` at some (s, u, t)? Returns
/// 1 for a meeting, 0 when proved apart, -1 when `max_pieces` pieces did not settle it.
int bezier_curves_meet_during(const Eigen::Vector3d a0[4], const Eigen::Vector3d a1[4], const Eigen::Vector3d b0[4], const Eigen::Vector3d b1[4],
                              double tolerance, int max_pieces = kMaxAuditPieces);

/// Gauss linking number of two closed polylines (exact for polylines: the solid angle of each pair of edges,
/// Klenin & Langowski 2000); an integer up to rounding when the curves do not meet.
double linking_number(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b);

/// The same by signed crossings (issue 27): the two polylines seen along a generic direction (`view` picks one
/// of several), Lk = the sum of the signs of the crossings where a passes over b. Exact for polylines and found in
/// near-linear time (edges bucketed in a grid of the view). nullopt when the view is degenerate (an end on the
/// other edge's line, or the polylines meet at a crossing): try another view.
std::optional<long> linking_number_by_crossings(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b, int view = 0);

/// Linking numbers between every two closed curves whose bounding boxes overlap (curves with apart boxes have
/// linking number 0). Each curve is sampled finely enough to stay within `deviation` r of itself (at least 4
/// samples a segment), and each pair more finely until neither polyline strays from its curve by half the gap
/// between them, so that the polylines' linking number is the curves' (up to kMaxLinkingSamples a segment:
/// curves closer than that resolves are as good as touching). The polylines' linking number is counted by
/// crossings (linking_number_by_crossings), the Gauss sum kept for views that are all degenerate.
struct Linking {
  int a = 0, b = 0;
  long number = 0;
};
inline constexpr int kMaxLinkingSamples = 1024;
std::vector<Linking> linking_numbers(const relax::YarnCurves& yarn, double deviation = 0.1);

/// What changed between two states of one yarn (`skein audit`, the app's audit): how far its control points
/// moved, the centreline crossings on the straight path from one to the other (TopologyAuditor) and the closed
/// curves whose linking number changed (linking_numbers at `deviation`). Unchanged topology: no crossing, no change.
struct StateAudit {
  int curves = 0, closed_curves = 0, points = 0;
  double largest_move = 0, rms_move = 0;  ///< [mm]
  std::vector<TopologyAuditor::Crossing> crossings;
  std::vector<std::array<int, 2>> segment_ends;  ///< per segment: the two control points it runs between (naming a crossing)
  long unresolved = 0;  ///< crossings the test could not settle in kMaxAuditPieces pieces (counted as crossings)
  struct LinkChange {
    int a = 0, b = 0;          ///< closed curves
    long before = 0, after = 0;
  };
  std::vector<LinkChange> linking_changes;  ///< by curve pair
  long linked_pairs = 0;                    ///< pairs of closed curves that come near in either state
  bool unchanged() const { return crossings.empty() && linking_changes.empty(); }
};
/// Throws skein::Error when `after` holds other curves than `before` (counts, sizes or closed flags).
StateAudit audit_states(const relax::YarnCurves& before, const relax::YarnCurves& after, double deviation = 0.1);

}  // namespace skein::relax
