// The CUDA relaxer against the CPU reference: contact pairs, parity of steps and of converged results, the
// pull-through guard, determinism and checkpoints. Every test skips when no GPU answers.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "cuda/device.hpp"
#include "cuda/yarn_device.hpp"
#include "cuda/yarn_relaxer.hpp"
#include "relax/yarn_audit.hpp"
#include "relax/yarn_checkpoint.hpp"
#include "skein/config.hpp"
#include "testing.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;

namespace {

#define SKIP_WITHOUT_GPU()                                                  \
  do {                                                                      \
    const auto q = cuda::query_devices();                                   \
    if (!q.available()) GTEST_SKIP() << "no CUDA device: " << q.reason;     \
  } while (0)

struct Run {
  YarnState state;
  YarnRelaxReport report;
};

Run relaxed(Backend backend, const YarnSystem& system, const YarnRelaxOptions& options, const ShapeTargets& targets = {}) {
  Run run{initial_state(system, options), {}};
  run.report = cuda::make_yarn_relaxer(backend, system, targets, options)->run(run.state);
  return run;
}

/// Largest distance between the same control point in two states, in yarn radii.
double largest_gap(const YarnSystem& system, const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b) {
  return (a - b).colwise().norm().maxCoeff() / system.radius;
}

}  // namespace

TEST(CudaYarnRelaxer, BackendCudaWithoutAGpuIsAClearError) {
  if (cuda::query_devices().available()) GTEST_SKIP() << "a GPU answered";
  const auto k = skein::testing::knitted(models::swatch(), "");
  try {
    cuda::make_yarn_relaxer(Backend::Cuda, k.system, {}, {});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no CUDA GPU answered"), std::string::npos) << e.what();
  }
  // Auto falls back to the CPU.
  const auto report = relaxed(Backend::Auto, k.system, [] {
    YarnRelaxOptions o;
    o.max_steps = 2;
    return o;
  }()).report;
  EXPECT_EQ(report.backend, "cpu");
}

#if SKEIN_HAS_CUDA  // DeviceYarn exists only in CUDA builds
TEST(CudaYarnRelaxer, ContactPairsFromTheGpuGridEqualBruteForce) {
  SKIP_WITHOUT_GPU();
  const auto k = skein::testing::knitted(models::swatch(), "rib");
  YarnRelaxOptions options;
  cuda::DeviceYarn device(k.system, k.targets, options);
  device.set_state(initial_state(k.system, options));
  device.rebuild_contacts();
  const auto gpu = device.contact_pairs();
  const auto cpu = find_contact_pairs_brute_force(k.system, k.system.points, options.contact_margin * k.system.radius);
  // Float spheres on the GPU: pairs within a hair of the reach may differ; none other may.
  long differ = 0;
  ASSERT_EQ(gpu.start.size(), cpu.start.size());
  for (int s = 0; s + 1 < static_cast<int>(cpu.start.size()); ++s) {
    std::vector<int> a(gpu.partner.begin() + gpu.start[s], gpu.partner.begin() + gpu.start[s + 1]);
    std::vector<int> b(cpu.partner.begin() + cpu.start[s], cpu.partner.begin() + cpu.start[s + 1]);
    EXPECT_TRUE(std::is_sorted(a.begin(), a.end()));
    std::vector<int> only;
    std::set_symmetric_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(only));
    differ += static_cast<long>(only.size());
  }
  EXPECT_LE(differ, cpu.pairs() / 1000 + 2) << "of " << cpu.pairs() << " pairs";
  EXPECT_GT(cpu.pairs(), 0);
}
#endif

TEST(CudaYarnRelaxer, FireStepsFollowTheCpuReference) {
  SKIP_WITHOUT_GPU();
  const auto k = skein::testing::knitted(models::swatch(), "rib");
  YarnRelaxOptions options;
  options.max_steps = 30;
  options.tolerance = 0;
  const auto cpu = relaxed(Backend::Cpu, k.system, options, k.targets);
  const auto gpu = relaxed(Backend::Cuda, k.system, options, k.targets);
  EXPECT_EQ(gpu.report.steps, 30);
  EXPECT_NE(gpu.report.backend.find("cuda"), std::string::npos);
  EXPECT_LT(largest_gap(k.system, cpu.state.points, gpu.state.points), 0.05);
  EXPECT_NEAR(gpu.report.energy, cpu.report.energy, 1e-3 * std::abs(cpu.report.energy));
  EXPECT_EQ(gpu.report.pull_through_events, 0);
}

TEST(CudaYarnRelaxer, EulerStepsFollowTheCpuReference) {
  SKIP_WITHOUT_GPU();
  const auto k = skein::testing::knitted(models::swatch(), "");
  YarnRelaxOptions options;
  options.method = YarnMethod::Euler;
  options.max_steps = 40;
  options.tolerance = 0;
  const auto cpu = relaxed(Backend::Cpu, k.system, options);
  const auto gpu = relaxed(Backend::Cuda, k.system, options);
  EXPECT_LT(largest_gap(k.system, cpu.state.points, gpu.state.points), 0.05);
  EXPECT_EQ(gpu.report.pull_through_events, 0);
}

TEST(CudaYarnRelaxer, ConvergedEnergyAgreesWithTheCpu) {
  SKIP_WITHOUT_GPU();
  for (const auto& [model, fill] : {std::pair{models::swatch(), "rib"}, std::pair{models::tube(), "seed"}}) {
    const auto k = skein::testing::knitted(model, fill, {12, 10});
    YarnRelaxOptions options;
    const auto cpu = relaxed(Backend::Cpu, k.system, options, k.targets);
    const auto gpu = relaxed(Backend::Cuda, k.system, options, k.targets);
    ASSERT_TRUE(cpu.report.converged);
    EXPECT_TRUE(gpu.report.converged) << gpu.report.stopped_by << " residual " << gpu.report.residual;
    EXPECT_NEAR(gpu.report.energy, cpu.report.energy, 1e-3 * std::abs(cpu.report.energy)) << fill;
    EXPECT_EQ(gpu.report.pull_through_events, 0) << fill;
  }
}

TEST(CudaYarnRelaxer, SqueezedLinkedRingsStayLinked) {
  SKIP_WITHOUT_GPU();
  const auto yarn = skein::testing::linked_rings();
  const auto system = make_yarn_system(yarn, 0.3);
  YarnRelaxOptions options;
  options.max_steps = 400;
  options.tolerance = 0;
  options.guard.max_move = 1.0;
  options.contact_margin = 2.0;
  const auto run = relaxed(Backend::Cuda, system, options);
  EXPECT_EQ(run.report.pull_through_events, 0);
  const auto links = linking_numbers(with_points(yarn, run.state.points));
  ASSERT_EQ(links.size(), 1u);
  EXPECT_EQ(std::abs(links[0].number), 1);
}

TEST(CudaYarnRelaxer, RunsAreDeterministic) {
  SKIP_WITHOUT_GPU();
  const auto k = skein::testing::knitted(models::swatch(), "seed");
  YarnRelaxOptions options;
  options.max_steps = 60;
  options.audit = false;
  const auto a = relaxed(Backend::Cuda, k.system, options, k.targets);
  const auto b = relaxed(Backend::Cuda, k.system, options, k.targets);
  EXPECT_EQ(a.state.points, b.state.points);
  EXPECT_EQ(a.report.guard.pairs_tested, b.report.guard.pairs_tested);
}

TEST(CudaYarnRelaxer, ResumeEqualsAnUninterruptedRun) {
  SKIP_WITHOUT_GPU();
  skein::testing::ScratchDir dir;
  const auto k = skein::testing::knitted(models::swatch(), "rib");
  YarnRelaxOptions options;
  options.max_steps = 70;
  options.tolerance = 0;
  options.audit = false;
  options.checkpoint = dir / "run.ckp";
  options.checkpoint_every = 25;
  const auto whole = relaxed(Backend::Cuda, k.system, options, k.targets);
  ASSERT_EQ(whole.report.steps, 70);
  options.checkpoint = dir / "part.ckp";
  options.max_steps = 50;
  relaxed(Backend::Cuda, k.system, options, k.targets);
  auto state = read_checkpoint(options.checkpoint, checkpoint_fingerprint(k.system, options.method), k.system.num_points());
  EXPECT_EQ(state.step, 50);
  options.max_steps = 70;
  const auto report = cuda::make_yarn_relaxer(Backend::Cuda, k.system, k.targets, options)->run(state);
  EXPECT_EQ(report.steps, 70);
  EXPECT_EQ(state.points, whole.state.points);
}
