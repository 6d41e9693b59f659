// L-BFGS directions (relax/lbfgs.hpp) on a quadratic, and --method lbfgs on knitted yarn: under the force stop
// rule it converges where FIRE, in the same number of steps, does not, and no yarn passes through another.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "relax/lbfgs.hpp"
#include "relax/yarn_relax.hpp"
#include "testing.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;

namespace {

/// E(x) = ½ Σ_i k_i |x_i|² over the columns, each with its own stiffness (an ill-conditioned quadratic).
Eigen::Matrix3Xd quadratic_gradient(const Eigen::Matrix3Xd& x, const Eigen::VectorXd& k) {
  Eigen::Matrix3Xd g = x;
  for (int i = 0; i < x.cols(); ++i) g.col(i) *= k[i];
  return g;
}

}  // namespace

TEST(Lbfgs, FirstDirectionIsSteepestDescentAndMemoryFindsTheMinimumOfAQuadratic) {
  const int n = 6;
  Eigen::VectorXd k(n);
  k << 1, 3, 10, 30, 100, 300;
  Eigen::Matrix3Xd x = Eigen::Matrix3Xd::Ones(3, n);
  LbfgsMemory memory(8);
  Eigen::Matrix3Xd g = quadratic_gradient(x, k);
  EXPECT_TRUE(memory.direction(g).isApprox(-g));
  // Unit steps along the directions, the first scaled as the relaxer scales it (no line search): 40 steps take
  // the gradient down by 10⁸; steepest descent at the largest safe step, 1 / 300, leaves the softest mode at
  // (1 - 1/300)⁴⁰ ≈ 0.88 of where it was.
  const double first = g.norm();
  for (int step = 0; step < 40; ++step) {
    Eigen::Matrix3Xd d = memory.direction(g);
    if (memory.empty()) d *= 1.0 / 300;
    x += d;
    const Eigen::Matrix3Xd next = quadratic_gradient(x, k);
    memory.remember(d, next - g);
    g = next;
  }
  EXPECT_LT(g.norm(), 1e-8 * first);
}

TEST(Lbfgs, PairsWithoutPositiveCurvatureAreSkippedAndAnUphillDirectionForgetsTheMemory) {
  LbfgsMemory memory(4);
  Eigen::Matrix3Xd s = Eigen::Matrix3Xd::Ones(3, 2), y = -s;
  memory.remember(s, y);  // sᵀy < 0: not a pair BFGS may keep
  EXPECT_TRUE(memory.empty());
  memory.remember(s, s);
  EXPECT_FALSE(memory.empty());
  // A gradient along which the remembered curvature is positive gives a descent direction.
  const Eigen::Matrix3Xd g = Eigen::Matrix3Xd::Constant(3, 2, 2.0);
  EXPECT_LT(memory.direction(g).cwiseProduct(g).sum(), 0);
}

TEST(YarnRelax, LbfgsConvergesUnderTheForceRuleWhereFireDoesNotInAsManySteps) {
  const auto k = skein::testing::knitted(models::swatch(), "rib");
  YarnRelaxOptions options;
  options.stop_rule = StopRule::Force;
  options.method = YarnMethod::Lbfgs;
  options.max_steps = 4000;
  auto state = initial_state(k.system, options);
  const auto lbfgs = make_cpu_yarn_relaxer(k.system, k.targets, options)->run(state);
  ASSERT_TRUE(lbfgs.converged) << lbfgs.stopped_by << " force " << lbfgs.force_residual;
  EXPECT_EQ(lbfgs.pull_through_events, 0);
  EXPECT_LE(lbfgs.force_residual, options.force_tolerance);

  options.method = YarnMethod::Fire;
  options.max_steps = lbfgs.steps;
  options.audit = false;  // FIRE's yarn is not in question here, only how far it gets
  auto fire_state = initial_state(k.system, options);
  const auto fire = make_cpu_yarn_relaxer(k.system, k.targets, options)->run(fire_state);
  EXPECT_FALSE(fire.converged);
  EXPECT_GT(fire.energy, lbfgs.energy);
}

TEST(YarnRelax, LbfgsRefusesTheActiveSet) {
  YarnRelaxOptions options;
  options.method = YarnMethod::Lbfgs;
  options.active_set.enabled = true;
  EXPECT_THROW(options.validate(), Error);
  options.active_set.enabled = false;
  options.lbfgs_memory = 0;
  EXPECT_THROW(options.validate(), Error);
}
