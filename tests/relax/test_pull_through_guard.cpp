// The pull-through guard (Yuksel 2012 §6.3, eqs. 8-10): its policy, its halvings and holds.
#include <gtest/gtest.h>

#include "relax/guard_model.hpp"
#include "relax/pull_through_guard.hpp"
#include "relax/yarn_audit.hpp"
#include "relax/yarn_relax.hpp"
#include "testing.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;
using Eigen::Vector3d;
using skein::testing::curve_points;

TEST(PullThroughGuard, StopsARingDraggedThroughAnother) {
  const auto yarn = skein::testing::linked_rings();
  const auto system = make_yarn_system(yarn);
  GuardOptions options;
  options.max_move = 1.0;
  PullThroughGuard guard(system, options);
  Eigen::Matrix3Xd points = system.points;
  long crossings = 0;
  TopologyAuditor auditor(system);
  for (int step = 0; step < 200; ++step) {  // keep pushing ring B across ring A's yarn
    Eigen::Matrix3Xd delta = Eigen::Matrix3Xd::Zero(3, system.num_points());
    for (int p = yarn.curve_start[1]; p < yarn.curve_start[2]; ++p) delta(0, p) = 0.5;
    guard.reset(find_contact_pairs(system, points, 4 * system.radius));
    guard.accept(points, delta);
    crossings += static_cast<long>(auditor.crossings(points, points + delta).size());
    points += delta;
  }
  EXPECT_EQ(crossings, 0);
  EXPECT_GT(guard.counters().finest_hits, 0);
  const auto moved = with_points(yarn, points);
  EXPECT_NEAR(std::abs(linking_number(curve_points(moved, 0), curve_points(moved, 1))), 1.0, 1e-6);
}

TEST(PullThroughGuard, AJammedPairSlowsOnlyItsOwnPoints) {
  // Ring B pushed across ring A's yarn jams against it; ring C, far from both, moves as far each step and keeps
  // its whole move: the halvings and holds are the jammed pairs' points' only.
  auto yarn = skein::testing::linked_rings();
  skein::testing::add_ring(yarn, {0, 40, 0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 3, 24);
  const auto system = make_yarn_system(yarn);
  GuardOptions options;
  options.max_move = 1.0;
  PullThroughGuard guard(system, options);
  TopologyAuditor auditor(system);
  Eigen::Matrix3Xd points = system.points;
  const double push = options.max_move * system.radius;  // at the movement limit, so no step is rate-limited
  long jammed = 0, crossings = 0;
  for (int step = 0; step < 100; ++step) {
    Eigen::Matrix3Xd delta = Eigen::Matrix3Xd::Zero(3, system.num_points());
    for (int p = yarn.curve_start[1]; p < yarn.curve_start[3]; ++p) delta(0, p) = push;
    guard.reset(find_contact_pairs(system, points, 4 * system.radius));
    const long hits = guard.counters().finest_hits;
    guard.accept(points, delta);
    for (int p = yarn.curve_start[2]; p < yarn.curve_start[3]; ++p) ASSERT_EQ(delta(0, p), push) << "step " << step;
    if (guard.counters().finest_hits > hits) {
      ++jammed;
      EXPECT_LT(delta.middleCols(yarn.curve_start[1], yarn.curve_size(1)).row(0).minCoeff(), push);
    }
    crossings += static_cast<long>(auditor.crossings(points, points + delta).size());
    points += delta;
  }
  EXPECT_GT(jammed, 0);
  EXPECT_GT(guard.counters().halvings, 0);
  EXPECT_EQ(crossings, 0);
}

TEST(PullThroughGuard, HeldYarnsThatHoldOthersPastTheHoldRoundsHoldTheWholeStep) {
  // A stack of straight yarns 0.15 mm apart, the lowest still and the others pushed down 0.2 mm: each held yarn
  // leaves the one above it hitting it, one guard round later. A ring far away keeps its whole move while the
  // holds settle the stack within kGuardHoldRounds rounds; past them every point is held (GuardRound::HoldAll,
  // the CUDA guard's policy too).
  for (const int yarns : {4, 6}) {
    SCOPED_TRACE(yarns);
    relax::YarnCurves yarn;
    yarn.radius = 0.5;
    yarn.curve_start = {0};
    for (int k = 0; k < yarns; ++k) {
      for (int i = 0; i < 12; ++i) {
        yarn.points.emplace_back(i, 0, 0.15 * k);
        yarn.point_face.push_back(-1);
        yarn.point_type.push_back(-1);
      }
      yarn.curve_start.push_back(static_cast<int>(yarn.points.size()));
      yarn.closed.push_back(0);
    }
    skein::testing::add_ring(yarn, {0, 40, 0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 3, 24);
    const auto system = make_yarn_system(yarn);
    GuardOptions options;
    options.max_move = 1.0;
    options.max_halvings = 0;
    PullThroughGuard guard(system, options);
    guard.reset(find_contact_pairs(system, system.points, 4 * system.radius));
    Eigen::Matrix3Xd delta = Eigen::Matrix3Xd::Zero(3, system.num_points());
    for (int p = yarn.curve_start[1]; p < system.num_points(); ++p) delta(2, p) = -0.2;
    guard.accept(system.points, delta);
    const auto ring = delta.middleCols(yarn.curve_start[yarns], yarn.curve_size(yarns));
    if (yarns == 1 + model::kGuardHoldRounds) {
      EXPECT_TRUE(delta.middleCols(yarn.curve_start[1], yarn.curve_start[yarns] - yarn.curve_start[1]).isZero());
      EXPECT_TRUE((ring.row(2).array() == -0.2).all());
    } else {
      EXPECT_TRUE(delta.isZero());
      EXPECT_EQ(guard.counters().held_points, system.num_points() - yarn.curve_start[1]);
    }
    EXPECT_EQ(TopologyAuditor(system).crossings(system.points, system.points + delta).size(), 0u);
  }
}

TEST(PullThroughGuard, ARoundsActionIsHalveThenHoldThenHoldAll) {
  using model::GuardRound;
  EXPECT_EQ(model::guard_round(0, 0, 2), GuardRound::Done);
  EXPECT_EQ(model::guard_round(0, 5, 2), GuardRound::Halve);
  EXPECT_EQ(model::guard_round(1, 5, 2), GuardRound::Halve);
  EXPECT_EQ(model::guard_round(2, 5, 2), GuardRound::Hold);
  EXPECT_EQ(model::guard_round(1 + model::kGuardHoldRounds, 5, 2), GuardRound::Hold);
  EXPECT_EQ(model::guard_round(2 + model::kGuardHoldRounds, 5, 2), GuardRound::HoldAll);
  EXPECT_EQ(model::guard_round(9, 0, 2), GuardRound::Done);
}
