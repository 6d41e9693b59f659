// Smocking patterns as text (docs/smocking.md): paths, walks, repeats, the three styles, every error.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "smocking/smocking_pattern.hpp"
#include "testing.hpp"

using namespace skein;
using namespace skein::smocking;

namespace {
std::string error_in(const std::string& text) {
  return skein::testing::error_of([&] { parse_smocking_pattern(text, "test.smock"); });
}
const std::string kHead = "format smocking\ngrid 9 5\n";
}  // namespace

TEST(SmockingPattern, PathsWalksAndRepeatsBecomeThreads) {
  const auto p = parse_smocking_pattern("# name: Test zigzag\n# source: made here\nformat smocking\nstyle italian\ngrid 9 5\nspacing 5\ngamma 0.25\n"
                                        "path back 0,0 1,1 2,0\nwalk 0,3 1,-1 1,1 x4   # a comment\nrepeat 4,0 x2\n",
                                        "t.smock");
  EXPECT_EQ(p.name, "Test zigzag");
  EXPECT_EQ(p.note, "made here");
  EXPECT_EQ(p.style, Style::Italian);
  EXPECT_EQ(p.columns, 9);
  EXPECT_EQ(p.rows, 5);
  EXPECT_DOUBLE_EQ(p.spacing, 5);
  EXPECT_DOUBLE_EQ(p.gamma, 0.25);
  ASSERT_EQ(p.threads.size(), 4u);  // two threads, then each again 4 columns on
  EXPECT_FALSE(p.threads[0].first_front);
  EXPECT_FALSE(p.threads[0].front(0));
  EXPECT_TRUE(p.threads[0].front(1));
  const std::vector<Eigen::Vector2i> walk{{0, 3}, {1, 2}, {2, 3}, {3, 2}, {4, 3}};
  EXPECT_EQ(p.threads[1].points, walk);
  EXPECT_TRUE(p.threads[1].first_front);
  EXPECT_EQ(p.threads[2].points[0], Eigen::Vector2i(4, 0));
  EXPECT_EQ(p.threads[3].points.back(), Eigen::Vector2i(8, 3));
  EXPECT_EQ(p.num_stitches(), 2 * (2 + 4));
  EXPECT_EQ(p.rest_position({2, 3}), Eigen::Vector2d(10, -15));
}

TEST(SmockingPattern, ErrorsNameTheLineColumnAndRule) {
  EXPECT_NE(error_in("").find("test.smock: empty: expected \"format smocking\""), std::string::npos) << error_in("");
  EXPECT_NE(error_in("grid 3 3\n").find("test.smock: line 1, column 1: expected the format first (\"format smocking\"), found \"grid\""), std::string::npos)
      << error_in("grid 3 3\n");
  EXPECT_NE(error_in("format knit\n").find("line 1, column 8: this reader takes \"format smocking\""), std::string::npos) << error_in("format knit\n");
  EXPECT_NE(error_in("format smocking\n").find("no grid"), std::string::npos);
  EXPECT_NE(error_in(kHead).find("no thread"), std::string::npos);
  EXPECT_NE(error_in("format smocking\npath 0,0 1,1\n").find("line 2, column 1: a thread before the grid"), std::string::npos);
  EXPECT_NE(error_in(kHead + "path 0,0 9,1\n").find("line 3: point 2 (9,1) is off the grid of 9 x 5 points (columns 0 to 8, rows 0 to 4)"),
            std::string::npos)
      << error_in(kHead + "path 0,0 9,1\n");
  EXPECT_NE(error_in(kHead + "path 0,0 0,0\n").find("stitch 1 goes from (0,0) to the same point"), std::string::npos);
  EXPECT_NE(error_in(kHead + "path 0,0\n").find("a path of at least two grid points"), std::string::npos);
  EXPECT_NE(error_in(kHead + "path 0,0 1;1\n").find("line 3, column 10: expected a grid point as COLUMN,ROW, found \"1;1\""), std::string::npos)
      << error_in(kHead + "path 0,0 1;1\n");
  EXPECT_NE(error_in(kHead + "path 0,0 a,1\n").find("expected a grid point (a whole number), found \"a,1\""), std::string::npos)
      << error_in(kHead + "path 0,0 a,1\n");
  EXPECT_NE(error_in(kHead + "walk 0,0 1,0 4\n").find("column 14: expected a count as xN"), std::string::npos) << error_in(kHead + "walk 0,0 1,0 4\n");
  EXPECT_NE(error_in(kHead + "walk 0,0 1,0 x9\n").find("point 10 (9,0) is off the grid"), std::string::npos);
  EXPECT_NE(error_in(kHead + "walk 0,0 x2\n").find("expected \"walk [front|back] C,R STEP... xN\""), std::string::npos);
  EXPECT_NE(error_in(kHead + "repeat 1,0 x2\n").find("nothing to repeat yet"), std::string::npos);
  EXPECT_NE(error_in(kHead + "walk 0,1 front 1,0 x2\n").find("column 10: \"front\" comes right after \"walk\""), std::string::npos)
      << error_in(kHead + "walk 0,1 front 1,0 x2\n");
  EXPECT_NE(error_in(kHead + "walk 0,1 x2 1,0\n").find("the count \"x2\" comes last, after the steps"), std::string::npos);
  EXPECT_NE(error_in(kHead + "walk 0,1 1,0 x99999999999\n").find("expected a count of 1 to 1000000 (a whole number)"), std::string::npos)
      << error_in(kHead + "walk 0,1 1,0 x99999999999\n");
  EXPECT_NE(error_in(kHead + "path 0,0 1,1\nrepeat 4,0 x3\n").find("line 4: copy 3 of the thread of line 3: point 2 (9,1) is off the grid"),
            std::string::npos)
      << error_in(kHead + "path 0,0 1,1\nrepeat 4,0 x3\n");
  EXPECT_NE(error_in(kHead + "path 0,0 1,1\nrepeat 4,0 x0\n").find("a count of 1 to"), std::string::npos);
  EXPECT_NE(error_in(kHead + "gamma 1.5\npath 0,0 1,1\n").find("line 3, column 7: gamma (the threads' length after pulling over before) in (0, 1]"),
            std::string::npos);
  EXPECT_NE(error_in(kHead + "spacing -2\npath 0,0 1,1\n").find("a grid spacing of 0.1 to 1000 mm"), std::string::npos);
  EXPECT_NE(error_in(kHead + "style woven\n").find("expected italian, canadian or english, found \"woven\""), std::string::npos);
  EXPECT_NE(error_in(kHead + "grid 3 3\n").find("a second grid (the first is on line 2)"), std::string::npos);
  EXPECT_NE(error_in("format smocking\ngrid 1000 1000\n").find("at most 250000 points"), std::string::npos);
  EXPECT_NE(error_in(kHead + "knot 0,0\n").find("unknown keyword \"knot\""), std::string::npos);
  EXPECT_NE(error_in(kHead + "style canadian\npath back 0,0 1,1\n").find("line 4: Canadian smocking is stitched on the front only"), std::string::npos);
  EXPECT_NE(error_in(kHead + "style english\nwalk 0,1 1,0 1,0 2,0 x3\n").find("English smocking gathers along straight rows of even stitches"),
            std::string::npos);
  EXPECT_NE(error_in(kHead + "style english\npath 0,1 1,2\n").find("stitch 1 goes by (1,1)"), std::string::npos);
  const std::string missing = skein::testing::error_of([] { read_smocking_pattern("/no/such/pattern.smock"); });
  EXPECT_NE(missing.find("/no/such/pattern.smock: does not exist"), std::string::npos) << missing;
}

TEST(SmockingPattern, EveryBundledPatternReads) {
  int read = 0;
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(SKEIN_PATTERNS_DIR) / "smocking")) {
    if (e.path().extension() != ".smock") continue;
    const auto p = read_smocking_pattern(e.path());
    EXPECT_FALSE(p.name.empty()) << e.path();
    EXPECT_FALSE(p.note.empty()) << e.path();
    EXPECT_GT(p.num_stitches(), 0) << e.path();
    ++read;
  }
  EXPECT_GE(read, 8);
}

TEST(SmockingPattern, StepsAndShiftsLongerThanTheGridAreRefused) {
  EXPECT_NE(error_in(kHead + "walk 0,0 2000000000,0 x3\n").find("column 10: a step longer than the grid"), std::string::npos)
      << error_in(kHead + "walk 0,0 2000000000,0 x3\n");
  EXPECT_NE(error_in(kHead + "path 0,0 1,0\nrepeat 0,-5 x2\n").find("a shift longer than the grid"), std::string::npos);
  EXPECT_NE(error_in(kHead + "path 0,0 1,0\nrepeat 0,0 x2\n").find("a shift of 0,0 puts every copy on top of the one before"), std::string::npos);
  // A walk's stitches count once against the limit; a byte order mark is not text.
  EXPECT_EQ(parse_smocking_pattern("\xEF\xBB\xBF" "format smocking\ngrid 2 1\nwalk 0,0 1,0 -1,0 x600000\n", "t").num_stitches(), 600000);
}
