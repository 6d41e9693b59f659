#pragma once
// A pattern's periodic patch relaxed under tension with its width free (issue 24): `skein pattern TEXT --relax
// --free-period x --no-audit --take-up T --period STARTx1 [--period-method bracket]` in memory.
#include <string>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "relax/yarn_relax.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/stitch_model.hpp"
#include "workflow/yarn_periodic.hpp"

namespace skein::testing {

/// The run, the repeat's width per wale, and the patch and its relaxed points.
struct TensionRun {
  relax::YarnRelaxReport run;
  double wale = 0;
  workflow::PeriodicPatch patch;
  Eigen::Matrix3Xd points;
};

/// `text` relaxed at `take_up` from `start` times its emitted width, with yarn of radius `radius` [mm]: L-BFGS,
/// the force rule, no audit, a 30,000-step cap; the free width by `method` (the frame or the bracket search).
/// Expects it to converge.
inline TensionRun relaxed_under_tension(const std::string& text, double take_up, double start, double radius = 0.6,
                                        relax::PeriodOptions::Method method = relax::PeriodOptions::Method::Frame) {
  const auto pattern = mesh::parse_pattern(text, "test.knit");
  TensionRun out;
  out.patch = workflow::periodic_patch(pattern, mesh::StitchLibrary::bundled(), {}, radius);
  auto system = relax::make_yarn_system(out.patch.yarn, take_up);
  relax::ShapeTargets targets;
  targets.periodic = out.patch.map;
  relax::scale_period(targets.periodic, system.points, start, 1);
  relax::YarnRelaxOptions options;
  options.method = relax::YarnMethod::Lbfgs;
  options.stop_rule = relax::StopRule::Force;
  options.audit = false;
  options.max_steps = 30000;
  options.period.free = true;
  options.period.free_y = false;
  options.period.method = method;
  auto state = relax::initial_state(system, options);
  out.run = relax::make_cpu_yarn_relaxer(system, targets, options)->run(state);
  EXPECT_TRUE(out.run.converged) << text << ": " << out.run.stopped_by;
  EXPECT_NEAR(state.period(0, 0), out.run.period(0, 0), 1e-12);  // the state ends at the period reported
  out.wale = out.run.period(0, 0) / pattern.width();
  out.points = state.points;
  return out;
}

}  // namespace skein::testing
