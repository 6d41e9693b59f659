// The free period found by a bracketing search over fixed widths (relax/period_search.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "relax/period_search.hpp"
#include "relax/yarn_cell.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/stitch_model.hpp"
#include "tension_run.hpp"
#include "workflow/yarn_periodic.hpp"

using namespace skein;
using namespace skein::relax;
using namespace skein::workflow;

namespace {

/// WidthSearch driven by a stress function from `start`: the widths it tries until it is over.
WidthSearch search_of(const std::function<double(double)>& stress, double start, double tolerance = 1e-3, int* trials = nullptr) {
  WidthSearch search(start, tolerance, 5e-3);
  int n = 0;
  for (double width = start; width > 0 && n < 200; ++n) width = search.next({width, stress(width)});
  if (trials) *trials = n;
  return search;
}

}  // namespace

TEST(WidthSearch, FindsTheZeroOfAStiffeningStressFromEitherSide) {
  const auto stress = [](double w) { return 0.05 * (w - 4.8) + 0.3 * std::pow(w - 4.8, 3); };
  for (double start : {6.0, 4.0}) {
    int trials = 0;
    const auto search = search_of(stress, start, 1e-3, &trials);
    ASSERT_TRUE(search.converged()) << start;
    EXPECT_NEAR(search.result().width, 4.8, 0.01 * 4.8) << start;
    EXPECT_LT(trials, 20) << start;
  }
}

TEST(WidthSearch, StopsAtTheWallAfterAPlateau) {
  // A rib under tension: a small, nearly flat inward stress over a wide range of widths, then the knit wales
  // meet and the stress turns sharply outward (period_search.hpp; the trials of docs/BENCHMARKS.md). The
  // search ends within its bracket at the wall, not at the plateau's smallest stress.
  const auto stress = [](double w) { return w > 5.9 ? 0.007 + 0.0001 * std::sin(7 * w) : 0.007 - 0.5 * (5.9 - w); };
  const auto search = search_of(stress, 12.0, 1e-3);
  ASSERT_TRUE(search.converged());
  EXPECT_NEAR(search.result().width, 5.886, 0.03);
}

TEST(WidthSearch, SaysSoWhenNoStressFreeWidthIsInReach) {
  const auto search = search_of([](double) { return 0.2; }, 6.0);  // always inward: it would shrink to nothing
  EXPECT_FALSE(search.converged());
  EXPECT_GE(search.result().width, 0.25 * 6.0);
}

namespace {
skein::testing::TensionRun bracket_run(const std::string& text, double take_up, double start) {
  return skein::testing::relaxed_under_tension(text, take_up, start, 0.6, PeriodOptions::Method::Bracket);
}
}  // namespace

// Under tension (take-up 0.8) the frame creeps along the width's soft mode for tens of thousands of steps (seed
// and the ribs were still narrowing at 40,000); the search converges there in a few thousand. Seed ends 4.56 and
// 4.48 mm a wale from two starts (2 % apart: its stress is nearly flat there), 0.90 to 0.92 of stockinette's:
// nearly flat, where scans of fixed widths from the emitted yarn had it fold like a rib (docs/BENCHMARKS.md, "The
// free width by bracketing"). Stockinette's is the frame's, from one start.
TEST(PeriodSearch, UnderTensionSeedFindsOneWidthNearStockinettes) {
  const auto plain = bracket_run("format knit\nk\n", 0.8, 1);
  const auto seed_wide = bracket_run("format knit\nk p\np k\n", 0.8, 1), seed_narrow = bracket_run("format knit\nk p\np k\n", 0.8, 0.85);
  std::printf("at a take-up of 0.8: stockinette %.3f mm a wale (%ld steps); seed %.3f and %.3f from 1 and 0.85 (%ld, %ld steps)\n", plain.wale,
              plain.run.steps, seed_wide.wale, seed_narrow.wale, seed_wide.run.steps, seed_narrow.run.steps);
  EXPECT_NEAR(seed_wide.wale, seed_narrow.wale, 0.03 * seed_wide.wale);
  EXPECT_GT(std::min(seed_wide.wale, seed_narrow.wale), 0.85 * plain.wale);
  EXPECT_NEAR(plain.wale, 4.97, 0.05);  // the frame's stress-free width (YarnCell.YarnUnderTensionFindsOneWidthFromEveryStart)
}

// The "rib at least 20 % narrower than stockinette", converged, and the same width from two starts. The
// 1x1 rib's stress under tension is about a hundredth of B/r³ from 0.59 to 0.71 of stockinette's width;
// relaxed to a force of 0.1 B/r³ at every width, the search read noise of that size as the stress and stopped at
// 0.71 from one start and 0.60 from the other. Relaxed more tightly as the stress gets small
// (WidthSearch::trial_force_tolerance), both starts end at about 0.61, within 1 %.
TEST(PeriodSearch, UnderTensionARibIsAtLeastAFifthNarrowerThanStockinetteFromEitherStart) {
  const auto plain = bracket_run("format knit\nk\n", 0.8, 1);
  const auto wide = bracket_run("format knit\nk p\n", 0.8, 1), narrow = bracket_run("format knit\nk p\n", 0.8, 0.85);
  std::printf("at a take-up of 0.8: 1x1 rib %.3f and %.3f mm a wale from 1 and 0.85, %.3f and %.3f of stockinette's (%ld, %ld steps)\n", wide.wale,
              narrow.wale, wide.wale / plain.wale, narrow.wale / plain.wale, wide.run.steps, narrow.run.steps);
  EXPECT_LT(std::max(wide.wale, narrow.wale), 0.8 * plain.wale);
  EXPECT_NEAR(wide.wale, narrow.wale, 0.01 * wide.wale);
}

TEST(WidthSearch, RelaxesTighterAsTheStressGetsSmall) {
  WidthSearch search(10, 1e-3, 5e-3);
  EXPECT_EQ(search.trial_force_tolerance(0.1), 0.1);  // nothing known yet
  search.next({10, 0.5});
  EXPECT_EQ(search.trial_force_tolerance(0.1), 0.1);  // far from the root: the loosest
  search.next({9.6, 0.004});
  EXPECT_NEAR(search.trial_force_tolerance(0.1), 0.04, 1e-12);  // ten times the smallest stress
  search.next({9.2, 0.0015});
  EXPECT_NEAR(search.trial_force_tolerance(0.1), 0.02, 1e-12);  // never below twenty times the tolerance
  search.next({8.8, 0.003});
  EXPECT_NEAR(search.trial_force_tolerance(0.1), 0.02, 1e-12);  // it does not loosen again
}

TEST(WidthSearch, BelievesAStressWithinTheToleranceOnlyFromATightRelaxation) {
  WidthSearch search(10, 1e-3, 5e-3);
  search.next({10, 0.5, 0.1});
  EXPECT_EQ(search.next({9.6, 0.0006, 0.1}), 9.6);  // perhaps noise: the same width again
  EXPECT_FALSE(search.converged());
  EXPECT_NEAR(search.trial_force_tolerance(0.1), 0.02, 1e-12);  // relaxed at the floor
  EXPECT_NE(search.next({9.6, 0.006, 0.02}), 0);  // it was noise: the search goes on
  EXPECT_FALSE(search.converged());
  EXPECT_EQ(search.next({9.3, -0.0004, 0.02}), 0);  // tight enough: believed
  EXPECT_TRUE(search.converged());
  EXPECT_EQ(search.result().width, 9.3);
}

TEST(PeriodSearch, AuditsEveryStepAndEveryStretch) {
  // The same search with the auditor on: the trials' steps and the stretches between them (an affine map, which
  // moves no yarn through another) are all audited, and none crosses.
  auto patch = periodic_patch(mesh::parse_pattern("format knit\nk p\n", "test.knit"), mesh::StitchLibrary::bundled(), {}, 0.6);
  const auto system = make_yarn_system(patch.yarn, 0.8);
  ShapeTargets targets;
  targets.periodic = patch.map;
  YarnRelaxOptions options;
  options.method = YarnMethod::Lbfgs;
  options.stop_rule = StopRule::Force;
  options.max_steps = 3000;  // several widths, not the whole search
  options.period.free = true;
  options.period.free_y = false;
  options.period.method = PeriodOptions::Method::Bracket;
  auto state = initial_state(system, options);
  std::vector<double> widths;
  const auto run = make_cpu_yarn_relaxer(system, targets, options)->run(state, [&](const YarnStepLog& s) {
    if (widths.empty() || widths.back() != s.period_x) widths.push_back(s.period_x);
  });
  EXPECT_GE(widths.size(), 3u);  // the log follows the widths tried
  EXPECT_EQ(run.pull_through_events, 0);
  EXPECT_EQ(run.steps, 3000);
  EXPECT_EQ(run.stopped_by, StopReason::StepCap);
  EXPECT_FALSE(run.converged);
  // Cut short, it keeps a width it finished, not the one it was relaxing, and the state is at that width.
  EXPECT_GE(run.period_trials, 1);
  EXPECT_NE(run.period(0, 0), widths.back());
  EXPECT_NE(std::find(widths.begin(), widths.end() - 1, run.period(0, 0)), widths.end() - 1);
  EXPECT_EQ(state.period(0, 0), run.period(0, 0));
  options.stop_rule = StopRule::Leaf;  // Leaf's relative rule would judge later widths by the first one's forces
  EXPECT_THROW(options.validate(), skein::Error);
}

TEST(PeriodSearch, FindsOneFreeLengthOnly) {
  PeriodOptions period;
  period.free = true;
  period.method = PeriodOptions::Method::Bracket;
  EXPECT_THROW(period.validate(), skein::Error);  // x and y free
  period.free_y = false;
  EXPECT_NO_THROW(period.validate());
  period.shear = true;
  EXPECT_THROW(period.validate(), skein::Error);
  period.shear = false;
  period.bracket = 0;
  EXPECT_THROW(period.validate(), skein::Error);
}
