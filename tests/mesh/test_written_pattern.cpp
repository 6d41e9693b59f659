// Written instructions as stitch dictionaries and yarn companies write them, read into patterns and written back.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <numeric>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "stitchmesh/chart_pattern.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/written_pattern.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "pattern_fixtures.hpp"
#include "testing.hpp"

using namespace skein;
using namespace skein::testing;

TEST(WrittenPattern, StitchDictionaryTextGivesTheBundledFabrics) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"stockinette", "Row 1 (RS): Knit.\nRow 2 (WS): Purl.\n"},
      {"stockinette", "Rnd 1: K.\n"},
      {"garter", "Row 1: Knit.\nRow 2: Knit.\n"},
      {"garter", "Rnd 1: Knit.\nRnd 2: Purl.\n"},
      {"rib-1x1", "Multiple of 2 sts plus 1.\nRow 1 (RS): K1, *p1, k1; rep from * to end.\nRow 2: P1, *k1, p1; rep from * to end.\n"},
      {"rib-2x2", "Multiple of 4 sts plus 2.\nRow 1 (RS): K2, *p2, k2; rep from * to end.\nRow 2: P2, *k2, p2; rep from * to end.\n"},
      {"rib-2x2", "Rnd 1: *K2, P2; rep from * around.\n"},
      {"seed", "Multiple of 2 sts plus 1.\nRow 1: K1, *p1, k1; rep from * to end.\nRep Row 1.\n"},
      {"moss", "Multiple of 2 sts.\nRows 1 and 2: *K1, p1; rep from * to end.\nRows 3 and 4: *P1, k1; rep from * to end.\n"},
      {"honeycomb", "Multiple of 4 sts.\nRow 1 (RS): *Sl1 wyib, k3; rep from *.\nRow 2: Purl.\nRow 3: K2, *sl1 wyib, k3; rep from * to last 2 sts, k2.\n"
                    "Row 4: Purl.\n"},
      {"honeycomb", "Rnd 1: [k3, sl1 wyib] 3 times.\nRnd 2: knit.\nRnd 3: [k1, sl1, k2] 3 times.\nRnd 4: K to end.\n"},
      {"honeycomb", "Rnd 1: [k3, sl1 wyib] twice.\nRnd 2: knit.\nRnd 3: (k1, sl1, k2) Two times.\nRnd 4: K to end.\n"},
      {"rib-1x1", "Rnd 1: [k1, p1] thrice, (k1, p1) once, [k1, p1] four times.\n"},
      {"seed", "Row 1 (right side): *K1, p1; rep from * to last st, k1.\nRow 2 (wrong side): Rep Row 1.\n"},
      {"seed", "Rnd 1: *K1, p1; rep from *.\nRnd 2: *P1, k1; rep from *.\nRep Rnds 1 and 2.\n"},
      {"slip-rib", "Row 1 (RS): *sl 1 pwise wyib, k3; rep from * to end.\nRow 2 (WS): *p3, k1; rep from * to end.\n"},
      {"cable-4", "Panel of 8 sts.\nRow 1 (RS): P2, C4B, p2.\nRow 2: K2, p4, k2.\nRow 3: P2, k4, p2.\nRow 4: Rep Row 2.\n"},
      {"cable-4", "Rnd 1: p2, 2/2 RC, p2.\nRnds 2-4: p2, k4, p2.\n"},
      {"twisted-rib", "Rnd 1: *k1 tbl, p1; rep from *.\n"},
      // Wrong-side rows said once for all, as stitch dictionaries write them.
      {"honeycomb", "Multiple of 4 sts.\nRow 1 (RS): *Sl1 wyib, k3; rep from *.\nRow 2 and all WS rows: Purl.\n"
                    "Row 3: K2, *sl1 wyib, k3; rep from * to last 2 sts, k2.\n"},
      {"stockinette", "All WS rows: Purl.\nRow 1 (RS): Knit.\n"},
      {"cable-4", "Panel of 8 sts.\nRow 1 (RS): P2, C4B, p2.\nRow 2 and all even-numbered rows: K2, p4, k2.\nRow 3: P2, k4, p2.\n"},
  };
  for (const auto& [name, text] : cases) {
    // Twisted rib is written with skein's k+1; a crossed knit (k1 tbl) is `x`: compare it as the same fabric.
    auto expected = bundled_knit(name);
    if (name == "twisted-rib") expected = mesh::parse_pattern("format knit\nx p\n", "x.knit");
    const auto written = mesh::parse_pattern(text, name + ".txt");
    EXPECT_TRUE(same_fabric(written, expected)) << name << ": " << text << "read as " << rows_text(written) << " cables " << written.cables.size();
  }
}

TEST(WrittenPattern, WrongSideRowsAreReadLeftToRightAndSeenFromTheFront) {
  // Flat: row 2 (WS) "k1, p3" is worked from the back, left to right as seen from the front: purl, knit x 3.
  auto p = mesh::parse_pattern("Row 1 (RS): p1, k3.\nRow 2 (WS): k1, p3.\n", "w.txt");
  ASSERT_EQ(p.rows.size(), 2u);
  EXPECT_EQ(p.rows[0], (std::vector<std::string>{"k", "k", "k", "p"}));  // RS read right to left
  EXPECT_EQ(p.rows[1], (std::vector<std::string>{"p", "k", "k", "k"}));
  // Unmarked rows alternate RS and WS from row 1; slips keep the float on the side the yarn was held.
  p = mesh::parse_pattern("Row 1: sl1 wyif, k1.\nRow 2: sl1 wyif, p1.\n", "s.txt");
  EXPECT_EQ(p.rows[0], (std::vector<std::string>{"k", "sk"}));
  EXPECT_EQ(p.rows[1], (std::vector<std::string>{"s", "k"}));
  // Decreases seen from the front, and Leaf's lace faces for a yarn-over with its decrease.
  p = mesh::parse_pattern("Row 1 (RS): k2tog, yo, k2, yo, ssk, k2.\nRow 2: purl.\n", "l.txt");
  EXPECT_EQ(p.rows[0], (std::vector<std::string>{"k", "k", "ys", "k", "k", "2u"}));
  p = mesh::parse_pattern("Rnd 1: k2, yo, sk2p, yo, k2.\nRnd 2: knit.\n", "y.txt");
  EXPECT_EQ(p.rows[0], (std::vector<std::string>{"k", "k", "y3y", "k", "k"}));
  // Cables read as a knitter means them: C4F's first two stitches (the right ones) cross left in front.
  p = mesh::parse_pattern("Rnd 1: C4F.\nRnd 2: k4.\n", "c.txt");
  ASSERT_EQ(p.cables.size(), 1u);
  EXPECT_EQ(p.cables[0], (mesh::PatternCable{0, 0, 2, 2, -1}));
  // Travelling stitches: knits cross over purls, the knits in front. T3B's two knits travel right (p k k from the
  // front), T3F's left (k k p); A/B RPC and LPC name the same crossings, T4 is two over two, T2 one over one.
  p = mesh::parse_pattern("Row 1 (RS): P1, T3B.\nRow 2: K1, p2, k1.\n", "t.txt");
  ASSERT_EQ(p.cables.size(), 1u);
  EXPECT_EQ(p.cables[0], (mesh::PatternCable{0, 0, 2, 1, 1}));  // worked right to left: the cable left of the p1
  EXPECT_EQ(p.rows[0], (std::vector<std::string>{"p", "k", "k", "p"}));
  p = mesh::parse_pattern("Row 1 (RS): P1, T3F.\nRow 2: P2, k2.\n", "t.txt");
  EXPECT_EQ(p.cables[0], (mesh::PatternCable{0, 0, 1, 2, -1}));
  EXPECT_EQ(p.rows[0], (std::vector<std::string>{"k", "k", "p", "p"}));
  EXPECT_EQ(mesh::parse_pattern("Rnd 1: p1, 2/1 LPC.\nRnd 2: p1, k2, p1.\n", "t.txt").cables, mesh::parse_pattern("Rnd 1: p1, T3F.\nRnd 2: p1, k2, p1.\n", "t.txt").cables);
  EXPECT_EQ(mesh::parse_pattern("Rnd 1: T4B.\nRnd 2: p2, k2.\n", "t.txt").rows[0], (std::vector<std::string>{"p", "p", "k", "k"}));
  EXPECT_EQ(mesh::parse_pattern("Rnd 1: 2/2 RPC.\nRnd 2: p2, k2.\n", "t.txt").cables[0], (mesh::PatternCable{0, 0, 2, 2, 1}));
  EXPECT_EQ(mesh::parse_pattern("Rnd 1: T2F, p1.\nRnd 2: p1, k1, p1.\n", "t.txt").rows[0], (std::vector<std::string>{"p", "k", "p"}));
  EXPECT_EQ(error_of([] { mesh::parse_pattern("Rnd 1: T5F.\nRnd 2: knit.\n", "t.txt"); }),
            "t.txt: line 1, column 8: 't5f': travelling cables of 2, 3 or 4 stitches (T2: 1 over 1, T3: 2 over 1, T4: 2 over 2) have models");
  // A yarn-over on either side of its decrease; "Rep Rows 1 and 2" adds no height to the repeat.
  p = mesh::parse_pattern("Row 1 (RS): *K1, yo, k2tog, k1; rep from * to end.\nRow 2: Purl.\n", "e.txt");
  EXPECT_EQ(p.rows[0], (std::vector<std::string>{"k", "2u", "k"}));
  p = mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/written/rib-2x2.txt");
  EXPECT_EQ(p.width(), 4);
  EXPECT_EQ(p.height(), 1);  // every row is k k p p from the front
  // Every bundled written example reads; the eyelet rows' wrong-side rows are said once ("Row 2 and all WS
  // rows: Purl."), and the one after its last right-side row is there too.
  for (const auto& entry : std::filesystem::directory_iterator(std::string(SKEIN_PATTERNS_DIR) + "/written")) {
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(mesh::read_pattern(entry.path()));
  }
  p = mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/written/eyelet-rows.txt");
  EXPECT_EQ(p.height(), 4);
  EXPECT_EQ(p.rows[3], p.rows[0]);
  // Rows of different repeats widen to the least common multiple.
  p = mesh::parse_pattern("Rnd 1: *k1, p1; rep from *.\nRnd 2: *k1, p2; rep from *.\n", "m.txt");
  EXPECT_EQ(p.width(), 6);
}

TEST(WrittenPattern, RowsRepeatedAsManyTimesMoreAsSaid) {
  // Six rows of stockinette and a garter ridge, written out, and written as books shorten them; rows repeated
  // are worked from the side the new rows are on (the last row, a wrong-side purl, again on the right side).
  const auto plain = mesh::parse_pattern("Row 1 (RS): knit.\nRow 2: purl.\nRow 3: knit.\nRow 4: purl.\nRow 5: knit.\nRow 6: purl.\nRow 7: purl.\nRow 8: knit.\n", "a.txt");
  ASSERT_EQ(plain.height(), 8);
  for (const char* text : {"Row 1 (RS): knit.\nRow 2: purl.\nRep Rows 1 and 2 twice more.\nRow 7: purl.\nRow 8: knit.\n",
                           "Row 1 (RS): knit.\nRow 2: purl.\nRep Rows 1-2 2 more times.\nRow 7: purl.\nRow 8: knit.\n",
                           "Row 1 (RS): knit.\nRow 2: purl.\nRep last 2 rows 2 times more.\nRow 7: purl.\nRow 8: knit.\n",
                           "Row 1 (RS): knit.\nRow 2: purl.\nRep Rows 1 and 2 once more.\nRep the last 2 rows once more.\nRow 7: purl.\nRow 8: knit.\n",
                           "Row 1 (RS): knit.\nRow 2: purl.\nRows 3-6: Rep Rows 1 and 2 twice.\nRow 7: purl.\nRow 8: knit.\n",
                           "Row 1 (RS): knit.\nRow 2: purl.\nRows 3-6: Rep Rows 1 and 2.\nRow 7: purl.\nRow 8: knit.\n",
                           "Row 1 (RS): knit.\nRow 2: purl.\nRep Rows 1 and 2 twice more.\nRep the last row.\nRow 8: knit.\n"}) {
    SCOPED_TRACE(text);
    const auto p = mesh::parse_pattern(text, "b.txt");
    EXPECT_EQ(p.rows, plain.rows);
  }
}

TEST(WrittenPattern, RowsListedApartAreWorkedWhenTheirTurnComes) {
  // Stitch dictionaries write alike rows under one heading: "Rows 1 and 3 (RS): ...", "Rows 2, 4 and 6: ...".
  const auto eight = mesh::parse_pattern("Row 1 (RS): knit.\nRow 2: purl.\nRow 3: knit.\nRow 4: purl.\nRow 5: purl.\nRow 6: purl.\n", "a.txt");
  for (const char* text : {"Rows 1 and 3 (RS): Knit.\nRows 2 and 4: Purl.\nRow 5: Purl.\nRow 6: Purl.\n",
                           "Rows 1 & 3: Knit.\nRows 2, 4 and 6: Purl.\nRow 5: Purl.\n",
                           "Rows 1, 3: Knit.\nRows 2, 4, and 6 (WS): Purl.\nRow 5 (RS): Purl.\n"}) {
    SCOPED_TRACE(text);
    const auto p = mesh::parse_pattern(text, "b.txt");
    EXPECT_EQ(p.rows, eight.rows);
  }
  // A row given twice, a row no line gives, and rows listed backwards are refused.
  const auto error = [](const std::string& text) { return error_of([&] { mesh::parse_pattern(text, "l.txt"); }); };
  EXPECT_EQ(error("Rows 1 and 3: Knit.\nRow 2: Purl.\nRow 3: Purl.\n"), "l.txt: line 3: row 3 is given twice: on line 1 too");
  EXPECT_EQ(error("Rows 1 and 3: Knit.\n"), "l.txt: line 1: gives row 3, but no line gives row 2 before it");
  EXPECT_EQ(error("Rows 1, 5 and 3: Knit.\nRow 2: Purl.\n"), "l.txt: line 1: lists rows out of order: 3 after 5");
}

TEST(WrittenPattern, AStitchPatternsCountsAndMultipleAreCheckedAgainstItsRows) {
  const auto error = [](const std::string& text) { return error_of([&] { mesh::parse_pattern(text, "m.txt"); }); };
  // As written: k2 edges and a repeat of 4, counts of 4 repeats plus 2 on every row that gives one.
  const std::string rib = "Multiple of 4 sts plus 2.\nRow 1 (RS): K2, *p2, k2; rep from * to end. (18 sts)\nRow 2: P2, *k2, p2; rep from * to end. (18 sts)\n";
  EXPECT_EQ(error(rib), "");
  EXPECT_EQ(error("Multiple of 6 sts plus 2.\nRow 1 (RS): K2, *p2, k2; rep from * to end.\nRow 2: Purl.\n"),
            "m.txt: line 1: says a multiple of 6 sts plus 2, but the row on line 2 repeats every 4 sts with 2 edge stitches");
  EXPECT_EQ(error("Multiple of 4 sts plus 1.\nRow 1 (RS): K2, *p2, k2; rep from * to end.\nRow 2: Purl.\n"),
            "m.txt: line 1: says a multiple of 4 sts plus 1, but the row on line 2 repeats every 4 sts with 2 edge stitches");
  EXPECT_EQ(error("Row 1 (RS): K2, *p2, k2; rep from * to end. (17 sts)\nRow 2: Purl.\n"),
            "m.txt: line 1, column 45: the count written after the row says 17, but the row makes 2 plus a multiple of 4 stitches");
  EXPECT_EQ(error("Multiple of 8 sts plus 2.\nRow 1 (RS): K2, *p2, k2; rep from * to end. (14 sts)\nRow 2: Purl.\n"),
            "m.txt: line 2, column 45: the count written after the row says 14, which is not a multiple of 8 sts plus 2 (line 1)");
  EXPECT_EQ(error("Row 1 (RS): K2, *p2, k2; rep from * to end. (18 sts)\nRow 2: P2, *k2, p2; rep from * to end. (22 sts)\n"),
            "m.txt: line 2, column 40: the count written after the row says 22, but the one after line 1 says 18: a stitch pattern keeps its count from row to row");
  // A multiple its rows' repeats divide is fine: "multiple of 8" over rows of 4.
  EXPECT_EQ(error("Multiple of 8 sts + 2.\nRow 1 (RS): K2, *p2, k2; rep from * to end.\nRow 2: Purl.\n"), "");
}

TEST(WrittenPattern, ACableOnAWrongSideRowCrossesAsTheSameCableOnARightSideRow) {
  // Worked in purl from the wrong side, its stitches are knits from the front, and the stitches held at the back
  // of the work (the fabric's front) travel in front: C4B from either side is the same right cross.
  const auto flat = mesh::parse_pattern("Row 1 (RS): p2, k4, p2.\nRow 2 (WS): k2, C4B, k2.\nRow 3: p2, k4, p2.\nRow 4: k2, p4, k2.\n", "f.txt");
  const auto round = mesh::parse_pattern("Rnd 1: p2, k4, p2.\nRnd 2: p2, C4B, p2.\nRnd 3: p2, k4, p2.\nRnd 4: p2, k4, p2.\n", "r.txt");
  EXPECT_EQ(flat.rows, round.rows);
  ASSERT_EQ(flat.cables.size(), 1u);
  EXPECT_EQ(flat.cables, round.cables);
  EXPECT_EQ(flat.cables[0].order, 1);
  // Written out it crosses on its own row, read back the same.
  EXPECT_EQ(mesh::parse_pattern(mesh::write_written_pattern(flat), "w.txt").cables, flat.cables);
}

TEST(WrittenPattern, ErrorsNameTheLineTheColumnAndTheClosestAbbreviations) {
  const auto error = [](const std::string& text) { return error_of([&] { mesh::parse_pattern(text, "p.txt"); }); };
  EXPECT_EQ(error("Row 1 (RS): *k2, p2tog, kk2; rep from * to end.\n"),
            "p.txt: line 1, column 25: unknown abbreviation 'kk2'; did you mean 'k', 'skp', 'p'? (patterns/FORMAT.md lists what is read)");
  // Columns count characters: the em dash before m1r is one, though three bytes.
  EXPECT_EQ(error("Row 1 (RS): K1\u2014m1r, k3.\n").substr(0, 25), "p.txt: line 1, column 16:");
  EXPECT_EQ(error("Row 1: k2, m1r, k2.\n"),
            "p.txt: line 1, column 12: 'm1r' is a knitting abbreviation skein has no stitch model for yet; its loop twists the other way from "
            "skein's crossed loops (k1tbl's and m1l's): the nearest are 'm1l' and 'kfb'");
  EXPECT_EQ(error("Row 1: knit.\nRow 3: purl.\n"), "p.txt: line 2: row 3 comes where row 2 was expected (rows are numbered from 1, in order)");
  EXPECT_EQ(error("Row 1: *k2, p2.\n"), "p.txt: line 1: a '*' without 'rep from *' after it");
  EXPECT_EQ(error("Row 1: [k1, p1].\n"), "p.txt: line 1, column 17: expected how many times the group is worked after it ('3 times' or 'x3')");
  EXPECT_EQ(error("Row 1: knit.\nRnd 2: knit.\n"), "p.txt: line 2: mixes rows (worked flat) and rounds (in the round)");
  EXPECT_EQ(error("Row 1 (RS): knit.\nRow 2: T3F.\n"),
            "p.txt: line 2, column 8: travelling stitches on wrong-side rows have no model yet: cross them on right-side rows (a cable of knits, "
            "worked in purl, crosses on either side)");
  EXPECT_EQ(error("Rnd 1: k1, sk2p, k1.\n"), "p.txt: line 1, column 12: 'sk2p' has a stitch model only between two yarn-overs ('yo, sk2p, yo', Leaf's y3y)");
  EXPECT_EQ(error("Cast on 8 sts.\nRnd 1: K1, m1, k to end. (9 sts)\nRnd 2: Knit.\n"),
            "p.txt: line 2: is a piece worked in rounds ('Cast on N sts.' and rounds written whole): a tube, which skein does not build from "
            "written instructions yet; without the cast-on line its rounds are read as a stitch pattern");
  EXPECT_EQ(error("Row 1: knit.\nCast on loosely.\n"), "p.txt: line 2: expected a row: 'Row N (RS): ...', 'Rows N and M: ...' or 'Rnd N: ...'");
  EXPECT_EQ(error("Rnd 1: k2tog.\nRnd 2: k2.\n"), "p.txt: line 2: this row takes 2 loops but the row below it (line 1) makes 1"
            " (a repeating stitch pattern keeps its count from row to row; a shaped piece is written with 'Cast on N sts.' and every row whole)");
  EXPECT_EQ(error("Row 1: " + std::string(5000, 'k') + "\n"), "p.txt: line 1: is longer than 4096 characters");
  EXPECT_EQ(error("Row 1: K4.\nRow 2: P5.\n"),
            "p.txt: line 1: is 4 stitches wide with no '*' repeat, but the pattern's repeat is 20: write the rows as wide, or mark their repeats with "
            "'*...; rep from * to end'");
  EXPECT_EQ(error("Row 1 (RS): K2, sl1, yo, sl1, k2.\nRow 2: Purl.\n"),
            "p.txt: line 1, column 22: a yarn-over has a stitch model beside its decrease ('yo, ssk', 'k2tog, yo', 'yo, sk2p, yo', ...) or beside a "
            "plain knit or purl stitch it increases into ('k1, yo', 'yo, p1'); here it has neither");
  EXPECT_EQ(error("Row 1 (RS): K2, yo, k2.\nRow 2: Purl.\n"), "p.txt: line 2: this row takes 4 loops but the row below it (line 1) makes 5"
            " (a repeating stitch pattern keeps its count from row to row; a shaped piece is written with 'Cast on N sts.' and every row whole)");
  EXPECT_EQ(error("Row 1: knit.\nRow 2 or so: purl.\n"),
            "p.txt: line 2: a row heading this reader cannot read: write 'Row N:', 'Row N (RS):', 'Rows N and M:', 'Rows N-M:' or 'Rnd N:' "
            "(patterns/FORMAT.md)");
  // Counts too long for an int (found by fuzzing) and counts that would make millions of stitches.
  EXPECT_EQ(error("Row 1 (RS): K2111111111111111111111111111111111111, *p2, k2; rep from * to end.\n"),
            "p.txt: line 1, column 13: 'k2111111111111111111111111111111111111': 1 to 1000 stitches");
  EXPECT_EQ(error("Rnd 1: yo999999999, k2tog.\n"), "p.txt: line 1, column 8: 'yo': 1 to 1000 stitches");
  EXPECT_EQ(error("Rnd 1: sl99999999999 wyib, k1.\n"), "p.txt: line 1, column 8: 'sl99999999999 wyib': 1 to 1000 stitches");
  EXPECT_EQ(error("Rnd 99999999999: k.\n"), "p.txt: line 1: round 1000000 comes where round 1 was expected (rows are numbered from 1, in order)");
  EXPECT_EQ(error("Row 1: knit.\nRow 4 and all WS rows: purl.\n"),
            "p.txt: line 2: says its wrong-side rows start at row 4, but the next wrong-side row is row 2");
  EXPECT_EQ(error("Rnd 1: knit.\nAll WS rows: purl.\n"), "p.txt: line 2: names wrong-side rows, but the pattern is worked in rounds");
  EXPECT_EQ(error("All WS rows: purl.\nRnd 1: knit.\n"), "p.txt: line 2: mixes rows (worked flat) and rounds (in the round)");
  EXPECT_EQ(error("Row 1: knit.\nRow 2: purl.\nRep Rows 1 and 2 three times.\n"),
            "p.txt: line 3: says how many times without 'more', which reads two ways: write 'three more times' (the rows again that many times), "
            "or give the rows a heading ('Rows N-M: Rep ...')");
  EXPECT_EQ(error("Row 1: knit.\nRow 2: purl.\nRows 3-6: Rep Rows 1 and 2 three times.\n"),
            "p.txt: line 3: repeats 2 rows 3 times, 6 rows, but its heading names 4");
  EXPECT_EQ(error("Row 1: knit.\nRow 2: purl.\nRep last 3 rows once more.\n"), "p.txt: line 3: repeats the last 3 rows, but 2 are written above it");
  EXPECT_EQ(error("Row 1: knit.\nRow 2: purl.\nRep Rows 2 and 3 once more.\n"), "p.txt: line 3: repeats rows 2-3, which are not all written above it");
  EXPECT_EQ(error("Row 1: knit.\nRow 2: purl.\nRep Rows 1 and 2 99999999 more times.\n"), "p.txt: line 3: repeats its rows more than 1000 times");
  // Not a written pattern: skein's own format keeps its errors.
  EXPECT_FALSE(mesh::is_written_pattern("format knit\nk p\n"));
  EXPECT_TRUE(mesh::is_written_pattern("# a comment\nMultiple of 2.\nRow 1: k1, p1.\n"));
  EXPECT_TRUE(mesh::is_written_pattern("format written\n"));
}

TEST(WrittenPattern, TheCorpusReadsAsTheBundledFabrics) {
  const std::string dir = std::string(SKEIN_PATTERNS_DIR) + "/written/";
  for (const auto& name : {"garter-rib", "broken-rib", "rib-3x1", "diagonal-rib", "checkerboard", "basketweave", "double-seed", "welt", "rib-2x2", "seed", "rib-1x1", "moss"}) {
    const auto written = mesh::read_pattern(dir + name + ".txt");
    EXPECT_TRUE(same_fabric(written, bundled_knit(name))) << name << " read as " << rows_text(written);
  }
  // The rest as the stitches a knitter would name: each row's mistake-rib offset, linen stitch's offset slips,
  // twisted knits, the lace rib's ys, the C6F cable and the 1/1 RT twists.
  EXPECT_TRUE(same_fabric(mesh::read_pattern(dir + "mistake-rib.txt"), mesh::parse_pattern("format knit\nk k p p\nk p p k\n", "m.knit")));
  EXPECT_TRUE(same_fabric(mesh::read_pattern(dir + "farrow-rib.txt"), mesh::parse_pattern("format knit\np k k\np k p\n", "f.knit")));
  EXPECT_TRUE(same_fabric(mesh::read_pattern(dir + "linen-stitch.txt"), mesh::parse_pattern("format knit\nk sk\nsk k\n", "l.knit")));
  EXPECT_TRUE(same_fabric(mesh::read_pattern(dir + "twisted-rib.txt"), mesh::parse_pattern("format knit\np x\np k\n", "t.knit")));
  const auto lace = mesh::read_pattern(dir + "lace-rib.txt");
  EXPECT_NE(rows_text(lace).find("ys"), std::string::npos) << rows_text(lace);
  const auto cable = mesh::read_pattern(dir + "cable-6-left.txt");
  ASSERT_EQ(cable.cables.size(), 1u);
  EXPECT_EQ(cable.cables[0].over + cable.cables[0].under, 6);
  EXPECT_EQ(cable.height(), 8);
  EXPECT_EQ(mesh::read_pattern(dir + "mini-cable-rib.txt").cables.size(), 1u);
  // Trinity stitch: on its wrong-side rows "(k1, p1, k1) in next st, p3tog", three from one beside three into one,
  // a purl row between (seen from the front: pkp and d123k on a purl ground), the clusters offset by two.
  EXPECT_EQ(rows_text(mesh::read_pattern(dir + "trinity.txt")), "p p p p / pkp d123k / p p p p / d123k pkp / ");
  // The charts of the corpus are their written instructions' fabrics.
  const std::string charts = std::string(SKEIN_PATTERNS_DIR) + "/charts/";
  for (const auto& name : {"checkerboard", "garter-rib", "linen-stitch", "diagonal-rib"}) {
    const auto chart = mesh::read_pattern(charts + name + ".txt"), written = mesh::read_pattern(dir + name + ".txt");
    EXPECT_TRUE(same_fabric(chart, written)) << name << ": chart " << rows_text(chart) << "written " << rows_text(written);
  }
  EXPECT_EQ(mesh::read_pattern(charts + "lace-rib.txt").rows, lace.rows);  // two-loop lace faces: compared as they lie
  EXPECT_TRUE(same_fabric(mesh::read_pattern(charts + "twisted-stitch-columns.txt"), mesh::parse_pattern("format knit\np x p\n", "t.knit")));
  // Every file of the corpus reads, named and sourced.
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    SCOPED_TRACE(entry.path().string());
    const auto p = mesh::read_pattern(entry.path());
    EXPECT_FALSE(p.name.empty());
    EXPECT_FALSE(p.note.empty());
  }
}

TEST(WrittenPattern, AMadeLoopJoinsItsPlainNeighbourIntoAnIncreaseFace) {
  // m1 / m1l: the bar between two stitches lifted and knit through its back loop, a crossed knit (x) from the
  // front; m1p / m1lp a crossed purl (q). It joins the plain stitch worked before it, or else the one after, as
  // kfb's loops do: a right-side row is worked right to left, a wrong-side row left to right with its knits purls.
  const auto rows_of = [](const std::string& rs, const std::string& ws = "Purl.") {
    return rows_text(mesh::parse_pattern("Row 1 (RS): " + rs + "\nRow 2: " + ws + "\n", "a.txt"));
  };
  EXPECT_EQ(rows_of("K2tog, k1, m1l."), "xk d12k / k k k / ");   // as "K2tog, kfb."
  EXPECT_EQ(rows_of("K2tog, M1, k1."), "kx d12k / k k k / ");    // made first: it lies right of the knit
  EXPECT_EQ(rows_of("P2tog, p1, m1p.", "Knit."), "qp d12p / p p p / ");
  EXPECT_EQ(rows_of("Knit.", "P2tog, p1, m1lp."), "k k k / d12k kx / ");  // purls from the wrong side: knits from the front
  EXPECT_EQ(rows_of("Knit.", "P2tog, k1, m1."), "k k k / d12k pq / ");
  // Counted as the increases they are: "K1, m1l, k to end" on four stitches makes five.
  EXPECT_EQ(mesh::parse_pattern("Cast on 4 sts.\nRow 1 (RS): K1, m1l, k to end. (5 sts)\nRow 2: Purl.\n", "w.txt").rows[1].size(), 5u);
  // Beside a stitch of the other kind it joins the one after: "K2, M1P, p2" widens a rib's purl column.
  EXPECT_EQ(rows_of("K2tog, k1, m1p, p1.", "Knit."), "pq k d12k / p p p p / ");
  // Wordings books use: spelled out, and purlwise or knitwise.
  EXPECT_EQ(rows_of("K2tog, k1, make 1."), "xk d12k / k k k / ");
  EXPECT_EQ(rows_of("P2tog, p1, M1 purlwise.", "Knit."), "qp d12p / p p p / ");
  // A made loop with no plain neighbour of its kind is refused, naming the faces it would make.
  const auto error = [](const std::string& text) { return error_of([&] { mesh::parse_pattern(text, "m.txt"); }); };
  EXPECT_EQ(error("Row 1 (RS): K2tog, p1, m1l.\nRow 2: Purl.\n"),
            "m.txt: line 1, column 24: 'm1l' would make the increase face 'xp' with its neighbours, which skein has no stitch model for: a made "
            "loop joins a plain stitch of its own kind, a knit beside a knit ('k1, m1l'), a purl beside a purl ('m1p, p1')");
  EXPECT_EQ(error("Row 1 (RS): K2tog, m1l, k2tog.\nRow 2: Purl.\n"),
            "m.txt: line 1, column 20: 'm1l' makes a loop that skein models beside a plain knit or purl stitch ('k1, m1l', 'm1p, p1'); here it "
            "has neither (beside 'k to end', write one stitch out: 'm1, k1, k to end')");
  // Its face takes one colour: a make-one in a colour of its own is refused, not drawn in its neighbour's.
  EXPECT_EQ(error("MC: cream\nCC: navy\nCast on 4 sts.\nRow 1 (RS): K2, m1 CC, k2. (5 sts)\nRow 2: Purl.\n"),
            "m.txt: line 4, column 17: 'm1' is in another colour than the stitch it joins ('k2'): the increase face they make takes one colour; "
            "give them the same");
}

TEST(WrittenPattern, StitchesWorkedIntoOneAreIncreaseFaces) {
  // "(k1, p1) in next st" and its kin: one loop below, two or three made, named as seen from the front (a
  // right-side row is worked right to left, a wrong-side row left to right with its knits purls from the front).
  const auto rows_of = [](const std::string& rs, const std::string& ws = "Purl.") {
    return rows_text(mesh::parse_pattern("Row 1 (RS): " + rs + "\nRow 2: " + ws + "\n", "a.txt"));
  };
  EXPECT_EQ(rows_of("K2tog, (k1, p1) in next st."), "pk d12k / k k k / ");
  EXPECT_EQ(rows_of("K2tog, [p1, k1] into the next stitch."), "kp d12k / k k k / ");
  EXPECT_EQ(rows_of("K3tog, (k1, p1, k1) all in next st."), "kpk d123k / k k k k / ");
  EXPECT_EQ(rows_of("Sssk, (k1, yo, k1) in same st."), "kyk d321k / k k k k / ");
  EXPECT_EQ(rows_of("Knit.", "P2tog, (k1, p1) in next st."), "k k k / d12k pk / ");  // wrong side: worked left to right, k1 a purl from the front
  EXPECT_EQ(rows_of("K4.", "(P1, k1, p1) in next st, p3tog."), "k k k k / kpk d123k / ");
  // kfb: a knit into the front leg, then a crossed knit into the back leg (right to left: xk from the front);
  // pfb on a wrong-side row is the same seen from the front, worked left to right (kx). From the other side they
  // are a purl beside a crossed purl (q). Written as a group too.
  EXPECT_EQ(rows_of("K2tog, kfb."), "xk d12k / k k k / ");
  EXPECT_EQ(rows_of("K2tog, (k1, k1 tbl) in next st."), "xk d12k / k k k / ");
  EXPECT_EQ(rows_of("Knit.", "P2tog, pfb."), "k k k / d12k kx / ");
  EXPECT_EQ(rows_of("K2tog, pfb."), "qp d12k / k k k / ");
  EXPECT_EQ(rows_of("Knit.", "P2tog, kfb."), "k k k / d12k pq / ");
  EXPECT_EQ(rows_of("K2tog, (p1, p1 tbl) in next st."), "qp d12k / k k k / ");
  // Through the back loop from either side: a crossed knit (x) or a crossed purl (q) from the front.
  EXPECT_EQ(rows_of("K1, p1 tbl, k1.", "P1, k1 tbl, p1."), "k q k / ");  // the two rows alike: one row repeats
  // What has no model is refused, naming the place and the face it would be.
  EXPECT_EQ(error_of([] { mesh::parse_pattern("Row 1 (RS): K3tog, (k1, p1, k1, p1) in next st.\nRow 2: Purl.\n", "e.txt"); }),
            "e.txt: line 1, column 20: '(k1, p1, k1, p1) in next st' has no stitch model: two or three stitches into one are read as skein's "
            "increase faces (kp, pk, kpk, pkp, kyk, pyp, xk, ...; seen from the front), and this one would be 'pkpk'");
  EXPECT_NE(error_of([] { mesh::parse_pattern("Row 1 (RS): K1, (k1, k2tog) in next st.\nRow 2: Purl.\n", "e.txt"); })
                .find("column 22: 'k2tog': a group worked into one stitch holds single knits, purls and yarn-overs"),
            std::string::npos);
  // Without "in next st" a group is still a repeat and needs its count.
  EXPECT_NE(error_of([] { mesh::parse_pattern("Row 1 (RS): (k1, p1).\nRow 2: Purl.\n", "e.txt"); }).find("expected how many times"), std::string::npos);
}

TEST(WrittenPattern, YarnOverIncreasesAndThreeWayDecreases) {
  // A lone yarn-over joins the plain stitch worked before it, else the one after (seen from the front, a
  // right-side row is worked right to left); three-into-one decreases stack as two-into-one do.
  const auto rows_of = [](const std::string& row) { return rows_text(mesh::parse_pattern("Row 1 (RS): " + row + "\nRow 2: Purl.\n", "a.txt")); };
  EXPECT_EQ(rows_of("K1, yo, k1, k2tog."), "d12k k yk / k k k k / ");
  EXPECT_EQ(rows_of("K3tog, yo, k1, yo, k1."), "ky ky d123k / k k k k k / ");
  EXPECT_EQ(rows_of("Sssk, yo, k1, yo."), "yky d321k / k k k k / ");
  EXPECT_EQ(rows_of("K1, yo, k2tog."), "2u k / k k k / ");  // a yarn-over beside its decrease is Leaf's lace face
  EXPECT_EQ(rows_of("P1, yo, p1, yo, p3tog."), "d123p yp yp / k k k k k / ");
  EXPECT_EQ(rows_of("Sssp, yo, p1, yo, p1."), "py py d321p / k k k k k / ");
  // Feather and fan: each row makes the loops the next one takes, the decreases away from the yarn-overs.
  const auto fan = mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/written/feather-and-fan.txt");
  ASSERT_EQ(fan.height(), 4);
  EXPECT_EQ(fan.width(), 18);
  // As worked (right to left): k2tog k2tog, then k2tog and the yarn-over after it as Leaf's 2u, five yarn-overs each
  // joining the knit worked before it, the last knit alone, three k2tog.
  EXPECT_EQ(fan.rows[2], (std::vector<std::string>{"d12k", "d12k", "d12k", "k", "yk", "yk", "yk", "yk", "yk", "2u", "d12k", "d12k"}));
  // Charts and written instructions carry the new faces both ways: the yarn-over as its own cell, k3tog and sssk by
  // keys of their own.
  const auto shell = mesh::parse_pattern("Row 1 (RS): *K1, yo, k1, yo, k3tog, p1, sssk, yo, k1, yo, k1; rep from * to end.\nRow 2: Purl.\n", "s.txt");
  EXPECT_EQ(rows_text(shell), "ky ky d321k p d123k yk yk / k k k k k k k k k k k / ");
  const auto chart = mesh::write_chart_pattern(shell);
  EXPECT_NE(chart.find("key { k3tog / p3tog"), std::string::npos) << chart;
  EXPECT_NE(chart.find(". o . o } - { o . o ."), std::string::npos) << chart;
  EXPECT_EQ(mesh::parse_pattern(chart, "c.txt").rows, shell.rows);
  EXPECT_EQ(mesh::parse_pattern(mesh::write_written_pattern(shell), "w.txt").rows, shell.rows);
  // Feather and fan's chart draws its last k2tog and yarn-over pair (Leaf's 2u) decrease first, as worked: read
  // back, the yarn-over pairs with that k2tog, not with the one before it.
  EXPECT_EQ(mesh::parse_pattern(mesh::write_chart_pattern(fan), "f.txt").rows, fan.rows) << mesh::write_chart_pattern(fan);
  // A yarn-over with no plain stitch beside it, and none to pair with, is still refused.
  EXPECT_EQ(error_of([] { mesh::parse_pattern("Row 1 (RS): Sl1, yo, sl1.\nRow 2: Purl.\n", "e.txt"); }),
            "e.txt: line 1, column 18: a yarn-over has a stitch model beside its decrease ('yo, ssk', 'k2tog, yo', 'yo, sk2p, yo', ...) or beside "
            "a plain knit or purl stitch it increases into ('k1, yo', 'yo, p1'); here it has neither");
  // On a wrong-side row, worked left to right from the front with its knits purls: "k1, yo" is py, "yo, k1" yp,
  // "yo, k1, yo" ypy; a yarn-over beside p2tog is 2u and beside ssp ys, as k2tog's and ssk's on a right-side row.
  const auto ws_of = [](const std::string& row) { return rows_text(mesh::parse_pattern("Row 1 (RS): Knit.\nRow 2 (WS): " + row + "\n", "w.txt")); };
  EXPECT_EQ(ws_of("K1, yo, k1, k2tog."), "k k k k / py p d12p / ");
  EXPECT_EQ(ws_of("P1, p2tog, yo, p1."), "k k k k / k 2u k / ");
  EXPECT_EQ(ws_of("P1, yo, ssp, p1."), "k k k k / k ys k / ");
  EXPECT_EQ(ws_of("Yo, k1, yo, k3tog."), "k k k k / ypy d123p / ");
  // Garter lace: "k2tog, yo" from the wrong side is a purl decrease beside its yarn-over from the front (2up, ysp).
  EXPECT_EQ(ws_of("K1, k2tog, yo, k1."), "k k k k / p 2up p / ");
  EXPECT_EQ(ws_of("K1, yo, ssk, k1."), "k k k k / p ysp p / ");
}

// Decreases as older stitch dictionaries write them out: the slipped stitch passed over ("sl 1, k1, psso", Walker's
// skp), read as the abbreviations they spell, and slips written without a comma before the next stitch.
TEST(WrittenPattern, PassedSlipStitchesAreTheDecreasesTheySpell) {
  const auto rows_of = [](const std::string& row) { return rows_text(mesh::parse_pattern("Row 1 (RS): " + row + "\nRow 2: Purl.\n", "a.txt")); };
  // skp however a book writes it, beside its yarn-over: Leaf's lace face ys, as "yo, ssk" is. Older books write
  // Walker's hyphens and dashes between a decrease's steps, "s1", "slip 1 as if to knit", "pass slipped st over",
  // "p.s.s.o.", and slips without a comma before the next stitch.
  for (const char* skp : {"sl1, k1, psso", "sl 1 kwise, k1, psso", "skp", "sl1 k1 psso", "sl 1-k1-psso", "s1, k1, psso",
                          "slip 1 as if to knit, k1, pass slipped st over", "sl 1, k1, p.s.s.o."})
    EXPECT_EQ(rows_of(std::string("*K1, yo, ") + skp + ", k1; rep from *."), "k ys k / k k k k / ") << skp;
  EXPECT_EQ(rows_of("*K1, yo, ssk, k1; rep from *."), "k ys k / k k k k / ");
  // The centred double decreases written out, between their yarn-overs: Leaf's y3y, as "yo, sk2p, yo" is.
  for (const char* centred : {"sl1, k2tog, psso", "sl2, k1, p2sso", "sl 1\u2014k2 tog\u2014psso", "sl 2 tog kwise, k1, p2sso"})
    EXPECT_EQ(rows_of(std::string("*K1, yo, ") + centred + ", yo, k2; rep from *."), "k k y3y k / k k k k k k / ") << centred;
  EXPECT_EQ(rows_of("*K1, yo, sk2p, yo, k2; rep from *."), "k k y3y k / k k k k k k / ");
  EXPECT_EQ(rows_of("[k1, yo, sl1, k1, psso] twice."), "ys k ys k / k k k k k k / ");
  // On a wrong-side row, worked from the back: a purl decrease from the front, as ssk's there.
  EXPECT_EQ(rows_text(mesh::parse_pattern("Row 1 (RS): Knit.\nRow 2 (WS): *P1, yo, sl1, k1, psso; rep from *.\n", "w.txt")),
            rows_text(mesh::parse_pattern("Row 1 (RS): Knit.\nRow 2 (WS): *P1, yo, ssk; rep from *.\n", "w.txt")));
  // "sl1 k1" and "sl 1 p1" with no comma: the slip, then the stitch (the letter after a slip is its knitwise or
  // purlwise only as a word of its own).
  EXPECT_EQ(rows_of("*Sl1 k1; rep from *."), rows_of("*Sl1, k1; rep from *."));
  EXPECT_EQ(rows_of("*Sl 1 p1; rep from *."), rows_of("*Sl1, p1; rep from *."));
  // Walker's "k1-b": through the back loop.
  EXPECT_EQ(rows_of("*K1-b, p1; rep from *."), rows_of("*K1 tbl, p1; rep from *."));
  // The decrease is in the colour of the stitch worked, the loop left on the needle; a lace face in its decrease's.
  const auto coloured = mesh::parse_pattern("MC: cream\nCC: red\nRow 1 (RS): *k1, yo, sl1 CC, k1, psso, k1, sl1, k1, psso CC, yo; rep from *.\nRow 2: Purl.\n",
                                            "c.txt");
  EXPECT_EQ(rows_text(coloured), "ys k ys k / k k k k k k / ");
  EXPECT_EQ(coloured.colours[0], (std::vector<int>{1, 0, 0, 0}));  // as seen from the front: the last worked first
  const auto error = [](const std::string& row) { return error_of([&] { mesh::parse_pattern("Row 1 (RS): " + row + "\nRow 2: Purl.\n", "e.txt"); }); };
  const std::string how = "passes the slipped stitch over the one worked after them: 'sl1, k1, psso' (skp), 'sl1, k2tog, psso' (sk2p) or "
                          "'sl2, k1, p2sso' (s2kp)";
  const std::string how2 = "passes the slipped stitches over the one worked after them: 'sl1, k1, psso' (skp), 'sl1, k2tog, psso' (sk2p) or "
                           "'sl2, k1, p2sso' (s2kp)";
  EXPECT_EQ(error("*K1, k1, psso, k1; rep from *."), "e.txt: line 1, column 22: 'psso' " + how + "; here 'k1' comes before 'k1'");
  EXPECT_EQ(error("K1, psso, k3."), "e.txt: line 1, column 17: 'psso' " + how + "; here nothing comes before 'k1'");
  EXPECT_EQ(error("*Psso, k3; rep from *."), "e.txt: line 1, column 14: 'psso' " + how + "; here a '*' comes before it");
  EXPECT_EQ(error("K1, sl1, *k1, psso, k2; rep from *."), "e.txt: line 1, column 27: 'psso' " + how + "; here a '*' comes before 'k1'");
  EXPECT_EQ(error("*K1, yo, sl1, k2, psso; rep from *."), "e.txt: line 1, column 31: 'psso' " + how + "; here 'k2' comes before it");
  EXPECT_EQ(error("*K1, sl1, [k1, psso] twice; rep from *."),
            "e.txt: line 1, column 28: 'psso' " + how + "; in a group it passes over only what the group works before it");
  EXPECT_EQ(error("*K1, yo, sl 2, k1, psso, k1; rep from *."), "e.txt: line 1, column 32: 'psso' " + how + "; here 'sl 2' slips two: pass them over with 'p2sso'");
  EXPECT_EQ(error("*K1, yo, sl 1, sl 1, k1, p2sso, yo; rep from *."),
            "e.txt: line 1, column 38: 'p2sso' " + how2 + "; here 'sl 1' slips one: 'p2sso' passes two slipped together ('sl2, k1, p2sso')");
}

// kfb on the right-side rows of a piece, with the stitch counts books write after a row ("(5 sts)", "— 5 sts").
TEST(WrittenPattern, AKfbWedgeWidensAndItsStitchCountsAreChecked) {
  const auto p = mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/written/stockinette-kfb-wedge.txt");
  ASSERT_TRUE(p.whole);
  ASSERT_EQ(p.height(), 8);
  EXPECT_EQ(p.rows[0], (std::vector<std::string>{"k", "k", "xk", "k"}));  // "K1, kfb, k2" worked right to left
  EXPECT_EQ(p.rows[7].size(), 8u);
  const auto piece = mesh::pattern_stitch_mesh(p, 1, 1);
  EXPECT_TRUE(mesh::validate(piece).valid());
  EXPECT_FALSE(mesh::emit_yarn(piece, mesh::StitchLibrary::bundled(), {}).points.empty());
  const auto error = [](const std::string& text) { return error_of([&] { mesh::parse_pattern(text, "w.txt"); }); };
  EXPECT_EQ(mesh::parse_pattern("Cast on 4 sts.\nRow 1 (RS): K1, kfb, k to end \u2014 5 sts.\nRow 2: Purl. (5 sts)\n", "w.txt").rows[1].size(), 5u);
  EXPECT_EQ(error("Cast on 4 sts.\nRow 1 (RS): K1, kfb, k2. (6 sts)\nRow 2: Purl.\n"),
            "w.txt: line 2, column 26: the row makes 5 stitches, but the count written after it says 6");
  // Repeated rows do not repeat the count of the row they copy.
  EXPECT_EQ(mesh::parse_pattern("Cast on 4 sts.\nRow 1 (RS): K1, kfb, k to end. (5 sts)\nRow 2: Purl.\nRep Rows 1 and 2 once more.\n", "w.txt").rows[3].size(), 6u);
  // Counts as books also write them: after a period, with the change, or the change alone; each checked.
  const auto four = [](const std::string& row) { return "Cast on 4 sts.\nRow 1 (RS): " + row + "\nRow 2: Purl.\n"; };
  for (const char* row : {"K1, kfb, k2. 5 sts.", "K1, kfb, k2 (5 sts; 1 st increased).", "K1, kfb, k2 (1 st inc).", "K1, kfb, k2 (1 st inc'd)."})
    EXPECT_EQ(mesh::parse_pattern(four(row), "w.txt").rows[1].size(), 5u) << row;
  EXPECT_EQ(mesh::parse_pattern(four("K1, k2tog, k1 (1 st dec)."), "w.txt").rows[1].size(), 3u);
  EXPECT_EQ(error_of([&] { mesh::parse_pattern(four("K1, kfb, k2 (2 sts inc'd)."), "w.txt"); }),
            "w.txt: line 2, column 25: the row makes 5 stitches from 4, but the count written after it says 2 increased");
}

TEST(WrittenPattern, AShapedPieceIsKnittedOnceAsWritten) {
  // "Cast on 8 sts." and rows of their own widths, no '*' repeat: a garter triangle decreased to a point.
  const auto p = mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/written/garter-triangle.txt");
  ASSERT_TRUE(p.whole);
  ASSERT_EQ(p.height(), 7);
  EXPECT_EQ(p.width(), 8);
  EXPECT_EQ(p.rows[0], (std::vector<std::string>{"k", "k", "k", "k", "k", "k", "d12k"}));  // RS: worked right to left, its k2tog on the right
  EXPECT_EQ(p.rows[1], (std::vector<std::string>{"d12p", "p", "p", "p", "p", "p"}));     // WS: garter's purl ridge from the front
  EXPECT_EQ(p.rows[6], (std::vector<std::string>{"d12k"}));
  // Knitted once: one face per stitch, every row narrower than the one below and centred on it; it emits.
  const auto piece = mesh::pattern_stitch_mesh(p, 1, 1);
  EXPECT_EQ(piece.faces.size(), 28u);
  EXPECT_TRUE(mesh::validate(piece).valid());
  double low = 1e9, high = -1e9;
  for (const auto& f : piece.faces)
    if (f.row == 6)
      for (int v : f.vertices) low = std::min(low, piece.vertices[v].x()), high = std::max(high, piece.vertices[v].x());
  EXPECT_NEAR(0.5 * (low + high), 0.5 * 8 * mesh::StitchSize{}.width, 1e-9);
  EXPECT_FALSE(mesh::emit_yarn(piece, mesh::StitchLibrary::bundled(), {}).points.empty());
  EXPECT_NE(error_of([&] { mesh::pattern_stitch_mesh(p, 2, 1); }).find("is a shaped piece, knitted once"), std::string::npos);
  EXPECT_TRUE(mesh::parse_pattern(mesh::write_chart_pattern(p), "c.txt").whole);  // its chart says "cast on", centred as its stitch mesh
  // The cast-on must be the first row's; "knit" rows are as wide as the row below; without "Cast on" the rows
  // are a repeat, and rows of other widths are refused as before.
  const auto error = [](const std::string& text) { return error_of([&] { mesh::parse_pattern(text, "s.txt"); }); };
  EXPECT_EQ(error("Cast on 5 sts.\nRow 1: K2tog, k2.\nRow 2: Knit.\n"), "s.txt: line 2: takes 4 stitches, but the pattern casts on 5");
  const auto filled = mesh::parse_pattern("Cast on 4 sts.\nRow 1 (RS): K2tog, k2.\nRow 2: Knit.\nRow 3: K1, k2tog.\n", "s.txt");
  ASSERT_TRUE(filled.whole);
  EXPECT_EQ(filled.rows[1], (std::vector<std::string>{"p", "p", "p"}));
  EXPECT_EQ(error("Row 1 (RS): K2, yo, k2.\nRow 2: Purl.\n"), "s.txt: line 2: this row takes 4 loops but the row below it (line 1) makes 5"
            " (a repeating stitch pattern keeps its count from row to row; a shaped piece is written with 'Cast on N sts.' and every row whole)");
  EXPECT_NE(error("Cast on 4 sts.\nRow 1: K2tog, k2.\nRow 2: K4.\n").find("this row takes 4 loops but the row below it (line 2) makes 3"), std::string::npos)
      << error("Cast on 4 sts.\nRow 1: K2tog, k2.\nRow 2: K4.\n");
  // Shaping as sweater patterns write it: "K1, ssk, k to last 3 sts, k2tog, k1", the fill as wide as the row below leaves.
  const auto cuff = mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/written/shaped-cuff.txt");
  ASSERT_TRUE(cuff.whole);
  ASSERT_EQ(cuff.height(), 12);
  std::vector<std::string> dec_row{"k", "d12k"};  // worked right to left: the k2tog on the left as seen from the front
  dec_row.insert(dec_row.end(), 10, "k");
  dec_row.insert(dec_row.end(), {"d21k", "k"});
  EXPECT_EQ(cuff.rows[2], dec_row);
  EXPECT_EQ(cuff.rows[3], std::vector<std::string>(14, "k"));  // a wrong-side purl row, 14 wide after the decreases
  EXPECT_EQ(cuff.rows[11].size(), 10u);
  EXPECT_TRUE(mesh::validate(mesh::pattern_stitch_mesh(cuff, 1, 1)).valid());
  EXPECT_EQ(error("Cast on 6 sts.\nRow 1: K1, k to last 3 sts, k2tog.\n"), "s.txt: line 2, column 12: 'k to last 3 sts' is followed by stitches that take 2 loops, not 3");
  // "k to last st" leaves one; rows all as wide after a cast-on are a piece too, knitted once.
  EXPECT_EQ(mesh::parse_pattern("Cast on 4 sts.\nRow 1 (RS): Ssk, k to last st, k1.\n", "l.txt").rows[0], (std::vector<std::string>{"k", "k", "d21k"}));
  const auto square = mesh::parse_pattern("Cast on 4 sts.\nRow 1: Knit.\nRow 2: Purl.\nRow 3: Knit.\n", "q.txt");
  EXPECT_TRUE(square.whole);
  EXPECT_EQ(square.height(), 3);
  EXPECT_EQ(error("Row 1: K2, k to end.\nRow 2: Purl.\n"),
            "s.txt: line 1, column 12: 'knit', 'purl', 'k to end' or 'p to end' stands alone in a row of a stitch pattern; beside other stitches, or "
            "'to last N sts', only in a shaped piece ('Cast on N sts.', each row taking the loops the row below made)");
}

TEST(WrittenPattern, AShapedPieceWorksItsRepeatAsOftenAsTheRowBelowLeavesRoom) {
  // Shaping inside a '*' repeat after a cast-on: each row's repeat is worked as often as the loops of the row below
  // leave room for beside its edge stitches, and the counts are checked as in any piece.
  const auto p = mesh::parse_pattern("Cast on 8 sts.\nRow 1 (RS): *K2, m1; rep from * to end. (12 sts)\nRow 2: Purl.\n"
                                     "Row 3: K1, *k2, k2tog; rep from * to last 3 sts, k3. (10 sts)\nRow 4: Purl.\n",
                                     "w.txt");
  ASSERT_TRUE(p.whole);
  ASSERT_EQ(p.height(), 4);
  EXPECT_EQ(p.rows[0], (std::vector<std::string>{"xk", "k", "xk", "k", "xk", "k", "xk", "k"}));  // four repeats, right to left
  EXPECT_EQ(p.rows[1].size(), 12u);
  std::vector<std::string> dec_row{"k", "k", "k", "d12k", "k", "k", "d12k", "k", "k", "k"};  // k3 on the left, k1 on the right
  EXPECT_EQ(p.rows[2], dec_row);
  EXPECT_EQ(p.rows[3].size(), 10u);
  EXPECT_TRUE(mesh::validate(mesh::pattern_stitch_mesh(p, 1, 1)).valid());
  const auto error = [](const std::string& text) { return error_of([&] { mesh::parse_pattern(text, "s.txt"); }); };
  EXPECT_EQ(error("Cast on 9 sts.\nRow 1 (RS): *K2, m1; rep from * to end.\nRow 2: Purl.\n"),
            "s.txt: line 2: its '*' repeat takes 2 loops, which do not fill the cast-on's 9 sts a whole number of times");
  EXPECT_EQ(error("Cast on 8 sts.\nRow 1 (RS): *K2, m1; rep from * to end.\nRow 2: P1, *p2, p2tog; rep from * to last st, p1.\n"),
            "s.txt: line 3: its '*' repeat takes 4 loops, which do not fill the row below's 12 sts less the row's 2 edge stitches (10) a whole number of times");
  EXPECT_EQ(error("Cast on 2 sts.\nRow 1 (RS): K1, *k2, m1; rep from * to last st, k1.\n"),
            "s.txt: line 2: its '*' repeat takes 2 loops, more than the cast-on's 2 sts less the row's 2 edge stitches leave (0)");
  EXPECT_EQ(error("Cast on 8 sts.\nRow 1 (RS): *K2, m1; rep from * to end.\nRow 2: p10.\n"),
            "s.txt: line 3: the row below makes 12 sts, but this row takes 10 loops (a piece cast on and shaped inside a '*' repeat takes, row by row, "
            "the loops the row below made)");
  // Shaped at its edges only, beside a repeat that keeps its count: a piece too.
  const auto edged = mesh::parse_pattern("Cast on 6 sts.\nRow 1 (RS): K1, m1, *p2, k2; rep from * to last st, m1, k1. (8 sts)\nRow 2: Purl.\n", "e.txt");
  ASSERT_TRUE(edged.whole);
  EXPECT_EQ(edged.rows[1].size(), 8u);
  EXPECT_EQ(error("Cast on 8 sts.\nRow 1 (RS): *K2, m1; rep from * to end. (13 sts)\nRow 2: Purl.\n"),
            "s.txt: line 2, column 41: the row makes 12 stitches, but the count written after it says 13");
  // Cast on, with repeats that keep the count: a stitch pattern, as before (the cast-on one width of it).
  EXPECT_FALSE(mesh::parse_pattern("Cast on 12 sts.\nRow 1 (RS): *K2, p2; rep from * to end.\nRow 2: *K2, p2; rep from * to end.\n", "r.txt").whole);
}

TEST(WrittenPattern, GroupsNestedPastSixteenDeepAreRefusedNotRecursedInto) {
  // A fuzzer's input: thousands of '(' overflowed the stack of the recursive group reader.
  const auto nested = [](int depth) {
    return "Row 1: *" + std::string(static_cast<size_t>(depth), '[') + "k1" + [&] {
      std::string closes;
      for (int i = 0; i < depth; ++i) closes += "] once";
      return closes;
    }() + "; rep from *.\n";
  };
  EXPECT_NO_THROW(mesh::parse_pattern(nested(16), "deep.txt"));
  EXPECT_EQ(error_of([&] { mesh::parse_pattern(nested(17), "deep.txt"); }), "deep.txt: line 1, column 25: groups are nested more than 16 deep");
  EXPECT_EQ(error_of([&] { mesh::parse_pattern("Row 1: *k2," + std::string(4000, '(') + "\n", "p.txt"); }), "p.txt: line 1, column 28: groups are nested more than 16 deep");
}
