// Variable-cell relaxation (issue 24): the period derivative of one repeat's energy against finite
// differences, and free periods that find the same stress-free repeat from different starts.
#include <algorithm>
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "relax/pull_through_guard.hpp"
#include "relax/yarn_audit.hpp"
#include "relax/yarn_cell.hpp"
#include "relax/yarn_contacts.hpp"
#include "relax/yarn_relax.hpp"
#include "open_area.hpp"
#include "tension_run.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/stitch_model.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "workflow/yarn_periodic.hpp"

using namespace skein;
using namespace skein::relax;
using namespace skein::workflow;

namespace {

/// A periodic patch of `text` a little relaxed, so that the yarn is in contact everywhere.
struct Patch {
  PeriodicPatch patch;
  YarnSystem system;
  Eigen::Matrix3Xd points;
};

Patch relaxed_patch(const std::string& text, long steps) {
  Patch out{periodic_patch(mesh::parse_pattern(text, "test.knit"), mesh::StitchLibrary::bundled(), {}, 0.6), {}, {}};
  out.system = make_yarn_system(out.patch.yarn);
  ShapeTargets targets;
  targets.periodic = out.patch.map;
  YarnRelaxOptions options;
  options.audit = false;
  options.max_steps = steps;
  auto state = initial_state(out.system, options);
  make_cpu_yarn_relaxer(out.system, targets, options)->run(state);
  out.points = state.points;
  return out;
}

}  // namespace

TEST(YarnCell, APeriodicPatchsForcesComputeOnlyWhatItsRealPointsNeedAndItsEnergyIsOneRepeats) {
  for (const char* text : {"format knit\nk\n", "format knit\nk k p p\n", "format knit\np k k k k p\np k k k k p\np cable2x2+ p\n"}) {
    SCOPED_TRACE(text);
    auto p = relaxed_patch(text, 40);
    const YarnParams params;
    const auto pairs = find_contact_pairs(p.system, p.points, 2 * p.system.radius);
    YarnForces whole(p.system, params), repeat(p.system, params);
    whole.set_pairs(pairs);
    repeat.set_pairs(pairs);
    repeat.set_periodic(p.patch.map);
    Eigen::Matrix3Xd g_whole, g_repeat;
    const double e_whole = whole.evaluate(p.points, nullptr, g_whole);
    const double e_repeat = repeat.evaluate(p.points, nullptr, g_repeat);
    EXPECT_LT(repeat.computed_segments(), whole.computed_segments() / 2);  // the virtual rings are most of the patch
    // The real points' forces bit for bit; the virtual points' are not degrees of freedom.
    constrain_gradient(p.patch.map, g_whole);
    constrain_gradient(p.patch.map, g_repeat);
    EXPECT_EQ(g_repeat, g_whole);
    // One repeat's energy, the variable-cell relaxation's, against the whole patch's several repeats.
    EXPECT_NEAR(e_repeat, cell_stress(p.system, params, pairs, p.patch.map, p.points).energy, 1e-9 * e_repeat);
    EXPECT_GT(e_whole, 4 * e_repeat);
  }
}

TEST(YarnCell, APeriodicPatchsAuditAndGuardTestOneCopyOfEachPairAndMissNothing) {
  auto p = relaxed_patch("format knit\np k k k k p\np k k k k p\np cable2x2+ p\n", 40);
  const auto tested = periodic_tested_segments(p.system, p.patch.map);
  const long marked = std::count(tested.begin(), tested.end(), 1);
  EXPECT_LT(marked, p.system.num_segments() / 4);
  // A periodic move: random on the real points, copied to the virtual ones, none on the frozen ones.
  const auto periodic_move = [&](double size, unsigned seed) {
    std::srand(seed);
    Eigen::Matrix3Xd delta = size * p.system.radius * Eigen::Matrix3Xd::Random(3, p.system.num_points());
    Eigen::Matrix3Xd velocities = Eigen::Matrix3Xd::Zero(3, p.system.num_points());
    apply_periodic(p.patch.map, delta, velocities);
    return delta;
  };
  const auto same_pair = [](const TopologyAuditor::Crossing& x, const TopologyAuditor::Crossing& y) {
    return x.segment_a == y.segment_a && x.segment_b == y.segment_b;
  };
  const auto translate = [&](int from, int to) -> std::optional<Eigen::Vector3d> {  // to's points = from's + t for one t
    const auto &f = p.system.segment_points[from], &g = p.system.segment_points[to];
    for (const bool reversed : {false, true}) {  // a piece of yarn may be listed either way along it
      const auto at = [&](int k) { return f[reversed ? 3 - k : k]; };
      const Eigen::Vector3d t = p.points.col(g[0]) - p.points.col(at(0));
      bool same = true;
      for (int k = 0; k < 4; ++k) same = same && (p.points.col(g[k]) - p.points.col(at(k)) - t).norm() < 1e-9;
      if (same) return t;
    }
    return std::nullopt;
  };
  // Every crossing the whole patch's auditor finds has a copy, translated as a pair, among `copies`, which holds
  // no other and each pair once.
  TopologyAuditor whole(p.system);
  const auto check = [&](const Eigen::Matrix3Xd& before, const Eigen::Matrix3Xd& after, const std::vector<TopologyAuditor::Crossing>& copies,
                         const std::string& where) {
    const auto all = whole.crossings(before, after);
    for (const auto& c : copies) EXPECT_TRUE(std::any_of(all.begin(), all.end(), [&](const auto& x) { return same_pair(x, c); })) << where;
    EXPECT_EQ(std::adjacent_find(copies.begin(), copies.end(), same_pair), copies.end()) << where;
    for (const auto& x : all) {
      const bool copied = std::any_of(copies.begin(), copies.end(), [&](const auto& c) {
        for (const auto& [a, b] : {std::pair{c.segment_a, c.segment_b}, std::pair{c.segment_b, c.segment_a}}) {
          const auto ta = translate(x.segment_a, a), tb = translate(x.segment_b, b);
          if (ta && tb && (*ta - *tb).norm() < 1e-9) return true;
        }
        return false;
      });
      EXPECT_TRUE(copied) << where << ": segments " << x.segment_a << " and " << x.segment_b;
    }
    return all.size();
  };
  // One move of 1.5 r: crossings everywhere.
  const Eigen::Matrix3Xd after = p.points + periodic_move(1.5, 7);
  TopologyAuditor one_copy(p.system);
  one_copy.restrict_to(tested);
  const auto copies = one_copy.crossings(p.points, after);
  ASSERT_GT(copies.size(), 0u);
  EXPECT_LT(copies.size(), check(p.points, after, copies, "one move"));
  // Step after step, one auditor kept from step to step (its buffers are reused) on a random walk of the yarn.
  Eigen::Matrix3Xd state = p.points;
  long found = 0;
  for (int step = 0; step < 30; ++step) {
    const Eigen::Matrix3Xd next = state + periodic_move(0.9, 100 + step);
    const auto kept = one_copy.crossings(state, next);
    check(state, next, kept, "step " + std::to_string(step));
    found += static_cast<long>(kept.size());
    state = next;
  }
  EXPECT_GT(found, 0);
  // The guard: the same move let through, testing one copy of each pair (groups hold a point with its copies);
  // a movement limit of 2 r lets the move bring pairs through each other.
  std::vector<int> groups(p.system.num_points(), -1);
  group_copies(p.patch.map, groups, 0);
  const auto pairs = find_contact_pairs(p.system, p.points, 2 * p.system.radius);
  GuardOptions options;
  options.max_move = 2;
  PullThroughGuard every(p.system, options, groups), restricted(p.system, options, groups);
  restricted.restrict_to(tested);
  every.reset(pairs);
  restricted.reset(pairs);
  Eigen::Matrix3Xd delta_every = periodic_move(1.5, 11), delta_restricted = delta_every;
  every.accept(p.points, delta_every);
  restricted.accept(p.points, delta_restricted);
  EXPECT_GT(every.counters().finest_hits, 0);
  EXPECT_LT(restricted.counters().pairs_tested, every.counters().pairs_tested / 4);
  EXPECT_EQ(delta_restricted, delta_every);
  EXPECT_THROW(restricted.restrict_to(std::vector<char>(3, 1)), Error);
}

TEST(YarnCell, ThePeriodDerivativeMatchesFiniteDifferences) {
  for (const char* text : {"format knit\nk\n", "format knit\nk k p p\n", "format knit\np k\nk p\n"}) {
    SCOPED_TRACE(text);
    auto p = relaxed_patch(text, 60);
    const YarnParams params;
    const auto pairs = find_contact_pairs(p.system, p.points, 2 * p.system.radius);  // fixed pairs: E is smooth in the period
    PeriodicMap map = p.patch.map;
    const auto base = cell_stress(p.system, params, pairs, map, p.points);
    ASSERT_GT(base.energy, 0);
    ASSERT_GT(base.gradient.norm(), 0);
    const double h = 1e-5;
    for (int col = 0; col < 2; ++col)
      for (int row = 0; row < 3; ++row) {
        const auto energy_at = [&](double t) {
          PeriodicMap m = map;
          Eigen::Matrix3Xd q = p.points;
          Eigen::Vector3d px = map.period_x, py = map.period_y;
          (col == 0 ? px : py)[row] += t;
          set_period(m, q, px, py);
          return cell_stress(p.system, params, pairs, m, q).energy;
        };
        const double fd = (energy_at(h) - energy_at(-h)) / (2 * h);
        EXPECT_NEAR(base.gradient(row, col), fd, 1e-5 * std::max(1.0, std::abs(fd))) << "component " << row << " of period " << col;
      }
  }
}

TEST(YarnCell, OneRepeatsEnergyIsTheRelaxersShareOfItsRealSegments) {
  // Moving one real point moves its copies too: the repeat's energy changes as the relaxer's constrained
  // gradient on that point says.
  auto p = relaxed_patch("format knit\nk k p p\n", 60);
  const YarnParams params;
  const auto pairs = find_contact_pairs(p.system, p.points, 2 * p.system.radius);
  Eigen::Matrix3Xd grad;
  yarn_energy(p.system, params, pairs, p.points, grad);
  constrain_gradient(p.patch.map, grad);
  // The real point with the largest force: every segment at it is whole (the virtual rings are two stitches
  // wide), so its gradient is what one repeat's energy feels when the point moves with its copies.
  Eigen::Index point;
  grad.colwise().norm().maxCoeff(&point);
  ASSERT_EQ(p.patch.ring[point], 0);
  const auto energy_with = [&](double t) {
    Eigen::Matrix3Xd q = p.points;
    q(0, point) += t;
    for (size_t i = 0; i < p.patch.map.virtual_points.size(); ++i)
      if (p.patch.map.real_points[i] == point) q(0, p.patch.map.virtual_points[i]) += t;
    return cell_stress(p.system, params, pairs, p.patch.map, q).energy;
  };
  const double h = 1e-5, fd = (energy_with(h) - energy_with(-h)) / (2 * h);
  EXPECT_NEAR(fd, grad(0, point), 1e-4 * std::abs(grad(0, point)));
}

TEST(YarnCell, TheFramesGradientMatchesFiniteDifferences) {
  // L-BFGS's variables with a free period (CellFrame): the points' reference coordinates X and the repeat's
  // deformation F, x = c + F (X − c), P = F P0. Checked at a deformed, sheared frame, so that Fᵀ g is tested too.
  auto p = relaxed_patch("format knit\nk k p p\n", 60);
  const YarnParams params;
  const auto pairs = find_contact_pairs(p.system, p.points, 2 * p.system.radius);
  PeriodOptions options;
  options.free = options.shear = true;
  PeriodicMap map = p.patch.map;
  Eigen::Matrix<double, 3, 2> period;
  period << map.period_x, map.period_y;
  CellFrame frame(options, period, map, p.points);
  const long n = p.points.cols();
  // Deform the frame: 3 % narrower, 2 % taller, sheared by a tenth of a millimetre.
  Eigen::Matrix<double, 3, 2> deformed = period;
  deformed(0, 0) *= 0.97, deformed(1, 1) *= 1.02, deformed(0, 1) += 0.1;
  Eigen::Matrix3Xd points = p.points + frame.affine_move(deformed, p.points);
  set_period(map, points, deformed.col(0), deformed.col(1));
  frame.accept(deformed);
  // The variables moved by t along one of them: the real points by F ΔX, then every point with the frame.
  const auto energy_at = [&](const Eigen::Matrix3Xd& move) {
    Eigen::Matrix3Xd points_move;
    const auto next = frame.split(move, points_move);
    PeriodicMap m = map;
    Eigen::Matrix3Xd q = points + points_move;
    q += frame.affine_move(next, q);
    set_period(m, q, next.col(0), next.col(1));
    return cell_stress(p.system, params, pairs, m, q).energy;
  };
  Eigen::Matrix3Xd grad;
  yarn_energy(p.system, params, pairs, points, grad);
  constrain_gradient(map, grad);
  const auto variables = frame.gradient(grad, cell_stress(p.system, params, pairs, map, points), points);
  ASSERT_EQ(variables.cols(), n + 1);
  const double h = 1e-5;
  const auto fd = [&](long col, int row) {
    Eigen::Matrix3Xd move = Eigen::Matrix3Xd::Zero(3, n + 1);
    move(row, col) = h;
    const double plus = energy_at(move);
    move(row, col) = -h;
    return (plus - energy_at(move)) / (2 * h);
  };
  for (int row = 0; row < 3; ++row) {
    const double expected = fd(n, row);
    EXPECT_GT(std::abs(expected), 1e-3) << "frame component " << row;  // the deformed frame is under stress
    EXPECT_NEAR(variables(row, n), expected, 1e-4 * std::max(1.0, std::abs(expected))) << "frame component " << row;
  }
  // The real point with the largest force, in each direction.
  Eigen::Index point;
  grad.colwise().norm().maxCoeff(&point);
  for (int row = 0; row < 3; ++row) {
    const double expected = fd(point, row);
    EXPECT_NEAR(variables(row, point), expected, 1e-4 * std::max(1.0, std::abs(expected))) << "point " << point << " component " << row;
  }
}

TEST(YarnCell, TheRepeatsEnergyByTermSumsToItAndEachTermIsItsStiffnessAlone) {
  auto p = relaxed_patch("format knit\nk p\n", 60);
  const YarnParams params;
  const auto pairs = find_contact_pairs(p.system, p.points, 2 * p.system.radius);
  const auto whole = cell_stress(p.system, params, pairs, p.patch.map, p.points);
  const auto& t = whole.terms;
  EXPECT_NEAR(t.bending + t.stretch + t.length + t.contact, whole.energy, 1e-12 * whole.energy);
  // Each term is the energy with every other stiffness zero (contact's can only be scaled down: it must be positive).
  const auto alone = [&](double bend, double stretch, double length, double contact) {
    YarnParams q = params;
    q.k_bend = bend, q.k_stretch = stretch, q.k_length = length, q.k_contact = contact;
    return cell_stress(p.system, q, pairs, p.patch.map, p.points).energy;
  };
  const double tiny = 1e-12;
  EXPECT_NEAR(t.bending, alone(params.k_bend, 0, 0, tiny), 1e-9 * t.bending);
  EXPECT_NEAR(t.stretch, alone(0, params.k_stretch, 0, tiny), 1e-9 * t.stretch);
  EXPECT_NEAR(t.length, alone(0, 0, params.k_length, tiny), 1e-9 * std::max(t.length, 1e-6));
  EXPECT_NEAR(t.contact, alone(0, 0, 0, params.k_contact), 1e-9 * t.contact);
  EXPECT_GT(t.bending, 0);
  EXPECT_GT(t.contact, 0);  // a little relaxed: the emitted yarn still presses on itself
}

namespace {

/// A pattern's periodic patch relaxed with a free period from its emitted period scaled by (sx, sy).
YarnRelaxReport free_period_run(const std::string& text, double sx = 1, double sy = 1) {
  auto patch = periodic_patch(mesh::parse_pattern(text, "test.knit"), mesh::StitchLibrary::bundled(), {}, 0.6);
  auto system = make_yarn_system(patch.yarn);  // rest lengths of the emitted yarn
  ShapeTargets targets;
  targets.periodic = patch.map;
  scale_period(targets.periodic, system.points, sx, sy);
  YarnRelaxOptions options;
  options.period.free = true;
  auto state = initial_state(system, options);
  return make_cpu_yarn_relaxer(system, targets, options)->run(state);
}

}  // namespace

TEST(YarnCell, AFreePeriodEndsStressFreeBelowTheEmittedPeriodsEnergy) {
  // The same patch relaxed at its emitted period and with a free one: the free period moves, ends without
  // stress, and one repeat's energy ends lower.
  auto patch = periodic_patch(mesh::parse_pattern("format knit\nk\n", "test.knit"), mesh::StitchLibrary::bundled(), {}, 0.6);
  const auto system = make_yarn_system(patch.yarn);
  ShapeTargets targets;
  targets.periodic = patch.map;
  YarnRelaxOptions options;
  auto state = initial_state(system, options);
  make_cpu_yarn_relaxer(system, targets, options)->run(state);
  const auto pairs = find_contact_pairs(system, state.points, options.contact_margin * system.radius);
  const double fixed = cell_stress(system, options.params, pairs, patch.map, state.points).energy;
  const auto free = free_period_run("format knit\nk\n");
  ASSERT_TRUE(free.converged) << free.stopped_by;
  EXPECT_EQ(free.pull_through_events, 0);
  std::printf("stockinette: one repeat's energy %.4f at the emitted %.0f x %.0f mm, %.4f at its free period %.3f x %.3f mm\n", fixed,
              patch.period_x.x(), patch.period_y.y(), free.repeat_energy, free.period(0, 0), free.period(1, 1));
  EXPECT_LT(free.repeat_energy, fixed);
  EXPECT_GT(std::abs(free.period(0, 0) - patch.period_x.x()) + std::abs(free.period(1, 1) - patch.period_y.y()), 0.3);
  EXPECT_LT(free.period_stress.cwiseAbs().maxCoeff(), YarnRelaxOptions{}.period.tolerance);
  EXPECT_EQ(free.period(0, 1), 0);  // no shear unless asked for
}

TEST(YarnCell, RibIsNarrowerAndGarterShorterThanStockinette) {
  // Stockinette's and the rib's one row are relaxed twice over up (PeriodicPatch::repeat): every repeat here is
  // two rows tall.
  const auto plain = free_period_run("format knit\nk\n"), rib = free_period_run("format knit\nk k p p\n"),
             garter = free_period_run("format knit\np\nk\n");
  ASSERT_TRUE(plain.converged && rib.converged && garter.converged);
  const double plain_course = plain.period(1, 1) / 2, rib_wale = rib.period(0, 0) / 4, garter_course = garter.period(1, 1) / 2;
  std::printf("stress-free: stockinette %.3f x %.3f mm a stitch, 2x2 rib %.3f mm a wale (%.3f), garter %.3f mm a course (%.3f)\n", plain.period(0, 0),
              plain_course, rib_wale, rib_wale / plain.period(0, 0), garter_course, garter_course / plain_course);
  // 0.956 and 0.992 (docs/BENCHMARKS.md, "Odd rows relaxed twice over"): far from real rib and garter.
  EXPECT_LT(rib_wale, 0.97 * plain.period(0, 0));
  EXPECT_LT(garter_course, plain_course);
}

TEST(YarnCell, AFreePeriodNeedsAPeriodicPatch) {
  const auto pattern = mesh::parse_pattern("format knit\nk\n", "test.knit");
  const auto yarn = mesh::emit_yarn(mesh::pattern_stitch_mesh(pattern, 3, 3, {}), mesh::StitchLibrary::bundled(), {.yarn_radius = 0.6});
  const auto system = make_yarn_system(yarn);
  YarnRelaxOptions options;
  options.period.free = true;
  EXPECT_THROW(make_cpu_yarn_relaxer(system, {}, options), skein::Error);
  options.period.tolerance = 0;
  EXPECT_THROW(options.validate(), skein::Error);
  options.period.tolerance = 1e-3;
  options.checkpoint = "x.ckpt";
  options.checkpoint_every = 10;
  EXPECT_THROW(options.validate(), skein::Error);
}

TEST(YarnStopRule, AForceConvergedRunLosesUnderOnePercentMoreWhenContinued) {
  // Leaf's rule at its default tolerance stops where going on still lowers the energy by several percent; the
  // force rule stops where it no longer does (issue 24: "converged" must mean it). Runs are deterministic, so a
  // run capped at twice the steps is the converged run continued for as many steps again.
  const auto patch = periodic_patch(mesh::parse_pattern("format knit\nk\n", "test.knit"), mesh::StitchLibrary::bundled(), {}, 0.6);
  const auto system = make_yarn_system(patch.yarn);
  ShapeTargets targets;
  targets.periodic = patch.map;
  const auto run = [&](StopRule rule, double force_tolerance, long cap) {
    YarnRelaxOptions o;
    o.audit = false;
    o.stop_rule = rule;
    o.force_tolerance = force_tolerance;
    o.max_steps = cap;
    auto state = initial_state(system, o);
    return make_cpu_yarn_relaxer(system, targets, o)->run(state);
  };
  const double tolerance = YarnRelaxOptions{}.force_tolerance;
  const auto leaf = run(StopRule::Leaf, tolerance, 40000), force = run(StopRule::Force, tolerance, 40000);
  ASSERT_TRUE(leaf.converged && force.converged) << leaf.stopped_by << " " << force.stopped_by;
  const auto leaf_on = run(StopRule::Force, 1e-12, 2 * leaf.steps), force_on = run(StopRule::Force, 1e-12, 2 * force.steps);
  const double leaf_loss = (leaf.energy - leaf_on.energy) / leaf.energy, force_loss = (force.energy - force_on.energy) / force.energy;
  std::printf("continued as long again: Leaf's rule (%ld steps) loses %.2f %% more energy, the force rule (%ld steps, force %.3g B/r^3) %.2f %%\n",
              leaf.steps, 100 * leaf_loss, force.steps, force.force_residual, 100 * force_loss);
  EXPECT_LE(force.force_residual, tolerance);
  EXPECT_LT(force_loss, 0.01);
  EXPECT_GT(leaf_loss, 0.01);
  EXPECT_THROW(parse_stop_rule("relative"), skein::Error);
}

namespace {
using skein::testing::relaxed_under_tension;
double wale_under_tension(const std::string& text, double take_up, double start, double radius = 0.6) {
  return relaxed_under_tension(text, take_up, start, radius).wale;
}
}  // namespace

// Issue 24's test of a stress-free width: two starts, 0.85 and 1.15 times the emitted width, end at one width.
// Stockinette's yarn as emitted (6 x 5 mm stitches, r = 0.6 mm) has none: its free width ends where it starts,
// 26.7 % apart. With its yarn 20 % shorter (a take-up of 0.8) the loops close on each other and the width is the
// fabric's: 4.97 mm a wale from every start, Kw 4.35 (docs/BENCHMARKS.md, "Odd rows relaxed twice over").
TEST(YarnCell, YarnUnderTensionFindsOneWidthFromEveryStart) {
  const double narrow = wale_under_tension("format knit\nk\n", 0.8, 0.85), wide = wale_under_tension("format knit\nk\n", 0.8, 1.15);
  std::printf("stockinette at a take-up of 0.8: %.3f and %.3f mm a wale from 0.85 and 1.15 of the emitted width\n", narrow, wide);
  EXPECT_NEAR(narrow, wide, 0.01 * wide);
  EXPECT_LT(wide, 0.9 * 6.0);  // narrower than emitted: the shorter yarn pulls the loops in
}

// Under the same tension a 1x1 rib's knit wales close over its purl ones: at a take-up of 0.7 it is 0.53 here
// (0.53 to 0.61 from other starts) of stockinette's width a wale, 4.04 mm, where at 1 it is as wide
// (docs/BENCHMARKS.md, "Odd rows relaxed twice over").
TEST(YarnCell, ARibUnderTensionIsNarrowerThanStockinette) {
  const double plain = wale_under_tension("format knit\nk\n", 0.7, 1), rib = wale_under_tension("format knit\nk p\n", 0.7, 1);
  std::printf("at a take-up of 0.7: stockinette %.3f mm a wale, 1x1 rib %.3f (%.3f)\n", plain, rib, rib / plain);
  EXPECT_LT(rib, 0.8 * plain);
}

// Lace opens under tension (issue 24: "eyelets: each hole's largest empty disc at least 3 times stockinette's").
// Eyelet columns (a yo and a k2tog every other row, patterns/charts/eyelet-columns.txt) relaxed with a free width
// at a take-up of 0.8: the yarn-over's hole is 2.3 times stockinette's largest gap at the same tension, where at
// a take-up of 1 it is 1.05 times (docs/BENCHMARKS.md, "Structures under tension").
TEST(YarnCell, EyeletsOpenUnderTension) {
  const auto plain = relaxed_under_tension("format knit\nk\n", 0.8, 1);
  const auto eyelets = relaxed_under_tension("format chart\n. . . .   4\n. / o .   3\n. . . .   2\n. / o .   1\n", 0.8, 1);
  const double gap = skein::testing::largest_open_disc(plain.patch.yarn, plain.points, 0.12);
  const double hole = skein::testing::largest_open_disc(eyelets.patch.yarn, eyelets.points, 0.12);
  std::printf("at a take-up of 0.8: stockinette's largest gap %.2f mm, the eyelet's %.2f mm (%.2f times)\n", gap, hole, hole / gap);
  EXPECT_GT(hole, 2 * gap);
}

// Doyle (1953) under tension: relaxed plain knit's stitch width follows its loop, not its yarn. Stockinette at a
// take-up of 0.8 with yarn of radius 0.5 and 0.6 mm (loops 20.96 and 21.60 mm), started at 0.85 and 1.15 of the
// emitted width, ends 4.974 and 4.968 mm a wale (docs/BENCHMARKS.md, "Structures under tension"); at a take-up of
// 1 the width stays where it starts, so only under tension is this a test.
TEST(YarnCell, UnderTensionTheStitchWidthFollowsTheLoopNotTheYarn) {
  const double thin = wale_under_tension("format knit\nk\n", 0.8, 0.85, 0.5), thick = wale_under_tension("format knit\nk\n", 0.8, 1.15, 0.6);
  std::printf("stockinette at a take-up of 0.8: %.3f mm a wale at r = 0.5 mm, %.3f at 0.6\n", thin, thick);
  EXPECT_NEAR(thin / thick, 1.0, 0.1);
  EXPECT_LT(thick, 0.9 * 6.0);  // pulled in from its start at 6.9 mm: the two starts were 35 % apart
}
