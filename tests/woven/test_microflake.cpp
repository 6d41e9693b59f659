// The microflake phase function (Zhao 2012 §6, Jakob 2010): normalized, and sampled as it says.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "testing.hpp"
#include "woven_fixtures.hpp"
#include "woven/microflake.hpp"

using namespace skein;
using namespace skein::woven;
using namespace skein::testing;

TEST(WovenMicroflake, TheFlakesAndThePhaseFunctionIntegrateToOneAndSamplingFollowsThePhase) {
  const FiberMicroflake flakes(20);
  const Eigen::Vector3d f = Eigen::Vector3d(1, 2, 0.5).normalized();
  // Quadrature over the sphere (z, φ).
  const auto integrate = [](const std::function<double(const Eigen::Vector3d&)>& g) {
    const int nz = 800, np = 400;
    double sum = 0;
    for (int a = 0; a < nz; ++a)
      for (int b = 0; b < np; ++b) {
        const double z = -1 + (a + 0.5) * 2.0 / nz, phi = (b + 0.5) * 2 * std::numbers::pi / np, s = std::sqrt(1 - z * z);
        sum += g({s * std::cos(phi), s * std::sin(phi), z});
      }
    return sum * (2.0 / nz) * (2 * std::numbers::pi / np);
  };
  EXPECT_NEAR(integrate([&](const Eigen::Vector3d& m) { return flakes.density(m, f); }), 1.0, 2e-3);
  const Eigen::Vector3d wi = Eigen::Vector3d(0.3, -0.2, 0.9).normalized();
  EXPECT_NEAR(integrate([&](const Eigen::Vector3d& m) { return std::abs(wi.dot(m)) * flakes.density(m, f); }), flakes.sigma(wi, f), 2e-3);
  EXPECT_NEAR(integrate([&](const Eigen::Vector3d& wo) { return flakes.phase(wi, wo, f); }), 1.0, 2e-2);
  // Light across the fibre meets more flakes than light along it.
  EXPECT_GT(flakes.sigma(f.unitOrthogonal(), f), 2 * flakes.sigma(f, f));
  // Sampling: the mean of wo and the share of wo in a cone agree with the phase function's.
  std::mt19937_64 random(3);
  const int n = 200000;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) mean += flakes.sample(wi, f, random);
  mean /= n;
  const Eigen::Vector3d expected(integrate([&](const Eigen::Vector3d& wo) { return wo.x() * flakes.phase(wi, wo, f); }),
                                 integrate([&](const Eigen::Vector3d& wo) { return wo.y() * flakes.phase(wi, wo, f); }),
                                 integrate([&](const Eigen::Vector3d& wo) { return wo.z() * flakes.phase(wi, wo, f); }));
  EXPECT_LT((mean - expected).norm(), 0.02) << mean.transpose() << " vs " << expected.transpose();
}
