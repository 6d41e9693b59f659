// Charts as knitters draw them: read as the written rows a knitter reads off them, errors by line and column,
// and every pattern a chart can say written back as a chart and as instructions.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "stitchmesh/chart_pattern.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/written_pattern.hpp"
#include "pattern_fixtures.hpp"
#include "testing.hpp"

using namespace skein;
using namespace skein::testing;

TEST(ChartPattern, ChartsReadAsTheWrittenRowsAKnitterReadsOffThem) {
  // Right-side rows right to left, wrong-side rows left to right with each symbol worked as its wrong-side stitch.
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"stockinette", "format chart\n. . . .\n. . . .\n"},
      {"garter", "format chart\n- - - -\n. . . .\n"},
      {"rib-2x2", "format chart round\n. . - -\n"},
      {"rib-2x2", "format chart\n..--\n..--\n"},
      {"seed", "format chart\n- .  2\n. -  1\n"},
      {"honeycomb", "format chart round\n. . . .\n. . v .\n. . . .\nv . . .\n"},
      {"cable-4", "format chart\nkey C C4B\n- - . . . . - -\n- - . . . . - -\n- - . . . . - -\n- - C C C C - -\n"},
      {"twisted-rib", "format chart round\nt -\n"},
  };
  for (const auto& [name, text] : cases) {
    auto expected = bundled_knit(name);
    if (name == "twisted-rib") expected = mesh::parse_pattern("format knit\nx p\n", "x.knit");
    const auto chart = mesh::parse_pattern(text, name + ".txt");
    EXPECT_TRUE(same_fabric(chart, expected)) << name << ": " << text << "read as " << rows_text(chart);
  }
  // Charts as printed, in Unicode: a bullet for purl, a ring for a yarn-over, a key of its own in UTF-8.
  EXPECT_EQ(mesh::parse_pattern("format chart\n\u2022 . \u2022 .\n. \u2022 . \u2022\n", "s.txt").rows,
            mesh::parse_pattern("format chart\n- . - .\n. - . -\n", "s.txt").rows);
  EXPECT_EQ(mesh::parse_pattern("format chart\n. . . .\n. / \u25CB .\n", "e.txt").rows, mesh::parse_pattern("format chart\n. . . .\n. / o .\n", "e.txt").rows);
  EXPECT_EQ(mesh::parse_pattern("format chart round\nkey \u25C6 k1 tbl\n\u25C6 \u2022\n", "t.txt").rows, mesh::parse_pattern("format chart round\nt -\n", "t.txt").rows);
  EXPECT_TRUE(same_fabric(mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/charts/moss-printed.txt"), bundled_knit("moss")));
  // A chart and the written rows it draws: the same stitches, decreases and yarn-overs included.
  const auto chart = mesh::parse_pattern("format chart\n. . . .\n. / o .\n", "e.txt");
  const auto written = mesh::parse_pattern("Row 1 (RS): *K1, yo, k2tog, k1; rep from * to end.\nRow 2: Purl.\n", "e.txt");
  EXPECT_EQ(chart.rows, written.rows);
  // A cable's key drawn over its cells; "no stitch" cells take none; the name comment carries over.
  const auto cable = mesh::parse_pattern("# name: Rope\nformat chart round\nkey C C4F\nkey _ no stitch\n. . . . . _\n. C C C C _\n", "c.txt");
  EXPECT_EQ(cable.name, "Rope");
  ASSERT_EQ(cable.cables.size(), 1u);
  EXPECT_EQ(cable.width(), 5);
  // Every bundled chart reads, and the rope cable's chart is its written instructions' fabric.
  for (const auto& entry : std::filesystem::directory_iterator(std::string(SKEIN_PATTERNS_DIR) + "/charts")) {
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(mesh::read_pattern(entry.path()));
  }
  EXPECT_TRUE(same_fabric(mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/charts/rope-cable.txt"),
                          mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/written/rope-cable.txt")));
}

TEST(ChartPattern, ErrorsNameTheChartsLineAndColumn) {
  const auto error = [](const std::string& text) { return error_of([&] { mesh::parse_pattern(text, "p.txt"); }); };
  EXPECT_EQ(error("format chart\n. . Q .\n"),
            "p.txt: line 2, column 5: 'Q' is not in the chart's key (- . / O V \\ ^ o t v x | \u039B \u2013 \u2022 \u2212 \u2227 \u2228 \u25A0 \u25A1 \u25CB \u25CF "
            "\u25EF; add 'key Q STITCH' above the chart)");
  EXPECT_EQ(error("format chart\nkey C C4F\n. C C C .\n"), "p.txt: line 3, column 3: 'C' is C4F, drawn over 4 cells, but here over 3");
  EXPECT_EQ(error("format chart\n. .  2\n. .  2\n"), "p.txt: line 3: is numbered 2 but is row 1 (the bottom row is row 1)");
  EXPECT_EQ(error("format chart\nt .\n. .\n"),
            "p.txt: line 2, column 1: 't' (k1 tbl) on a wrong-side row: the key gives it no wrong-side stitch (key t RS / WS)");
  EXPECT_EQ(error("format chart\n. .\nkey C C4F\n"), "p.txt: line 3: a key line after the chart's rows: give the key first");
  EXPECT_EQ(error("format chart\n. 3 .\n"), "p.txt: line 2, column 3: a number inside a chart row: row numbers go at its start or its end");
  EXPECT_EQ(error("format chart\n"), "p.txt: holds no chart rows");
  EXPECT_EQ(error("format chart\nkey 7 k\n. .\n"), "p.txt: line 2: a chart symbol is one printable character other than a digit (digits number the rows)");
  // Columns count characters, not bytes: the ring is three bytes of UTF-8 and one cell.
  EXPECT_EQ(error("format chart\n\u25CB Q\n"), error("format chart\n. Q\n"));
  EXPECT_EQ(error("format chart\n. \xff .\n"), "p.txt: line 2, column 3: is not UTF-8 text here: a chart cell is one character (ASCII or UTF-8)");
  EXPECT_EQ(error("format chart\n. \xe2\x80\n"), "p.txt: line 2, column 3: is not UTF-8 text here: a chart cell is one character (ASCII or UTF-8)");
  // What the written reader refuses in the row a chart makes, placed on the chart: the lone yarn-over's cell.
  const auto lone = error("format chart\n. . . .\n. v o v\n");
  EXPECT_EQ(lone.rfind("p.txt: line 3, column 5: a yarn-over has a stitch model beside its decrease", 0), 0u) << lone;
  // A cable key of no stitches (found by fuzzing: it drew the cable over no cells and never ended) is no cable.
  const auto none = error("format chart\nkey C C0B\n- C C -\n");
  EXPECT_EQ(none, "p.txt: line 3, column 5: 'c0b': cables of 2, 4 or 6 stitches (half over half) have models");
  const auto width = error("format chart round\n. . . . .\n. / . .\n");
  EXPECT_NE(width.find("(line 3)"), std::string::npos) << width;
}

TEST(ChartPattern, EveryPatternAChartCanSayIsWrittenAsAChartAndAsInstructionsThatReadBackAsItsStitches) {
  // Every bundled knit, written pattern and chart: written out as chart text and as written instructions, each
  // read back by its own reader gives the same stitches and cables; the rest are refused naming the stitch.
  int written = 0, refused = 0;
  for (const char* folder : {"", "/written", "/charts"})
    for (const auto& entry : std::filesystem::directory_iterator(std::string(SKEIN_PATTERNS_DIR) + folder)) {
      const auto ext = entry.path().extension();
      if (!entry.is_regular_file() || ext == ".weave" || ext == ".md") continue;
      SCOPED_TRACE(entry.path().string());
      const auto pattern = mesh::read_pattern(entry.path());
      std::string chart, instructions;
      try {
        chart = mesh::write_chart_pattern(pattern);
      } catch (const Error& e) {
        EXPECT_NE(std::string(e.rule()).find("has no chart symbol yet"), std::string::npos) << e.what();
        EXPECT_NE(e.place().find("row "), std::string::npos) << e.what();
        EXPECT_NE(error_of([&] { mesh::write_written_pattern(pattern); }), "");
        ++refused;
        continue;
      }
      instructions = mesh::write_written_pattern(pattern);
      for (const auto& [text, what] : {std::pair{chart, "chart"}, {instructions, "instructions"}}) {
        const auto back = mesh::parse_pattern(text, "back.txt");
        EXPECT_EQ(back.rows, pattern.rows) << what << ":\n" << text;
        EXPECT_EQ(back.colours, pattern.colours) << what << ":\n" << text;
        EXPECT_EQ(back.palette, pattern.palette) << what << ":\n" << text;
        EXPECT_EQ(back.cables.size(), pattern.cables.size()) << what << ":\n" << text;
        for (const auto& c : pattern.cables) EXPECT_NE(std::find(back.cables.begin(), back.cables.end(), c), back.cables.end()) << what << ":\n" << text;
        EXPECT_EQ(back.name, pattern.name);
        EXPECT_EQ(back.whole, pattern.whole) << what << ":\n" << text;
      }
      EXPECT_TRUE(mesh::is_chart_pattern(chart));
      ++written;
    }
  EXPECT_GE(written, 30);
  EXPECT_GT(refused, 0);
  // As a knitter reads them: a flat chart with its cable key and numbered rows (wrong-side rows at the left, where
  // they are read from), runs counted in the instructions.
  const auto cable = bundled_knit("cable-4");
  EXPECT_NE(mesh::write_chart_pattern(cable).find("format chart\nkey C C4B\n4   - - . . . . - -\n    - - . . . . - -   3\n"), std::string::npos) << mesh::write_chart_pattern(cable);
  EXPECT_NE(mesh::write_written_pattern(cable).find("Row 1 (RS): p2, C4B, p2.\nRow 2 (WS): k2, p4, k2.\n"), std::string::npos)
      << mesh::write_written_pattern(cable);
  // A lace pair on a wrong-side row is worked from that side: "yo, ssp" is ys from the front.
  const auto lace = mesh::parse_pattern("format knit\nk ys k\nk k k k\n", "l.knit");  // the top line is row 2
  EXPECT_NE(mesh::write_chart_pattern(lace).find("format chart\n"), std::string::npos) << mesh::write_chart_pattern(lace);
  EXPECT_NE(mesh::write_written_pattern(lace).find("Row 2 (WS): p1, yo, ssp, p1."), std::string::npos) << mesh::write_written_pattern(lace);
  EXPECT_NE(error_of([] { mesh::write_chart_pattern(mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/plain-weave.weave")); }).find("woven"),
            std::string::npos);
  // Increases into one stitch, drawn over the stitches they make: kfb on either side, a group as books write it.
  const auto kfb = mesh::parse_pattern("format knit\npq d12p\nk k k\n", "i.knit");
  EXPECT_NE(mesh::write_written_pattern(kfb).find("Row 2 (WS): kfb, k2tog."), std::string::npos) << mesh::write_written_pattern(kfb);
  const auto trinity = mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/written/trinity.txt");
  EXPECT_NE(mesh::write_written_pattern(trinity).find("Row 2 (WS): (k1, p1, k1) in next st, p3tog."), std::string::npos) << mesh::write_written_pattern(trinity);
  EXPECT_NE(mesh::write_chart_pattern(trinity).find("key + (p1, k1, p1) in next st / (k1, p1, k1) in next st\n4   { + + +\n"), std::string::npos)
      << mesh::write_chart_pattern(trinity);
  // A shaped piece: cast on, every row whole with the counts of the rows that change it; its chart's rows centred
  // between 'no stitch' cells.
  const auto wedge = mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/written/stockinette-kfb-wedge.txt");
  EXPECT_NE(mesh::write_written_pattern(wedge).find("Cast on 4 sts.\n# written instructions, by skein (patterns/FORMAT.md)\nRow 1 (RS): k1, kfb, k2. (5 sts)\nRow 2 (WS): p5.\n"),
            std::string::npos)
      << mesh::write_written_pattern(wedge);
  EXPECT_NE(mesh::write_chart_pattern(wedge).find("cast on 4 sts\nkey + kfb / (p1 tbl, p1) in next st\n"), std::string::npos) << mesh::write_chart_pattern(wedge);
  EXPECT_NE(mesh::write_chart_pattern(wedge).find("x x . . + + . x   1\n"), std::string::npos) << mesh::write_chart_pattern(wedge);
  // Travelling stitches: knits crossing purls behind them, named as the source names them.
  const auto zigzag = mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/written/travelling-zigzag.txt");
  EXPECT_NE(mesh::write_written_pattern(zigzag).find("Row 1 (RS): p3, T3B."), std::string::npos) << mesh::write_written_pattern(zigzag);
  // Lace pairs drawn so that each yarn-over goes back to its own decrease: feather and fan's three k2tog before the yarn-overs.
  const auto fan = mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/written/feather-and-fan.txt");
  EXPECT_NE(mesh::write_written_pattern(fan).find("Row 3 (RS): k2tog, k2tog, k2tog, yo, k1, yo, k1,"), std::string::npos) << mesh::write_written_pattern(fan);
}
