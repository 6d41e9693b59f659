// skein label: knitting rows labelled by hand and stored
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_support.hpp"

using namespace skein::testing::cli;
using skein::testing::ScratchDir;

TEST(Cli, LabelRowByRowByHand) {
  ScratchDir dir;
  const auto out = (dir / "l.skein").string();
  // The swatch's bottom border edge 0, then the next row across course edge 2 (face 0's top edge).
  // Rows 2 and 3 are still unlabeled: named, and nothing is written (exit 2) unless --partial asks for it.
  const auto refused = run_skein("label " + kModels + "/swatch.obj --first-row 0 --next-row 2 -o " + out);
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_NE(refused.output.find("8 of 16 faces are not labeled (listed above); nothing written. --partial writes"), std::string::npos) << refused.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  const auto partial = run_skein("label " + kModels + "/swatch.obj --first-row 0 --next-row 2 --partial -o " + out);
  EXPECT_EQ(partial.status, 1) << partial.output;
  EXPECT_NE(partial.output.find("is not labeled"), std::string::npos) << partial.output;
  const auto stats = run_skein("stats " + out + " --json");
  EXPECT_NE(stats.output.find("\"invalid_faces\": 8"), std::string::npos) << stats.output;
  const auto bad = run_skein("label " + kModels + "/swatch.obj --first-row 2 -o " + out);  // an inner edge
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.output.find("not a border edge"), std::string::npos) << bad.output;
}
