// The yarn relaxer: the auditor inside its runs, shape preservation, convergence on
// knitted pieces, the run policy and determinism.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <atomic>

#include <omp.h>

#include "common/error.hpp"
#include "relax/yarn_audit.hpp"
#include "relax/yarn_checkpoint.hpp"
#include "relax/yarn_relax.hpp"
#include "testing.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;
using Eigen::Vector3d;
using skein::testing::relaxed;
using skein::testing::curve_points;

namespace {

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

