#include <gtest/gtest.h>

#include <random>

#include "surface/mesh_forces.hpp"

using namespace skein::surface::forces;

namespace {
constexpr double kStep = 1e-6, kTolerance = 1e-6;
std::mt19937 rng(42);
Vec3 random_point(double scale = 5) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}
/// Central difference of a force (as a function of one point) along each axis: a 3x3 Jacobian block.
template <class F>
Mat3 numeric_jacobian(F force_of, const Vec3& x) {
  Mat3 j;
  for (int c = 0; c < 3; ++c) {
    Vec3 a = x, b = x;
    a[c] += kStep;
    b[c] -= kStep;
    j.col(c) = (force_of(a) - force_of(b)) / (2 * kStep);
  }
  return j;
}
template <class E>
Vec3 numeric_gradient(E energy_of, const Vec3& x) {
  return numeric_jacobian([&](const Vec3& p) { return Vec3(energy_of(p), 0, 0); }, x).row(0).transpose();
}
void expect_close(const Mat3& analytic, const Mat3& numeric, const char* what) {
  EXPECT_LT((analytic - numeric).norm(), kTolerance * std::max(1.0, numeric.norm())) << what << "\nanalytic\n" << analytic << "\nnumeric\n" << numeric;
}
}  // namespace

TEST(MeshForces, StretchIsTheEnergyGradientAndItsJacobianMatches) {
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3 xi = random_point(), xj = random_point();
    const double rest = 3.0;
    const auto s = stretch(xi, xj, rest, 2.0);
    const Vec3 grad = numeric_gradient([&](const Vec3& x) { return stretch(x, xj, rest, 2.0).energy; }, xi);
    EXPECT_LT((s.force_i + grad).norm(), 1e-6 * std::max(1.0, grad.norm()));
    expect_close(stretch_jacobian(xi, xj, rest, 2.0), numeric_jacobian([&](const Vec3& x) { return stretch(x, xj, rest, 2.0).force_i; }, xi), "d f_i / d x_i");
    expect_close(-stretch_jacobian(xi, xj, rest, 2.0), numeric_jacobian([&](const Vec3& x) { return stretch(xi, x, rest, 2.0).force_i; }, xj), "d f_i / d x_j");
  }
  // At rest: no force, no energy.
  const auto r = stretch(Vec3(3, 0, 0), Vec3::Zero(), 3.0, 2.0);
  EXPECT_NEAR(r.energy, 0.0, 1e-12);
  EXPECT_NEAR(r.force_i.norm(), 0.0, 1e-12);
}

TEST(MeshForces, ShearIsTheEnergyGradientAndItsJacobianMatches) {
  for (int trial = 0; trial < 20; ++trial) {
    Vec3 x[3] = {random_point(), random_point(), random_point()};
    const auto s = shear(x[0], x[1], x[2], 0.2);
    // The corner's force is Yuksel's eq. 3.
    EXPECT_LT((s.force[1] - (-0.2 * (x[0] - x[1]).dot(x[2] - x[1]) * (x[1] - 0.5 * (x[0] + x[2])))).norm(), 1e-9);
    const auto jacobian = shear_jacobian(x[0], x[1], x[2], 0.2);
    for (int a = 0; a < 3; ++a) {
      const auto energy_at = [&](const Vec3& p) {
        Vec3 y[3] = {x[0], x[1], x[2]};
        y[a] = p;
        return shear(y[0], y[1], y[2], 0.2).energy;
      };
      EXPECT_LT((s.force[a] + numeric_gradient(energy_at, x[a])).norm(), 1e-5 * std::max(1.0, s.force[a].norm()));
      for (int b = 0; b < 3; ++b) {
        const auto force_at = [&](const Vec3& p) {
          Vec3 y[3] = {x[0], x[1], x[2]};
          y[b] = p;
          return shear(y[0], y[1], y[2], 0.2).force[a];
        };
        expect_close(jacobian.block[a][b], numeric_jacobian(force_at, x[b]), "shear block");
      }
    }
  }
}

TEST(MeshForces, WaleStrutJacobianMatchesWithAndWithoutItsMovingRest) {
  for (int trial = 0; trial < 20; ++trial) {
    Vec3 x[3] = {random_point(), random_point(), random_point()};
    for (const double rest_wale : {0.5, 100.0}) {  // rest follows the wale edges / stays r_wale
      const auto jacobian = wale_strut_jacobian(x[0], x[1], x[2], rest_wale, 2.0);
      for (int b = 0; b < 3; ++b) {
        const auto force_at = [&](const Vec3& p) {
          Vec3 y[3] = {x[0], x[1], x[2]};
          y[b] = p;
          return wale_strut(y[0], y[1], y[2], rest_wale, 2.0).force_i;
        };
        expect_close(jacobian.block[0][b], numeric_jacobian(force_at, x[b]), "strut d f_i / d x_b");
        EXPECT_LT((jacobian.block[1][b] + jacobian.block[0][b]).norm(), 1e-12);
      }
    }
  }
  // A straight wale column feels no strut force.
  const auto straight = wale_strut(Vec3(0, 0, 0), Vec3(0, 5, 0), Vec3(0, 10, 0), 4.0, 2.0);
  EXPECT_NEAR(straight.force_i.norm(), 0.0, 1e-12);
  // A bent one is pushed straight: i moves away from k.
  const auto bent = wale_strut(Vec3(0, 0, 0), Vec3(3, 4, 0), Vec3(0, 8, 0), 4.0, 2.0);
  EXPECT_LT(bent.force_i.y(), 0);
}

TEST(MeshForces, FoldGuardIsTheEnergyGradientAndOnlyActsOnSquashedCorners) {
  const Vec3 n(0, 0, 1);
  for (int trial = 0; trial < 20; ++trial) {
    Vec3 x[3] = {random_point(), random_point(), random_point()};
    const auto g = fold_guard(x[0], x[1], x[2], n, 20.0, 0.25, 2.0);
    for (int a = 0; a < 3; ++a) {
      const auto energy_at = [&](const Vec3& p) {
        Vec3 y[3] = {x[0], x[1], x[2]};
        y[a] = p;
        return fold_guard(y[0], y[1], y[2], n, 20.0, 0.25, 2.0).energy;
      };
      EXPECT_LT((g.force[a] + numeric_gradient(energy_at, x[a])).norm(), 1e-5 * std::max(1.0, g.force[a].norm()));
    }
  }
  // A healthy right-angled corner feels nothing; the same corner turned over is pushed back.
  const auto healthy = fold_guard(Vec3(5, 0, 0), Vec3::Zero(), Vec3(0, 4, 0), n, 20.0, 0.25, 2.0);
  EXPECT_FALSE(healthy.active);
  EXPECT_EQ(healthy.energy, 0.0);
  const auto turned = fold_guard(Vec3(0, 4, 0), Vec3::Zero(), Vec3(5, 0, 0), n, 20.0, 0.25, 2.0);
  EXPECT_TRUE(turned.active);
  EXPECT_GT(turned.energy, 0.0);
}
