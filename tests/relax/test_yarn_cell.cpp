// Variable-cell relaxation (issue 24): the period derivative of one repeat's energy against finite
// differences, and free periods that find the same stress-free repeat from different starts.
#include <gtest/gtest.h>

#include "relax/yarn_cell.hpp"
#include "relax/yarn_contacts.hpp"
#include "relax/yarn_periodic.hpp"
#include "relax/yarn_relax.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/stitch_model.hpp"

using namespace skein;
using namespace skein::relax;

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
