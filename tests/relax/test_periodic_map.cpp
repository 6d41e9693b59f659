// The periodic map (Leaf 2018 §5): virtual points follow their real points through a relaxation, frozen ones
// stay, and a scaled period keeps them on their real points and the yarn's length.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <string>
#include <utility>

#include "common/error.hpp"
#include "relax/periodic_map.hpp"
#include "relax/yarn_relax.hpp"
#include "stitchmesh/pattern.hpp"
#include "workflow/yarn_periodic.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;
using namespace skein::workflow;
using skein::testing::relaxed;

TEST(PeriodicMap, VirtualPointsFollowTheirRealPointsAndFrozenOnesStay) {
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

TEST(PeriodicMap, AScaledPeriodKeepsVirtualPointsOnTheirRealOnesAndTheYarnLength) {
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

// One repeat's yarn per stitch is the yarn of a stitch inside a large tiling: for a repeat of one row or three
// (a flat tiling's rows alternate in direction, so the patch repeats them twice over), of two, and with the yarn
// cut by a take-up, that share of it.
TEST(PeriodicMap, ALoopLengthIsTheYarnOfAStitchInsideALargeTiling) {
  const auto& library = mesh::StitchLibrary::bundled();
  const auto stockinette = [](int wales, int courses) {
    std::string rows = "format knit\n";
    for (int r = 0; r < courses; ++r) {
      for (int c = 0; c < wales; ++c) rows += "k ";
      rows += "\n";
    }
    return mesh::parse_pattern(rows, "k.knit");
  };
  // A stitch inside a tiling: the yarn of 12 x 10 more stitches, edges and turns cancelled by differences.
  const auto yarn_of = [&](int across, int up) {
    mesh::EmitOptions emit;
    emit.yarn_radius = 0.6;
    const auto system = make_yarn_system(mesh::emit_yarn(mesh::pattern_stitch_mesh(stockinette(1, 1), across, up), library, emit));
    double length = 0;
    for (const double l : system.rest_length) length += l;
    return length;
  };
  const double inside = (yarn_of(24, 20) - yarn_of(12, 20) - yarn_of(24, 10) + yarn_of(12, 10)) / (12 * 10);
  for (const auto& [wales, courses] : {std::pair{1, 1}, std::pair{2, 1}, std::pair{1, 2}, std::pair{2, 2}, std::pair{1, 3}}) {
    const auto patch = periodic_patch(stockinette(wales, courses), library, {}, 0.6);
    EXPECT_EQ(patch.repeat, (std::array<int, 2>{wales, courses % 2 ? 2 * courses : courses}));
    EXPECT_NEAR(patch_loop_length(make_yarn_system(patch.yarn), patch.map, patch.repeat), inside, 1e-9 * inside) << wales << " x " << courses;
    EXPECT_NEAR(patch_loop_length(make_yarn_system(patch.yarn, 0.8), patch.map, patch.repeat), 0.8 * inside, 1e-9 * inside);
  }
}
