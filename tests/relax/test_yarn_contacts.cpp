// Contact pairs (Leaf 2018 §3.1): the grid search against brute force.
#include <gtest/gtest.h>

#include <random>

#include "relax/yarn_contacts.hpp"
#include "relax/yarn_model.hpp"
#include "relax/yarn_relax.hpp"
#include "relax/yarn_system.hpp"
#include "workflow/yarn_shape.hpp"
#include "testing.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;
using namespace skein::workflow;
using V = model::Vec3<double>;

namespace {
void expect_grid_finds_brute_forces_pairs(const YarnSystem& system) {
  for (double margin : {0.0, 0.5, 2.0}) {
    const auto grid = find_contact_pairs(system, system.points, margin);
    const auto brute = find_contact_pairs_brute_force(system, system.points, margin);
    EXPECT_GT(grid.pairs(), 0);
    EXPECT_EQ(grid.start, brute.start);
    EXPECT_EQ(grid.partner, brute.partner);
  }
}
}  // namespace

TEST(YarnContacts, GridFindsTheSamePairsAsBruteForce) {
  const auto yarn = skein::testing::yarn_of(skein::testing::small_piece(models::swatch(), "rib"));
  expect_grid_finds_brute_forces_pairs(make_yarn_system(yarn));
}

TEST(YarnContacts, GridFindsTheSamePairsAsBruteForceAmongLongAndShortSegments) {
  // Random yarn tangled in a box, a few of its steps six to twelve times longer than the rest: the long segments'
  // spheres are larger than the grid's cells, and look further out than one cell.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1, 1), chance(0, 1);
  for (int trial = 0; trial < 3; ++trial) {
    YarnCurves yarn;
    yarn.radius = 0.3;
    for (int c = 0; c < 30; ++c) {
      Eigen::Vector3d at(10 * unit(random), 10 * unit(random), 3 * unit(random));
      for (int k = 0; k < 60; ++k) {
        const Eigen::Vector3d step = Eigen::Vector3d(unit(random), unit(random), unit(random)).normalized();
        at += step * (chance(random) < 0.03 ? 6 + 6 * chance(random) : 1.0);
        yarn.points.push_back(at);
        yarn.point_face.push_back(-1);
        yarn.point_type.push_back(-1);
      }
      yarn.curve_start.push_back(static_cast<int>(yarn.points.size()));
      yarn.closed.push_back(c % 4 == 0);
    }
    expect_grid_finds_brute_forces_pairs(make_yarn_system(yarn));
  }
}
