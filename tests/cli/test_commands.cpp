// What the commands share when they relax: OpenMP threads that sleep while they wait
#include <gtest/gtest.h>

#include <string>

#include "cli_support.hpp"

using namespace skein::testing::cli;
using skein::testing::ScratchDir;

// Issue 28 part 3: skein's OpenMP threads sleep while they wait unless the user chose a policy, and the thread
// count follows the free cores unless OMP_NUM_THREADS is set (ctest sets OMP_WAIT_POLICY=PASSIVE for every test).
TEST(Cli, ThreadsSleepWhileTheyWaitUnlessTheUserChose) {
  ScratchDir dir;
  const std::string relax = "pattern " + std::string(SKEIN_PATTERNS_DIR) + "/garter.knit --relax --max-steps 5 --no-audit -o " +
                            (dir / "g.bcc").string() + " --report " + (dir / "r.json").string();
  auto r = skein::testing::run_command("env -u OMP_WAIT_POLICY -u OMP_NUM_THREADS " + std::string(SKEIN_BIN) + " " + relax);
  ASSERT_EQ(r.status, 0) << r.output;
  auto report = slurp(dir / "r.json");
  EXPECT_NE(report.find("\"wait_policy\": \"passive\""), std::string::npos) << report;
  EXPECT_NE(report.find("\"threads_follow_free_cores\": true"), std::string::npos) << report;
  r = skein::testing::run_command("env OMP_WAIT_POLICY=active OMP_NUM_THREADS=1 " + std::string(SKEIN_BIN) + " " + relax);
  ASSERT_EQ(r.status, 0) << r.output;
  report = slurp(dir / "r.json");
  EXPECT_NE(report.find("\"wait_policy\": \"active\""), std::string::npos) << report;
  EXPECT_NE(report.find("\"threads_follow_free_cores\": false"), std::string::npos) << report;
  EXPECT_NE(report.find("\"threads\": 1,"), std::string::npos) << report;
}
