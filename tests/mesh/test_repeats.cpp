// Repeats read back from a stitch mesh's types: the smallest period, one canonical phase wherever a pattern
// is found, regions that reach to one stitch from another pattern, and none around odd stitches.
#include <algorithm>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "stitchmesh/edits.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/repeats.hpp"
#include "testing.hpp"

using namespace skein;
using namespace skein::mesh;

namespace {
StitchMesh sheet(const std::string& rows, int across, int up) {
  return pattern_stitch_mesh(parse_pattern("format knit\n" + rows, "test.knit"), across, up);
}
/// Every face in a repeat has the repeat's type at its place, and its neighbours along the row and the wale
/// in the same repeat are one place on.
void expect_consistent(const StitchMesh& mesh, const RepeatRegions& found) {
  const auto table = edge_table(mesh);
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f) {
    const int r = found.repeat[f];
    if (r < 0) continue;
    const auto& rows = found.repeats[r].rows;
    const int P = static_cast<int>(rows[0].size()), Q = static_cast<int>(rows.size());
    EXPECT_EQ(mesh.faces[f].type, rows[found.row[f]][found.column[f]]) << "face " << f;
    if (const int g = step(mesh, table, f, Step::Right); g >= 0 && found.repeat[g] == r) {
      EXPECT_EQ(found.column[g], (found.column[f] + 1) % P);
      EXPECT_EQ(found.row[g], found.row[f]);
    }
    if (const int g = step(mesh, table, f, Step::Up); g >= 0 && found.repeat[g] == r) {
      EXPECT_EQ(found.row[g], (found.row[f] + 1) % Q);
      EXPECT_EQ(found.column[g], found.column[f]);
    }
  }
}
}  // namespace

TEST(Repeats, EachFillIsFoundWithItsSmallestPeriodInsideTheSheet) {
  // pattern rows bottom-up as written in a pattern file (the last line first), and the period expected
  const std::vector<std::tuple<std::string, std::string, int, int>> cases = {
      {"k\n", "k", 1, 1},
      {"k k p p\n", "k k p p", 4, 1},
      {"p k k p\n", "k k p p", 4, 1},  // another phase of the same rib: the same repeat
      {"p k\nk p\n", "p k / k p", 2, 2},
      {"p\nk\n", "p / k", 1, 2},
      {"k k p p\nk k p p\nk k k k\n", "k k p p / k k p p / k k k k", 4, 3},
      {"k p k p\np k p k\n", "p k / k p", 2, 2},  // written twice as wide as it needs
  };
  for (const auto& [rows, text, P, Q] : cases) {
    SCOPED_TRACE(rows);
    const auto pattern = parse_pattern("format knit\n" + rows, "t");
    const auto mesh = sheet(rows, 12 / pattern.width(), 12 / pattern.height());
    const auto found = find_repeats(mesh);
    ASSERT_EQ(found.repeats.size(), 1u);
    EXPECT_EQ(repeat_text(found.repeats[0]), text);
    EXPECT_EQ(found.repeats[0].width(), P);
    EXPECT_EQ(found.repeats[0].height(), Q);
    // Every stitch with a full ring of stitches around it, and no other.
    for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f) {
      const int row = f / 12, col = f % 12;
      const bool inside = row > 0 && row < 11 && col > 0 && col < 11;
      EXPECT_EQ(found.repeat[f] == 0, inside) << "face " << f;
    }
    expect_consistent(mesh, found);
  }
}

TEST(Repeats, RegionsReachToOneStitchFromAnotherPatternAndTheSamePatternTwiceIsOneRepeat) {
  // A stockinette sheet, 16 x 24, with 2 x 2 rib in its bottom 8 rows and its top 8 rows.
  auto mesh = sheet("k\n", 16, 24);
  std::vector<int> rib;
  for (int f = 0; f < 16 * 24; ++f)
    if (f / 16 < 8 || f / 16 >= 16) rib.push_back(f);
  mesh = fill(mesh, rib, parse_fill("rib2x2"));
  const auto found = find_repeats(mesh);
  ASSERT_EQ(found.repeats.size(), 2u);
  EXPECT_EQ(repeat_text(found.repeats[0]), "k");
  EXPECT_EQ(repeat_text(found.repeats[1]), "k k p p");
  for (int f = 0; f < 16 * 24; ++f) {
    const int row = f / 16, col = f % 16;
    // The sheet's border and the rows where the patterns meet (every 3 stitches of a 2 x 2 rib row hold a purl)
    // are in no repeat.
    int expected = -1;
    if (col > 0 && col < 15 && ((row >= 1 && row <= 6) || (row >= 17 && row <= 22))) expected = 1;
    if (col > 0 && col < 15 && row >= 9 && row <= 14) expected = 0;
    EXPECT_EQ(found.repeat[f], expected) << "row " << row << ", column " << col;
  }
  expect_consistent(mesh, found);
  EXPECT_EQ(found.faces_of(1), 2 * 6 * 14);

  // Two rings beyond: every stitch is of its own pattern, the borders and the rows where they meet too. (One
  // ring leaves the corners and the border stitches of those rows, whose neighbours joined in the same ring.)
  const auto one = find_repeats(mesh, 8, 1);
  EXPECT_EQ(std::count(one.repeat.begin(), one.repeat.end(), -1), 4 + 8);
  const auto reached = find_repeats(mesh, 8, 2);
  for (int f = 0; f < 16 * 24; ++f) EXPECT_EQ(reached.repeat[f], f / 16 < 8 || f / 16 >= 16 ? 1 : 0) << "face " << f;
  expect_consistent(mesh, reached);
  EXPECT_NE(skein::testing::error_of([&] { find_repeats(mesh, 8, -1); }).find("0 or more"), std::string::npos);
}

TEST(Repeats, TheMiddleOfAWideRibIsNoStockinette) {
  // 3 x 3 rib: the middle knit column has knits all around it, but the rib is three stitches away.
  const auto found = find_repeats(sheet("k k k p p p\n", 4, 12));
  ASSERT_EQ(found.repeats.size(), 1u);
  EXPECT_EQ(repeat_text(found.repeats[0]), "k k k p p p");
}

TEST(Repeats, NoRepeatTakesAnOddStitchOrItsNeighbours) {
  auto mesh = sheet("k\n", 16, 16);
  const int odd = 8 * 16 + 8;
  mesh.faces[odd].type = "p";
  const auto found = find_repeats(mesh);
  ASSERT_EQ(found.repeats.size(), 1u);
  for (int row = 7; row <= 9; ++row)
    for (int col = 7; col <= 9; ++col) EXPECT_EQ(found.repeat[row * 16 + col], -1) << row << ", " << col;
  EXPECT_EQ(found.repeat[6 * 16 + 6], 0);
  EXPECT_EQ(found.faces_of(0), 14 * 14 - 9);
}

TEST(Repeats, ALongerPeriodThanAllowedIsNoRepeatAndTheLimitIsChecked) {
  const auto mesh = sheet("k k k p p p\n", 4, 12);
  EXPECT_TRUE(find_repeats(mesh, 5).repeats.empty());
  EXPECT_EQ(find_repeats(mesh, 6).repeats.size(), 1u);
  EXPECT_NE(skein::testing::error_of([&] { find_repeats(mesh, 0); }).find("1 to 16"), std::string::npos);
  EXPECT_NE(skein::testing::error_of([&] { find_repeats(mesh, 17); }).find("found 17"), std::string::npos);
}

TEST(Repeats, ASquareOfFiveByFiveStitchesIsARegionOfItsNineInnerOnes) {
  auto mesh = sheet("k\n", 16, 16);
  for (int row = 5; row <= 9; ++row)
    for (int col = 5; col <= 9; ++col) mesh.faces[row * 16 + col].type = "p";
  const auto found = find_repeats(mesh);
  ASSERT_EQ(found.repeats.size(), 2u);
  EXPECT_EQ(repeat_text(found.repeats[1]), "p");
  EXPECT_EQ(found.faces_of(1), 9);
  for (int row = 6; row <= 8; ++row)
    for (int col = 6; col <= 8; ++col) EXPECT_EQ(found.repeat[row * 16 + col], 1) << row << ", " << col;
}

namespace {
const char* kCable = "format knit\np p k k k k p p\np p k k k k p p\np p k k k k p p\np p cable2x2+ p p\n";
const char* kLace = "format knit\nk k k k k\nkyk d123k k\nk k k k k\n";

/// A stockinette sheet 40 stitches wide and 16 high, a cable tiled over its left 24 columns and a lace over
/// its right 15 (a column of stockinette between them).
struct TiledSheet {
  Pattern cable = parse_pattern(kCable, "cable.knit"), lace = parse_pattern(kLace, "lace.knit");
  StitchMesh mesh;
  TileReport cables, laces;
  TiledSheet() {
    const StitchSize size;
    mesh = sheet("k\n", 40, 16);
    const auto columns = [&](double from, double to) {
      std::vector<int> faces;
      for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f) {
        const double x = mesh.vertices[mesh.faces[f].vertex(0)].x() / size.width;
        if (x >= from - 0.5 && x < to - 0.5) faces.push_back(f);
      }
      return faces;
    };
    auto faces = columns(0, 24);
    mesh = tile_pattern(mesh, faces, cable, lowest_left(mesh, faces), &cables);
    faces = columns(25, 40);
    mesh = tile_pattern(mesh, faces, lace, lowest_left(mesh, faces), &laces);
  }
};
}  // namespace

TEST(TiledRepeats, EveryWholeRepeatOfACableAndALaceIsFoundFaceForFace) {
  const TiledSheet s;
  ASSERT_EQ(s.cables.repeats, 12);  // 3 across, 4 up
  ASSERT_EQ(s.laces.repeats, 15);   // 3 across, 5 up
  const auto found = find_tiled_repeats(s.mesh, {s.cable, s.lace});
  ASSERT_EQ(found.patterns.size(), 2u);
  EXPECT_EQ(found.repeats, (std::vector<int>{12, 15}));
  const auto cable_unit = pattern_stitch_mesh(s.cable, 1, 1), lace_unit = pattern_stitch_mesh(s.lace, 1, 1);
  std::vector<std::vector<int>> seen(2, std::vector<int>(std::max(s.cable.stitches(), s.lace.stitches()), 0));
  for (int f = 0; f < static_cast<int>(s.mesh.faces.size()); ++f) {
    const int k = found.pattern[f];
    if (k < 0) {
      EXPECT_TRUE(is_plain(s.mesh.faces[f]) && s.mesh.faces[f].type == "k") << "face " << f << " (" << s.mesh.faces[f].type << ") is in no repeat";
      continue;
    }
    const auto& own = (k == 0 ? cable_unit : lace_unit).faces[found.place[f]];
    EXPECT_EQ(s.mesh.faces[f].type, own.type) << "face " << f;
    EXPECT_EQ(s.mesh.faces[f].size(), own.size()) << "face " << f;
    ++seen[k][found.place[f]];
  }
  for (int q = 0; q < s.cable.stitches(); ++q) EXPECT_EQ(seen[0][q], 12) << "cable place " << q;
  for (int q = 0; q < s.lace.stitches(); ++q) EXPECT_EQ(seen[1][q], 15) << "lace place " << q;
}

TEST(TiledRepeats, ARepeatWithAStitchChangedOrACableLostIsNotOne) {
  TiledSheet s;
  const auto before = find_tiled_repeats(s.mesh, {s.cable, s.lace});
  // A purl of one cable repeat knitted, and the cable mark farthest from it taken off (another repeat's).
  const auto purl = std::find_if(s.mesh.faces.begin(), s.mesh.faces.end(), [](const StitchFace& f) { return f.type == "p"; });
  ASSERT_NE(purl, s.mesh.faces.end());
  EXPECT_EQ(before.pattern[purl - s.mesh.faces.begin()], 0);
  purl->type = "k";
  const Eigen::Vector3d there = s.mesh.vertices[purl->vertex(0)];
  ASSERT_FALSE(s.mesh.cables.empty());
  const auto farthest = std::max_element(s.mesh.cables.begin(), s.mesh.cables.end(), [&](const auto& a, const auto& b) {
    return (s.mesh.vertices[a.first.first] - there).norm() < (s.mesh.vertices[b.first.first] - there).norm();
  });
  s.mesh.cables.erase(farthest);
  const auto after = find_tiled_repeats(s.mesh, {s.cable, s.lace});
  EXPECT_EQ(after.repeats, (std::vector<int>{10, 15}));
}

TEST(TiledRepeats, PatternsThatDoNotReMeshAreLeftToTheStitchTypesAndWovensAreRefused) {
  const TiledSheet s;
  const auto found = find_tiled_repeats(s.mesh, {parse_pattern("format knit\nk k p p\n", "rib.knit"), s.lace});
  ASSERT_EQ(found.patterns.size(), 1u);
  EXPECT_EQ(found.patterns[0].name, s.lace.name);
  EXPECT_EQ(found.repeats, std::vector<int>{15});
  const auto error = skein::testing::error_of([&] { find_tiled_repeats(s.mesh, {parse_pattern("format woven\n10\n01\n", "twill.weave")}); });
  EXPECT_NE(error.find("woven"), std::string::npos) << error;
}
