// Shape preservation's patch tracking (Yuksel 2012 §6.2 with Leaf's periodic map beside it): its gradient on both
// phases of the biphasic spring.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "gradient_check.hpp"
#include "relax/shape_targets.hpp"

using namespace skein::relax;
using skein::testing::expect_gradient;
using skein::testing::random_points;

TEST(YarnModel, PatchTrackingGradientMatchesFiniteDifferencesOnBothPhases) {
  ShapeTargets targets;
  ShapeTargets::Patch patch;
  patch.points = {0, 1, 2};
  patch.weights = {1, 0.5, 0.5};
  patch.weight_sum = 2;
  patch.normal = Eigen::Vector3d(0.2, 0.3, 1).normalized();
  targets.patches.push_back(patch);
  ShapeOptions options;
  for (const double drift : {0.1, 3.0}) {  // under and over the biphasic threshold
    Eigen::Matrix3Xd p = random_points(3, 0.3, 7);
    targets.patches[0].start_sum = p.col(0) + 0.5 * p.col(1) + 0.5 * p.col(2);
    p.row(2).array() += drift;
    Eigen::Matrix3Xd grad = Eigen::Matrix3Xd::Zero(3, 3);
    patch_energy(targets, options, 1.0, p, grad);
    expect_gradient(p, grad, [&](const Eigen::Matrix3Xd& x) {
      Eigen::Matrix3Xd g = Eigen::Matrix3Xd::Zero(3, 3);
      return patch_energy(targets, options, 1.0, x, g);
    });
  }
}
