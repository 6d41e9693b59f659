// Charts as pictures: symbols for what a pattern holds, shaped pieces, row numbers on the right and wrong sides.
#include <gtest/gtest.h>

#include <utility>

#include "common/error.hpp"
#include "render/chart_view.hpp"
#include "stitchmesh/pattern.hpp"
#include "testing.hpp"

using namespace skein;

namespace {
/// Pixels darker than the grid lines (the symbols' ink) and bluish ones (cable strands).
std::pair<long, long> ink_and_cable(const render::Image& img) {
  long ink = 0, cable = 0;
  for (size_t i = 0; i < img.rgb.size(); i += 3) {
    const int r = img.rgb[i], g = img.rgb[i + 1], b = img.rgb[i + 2];
    ink += r < 150 && g < 150 && b < 150;
    cable += b > r + 60;
  }
  return {ink, cable};
}
}  // namespace

TEST(Chart, SymbolsForWhatThePatternHoldsAndNoneForPlainKnit) {
  const auto chart = [](const std::string& text) { return render::draw_chart(mesh::parse_pattern(text, "c.knit"), 20); };
  const auto plain = ink_and_cable(chart("format knit\nk k\nk k\n"));
  const auto seed = ink_and_cable(chart("format knit\np k\nk p\n"));
  const auto lace = ink_and_cable(chart("format knit\nk k\n2u\n"));
  const auto cable = ink_and_cable(chart("format written\nRnd 1: p1, C4F, p1.\nRnd 2: p1, k4, p1.\n"));
  EXPECT_EQ(plain.first, 0);   // knit is a blank cell
  EXPECT_GT(seed.first, 20);   // two purl dots
  EXPECT_GT(lace.first, 20);   // k2tog and a yarn-over
  EXPECT_GT(cable.second, 50); // the crossing strands
  EXPECT_EQ(plain.second, 0);
  EXPECT_THROW(render::draw_chart(mesh::parse_pattern("format woven\n1 0\n0 1\n", "w.weave")), Error);
}

TEST(Chart, AShapedPieceCentresItsRowsBetweenGreyNoStitchCellsAndBracketsIncreasesIntoOne) {
  // Cast on 2, kfb twice (4 sts), purl back: the first row's cells stand between grey 'no stitch' cells.
  const auto count_grey = [](const render::Image& img) {
    long grey = 0;
    for (size_t i = 0; i + 2 < img.rgb.size(); i += 3) grey += img.rgb[i] > 150 && img.rgb[i] < 215 && std::abs(img.rgb[i] - img.rgb[i + 2]) < 12;
    return grey;
  };  // the grid's lines are grey too: compare charts of one size
  const auto piece = mesh::parse_pattern("Cast on 2 sts.\nRow 1 (RS): Kfb, kfb. (4 sts)\nRow 2: Purl.\n", "s.txt");
  ASSERT_TRUE(piece.whole);
  const auto square = mesh::parse_pattern("Cast on 4 sts.\nRow 1 (RS): Knit.\nRow 2: Purl.\n", "q.txt");
  const long grid = count_grey(render::draw_chart(square, 60));
  EXPECT_LT(count_grey(render::draw_chart(piece, 60)), grid + 600);  // both rows hold 4 stitches: kfb makes two (its glyphs' edges are grey too)
  const auto wedge = mesh::parse_pattern("Cast on 2 sts.\nRow 1 (RS): K1, kfb. (3 sts)\nRow 2: Kfb, k2. (4 sts)\n", "w.txt");
  EXPECT_GT(count_grey(render::draw_chart(wedge, 60)), grid + 2000);  // row 1's 3 cells beside a grey one
  // The bracket under kfb's two cells (a crossed knit and a knit from one stitch) is ink that a k1 tbl and a k1
  // from two stitches do not have.
  const auto kfb = mesh::parse_pattern("Cast on 1 sts.\nRow 1 (RS): Kfb. (2 sts)\nRow 2: Purl.\n", "k.txt");
  const auto two = mesh::parse_pattern("Cast on 2 sts.\nRow 1 (RS): K1, k1 tbl.\nRow 2: Purl.\n", "t.txt");
  EXPECT_EQ(kfb.rows[0], (std::vector<std::string>{"xk"}));
  EXPECT_EQ(two.rows[0], (std::vector<std::string>{"x", "k"}));
  EXPECT_GT(ink_and_cable(render::draw_chart(kfb, 60)).first, ink_and_cable(render::draw_chart(two, 60)).first + 100);
}

TEST(Chart, EveryRowIsNumberedAtTheRight) {
  // The numbers' slate blue, right of the grid: a chart of 12 rows prints 1 to 12 (15 digits), one of 1 row "1".
  const auto numbered = [](int rows) {
    std::string text = "format knit\n";
    for (int r = 0; r < rows; ++r) text += "k p\n";
    const auto img = render::draw_chart(mesh::parse_pattern(text, "c.knit"), 20);
    long number = 0, left = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const unsigned char* px = &img.rgb[3 * (static_cast<size_t>(y) * img.width + x)];
        const bool slate = px[2] > px[0] + 20 && px[2] < px[0] + 60 && px[0] < 200;
        number += slate;
        left += slate && x < img.width / 2;
      }
    return std::pair{number, left};
  };
  const auto one = numbered(1), twelve = numbered(12);
  EXPECT_GT(one.first, 5);
  EXPECT_GT(twelve.first, 8 * one.first);
  EXPECT_EQ(twelve.second, 0) << "the numbers stand right of the chart";
}

TEST(Chart, AFlatChartNumbersItsWrongSideRowsAtTheLeft) {
  // Slate-blue pixels left of the chart's middle: row 2 of a piece worked flat; none for the same rows in the round.
  const auto left_numbers = [](const std::string& text) {
    const auto img = render::draw_chart(mesh::parse_pattern(text, "f.txt"), 40);
    long left = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width / 2; ++x) {
        const unsigned char* px = &img.rgb[3 * (static_cast<size_t>(y) * img.width + x)];
        left += px[2] > px[0] + 20 && px[2] < px[0] + 60 && px[0] < 200;
      }
    return left;
  };
  EXPECT_GT(left_numbers("Row 1 (RS): *K1, p1; rep from * to end.\nRow 2: *P1, k1; rep from * to end.\n"), 5);  // seed stitch
  EXPECT_EQ(left_numbers("Rnd 1: *K1, p1; rep from * to end.\nRnd 2: *P1, k1; rep from * to end.\n"), 0);
}
