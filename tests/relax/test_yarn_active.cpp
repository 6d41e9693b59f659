// Modelling no more than the scene needs (issue 10). The active set: forces kept per segment between
// evaluations give the numbers of a fresh evaluation bit for bit; points sleep when quiet and wake when their
// force grows or a neighbour moves; a relaxation with the active set ends where one without it does,
// integrating fewer points. Periodic stand-ins: a relaxed patch mapped over the faces of its repeat.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "common/error.hpp"
#include "relax/yarn_active.hpp"
#include "relax/yarn_relax.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "workflow/yarn_standin.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;
using namespace skein::workflow;

namespace {
/// Every `stride`-th control point moved by a small offset that differs from point to point.
Eigen::Matrix3Xd nudged(const Eigen::Matrix3Xd& points, int stride, double size, std::vector<char>& changed) {
  Eigen::Matrix3Xd out = points;
  changed.assign(points.cols(), 0);
  for (int p = 0; p < points.cols(); p += stride) {
    out.col(p) += size * Eigen::Vector3d(std::sin(p), std::cos(3.0 * p), std::sin(7.0 * p));
    changed[p] = 1;
  }
  return out;
}

bool same_bits(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b) {
  return a.cols() == b.cols() && std::equal(a.data(), a.data() + a.size(), b.data());
}
}  // namespace

TEST(YarnForces, KeptSharesEqualAFreshEvaluationBitForBit) {
  const auto k = skein::testing::knitted(models::swatch(), "rib");
  const auto& system = k.system;
  const YarnParams params;
  const double r = system.radius;
  const auto pairs = find_contact_pairs(system, system.points, r);
  YarnForces forces(system, params);
  forces.set_pairs(pairs);
  Eigen::Matrix3Xd kept, fresh;
  forces.evaluate(system.points, nullptr, kept);
  EXPECT_EQ(forces.computed_segments(), system.num_segments());

  // A few points move: only the segments that see them are computed again, to the same numbers.
  std::vector<char> changed;
  const Eigen::Matrix3Xd moved = nudged(system.points, 37, 0.05 * r, changed);
  const double e_kept = forces.evaluate(moved, &changed, kept);
  const double e_fresh = yarn_energy(system, params, pairs, moved, fresh);
  EXPECT_LT(forces.computed_segments(), system.num_segments() / 2);
  EXPECT_GT(forces.computed_segments(), 0);
  EXPECT_EQ(e_kept, e_fresh);
  EXPECT_TRUE(same_bits(kept, fresh));

  // New contact pairs, no point moved: the segments whose partners changed are computed again.
  const auto wider = find_contact_pairs(system, moved, 1.5 * r);
  forces.set_pairs(wider);
  const std::vector<char> none(system.num_points(), 0);
  EXPECT_EQ(forces.evaluate(moved, &none, kept), yarn_energy(system, params, wider, moved, fresh));
  EXPECT_TRUE(same_bits(kept, fresh));
  EXPECT_LT(forces.computed_segments(), system.num_segments());

  // Euler's damping: velocities count as a change too.
  Eigen::Matrix3Xd velocities = Eigen::Matrix3Xd::Zero(3, system.num_points()), damping, damping_fresh;
  forces.evaluate(moved, nullptr, kept, &velocities, &damping);
  const Eigen::Matrix3Xd faster = nudged(velocities, 53, 1.0, changed);
  forces.evaluate(moved, &changed, kept, &faster, &damping);
  yarn_energy(system, params, wider, moved, fresh, &faster, &damping_fresh);
  EXPECT_TRUE(same_bits(kept, fresh));
  EXPECT_TRUE(same_bits(damping, damping_fresh));
}

TEST(ActiveSet, PointsSleepWhenQuietAndWakeWhenTheirForceGrowsOrANeighbourMoves) {
  const auto k = skein::testing::knitted(models::swatch(), "");
  const auto& system = k.system;
  const double r = system.radius;
  const auto pairs = find_contact_pairs(system, system.points, r);
  ActiveSetOptions options;
  options.enabled = true;
  std::vector<char> never(system.num_points(), 0);
  never[0] = 1;
  ActiveSet active(system, options, never);
  const Eigen::Matrix3Xd zero = Eigen::Matrix3Xd::Zero(3, system.num_points());
  const int n = system.num_points();

  // Not yet quiet for long enough: every point stays awake; then all but the tied one sleep.
  EXPECT_EQ(active.choose(zero, 1.0), n);
  for (int i = 0; i < options.quiet_steps; ++i) active.moved(zero, pairs);
  EXPECT_EQ(active.choose(zero, 1.0), 1);
  EXPECT_FALSE(active.asleep(0));

  // One point moves 0.03 r per step: its neighbours wake once the moves add up to 0.05 r, points far off sleep on.
  const int c = system.num_curves() / 2, mover = (system.curve_start[c] + system.curve_start[c + 1]) / 2, neighbour = mover + 1;
  int far = 1;
  for (int p = 1; p < n; ++p)
    if ((system.points.col(p) - system.points.col(mover)).norm() > (system.points.col(far) - system.points.col(mover)).norm()) far = p;
  Eigen::Matrix3Xd delta = zero;
  delta(0, mover) = 0.03 * r;
  active.moved(delta, pairs);
  EXPECT_TRUE(active.asleep(neighbour));
  active.moved(delta, pairs);
  EXPECT_FALSE(active.asleep(neighbour));
  EXPECT_TRUE(active.asleep(far));
  EXPECT_EQ(active.counters().wakes_by_force, 0);
  EXPECT_GT(active.counters().wakes_by_move, 1);

  // A sleeping point whose force grows past twice the sleep level... stays asleep under the wake level, wakes above it.
  Eigen::Matrix3Xd gradient = zero;
  gradient(1, far) = 1.5;
  active.choose(gradient, 1.0);
  EXPECT_TRUE(active.asleep(far));
  gradient(1, far) = 2.5;
  active.choose(gradient, 1.0);
  EXPECT_FALSE(active.asleep(far));
  EXPECT_EQ(active.counters().wakes_by_force, 1);
}

TEST(ActiveSet, OptionsAreValidated) {
  const auto bad = [](auto change) {
    ActiveSetOptions o;
    change(o);
    EXPECT_THROW(o.validate(), Error);
  };
  bad([](ActiveSetOptions& o) { o.sleep_force = 0; });
  bad([](ActiveSetOptions& o) { o.wake_force = o.sleep_force; });
  bad([](ActiveSetOptions& o) { o.wake_move = -1; });
  bad([](ActiveSetOptions& o) { o.sleep_move = NAN; });
  bad([](ActiveSetOptions& o) { o.quiet_steps = 0; });
}

TEST(YarnRelax, TheActiveSetEndsWhereAFullRelaxationDoesIntegratingFewerPoints) {
  const auto k = skein::testing::knitted(models::swatch(), "rib");
  YarnRelaxOptions options;
  YarnState full = initial_state(k.system, options);
  const auto full_report = make_cpu_yarn_relaxer(k.system, k.targets, options)->run(full);
  options.active_set.enabled = true;
  YarnState active = initial_state(k.system, options);
  long least_awake = k.system.num_points();
  const auto report = make_cpu_yarn_relaxer(k.system, k.targets, options)->run(active, [&](const YarnStepLog& log) {
    least_awake = std::min(least_awake, log.awake);
  });
  ASSERT_TRUE(full_report.converged);
  ASSERT_TRUE(report.converged) << report.stopped_by;
  EXPECT_EQ(report.pull_through_events, 0);
  EXPECT_GT(report.active.sleeps, 0);
  EXPECT_LT(least_awake, k.system.num_points());
  EXPECT_LT(report.active.point_steps, report.steps * k.system.num_points());
  const double r = k.system.radius;
  const double rms = std::sqrt((active.points - full.points).colwise().squaredNorm().mean()) / r;
  std::printf("full: %ld steps; active set: %ld steps, %.1f %% of the point-steps, %ld sleeps, %ld + %ld wakes, RMS %.4f r, energy %.6g vs %.6g\n",
              full_report.steps, report.steps, 100.0 * report.active.point_steps / (report.steps * k.system.num_points()), report.active.sleeps,
              report.active.wakes_by_force, report.active.wakes_by_move, rms, report.energy, full_report.energy);
  EXPECT_LT(rms, 0.1);
  EXPECT_NEAR(report.energy, full_report.energy, 0.01 * full_report.energy);
}

