// skein edit: stitch types painted and rows filled on a project
#include <gtest/gtest.h>

#include <string>

#include "cli_support.hpp"

using namespace skein::testing::cli;
using skein::testing::ScratchDir;

TEST(Cli, EditFillsRows) {
  ScratchDir dir;
  ASSERT_EQ(run_skein("stitch " + kModels + "/swatch.obj --auto-label -o " + (dir / "s.skein").string()).status, 0);
  const auto r = run_skein("edit " + (dir / "s.skein").string() + " --fill rib2x2 --rows 0:3 -o " + (dir / "r.skein").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto stats = run_skein("stats " + (dir / "r.skein").string() + " --json");
  EXPECT_NE(stats.output.find("\"p\": 40"), std::string::npos) << stats.output;  // 4 rows x 10 purls of 20
  EXPECT_EQ(run_skein("edit " + (dir / "s.skein").string() + " --fill ribbing -o " + (dir / "x.skein").string()).status, 2);
}

TEST(Cli, EditedTessellationValuesCarryIntoTheStitchMesh) {
  ScratchDir dir;
  const auto labels = dir / "labels.skein";
  // Row 0 of the swatch gets 2 stitch rows instead of 5.
  const auto r = run_skein("label " + kModels + "/swatch.obj --row-value 0=2 -o " + labels.string());
  ASSERT_EQ(r.status, 0) << r.output;
  ASSERT_EQ(run_skein("stitch " + kModels + "/swatch.obj --labels " + labels.string() + " -o " + (dir / "s.skein").string()).status, 0);
  const auto stats = run_skein("stats " + (dir / "s.skein").string() + " --json");
  EXPECT_NE(stats.output.find("\"faces\": 340"), std::string::npos) << stats.output;  // 17 rows of 20
  const auto bad = run_skein("label " + kModels + "/swatch.obj --row-value 0=0 -o " + labels.string());
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.output.find("at least 1"), std::string::npos) << bad.output;
}
