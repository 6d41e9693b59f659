// Contact pairs (Leaf 2018 §3.1): the grid search against brute force.
#include <gtest/gtest.h>

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

TEST(YarnContacts, GridFindsTheSamePairsAsBruteForce) {
  const auto yarn = skein::testing::yarn_of(skein::testing::small_piece(models::swatch(), "rib"));
  const auto system = make_yarn_system(yarn);
  for (double margin : {0.0, 0.5, 2.0}) {
    const auto grid = find_contact_pairs(system, system.points, margin);
    const auto brute = find_contact_pairs_brute_force(system, system.points, margin);
    EXPECT_GT(grid.pairs(), 0);
    EXPECT_EQ(grid.start, brute.start);
    EXPECT_EQ(grid.partner, brute.partner);
  }
}
