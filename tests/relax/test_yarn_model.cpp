// The yarn model's energies against finite differences, and the contact pairs against brute force.
#include <gtest/gtest.h>

#include <random>

#include "relax/yarn_contacts.hpp"
#include "relax/yarn_model.hpp"
#include "relax/yarn_relax.hpp"
#include "relax/yarn_system.hpp"
#include "stitchmesh/pattern.hpp"
#include "workflow/yarn_shape.hpp"
#include "testing.hpp"
#include "gradient_check.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;
using namespace skein::workflow;
using V = model::Vec3<double>;
using skein::testing::expect_gradient;
using skein::testing::random_points;

namespace {

void to_vec(const Eigen::Matrix3Xd& m, int first, V out[4]) {
  for (int k = 0; k < 4; ++k) out[k] = {m(0, first + k), m(1, first + k), m(2, first + k)};
}

}  // namespace

TEST(YarnModel, BasisSumsToOneAndPieceHullHoldsTheCurve) {
  for (double s : {0.0, 0.3, 0.5, 1.0}) {
    double w[4], d[4], dd[4];
    model::basis(s, w);
    model::basis_d1(s, d);
    model::basis_d2(s, dd);
    EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1, 1e-15);
    EXPECT_NEAR(d[0] + d[1] + d[2] + d[3], 0, 1e-15);
    EXPECT_NEAR(dd[0] + dd[1] + dd[2] + dd[3], 0, 1e-15);
  }
  const auto p = random_points(4, 2.0, 3);
  V q[4], b[4];
  to_vec(p, 0, q);
  model::piece_bezier(q, 0.2, 0.7, b);
  const V c = (b[0] + b[1] + b[2] + b[3]) * 0.25;
  double radius = 0;
  for (const auto& x : b) radius = std::max(radius, model::norm(x - c));
  for (int i = 0; i <= 50; ++i) {
    double w[4];
    model::basis(0.2 + 0.5 * i / 50.0, w);
    EXPECT_LE(model::norm(model::combine(w, q) - c), radius + 1e-12);
  }
}

TEST(YarnModel, IntrinsicGradientMatchesFiniteDifferences) {
  const model::IntrinsicParams<double> k{0.7, 3.0, 11.0};
  const auto p0 = random_points(4, 0.4, 1);
  const double rest = 1.3;
  const auto energy = [&](const Eigen::Matrix3Xd& p) {
    V q[4], g[4] = {};
    to_vec(p, 0, q);
    return model::segment_intrinsic(q, rest, k, g);
  };
  V q[4], g[4] = {};
  to_vec(p0, 0, q);
  model::segment_intrinsic(q, rest, k, g);
  Eigen::Matrix3Xd grad(3, 4);
  for (int i = 0; i < 4; ++i) grad.col(i) << g[i].x, g[i].y, g[i].z;
  expect_gradient(p0, grad, energy);
}

TEST(YarnModel, ContactGradientMatchesFiniteDifferencesIncludingTheSoftCore) {
  for (const double gap : {0.8, 0.15}) {  // ordinary overlap, and centrelines inside the linear core
    // Two open yarns of four points crossing each other `gap` apart (yarn radius 0.5).
    relax::YarnCurves yarn;
    yarn.radius = 0.5;
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0), {1, 0.1, 0}, {2, -0.1, 0.1}, {3, 0, 0}, {1.5, -1.5, gap}, {1.6, -0.5, gap + 0.05},
                                    {1.4, 0.5, gap - 0.05}, {1.5, 1.5, gap}})
      yarn.points.push_back(p);
    yarn.curve_start = {0, 4, 8};
    yarn.closed = {0, 0};
    yarn.point_face.assign(8, -1);
    yarn.point_type.assign(8, -1);
    const auto system = make_yarn_system(yarn);
    YarnParams params;
    params.k_bend = params.k_stretch = params.k_length = 0;  // contact alone
    const auto pairs = find_contact_pairs(system, system.points, 0.5);
    ASSERT_GT(pairs.pairs(), 0);
    Eigen::Matrix3Xd grad;
    EXPECT_GT(yarn_energy(system, params, pairs, system.points, grad), 0);
    expect_gradient(system.points, grad, [&](const Eigen::Matrix3Xd& x) {
      Eigen::Matrix3Xd g;
      return yarn_energy(system, params, pairs, x, g);
    });
  }
}

TEST(YarnModel, ContactDampingOpposesRelativeVelocity) {
  const model::ContactParams<double> k{1.0, 0.3, 2.0, 0.5, 0.5};
  V g{0, 0, 0}, d{0, 0, 0};
  // b sits 0.6 above a and moves away along the normal: the damping drags a along (+z), and only along z.
  model::sample_contact(V{0, 0, 0}, V{0, 0, 0.6}, V{0, 0, 0}, V{0, 0, 1}, 1.0, k, g, d);
  EXPECT_GT(d.z, 0);
  EXPECT_NEAR(d.x, 0, 1e-12);
  EXPECT_GT(g.z, 0);  // the energy grows toward b: the contact force pushes a down, away from it
}

TEST(YarnModel, StepBoundKeepsTheMoveUnderTheLimit) {
  for (double u : {0.0, 0.5, 3.0})
    for (double a : {0.0, 1.0, 100.0}) {
      if (u == 0 && a == 0) continue;
      const double dt = model::step_bound(u, a, 0.1);
      EXPECT_NEAR(u * dt + a * dt * dt, 0.1, 1e-12) << u << " " << a;
    }
}

TEST(YarnModel, WholeYarnEnergyGradientMatchesFiniteDifferences) {
  auto yarn = skein::testing::linked_rings(0.6, 12);
  for (auto& p : yarn.points) p *= 0.5;  // squeeze: the rings overlap
  const auto system = make_yarn_system(yarn, 0.9);
  YarnParams params;
  params.k_bend = 0.5;
  const auto pairs = find_contact_pairs(system, system.points, 2 * system.radius);
  ASSERT_GT(pairs.pairs(), 0);
  Eigen::Matrix3Xd grad;
  const double e = yarn_energy(system, params, pairs, system.points, grad);
  EXPECT_GT(e, 0);
  expect_gradient(system.points, grad, [&](const Eigen::Matrix3Xd& x) {
    Eigen::Matrix3Xd g;
    return yarn_energy(system, params, pairs, x, g);
  }, 1e-6, 2e-5);
}
