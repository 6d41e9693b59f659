// Colour in patterns: declared and named, per stitch or per row in knit files, and as knitters write it in
// instructions.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <optional>
#include <vector>

#include "common/error.hpp"
#include "stitchmesh/chart_pattern.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/written_pattern.hpp"
#include "pattern_fixtures.hpp"
#include "testing.hpp"

using namespace skein;
using namespace skein::testing;

TEST(PatternColours, DeclaredAsPatternsNameThem) {
  const auto read = [](const std::string& line, bool bare = true) { return mesh::read_colour_declaration(line, bare, 0, "", "line 1"); };
  const auto hex = [](const std::optional<mesh::PatternColour>& c) { return c ? mesh::colour_code(c->srgb) : std::string("none"); };
  EXPECT_EQ(hex(read("MC: cream")), "#f0e6cf");                             // a colour word
  EXPECT_EQ(hex(read("Colour A (MC): natural #E9DCC3")), "#e9dcc3");        // a code beats the word
  EXPECT_EQ(hex(read("CC = Deep Navy Blue")), "#1f2a44");                   // the first colour word it holds
  EXPECT_EQ(hex(read("colour X2: my own heather", false)), "#f0e6cf");     // no word: the default palette's first
  EXPECT_EQ(read("Colour B (CC): red #b3261e")->description, "red");
  EXPECT_EQ(read("Colour B (CC): red #b3261e")->name, "B");
  EXPECT_FALSE(read("MC: cream", false));  // skein's own formats want the word 'colour'
  EXPECT_FALSE(read("Multiple of 4 sts plus 2."));
  EXPECT_FALSE(read("Note: work loosely."));
  EXPECT_EQ(error_of([&] { read("colour A: red #b326"); }), "line 1: a colour code is # and six hex digits (#f0e6cf), found '#b326'");
  EXPECT_EQ(error_of([&] { read("colour k: red"); }), "line 1: 'k' cannot name a colour: it reads as a stitch or a count (name colours MC, CC, A, B, ...)");
  EXPECT_EQ(mesh::comment_start("colour A: cream #f0e6cf  # the main colour"), 25u);
  EXPECT_EQ(mesh::comment_start("k p # note"), 4u);
  // A code without its '#', a code that is not one, a second name in brackets, a stitch letter as a name.
  EXPECT_EQ(hex(read("CC: 1f2a44")), "#1f2a44");
  EXPECT_EQ(error_of([&] { read("A: natural #e9dcg3"); }), "line 1: a colour code is # and six hex digits (#f0e6cf), found '#e9dcg3'");
  EXPECT_EQ(read("Colour A (MC): natural")->alias, "MC");
  EXPECT_EQ(error_of([&] { read("K: cream"); }), "line 1: 'K' cannot name a colour: it reads as a stitch or a count (name colours MC, CC, A, B, ...)");
  EXPECT_EQ(error_of([] { mesh::parse_pattern("Colour A (MC): natural\nMC: white\nRow 1: knit.\n", "d.txt"); }), "d.txt: line 2: colour 'MC' is declared twice");
  EXPECT_EQ(mesh::parse_pattern("Colour A (MC): natural\nColour B (CC): red\nRnd 1: k1, with CC, k1.\n", "a.txt").colours[0], (std::vector<int>{1, 0}));
  EXPECT_EQ(error_of([] { mesh::parse_pattern("MC: white\nRnd 1: k1, with DC, k1.\n", "u.txt"); }),
            "u.txt: line 2, column 17: 'with dc' names a colour the pattern does not declare (MC)");
  // A colour after a stitch that is not declared is named as one (and as the abbreviation it is not).
  EXPECT_EQ(error_of([] { mesh::parse_pattern("MC: white\nCC: navy\nRnd 1: k2 DC, k2.\n", "k.txt"); }),
            "k.txt: line 3, column 11: 'dc' after a stitch would be its colour, but the pattern does not declare it (MC, CC); as an "
            "abbreviation it is unknown: did you mean 'k', 'p', 'yo'?");
}

TEST(PatternColours, KnitFilesGiveEachStitchAColourOrEachRowOne) {
  const auto p = mesh::parse_pattern(
      "format knit\ncolour MC: cream #f0e6cf  # main\ncolour CC: red\np cable2x2+ p\nk k k k k k\ncolours\nMC CC CC CC CC MC\nCC\n", "c.knit");
  ASSERT_EQ(p.palette.size(), 2u);
  EXPECT_EQ(mesh::colour_code(p.palette[0].srgb), "#f0e6cf");
  EXPECT_EQ(p.colours, (std::vector<std::vector<int>>{{1, 1, 1, 1, 1, 1}, {0, 1, 1, 1, 1, 0}}));  // bottom row first; the cable's four faces each
  // The faces of a tiling take their stitches' colours (row by row, each row's repeats left to right), its palette the pattern's.
  const auto tiling = mesh::pattern_stitch_mesh(p, 2, 1);
  std::vector<int> faces;
  for (const auto& f : tiling.faces) faces.push_back(f.colour);
  EXPECT_EQ(faces, (std::vector<int>{1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 1, 1, 1, 1, 0, 0, 1, 1, 1, 1, 0}));
  EXPECT_EQ(tiling.palette, p.palette);
  EXPECT_TRUE(mesh::pattern_stitch_mesh(mesh::parse_pattern("format knit\nk p\n", "p.knit"), 2, 2).palette.empty());
  const auto error = [](const std::string& text) { return error_of([&] { mesh::parse_pattern(text, "c.knit"); }); };
  EXPECT_EQ(error("format knit\ncolour A: red\nk k\ncolours\nA B\n"), "c.knit: line 5, column 3: 'B' is not a declared colour (A)");
  EXPECT_EQ(error("format knit\ncolour A: red\nk k\ncolours\nA A A\n"),
            "c.knit: line 5: gives 3 colours for row 1 (line 3), which has 2 stitches (a cable's each): one colour per stitch, or one for the whole row");
  EXPECT_EQ(error("format knit\ncolour A: red\nk k\nk k\ncolours\nA\n"), "c.knit: line 6: the colours block has 1 line but the pattern 2 rows");
  EXPECT_EQ(error("format knit\nk k\ncolours\nA\n"), "c.knit: line 3: 'colours' with no colour declared: declare them first ('colour A: cream')");
  EXPECT_EQ(error("format knit\ncolour A: red\ncolour a: blue\nk k\n"), "c.knit: line 3: colour 'a' is declared twice");
  EXPECT_EQ(error("format knit\nk k\ncolour A: red\n"), "c.knit: line 3: a colour declaration after the rows: declare the colours first");
}

TEST(PatternColours, WrittenInstructionsSayTheColourAsKnittersDo) {
  // "With CC" holds for the rows after it until another colour is named; "k2 B" colours those stitches alone.
  const auto stripes = mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/written/garter-stripes.txt");
  ASSERT_EQ(stripes.height(), 8);  // four rows of each colour: not the two-row garter repeat
  for (int r = 0; r < 8; ++r) EXPECT_EQ(stripes.colours[r], std::vector<int>{r < 4 ? 0 : 1}) << "row " << r + 1;
  const auto rib = mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/written/corrugated-rib.txt");
  EXPECT_EQ(rib.rows, (std::vector<std::vector<std::string>>{{"p", "p", "k", "k"}}));  // the WS row is the RS row seen from the front
  EXPECT_EQ(rib.colours, (std::vector<std::vector<int>>{{0, 0, 1, 1}}));               // knits in B, purls in A
  // "with CC" in round 1 holds into round 2; rounds are worked right to left as seen from the front.
  const auto p = mesh::parse_pattern("MC: white\nCC: black\nRnd 1: k1, with CC, k1, k1 in MC, k1.\nRnd 2: k2 MC, k1 CC, k1.\n", "w.txt");
  EXPECT_EQ(p.colours, (std::vector<std::vector<int>>{{1, 0, 1, 0}, {1, 1, 0, 0}}));
  // Without a palette, a colour name is an unknown abbreviation, as before.
  EXPECT_NE(error_of([] { mesh::parse_pattern("Rnd 1: k1 CC, k1.\n", "w.txt"); }).find("unknown abbreviation 'cc'"), std::string::npos);
  // The peerie chart: 'X' is keyed "k1 CC", the rest the main colour; charts are drawn as seen from the front.
  const auto peerie = mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/charts/peerie.txt");
  ASSERT_EQ(peerie.height(), 7);
  EXPECT_EQ(peerie.colours[3], (std::vector<int>{1, 0, 0, 0, 1, 0}));
  EXPECT_EQ(peerie.colours[0], (std::vector<int>(6, 0)));
}
