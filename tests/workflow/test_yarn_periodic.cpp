// Periodic patches (Leaf 2018 §5): built from patterns, relaxed with periodic boundary conditions, against tilings.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "common/error.hpp"
#include "relax/yarn_relax.hpp"
#include "stitchmesh/pattern.hpp"
#include "workflow/yarn_periodic.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;
using namespace skein::workflow;
using Eigen::Vector3d;
using skein::testing::relaxed;

namespace {
/// RMS distance [r] between the periodic patch's real points and the matching points of the centre repeat of
/// a 5 x 5 tiling of the patch's repeat relaxed with free borders, the common translation removed.
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

  const auto stitch = mesh::pattern_stitch_mesh(pattern, 5, 5 * patch.repeat[1] / pattern.height());  // 5 x 5 of the patch's repeat
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
