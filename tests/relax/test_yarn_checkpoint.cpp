// Checkpoints: a run written and read back goes on bit for bit; broken checkpoints are refused.
#include <gtest/gtest.h>

#include <fstream>

#include "common/error.hpp"
#include "relax/yarn_checkpoint.hpp"
#include "relax/yarn_relax.hpp"
#include "testing.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;
using Eigen::Vector3d;
using skein::testing::relaxed;

TEST(YarnCheckpoint, ResumeEqualsAnUninterruptedRun) {
  skein::testing::ScratchDir dir;
  const auto [piece, yarn, system, targets] = skein::testing::knitted(models::swatch(), "rib");
  for (const auto method : {YarnMethod::Fire, YarnMethod::Lbfgs}) {
    SCOPED_TRACE(to_string(method));
    YarnRelaxOptions options;
    options.method = method;
    options.max_steps = 70;
    options.tolerance = 0;
    options.checkpoint = dir / "run.ckp";
    options.checkpoint_every = 25;
    const auto whole = relaxed(system, options, targets);
    ASSERT_EQ(whole.report.steps, 70);
    // Interrupted at step 50 (the cap stands in for a killed job: the last checkpoint is from step 50), then resumed.
    options.checkpoint = dir / "part.ckp";
    options.max_steps = 50;
    relaxed(system, options, targets);
    auto state = read_checkpoint(options.checkpoint, checkpoint_fingerprint(system, options.method), system.num_points());
    EXPECT_EQ(state.step, 50);
    options.max_steps = 70;
    const auto report = make_cpu_yarn_relaxer(system, targets, options)->run(state);
    EXPECT_EQ(report.steps, 70);
    EXPECT_EQ(state.points, whole.state.points);
    EXPECT_EQ(state.velocities, whole.state.velocities);
    EXPECT_EQ(report.guard.pairs_tested, whole.report.guard.pairs_tested);
    // A run stopped by its cap leaves its last state behind.
    EXPECT_EQ(read_checkpoint(options.checkpoint, checkpoint_fingerprint(system, options.method), system.num_points()).step, 70);
  }
}

TEST(YarnCheckpoint, DamagedOrForeignCheckpointsAreRejected) {
  skein::testing::ScratchDir dir;
  const auto yarn = skein::testing::linked_rings();
  const auto system = make_yarn_system(yarn);
  YarnRelaxOptions options;
  const auto fingerprint = checkpoint_fingerprint(system, options.method);
  const auto path = dir / "good.ckp";
  write_checkpoint(path, fingerprint, initial_state(system, options));
  EXPECT_NO_THROW(read_checkpoint(path, fingerprint, system.num_points()));
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto error_for = [&](const std::string& name, const std::string& content, std::uint64_t fp) {
    const auto p = dir.write(name, content);
    return skein::testing::error_of([&] { read_checkpoint(p, fp, system.num_points()); });
  };
  std::string flipped = bytes;
  flipped[200] ^= 0x10;
  EXPECT_NE(error_for("flipped.ckp", flipped, fingerprint).find("checksum does not match"), std::string::npos);
  EXPECT_NE(error_for("short.ckp", bytes.substr(0, bytes.size() / 2), fingerprint).find("damaged or truncated"), std::string::npos);
  EXPECT_NE(error_for("tiny.ckp", bytes.substr(0, 10), fingerprint).find("truncated"), std::string::npos);
  EXPECT_NE(error_for("text.ckp", "hello, this is not a checkpoint at all", fingerprint).find("not a skein checkpoint"), std::string::npos);
  EXPECT_NE(error_for("other.ckp", bytes, checkpoint_fingerprint(system, YarnMethod::Euler)).find("another yarn or method"), std::string::npos);
  const auto missing = skein::testing::error_of([&] { read_checkpoint(dir / "none.ckp", fingerprint, system.num_points()); });
  EXPECT_NE(missing.find("none.ckp"), std::string::npos);
  EXPECT_NE(error_for("flipped.ckp", flipped, fingerprint).find("flipped.ckp"), std::string::npos);
}
