#pragma once
// Finite-difference checks of gradients, and random points to check them at.
#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Core>
#include <gtest/gtest.h>

namespace skein::testing {

/// Central differences of `energy` over the 3 x n coordinates of `x`, compared with `gradient`.
template <class F>
void expect_gradient(Eigen::Matrix3Xd x, const Eigen::Matrix3Xd& gradient, F energy, double h = 1e-6, double rel = 1e-5) {
  double scale = 0;
  for (int i = 0; i < x.size(); ++i) scale = std::max(scale, std::abs(gradient.data()[i]));
  ASSERT_GT(scale, 0);
  for (int i = 0; i < x.size(); ++i) {
    const double keep = x.data()[i];
    x.data()[i] = keep + h;
    const double up = energy(x);
    x.data()[i] = keep - h;
    const double down = energy(x);
    x.data()[i] = keep;
    EXPECT_NEAR((up - down) / (2 * h), gradient.data()[i], rel * scale + 1e-9) << "coordinate " << i;
  }
}

/// n points about 1 apart along x, each moved by up to `spread` in every coordinate.
inline Eigen::Matrix3Xd random_points(int n, double spread, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-spread, spread);
  Eigen::Matrix3Xd p(3, n);
  for (int i = 0; i < n; ++i) p.col(i) = Eigen::Vector3d(i * 1.0 + u(rng), u(rng), u(rng));
  return p;
}

}  // namespace skein::testing
