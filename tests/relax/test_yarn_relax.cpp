// The yarn relaxer: the pull-through guard, the independent auditor, shape preservation, convergence on
// knitted pieces, checkpoints and determinism.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <atomic>

#include <fstream>
#include <set>

#include <omp.h>

#include "common/error.hpp"
#include "relax/guard_model.hpp"
#include "relax/pull_through_guard.hpp"
#include "relax/yarn_audit.hpp"
#include "relax/yarn_checkpoint.hpp"
#include "relax/yarn_relax.hpp"
#include "stitchmesh/pattern.hpp"
#include "workflow/yarn_options.hpp"
#include "workflow/yarn_periodic.hpp"
#include "workflow/yarn_settings.hpp"
#include "testing.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;
using namespace skein::workflow;
using Eigen::Vector3d;

namespace {

std::vector<Vector3d> curve_points(const relax::YarnCurves& y, int c) {
  return {y.points.begin() + y.curve_start[c], y.points.begin() + y.curve_start[c + 1]};
}

struct Run {
  YarnState state;
  YarnRelaxReport report;
};

Run relaxed(const YarnSystem& system, const YarnRelaxOptions& options, const ShapeTargets& targets = {}) {
  Run run{initial_state(system, options), {}};
  run.report = make_cpu_yarn_relaxer(system, targets, options)->run(run.state);
  return run;
}

/// Two linked rings whose yarn is given only 30% of its length: they pull tight against each other.
YarnRelaxOptions squeeze_options() {
  YarnRelaxOptions o;
  o.max_steps = 400;
  o.tolerance = 0;
  o.guard.max_move = 1.0;  // the largest steps the guard allows
  o.contact_margin = 2.0;
  return o;
}

}  // namespace

TEST(YarnAudit, LinkingNumbersOfLinkedAndSeparateRings) {
  const auto linked = skein::testing::linked_rings();
  EXPECT_NEAR(std::abs(linking_number(curve_points(linked, 0), curve_points(linked, 1))), 1.0, 1e-9);
  auto apart = linked;
  for (int p = apart.curve_start[1]; p < apart.curve_start[2]; ++p) apart.points[p].z() += 10;
  EXPECT_NEAR(linking_number(curve_points(apart, 0), curve_points(apart, 1)), 0.0, 1e-9);
  const auto all = linking_numbers(linked);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(std::abs(all[0].number), 1);
}

TEST(YarnAudit, LinkingNumbersSeeARingHookedCloserThanFourSamplesASegmentResolve) {
  // A: a closed Catmull-Rom curve through the four corners of a diamond (a rounded square, 5 mm). B: a ring of
  // radius 0.02 mm around A's curve where four samples a segment cut the corner by three times that, so B
  // hooks the curve but not the coarse polyline; the fixed 4-sample rule called this pair unlinked.
  relax::YarnCurves y;
  y.radius = 0.3;
  y.points = {{5, 0, 0}, {0, 5, 0}, {-5, 0, 0}, {0, -5, 0}};
  const auto cr = [](const Vector3d& p0, const Vector3d& p1, const Vector3d& p2, const Vector3d& p3, double t) {
    const double t2 = t * t, t3 = t2 * t;
    return Vector3d(0.5 * ((-t3 + 2 * t2 - t) * p0 + (3 * t3 - 5 * t2 + 2) * p1 + (-3 * t3 + 4 * t2 + t) * p2 + (t3 - t2) * p3));
  };
  const auto& P = y.points;
  const Vector3d centre = cr(P[3], P[0], P[1], P[2], 0.625), before = cr(P[3], P[0], P[1], P[2], 0.5), after = cr(P[3], P[0], P[1], P[2], 0.75);
  ASSERT_GT((centre - 0.5 * (before + after)).norm(), 0.06);  // the coarse polyline passes 0.06 mm and more away
  const Vector3d tangent = (after - before).normalized(), u = tangent.unitOrthogonal(), v = tangent.cross(u);
  for (int k = 0; k < 8; ++k) {
    const double a = 2 * M_PI * k / 8;
    y.points.push_back(centre + 0.02 * (std::cos(a) * u + std::sin(a) * v));
  }
  y.curve_start = {0, 4, 12};
  y.closed = {1, 1};
  y.point_face.assign(y.points.size(), -1);
  std::vector<Vector3d> coarse;  // A as the fixed rule sampled it: four samples a segment
  for (int k = 0; k < 4; ++k)
    for (int m = 0; m < 4; ++m) coarse.push_back(cr(P[(k + 3) % 4], P[k], P[(k + 1) % 4], P[(k + 2) % 4], m / 4.0));
  EXPECT_NEAR(linking_number(coarse, curve_points(y, 1)), 0.0, 1e-9);
  const auto links = linking_numbers(y);
  ASSERT_EQ(links.size(), 1u);
  EXPECT_EQ(std::abs(links[0].number), 1);
  // Moved off the curve by 0.3 mm (outside the corner), the ring is free: 0.
  for (int p = 4; p < 12; ++p) y.points[p] += 0.3 * (centre - 0.5 * (before + after)).normalized();
  EXPECT_EQ(linking_numbers(y)[0].number, 0);
}

TEST(YarnAudit, AuditorCountsARingPulledThroughAnother) {
  const auto yarn = skein::testing::linked_rings();
  const auto system = make_yarn_system(yarn);
  Eigen::Matrix3Xd after = system.points;
  for (int p = yarn.curve_start[1]; p < yarn.curve_start[2]; ++p) after(0, p) += 8;  // drag ring B off ring A
  EXPECT_GT(TopologyAuditor(system).crossings(system.points, after).size(), 0u);
  Eigen::Matrix3Xd lifted = system.points;
  for (int p = yarn.curve_start[1]; p < yarn.curve_start[2]; ++p) lifted(1, p) += 0.1;  // a small slide
  EXPECT_TRUE(TopologyAuditor(system).crossings(system.points, lifted).empty());
}

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

TEST(RunControl, StopReasonsWinInOneOrderRollbacksRunOutAndCheckpointsComeOnTime) {
  // The policy both back-ends share (the CPU loop and the GPU's batches).
  YarnRelaxOptions options;
  options.max_steps = 100;
  options.checkpoint_every = 25;
  RunControl control(options);
  EXPECT_EQ(control.stop(100, true, true, true, true), StopReason::Converged);
  EXPECT_EQ(control.stop(100, false, true, true, true), StopReason::StepCap);
  EXPECT_EQ(control.stop(99, false, true, true, true), StopReason::TimeCap);
  EXPECT_EQ(control.stop(99, false, false, true, true), StopReason::Interrupted);
  EXPECT_EQ(control.stop(99, false, false, false, true), StopReason::Jammed);
  EXPECT_EQ(control.stop(99, false, false, false, false), StopReason::None);
  EXPECT_FALSE(control.out_of_time());  // no time cap
  EXPECT_FALSE(control.interrupted());
  for (int k = 0; k < RunControl::kMaxRollbacks; ++k) EXPECT_TRUE(control.roll_back());
  EXPECT_FALSE(control.roll_back());
  control.step_taken();
  EXPECT_TRUE(control.roll_back());
  EXPECT_TRUE(control.checkpoint_due(50));
  EXPECT_FALSE(control.checkpoint_due(51));
  options.max_seconds = 1e-9;
  std::atomic<bool> stop{true};
  options.interrupt = &stop;
  const RunControl capped(options);
  EXPECT_TRUE(capped.out_of_time());
  EXPECT_TRUE(capped.interrupted());
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

TEST(YarnRelax, AKnitPulledTightWithWeakContactsUnhooksStitchesWithoutTheGuardAndTheAuditorSeesIt) {
  // Issue 27's negative control on knitting: stockinette given half its yarn and a contact a thousandth as stiff,
  // so the loops pull through one another unless the guard stops them. Unguarded, the per-step auditor counts
  // the crossings; guarded, the same run has none.
  const auto k = skein::testing::knitted(models::swatch(), "");
  const auto system = make_yarn_system(k.yarn, 0.5);
  YarnRelaxOptions options;
  options.max_steps = 300;
  options.tolerance = 0;
  options.audit = true;
  options.params.k_contact = 0.05;
  options.guard.max_move = 1.0;
  options.contact_margin = 2.0;
  options.guard.enabled = false;
  const auto unguarded = relaxed(system, options);
  EXPECT_GT(unguarded.report.pull_through_events, 0);
  options.guard.enabled = true;
  const auto guarded = relaxed(system, options);
  EXPECT_EQ(guarded.report.pull_through_events, 0);
  EXPECT_GT(guarded.report.guard.finest_hits, 0);  // the guard had pulls to stop
}

TEST(YarnRelax, SqueezedLinkedRingsStayLinkedWithTheGuard) {
  const auto yarn = skein::testing::linked_rings();
  const auto system = make_yarn_system(yarn, 0.3);
  const auto run = relaxed(system, squeeze_options());
  EXPECT_EQ(run.report.pull_through_events, 0);
  const auto out = with_points(yarn, run.state.points);
  EXPECT_NEAR(std::abs(linking_number(curve_points(out, 0), curve_points(out, 1))), 1.0, 1e-6);
  // They did pull tight: the rings shrank well below their 3 mm start.
  EXPECT_LT((out.points[0] - out.points[12]).norm(), 4.0);
}

TEST(YarnRelax, TheRelaxersEnergyAtAStateIsTheEnergyItsRunEndsWithThere) {
  // relaxer_energy prices a state (a stand-in, a preview) as a relaxation does: at a relaxation's last state
  // it gives that run's energy, and the emitted state costs more.
  const auto yarn = skein::testing::linked_rings();
  const auto system = make_yarn_system(yarn, 0.3);
  const auto options = squeeze_options();
  const auto run = relaxed(system, options);
  EXPECT_NEAR(relaxer_energy(system, {}, options, run.state.points), run.report.energy, 1e-9 * std::abs(run.report.energy));
  EXPECT_GT(relaxer_energy(system, {}, options, system.points), run.report.energy);
}

TEST(JamWatch, AJamIsStepsOfHeldPointsOverWhichTheEnergyHardlyFalls) {
  JamWatch watch(10, 1e-4);
  double energy = 1000;
  // Relaxing with points held: the energy falls 0.1 % a step, far more than 10⁻⁴ over ten steps.
  for (int step = 0; step < 50; ++step, energy *= 0.999) EXPECT_FALSE(watch.jammed(energy, 5)) << step;
  // Creeping with points held: ten steps in a row are a jam, not nine.
  for (int step = 0; step < 9; ++step, energy *= 1 - 1e-6) EXPECT_FALSE(watch.jammed(energy, 5)) << step;
  EXPECT_TRUE(watch.jammed(energy, 5));
  EXPECT_NE(watch.describe().find("5 points on the last"), std::string::npos) << watch.describe();
  // A step that holds nothing starts the count again; so does a window that fell enough.
  JamWatch again(10, 1e-4);
  for (int step = 0; step < 30; ++step) EXPECT_FALSE(again.jammed(energy, step % 7 == 6 ? 0 : 3)) << step;
  // Off.
  JamWatch off(0, 1e-4);
  for (int step = 0; step < 30; ++step) EXPECT_FALSE(off.jammed(energy, 3));
}

TEST(YarnRelax, LinkedRingsSqueezedTightJamAndTheRunSaysSo) {
  // Two linked rings given a tenth of their yarn: they pull against each other until the guard holds them, and
  // the energy stops falling. The run ends jammed, not converged, well before its cap, with nothing passed
  // through; with the rule off it runs on to the cap.
  const auto yarn = skein::testing::linked_rings();
  const auto system = make_yarn_system(yarn, 0.1);
  auto options = squeeze_options();
  options.max_steps = 4000;
  options.jam_steps = 50;
  const auto run = relaxed(system, options);
  EXPECT_EQ(run.report.stopped_by, StopReason::Jammed);
  EXPECT_FALSE(run.report.converged);
  EXPECT_LT(run.report.steps, options.max_steps);
  EXPECT_GT(run.report.guard.held_points, 0);
  EXPECT_EQ(run.report.pull_through_events, 0);
  options.jam_steps = 0;
  options.max_steps = run.report.steps + 50;
  EXPECT_EQ(relaxed(system, options).report.stopped_by, StopReason::StepCap);
}

TEST(YarnRelax, AClippedStopScaleRelaxesPastAKink) {
  // Thirty rings far apart (2,160 points), one point of one pulled out into a kink: its forces dominate
  // |∇E_0|, so Leaf's relative rule is met once the kink has eased. Clipped, the scale leaves the largest 0.1 %
  // of the forces (2) out and the run relaxes the rings further.
  relax::YarnCurves yarn;
  yarn.radius = 0.5;
  for (int k = 0; k < 30; ++k) skein::testing::add_ring(yarn, {10.0 * k, 0, 0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 3, 72);
  yarn.points[0].x() += 1.5;
  const auto system = make_yarn_system(yarn);
  YarnRelaxOptions options;
  const auto leaf = relaxed(system, options);
  options.clipped_scale = true;
  const auto clipped = relaxed(system, options);
  ASSERT_TRUE(leaf.report.converged && clipped.report.converged) << leaf.report.stopped_by << " " << clipped.report.stopped_by;
  EXPECT_GT(leaf.report.first_residual_peak, 0.5);
  EXPECT_GT(clipped.report.steps, leaf.report.steps);
  EXPECT_LT(clipped.report.energy, leaf.report.energy);
  std::printf("Leaf's scale: %ld steps, energy %.6g; clipped: %ld steps, energy %.6g\n", leaf.report.steps, leaf.report.energy, clipped.report.steps,
              clipped.report.energy);
}

TEST(YarnRelax, WithoutTheGuardAndWithOversizedStepsTheAuditorSeesThePassThrough) {
  const auto yarn = skein::testing::linked_rings();
  const auto system = make_yarn_system(yarn, 0.3);
  auto options = squeeze_options();
  options.guard.enabled = false;
  options.guard.max_move = 8.0;  // steps of 4 mm: far more than the yarn is thick
  options.contact_margin = 16.0;
  options.time_step = 0.2;
  options.fire_max_step = 1.0;
  const auto run = relaxed(system, options);
  const auto out = with_points(yarn, run.state.points);
  EXPECT_GT(run.report.pull_through_events, 0);
  EXPECT_NEAR(linking_number(curve_points(out, 0), curve_points(out, 1)), 0.0, 1e-6);
}

TEST(YarnRelax, AFirstResidualFromAFewSpotsIsReported) {
  YarnRelaxOptions options;
  options.max_steps = 0;  // the first evaluation only
  // A swatch's emitted yarn spreads its first force over the whole yarn ...
  const auto swatch = skein::testing::knitted(models::swatch(), "rib");
  const auto spread = relaxed(swatch.system, options, swatch.targets);
  EXPECT_GE(spread.report.first_residual_peak, 0.0);
  EXPECT_LT(spread.report.first_residual_peak, 0.1);
  // ... the mitten's, tessellated and not relaxed on its surface, has a few spots where it doubles back on itself,
  // whose bending forces make most of it: Leaf's relative stop rule is then set by them.
  const auto mitten = skein::testing::knitted(models::mitten(), "");
  const auto peaked = relaxed(mitten.system, options, mitten.targets);
  EXPECT_GT(peaked.report.first_residual_peak, 0.5);
  // A state that brings its own scale has no first residual of its own.
  auto state = peaked.state;
  EXPECT_EQ(make_cpu_yarn_relaxer(mitten.system, mitten.targets, options)->run(state).first_residual_peak, -1.0);
}

TEST(YarnRelax, KnitPurlSwatchConvergesWithoutPullThrough) {
  const auto [piece, yarn, system, targets] = skein::testing::knitted(models::swatch(), "rib");
  EXPECT_FALSE(targets.boundary_loops.empty());
  EXPECT_FALSE(targets.patches.empty());
  YarnRelaxOptions options;
  const auto run = relaxed(system, options, targets);
  EXPECT_TRUE(run.report.converged) << run.report.stopped_by << " residual " << run.report.residual;
  EXPECT_EQ(run.report.pull_through_events, 0);
  Eigen::Matrix3Xd gradient;
  EXPECT_LT(run.report.energy, yarn_energy(system, options.params, find_contact_pairs(system, system.points, system.radius), system.points, gradient));
  // Eq. 5 held: every border loop's sum of positions is where it started.
  for (const auto& loop : targets.boundary_loops) {
    Vector3d before = Vector3d::Zero(), after = Vector3d::Zero();
    for (int p : loop) {
      before += system.points.col(p);
      after += run.state.points.col(p);
    }
    EXPECT_LT((after - before).norm(), 1e-9 * loop.size());
  }
}

TEST(YarnRelax, RibbedTubeConvergesWithoutPullThrough) {
  const auto k = skein::testing::knitted(models::tube(), "rib", {12, 10});
  const auto run = relaxed(k.system, {}, k.targets);
  EXPECT_TRUE(run.report.converged) << run.report.stopped_by << " residual " << run.report.residual;
  EXPECT_EQ(run.report.pull_through_events, 0);
}

TEST(YarnRelax, EulerStaysUnderTheStepBoundAndLowersTheEnergy) {
  const auto system = skein::testing::knitted(models::swatch(), "").system;
  YarnRelaxOptions options;
  options.method = YarnMethod::Euler;
  options.max_steps = 150;
  auto state = initial_state(system, options);
  double first = -1, last = 0, largest = 0;
  make_cpu_yarn_relaxer(system, {}, options)->run(state, [&](const YarnStepLog& s) {
    if (first < 0) first = s.energy;
    last = s.energy;
    largest = std::max(largest, s.moved);
  });
  EXPECT_LT(last, first);
  EXPECT_LE(largest, options.guard.max_move * system.radius * (1 + 1e-9));
}

TEST(YarnRelax, RunsAreDeterministicForAnyThreadCount) {
  const auto [piece, yarn, system, targets] = skein::testing::knitted(models::swatch(), "seed");
  YarnRelaxOptions options;
  options.max_steps = 60;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto one = relaxed(system, options, targets);
  omp_set_num_threads(std::max(2, threads));
  const auto two = relaxed(system, options, targets);
  omp_set_num_threads(threads);
  EXPECT_EQ(one.state.points, two.state.points);
  EXPECT_EQ(one.report.guard.pairs_tested, two.report.guard.pairs_tested);
}

TEST(YarnCheckpoint, ResumeEqualsAnUninterruptedRun) {
  skein::testing::ScratchDir dir;
  const auto [piece, yarn, system, targets] = skein::testing::knitted(models::swatch(), "rib");
  for (const auto method : {YarnMethod::Fire, YarnMethod::Lbfgs}) {
    SCOPED_TRACE(to_string(method));
    YarnRelaxOptions options;
    options.method = method;
    options.max_steps = 70;
    options.tolerance = 0;
    options.checkpoint = dir / "run.ckp";
    options.checkpoint_every = 25;
    const auto whole = relaxed(system, options, targets);
    ASSERT_EQ(whole.report.steps, 70);
    // Interrupted at step 50 (the cap stands in for a killed job: the last checkpoint is from step 50), then resumed.
    options.checkpoint = dir / "part.ckp";
    options.max_steps = 50;
    relaxed(system, options, targets);
    auto state = read_checkpoint(options.checkpoint, checkpoint_fingerprint(system, options.method), system.num_points());
    EXPECT_EQ(state.step, 50);
    options.max_steps = 70;
    const auto report = make_cpu_yarn_relaxer(system, targets, options)->run(state);
    EXPECT_EQ(report.steps, 70);
    EXPECT_EQ(state.points, whole.state.points);
    EXPECT_EQ(state.velocities, whole.state.velocities);
    EXPECT_EQ(report.guard.pairs_tested, whole.report.guard.pairs_tested);
    // A run stopped by its cap leaves its last state behind.
    EXPECT_EQ(read_checkpoint(options.checkpoint, checkpoint_fingerprint(system, options.method), system.num_points()).step, 70);
  }
}

TEST(YarnRelax, AnInterruptedRunGoesOnFromItsState) {
  const auto [piece, yarn, system, targets] = skein::testing::knitted(models::swatch(), "rib");
  std::atomic<bool> interrupt{false};
  YarnRelaxOptions options;
  options.interrupt = &interrupt;
  const auto relaxer = make_cpu_yarn_relaxer(system, targets, options);
  auto state = initial_state(system, options);
  const auto paused = relaxer->run(state, [&](const YarnStepLog& log) {
    if (log.step == 12) interrupt = true;
  });
  EXPECT_EQ(paused.stopped_by, StopReason::Interrupted);
  EXPECT_FALSE(paused.converged);
  EXPECT_EQ(state.step, 12);
  interrupt = false;
  const auto finished = relaxer->run(state);
  EXPECT_TRUE(finished.converged) << finished.stopped_by;
  EXPECT_GT(state.step, 12);
  EXPECT_EQ(finished.pull_through_events, 0);
}

TEST(YarnCheckpoint, DamagedOrForeignCheckpointsAreRejected) {
  skein::testing::ScratchDir dir;
  const auto yarn = skein::testing::linked_rings();
  const auto system = make_yarn_system(yarn);
  YarnRelaxOptions options;
  const auto fingerprint = checkpoint_fingerprint(system, options.method);
  const auto path = dir / "good.ckp";
  write_checkpoint(path, fingerprint, initial_state(system, options));
  EXPECT_NO_THROW(read_checkpoint(path, fingerprint, system.num_points()));
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto error_for = [&](const std::string& name, const std::string& content, std::uint64_t fp) {
    const auto p = dir.write(name, content);
    return skein::testing::error_of([&] { read_checkpoint(p, fp, system.num_points()); });
  };
  std::string flipped = bytes;
  flipped[200] ^= 0x10;
  EXPECT_NE(error_for("flipped.ckp", flipped, fingerprint).find("checksum does not match"), std::string::npos);
  EXPECT_NE(error_for("short.ckp", bytes.substr(0, bytes.size() / 2), fingerprint).find("damaged or truncated"), std::string::npos);
  EXPECT_NE(error_for("tiny.ckp", bytes.substr(0, 10), fingerprint).find("truncated"), std::string::npos);
  EXPECT_NE(error_for("text.ckp", "hello, this is not a checkpoint at all", fingerprint).find("not a skein checkpoint"), std::string::npos);
  EXPECT_NE(error_for("other.ckp", bytes, checkpoint_fingerprint(system, YarnMethod::Euler)).find("another yarn or method"), std::string::npos);
  const auto missing = skein::testing::error_of([&] { read_checkpoint(dir / "none.ckp", fingerprint, system.num_points()); });
  EXPECT_NE(missing.find("none.ckp"), std::string::npos);
  EXPECT_NE(error_for("flipped.ckp", flipped, fingerprint).find("flipped.ckp"), std::string::npos);
}

TEST(YarnRelax, AStateThatIsNotFiniteIsRolledBackAndReportedAsDiverged) {
  const auto system = make_yarn_system(skein::testing::linked_rings());
  YarnRelaxOptions options;
  auto state = initial_state(system, options);
  state.points(0, 3) = std::nan("");
  const auto report = make_cpu_yarn_relaxer(system, {}, options)->run(state);
  EXPECT_EQ(report.stopped_by, StopReason::Diverged);
  EXPECT_GT(report.rollbacks, 0);
  EXPECT_FALSE(report.converged);
}

TEST(YarnRelax, OptionsAreValidated) {
  YarnRelaxOptions o;
  o.params.k_contact = 0;
  EXPECT_NE(skein::testing::error_of([&] { o.validate(); }).find("k_contact must be positive"), std::string::npos);
  o = {};
  o.guard.max_move = 0;
  EXPECT_NE(skein::testing::error_of([&] { o.validate(); }).find("movement limit"), std::string::npos);
  o = {};
  o.checkpoint_every = 10;
  EXPECT_NE(skein::testing::error_of([&] { o.validate(); }).find("needs a checkpoint file"), std::string::npos);
  EXPECT_NE(skein::testing::error_of([] { parse_yarn_method("newton"); }).find("expected euler, fire or lbfgs"), std::string::npos);
}

namespace {
/// RMS distance [r] between the periodic patch's real points and the matching points of the centre repeat of
/// a 5 x 5 tiling relaxed with free borders, the common translation removed. (A repeat of one row makes a
/// tiling of five rows whose centre row feels the cast-on and bind-off: 2x2 rib written as one row differs by
/// 0.15 r, written as two rows by 0.03 r.)
double periodic_against_tiled(const std::string& text) {
  const auto pattern = mesh::parse_pattern(text, "test.knit");
  const auto& library = mesh::StitchLibrary::bundled();
  const double r = 0.6;
  auto patch = periodic_patch(pattern, library, {}, r);
  ShapeTargets periodic_targets;
  periodic_targets.periodic = patch.map;
  const auto periodic_system = make_yarn_system(patch.yarn);
  YarnRelaxOptions options;
  options.audit = false;
  const auto periodic = relaxed(periodic_system, options, periodic_targets);
  EXPECT_TRUE(periodic.report.converged) << periodic.report.stopped_by;

  const auto stitch = mesh::pattern_stitch_mesh(pattern, 5, 5);
  mesh::EmitOptions emit;
  emit.yarn_radius = r;
  const auto yarn = mesh::emit_yarn(stitch, library, emit);
  const auto tiled_system = make_yarn_system(yarn);
  const auto tiled = relaxed(tiled_system, options);
  EXPECT_TRUE(tiled.report.converged) << tiled.report.stopped_by;

  const auto difference = centre_repeat_difference(patch, periodic.state.points, yarn, tiled.state.points, 5);
  EXPECT_EQ(difference.points, std::count(patch.ring.begin(), patch.ring.end(), 0));
  return difference.rms / r;
}
}  // namespace

TEST(YarnPeriodic, VirtualPointsFollowTheirRealPointsAndFrozenOnesStay) {
  const auto pattern = mesh::parse_pattern("format knit\np k\nk p\n", "seed.knit");
  auto patch = periodic_patch(pattern, mesh::StitchLibrary::bundled(), {}, 0.6);
  EXPECT_EQ(patch.tiles, 5);
  const long real = std::count(patch.ring.begin(), patch.ring.end(), 0);
  EXPECT_EQ(static_cast<long>(patch.map.virtual_points.size()), 8 * real);  // one ring of 8 repeats, every point matched
  ShapeTargets targets;
  targets.periodic = patch.map;
  const auto system = make_yarn_system(patch.yarn);
  YarnRelaxOptions options;
  options.max_steps = 40;
  const auto run = relaxed(system, options, targets);
  EXPECT_EQ(run.report.pull_through_events, 0);
  for (size_t i = 0; i < patch.map.virtual_points.size(); ++i) {
    const Eigen::Vector3d expected = run.state.points.col(patch.map.real_points[i]) + patch.map.offsets[i];
    EXPECT_LT((run.state.points.col(patch.map.virtual_points[i]) - expected).norm(), 1e-9);
  }
  for (int p : patch.map.frozen) EXPECT_EQ(run.state.points.col(p), system.points.col(p));
  EXPECT_GT((run.state.points - system.points).cwiseAbs().maxCoeff(), 0.01);  // the real points did move
}

TEST(YarnPeriodic, PeriodicPatchAgreesWithTheCentreOfATiledRelaxation) {
  const double seed = periodic_against_tiled("format knit\np k\nk p\n");
  const double rib = periodic_against_tiled("format knit\nk k p p\nk k p p\n");
  std::printf("periodic against the centre of a 5 x 5 tiling, RMS: seed %.4f r, 2x2 rib %.4f r\n", seed, rib);
  EXPECT_LT(seed, 0.05);
  EXPECT_LT(rib, 0.05);
}

TEST(YarnPeriodic, EveryBundledPatternConvergesWithoutPullThrough) {
  int patterns = 0;
  for (const auto& entry : std::filesystem::directory_iterator(SKEIN_PATTERNS_DIR)) {
    const auto ext = entry.path().extension();
    if (ext != ".knit" && ext != ".weave") continue;
    SCOPED_TRACE(entry.path().filename().string());
    const auto pattern = mesh::read_pattern(entry.path());
    auto patch = pattern.format == mesh::PatternFormat::Woven ? periodic_woven_patch(pattern, 2.4, 0.6)
                                                               : periodic_patch(pattern, mesh::StitchLibrary::bundled(), {}, 0.6);
    ShapeTargets targets;
    targets.periodic = patch.map;
    const auto run = relaxed(make_yarn_system(patch.yarn), {}, targets);
    EXPECT_TRUE(run.report.converged) << run.report.stopped_by;
    EXPECT_EQ(run.report.pull_through_events, 0);
    ++patterns;
  }
  EXPECT_GE(patterns, 28);
}

TEST(YarnPeriodic, RadiusScalingMatchesThePhysicalModel) {
  // Leaf 2018 §6.2: relax at gamma r with the stiffnesses of eq. 4, scale by 1/gamma; against the physical
  // model itself: the same start scaled by 1/gamma (so 1/gamma of the yarn length) at radius r.
  const double r = 0.6, gamma = 1.25;
  const auto pattern = mesh::parse_pattern("format knit\np k\nk p\n", "seed.knit");
  const auto scaled = periodic_patch(pattern, mesh::StitchLibrary::bundled(), {}, gamma * r);
  auto physical = scaled;
  for (auto& p : physical.yarn.points) p /= gamma;
  physical.yarn.radius = r;
  for (auto& d : physical.map.offsets) d /= gamma;
  YarnRelaxOptions options;
  options.audit = false;
  options.tolerance = 1e-3;
  ShapeTargets a, b;
  a.periodic = scaled.map;
  b.periodic = physical.map;
  auto scaled_options = options;
  scaled_options.params = radius_scaled(options.params, gamma);
  const auto system_a = make_yarn_system(scaled.yarn), system_b = make_yarn_system(physical.yarn);
  const auto run_a = relaxed(system_a, scaled_options, a);
  const auto run_b = relaxed(system_b, options, b);
  ASSERT_TRUE(run_a.report.converged && run_b.report.converged);
  EXPECT_NEAR(run_a.report.energy, run_b.report.energy, 1e-2 * run_b.report.energy);  // eq. 4 keeps every energy term
  double sum = 0;
  long n = 0;
  for (int p = 0; p < system_a.num_points(); ++p)
    if (scaled.ring[p] == 0) {
      sum += (run_a.state.points.col(p) / gamma - run_b.state.points.col(p)).squaredNorm();
      ++n;
    }
  const double rms = std::sqrt(sum / n) / r;
  std::printf("radius scaling gamma %.2f against the physical model: RMS %.4f r, energies %.6g and %.6g\n", gamma, rms, run_a.report.energy,
              run_b.report.energy);
  EXPECT_LT(rms, 0.05);
}

TEST(YarnPeriodic, AScaledPeriodKeepsVirtualPointsOnTheirRealOnesAndTheYarnLength) {
  const auto pattern = mesh::parse_pattern("format knit\nk k p p\nk k p p\n", "rib.knit");
  auto patch = periodic_patch(pattern, mesh::StitchLibrary::bundled(), {}, 0.6);
  auto system = make_yarn_system(patch.yarn);
  const auto rest = system.rest_length;
  ShapeTargets targets;
  targets.periodic = patch.map;
  scale_period(targets.periodic, system.points, 0.9, 1.05);
  EXPECT_NEAR(targets.periodic.offsets[0].x(), 0.9 * patch.map.offsets[0].x(), 1e-12);
  for (size_t i = 0; i < targets.periodic.virtual_points.size(); ++i)
    EXPECT_LT((system.points.col(targets.periodic.virtual_points[i]) - system.points.col(targets.periodic.real_points[i]) - targets.periodic.offsets[i]).norm(),
              1e-9);
  EXPECT_EQ(system.rest_length, rest);
  YarnRelaxOptions options;
  options.audit = false;
  const auto run = relaxed(system, options, targets);
  EXPECT_TRUE(run.report.converged) << run.report.stopped_by;
  EXPECT_THROW(scale_period(targets.periodic, system.points, 0, 1), skein::Error);
}

TEST(YarnPeriodic, TiledPreviewPlacesEveryCopyOfARealPointAndBordersFollow) {
  // The relaxed repeat's positions, tiled: a copy of real point q in repeat (i, j) lies at q's relaxed
  // position plus the repeat's offset; border points move as the nearest placed point of their yarn.
  const auto pattern = mesh::parse_pattern("format tiles\nK K K K K\nYS Y3Y\n", "lace.knit");
  const auto& library = mesh::StitchLibrary::bundled();
  const auto patch = periodic_patch(pattern, library, {}, 0.6);
  mesh::EmitOptions emit;
  emit.yarn_radius = 0.6;
  const auto tiled = mesh::emit_yarn(mesh::pattern_stitch_mesh(pattern, 3, 4), library, emit);
  Eigen::Matrix3Xd emitted(3, patch.yarn.points.size());
  for (size_t p = 0; p < patch.yarn.points.size(); ++p) emitted.col(p) = patch.yarn.points[p];
  // Unmoved: the preview is the tiling as emitted, where it has copies of real points.
  const auto same = tile_relaxed_patch(patch, emitted, tiled);
  EXPECT_GT(same.matched, static_cast<int>(0.9 * tiled.points.size()));
  EXPECT_LT(same.matched, static_cast<int>(tiled.points.size()));  // the cast-on and bind-off have no copy
  int exact = 0;
  for (size_t p = 0; p < tiled.points.size(); ++p) exact += (same.points.col(p) - tiled.points[p]).norm() < 1e-9;
  EXPECT_EQ(exact, static_cast<int>(tiled.points.size()));  // and the borders follow a zero move
  // Real points moved by d (and the period scaled): every point of the preview moves alike.
  const Eigen::Vector3d d(0.3, -0.2, 0.1);
  const Eigen::Vector2d scale(0.9, 1.1);
  Eigen::Matrix3Xd moved = emitted;
  moved.row(0) *= scale.x();
  moved.row(1) *= scale.y();
  moved.colwise() += d;
  const auto shifted = tile_relaxed_patch(patch, moved, tiled, scale);
  double largest = 0;
  for (size_t p = 0; p < tiled.points.size(); ++p) {
    const Eigen::Vector3d expected(scale.x() * tiled.points[p].x() + d.x(), scale.y() * tiled.points[p].y() + d.y(), tiled.points[p].z() + d.z());
    largest = std::max(largest, (shifted.points.col(p) - expected).norm());
  }
  EXPECT_LT(largest, 1e-9);
}

TEST(YarnSettings, WrittenAsProjectLinesTheyReadBackTheSame) {
  YarnSettings s;
  s.relax.method = YarnMethod::Euler;
  s.relax.tolerance = 0.0035;
  s.relax.max_steps = 1234;
  s.take_up = 0.9;
  s.relax.audit = false;
  s.relax.active_set.enabled = true;
  s.relax.sampling.spacing = 2.2;
  s.relax.jam_steps = 0;
  s.relax.clipped_scale = true;
  s.local.rings = 2;
  s.local.halo = 3;
  s.weight = "worsted";
  const auto lines = yarn_setting_lines(s);
  EXPECT_EQ(lines.size(), 12u);
  const auto back = read_yarn_settings(lines, "p.skein");
  EXPECT_EQ(back.relax.method, s.relax.method);
  EXPECT_EQ(back.relax.tolerance, s.relax.tolerance);
  EXPECT_EQ(back.relax.max_steps, s.relax.max_steps);
  EXPECT_EQ(back.take_up, s.take_up);
  EXPECT_EQ(back.relax.audit, s.relax.audit);
  EXPECT_EQ(back.relax.active_set.enabled, s.relax.active_set.enabled);
  EXPECT_EQ(back.relax.sampling.spacing, s.relax.sampling.spacing);
  EXPECT_EQ(back.relax.jam_steps, s.relax.jam_steps);
  EXPECT_EQ(back.relax.clipped_scale, s.relax.clipped_scale);
  EXPECT_EQ(back.local.rings, s.local.rings);
  EXPECT_EQ(back.local.halo, s.local.halo);
  EXPECT_EQ(back.weight, "worsted");
  // A project without settings: the defaults (no yarn weight: written as none). A weight by alias or CYC number.
  const auto none = read_yarn_settings({}, "p.skein");
  EXPECT_EQ(none.relax.tolerance, YarnRelaxOptions{}.tolerance);
  EXPECT_EQ(none.take_up, 1.0);
  EXPECT_EQ(none.weight, "");
  for (const auto& line : yarn_setting_lines(none))
    if (line.key == "yarn.weight") {
      EXPECT_EQ(line.value, "none");
    }
  EXPECT_EQ(read_yarn_settings({{"yarn.weight", "aran", 3}}, "p.skein").weight, "worsted");
  EXPECT_EQ(read_yarn_settings({{"yarn.weight", "3", 3}}, "p.skein").weight, "dk");
}

TEST(YarnOptions, EachOptionHasOneRangeAndItsDefaultIsInIt) {
  const YarnSettings defaults;
  std::set<std::string> keys;
  for (const auto& option : yarn_options()) {
    SCOPED_TRACE(option.key);
    EXPECT_TRUE(keys.insert(option.key).second);  // declared once
    EXPECT_FALSE(option.help.empty());
    EXPECT_EQ(&yarn_option(option.key), &option);
    // The default reads back as itself.
    YarnSettings copy = defaults;
    option.set(copy, option.get(defaults));
    EXPECT_EQ(option.get(copy), option.get(defaults));
    if (option.kind != YarnOption::Kind::Number && option.kind != YarnOption::Kind::Integer) continue;
    EXPECT_TRUE(option.allows(std::stod(option.get(defaults))));
    EXPECT_TRUE(option.allows(option.high));
    EXPECT_EQ(option.allows(option.low), !option.above_low);
    EXPECT_FALSE(option.allows(option.high * 2 + 1));
    EXPECT_FALSE(option.allows(option.low - 1));
    // A project line past the range is refused, naming the key and the range.
    if (!option.in_project) continue;
    const std::string too_big = option.kind == YarnOption::Kind::Integer ? std::to_string(static_cast<long>(option.high) + 1) : "1e12";
    const std::string msg = skein::testing::error_of([&] { read_yarn_settings({{"yarn." + option.key, too_big, 3}}, "p.skein"); });
    EXPECT_NE(msg.find("yarn." + option.key + ": must be in " + option.range()), std::string::npos) << msg;
  }
  EXPECT_THROW(yarn_option("colour"), Error);
}

TEST(YarnSettings, BadLinesNameTheFileTheLineAndTheRule) {
  const std::vector<std::pair<mesh::ProjectSetting, std::string>> cases{
      {{"yarn.colour", "red", 7}, "'yarn.colour' is not a setting this skein knows"},
      {{"yarn.tolerance", "tight", 7}, "'tight' is not a number"},
      {{"yarn.max_steps", "1.5", 7}, "'1.5' is not an integer"},
      {{"yarn.audit", "yes", 7}, "neither true nor false"},
      {{"yarn.method", "verlet", 7}, "verlet"},
      {{"yarn.take_up", "20", 7}, "yarn.take_up: must be in [0.1, 10], found 20"},
      {{"yarn.jam_steps", "-3", 7}, "yarn.jam_steps: must be in [0, 1e+09] steps, found -3"},
      {{"yarn.stop_scale", "median", 7}, "'median' is not first or clipped"},
      {{"yarn.weight", "wool", 7}, "'wool' is not a yarn weight; one of lace, fingering"},
  };
  for (const auto& [line, rule] : cases) {
    const std::string msg = skein::testing::error_of([&] { read_yarn_settings({line}, "p.skein"); });
    EXPECT_NE(msg.find("p.skein"), std::string::npos) << msg;
    EXPECT_NE(msg.find("line 7"), std::string::npos) << msg;
    EXPECT_NE(msg.find(rule), std::string::npos) << msg;
  }
}
