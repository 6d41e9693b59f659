#pragma once
#include <vector>

#include <Eigen/Core>

#include "relax/guard_model.hpp"
#include "relax/yarn_contacts.hpp"
#include "relax/yarn_system.hpp"

namespace skein::relax {

struct GuardOptions {
  bool enabled = true;       ///< off: only the movement limit holds (for measuring what the guard costs)
  double max_move = 0.25;    ///< ε: no point of any yarn moves more than ε r in one step (at most half the contact margin)
  int max_depth = 10;        ///< bounding-sphere refinement levels (pieces of 1/2^depth of a segment)
  int max_halvings = 6;      ///< halvings of the still-hit pairs' moves before their points are held for the step
  bool safe_bounds = true;   ///< Yuksel eqs. 8–10: skip pairs whose points stay inside their safe movement
  void validate() const;     ///< throws skein::Error for values out of range
};

/// How often each part of the guard fired (Yuksel 2012 §6.3), summed over steps.
struct GuardCounters {
  long steps = 0;
  long rate_limited = 0;   ///< steps scaled down to the ε r movement limit
  long pairs_tested = 0;   ///< contact pairs given the hierarchical sphere test
  long pairs_skipped = 0;  ///< pairs skipped because every point stayed inside its safe bound
  long sphere_tests = 0;   ///< sphere-against-sphere tests over the step
  long finest_hits = 0;    ///< pairs whose spheres still met at the finest level
  long halvings = 0;       ///< rounds that halved the moves of such pairs' points
  long held_points = 0;    ///< points held in place for a step after the halvings ran out
};

/// The pull-through guard (Yuksel 2012 §6.3, Leaf 2018 eq. 2): takes a proposed displacement of every
/// control point and returns one no yarn can pass through another with. First every point's movement is
/// limited to ε r, so only pairs already in contact can pass through each other; for those (the contact
/// pairs), bounding spheres of both segments swept over the step are tested and refined hierarchically; a hit
/// at the finest level halves the moves of the hit pair's points (the rest of the yarn keeps its whole step,
/// so one jammed pair does not slow the whole garment); after `max_halvings`, the points of pairs still hit
/// stay put for this step. Pairs that come through clean leave safe movement bounds (Yuksel eqs. 8–10) that
/// let later steps skip them while their points stay inside.
class PullThroughGuard {
public:
  /// `groups`: per point a group id or -1; holding one point of a group holds the whole group (boundary loops
  /// whose sum of positions is constrained).
  PullThroughGuard(const YarnSystem& system, const GuardOptions& options, std::vector<int> groups = {});

  /// A new pair set (after the contact cache is rebuilt): every pair is tested again. Pairs of one piece of
  /// yarn (YarnSystem::adjacent) are left out.
  void reset(const ContactPairs& pairs);
  /// From the next reset on, only pairs with at least one segment marked here are tested (a periodic patch's
  /// periodic_tested_segments: one copy of each pair); empty: every pair.
  void restrict_to(std::vector<char> segments);
  /// Makes `delta` [mm] safe to add to `points` in place; returns at most the smallest factor a point's move
  /// was scaled by (1 when untouched, 0 when only held points would have moved).
  double accept(const Eigen::Matrix3Xd& points, Eigen::Matrix3Xd& delta);

  const GuardCounters& counters() const { return m_counters; }
  void set_counters(const GuardCounters& counters) { m_counters = counters; }

private:
  struct PairState {
    int a = 0, b = 0;
    double budget = -1;          ///< safe movement left for every one of the pair's points; < 0: none
    double travel[8] = {};       ///< the points' travel when the budget was set
  };
  /// The hierarchical sphere test of one pair over the step; the smallest end gap of clean pieces goes to
  /// `gap` (for the safe bound). Returns true when the finest level still meets.
  bool pieces_meet(const PairState& pair, const Eigen::Matrix3Xd& points, const Eigen::Matrix3Xd& delta, double& gap, long& tests) const;
  /// The segments' whole spheres swept over the step (the hierarchical test's first level), into m_swept: a
  /// segment has some twenty partners, and most pairs are clean at that level. Only the `changed` segments
  /// (all when it is empty).
  void sweep_segments(const Eigen::Matrix3Xd& points, const Eigen::Matrix3Xd& delta, const std::vector<char>& changed);
  bool skip(const PairState& pair, const Eigen::VectorXd& move) const;

  const YarnSystem& m_system;
  GuardOptions m_options;
  std::vector<int> m_groups;
  std::vector<char> m_tested;    ///< per segment: pairs with none of their two marked are left out; empty: none left out
  std::vector<PairState> m_pairs;
  std::vector<double> m_travel;  ///< per point: total distance moved [mm]
  std::vector<model::SweptSphere<double>> m_swept;  ///< per segment, this round's (sweep_segments)
  GuardCounters m_counters;
};

}  // namespace skein::relax
