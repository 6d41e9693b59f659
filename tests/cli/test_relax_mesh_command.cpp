// skein relax-mesh: the relaxed project, its stretch picture and report
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_support.hpp"

using namespace skein::testing::cli;
using skein::testing::ScratchDir;

TEST(Cli, RelaxMeshWritesTheRelaxedProjectStretchAndReport) {
  ScratchDir dir;
  const auto project = (dir / "tube.skein").string();
  ASSERT_EQ(run_skein("stitch " + kModels + "/tube.obj --auto-label -o " + project).status, 0);
  const auto r = run_skein("relax-mesh " + project + " -o " + (dir / "r.skein").string() + " --png " + (dir / "s.png").string() + " --ply " +
                           (dir / "s.ply").string() + " --report " + (dir / "r.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("largest move"), std::string::npos) << r.output;  // the per-step log
  EXPECT_NE(r.output.find("converged"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "s.png"));
  const std::string ply = slurp(dir / "s.ply");
  EXPECT_NE(ply.find("property uchar red"), std::string::npos);
  EXPECT_NE(ply.find("property float area_strain"), std::string::npos);
  EXPECT_NE(slurp(dir / "r.json").find("\"r_course\""), std::string::npos);
  // The relaxed project still holds a valid stitch mesh that yarn can be emitted from.
  EXPECT_EQ(run_skein("yarn " + (dir / "r.skein").string() + " -o " + (dir / "y.bcc").string()).status, 0);
  const auto labels_only = run_skein("relax-mesh " + kModels + "/tube.skein -o " + (dir / "x.skein").string());
  EXPECT_EQ(labels_only.status, 2);
  EXPECT_NE(labels_only.output.find("needs an input mesh and a stitch mesh"), std::string::npos) << labels_only.output;
  EXPECT_EQ(run_skein("relax-mesh " + project + " --alpha 2 -o " + (dir / "x.skein").string()).status, 2);
}
