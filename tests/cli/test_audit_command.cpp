// skein audit: what changed between two states, named by stitch
#include <gtest/gtest.h>

#include <string>

#include "workflow/yarn_io.hpp"
#include "cli_support.hpp"

using namespace skein::testing::cli;
using skein::testing::ScratchDir;

TEST(Cli, AuditWithTheStitchIdsNamesTheStitchesOfEachCrossing) {
  ScratchDir dir;
  const auto project = dir / "s.skein";
  ASSERT_EQ(run_skein("stitch " + kModels + "/swatch.obj --auto-label --stitch-size 15 -o " + project.string()).status, 0);
  ASSERT_EQ(run_skein("yarn " + project.string() + " -o " + (dir / "a.bcc").string() + " --ids " + (dir / "ids.csv").string()).status, 0);
  // A negative control: one control point of a stitch pulled 1.5 stitches up through the rows above it.
  auto yarn = skein::workflow::read_bcc(dir / "a.bcc");
  const auto ids = read_ids(dir / "ids.csv");
  int p = static_cast<int>(yarn.points.size()) / 2;
  while (ids[p].face < 0) ++p;
  yarn.points[p].y() += 20;
  skein::workflow::write_bcc(yarn, dir / "b.bcc");
  auto r = run_skein("audit " + (dir / "a.bcc").string() + " " + (dir / "b.bcc").string() + " --ids " + (dir / "ids.csv").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("[face " + std::to_string(ids[p].face) + ", row " + std::to_string(ids[p].row) + ", " + ids[p].type + "]"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("stitches in the crossings: "), std::string::npos) << r.output;
  // Ids of another yarn are refused, naming the file.
  ASSERT_EQ(run_skein("stitch " + kModels + "/tube.obj --auto-label --stitch-size 15 -o " + (dir / "t.skein").string()).status, 0);
  ASSERT_EQ(run_skein("yarn " + (dir / "t.skein").string() + " -o " + (dir / "t.bcc").string() + " --ids " + (dir / "t.csv").string()).status, 0);
  r = run_skein("audit " + (dir / "a.bcc").string() + " " + (dir / "b.bcc").string() + " --ids " + (dir / "t.csv").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("t.csv"), std::string::npos) << r.output;
}
