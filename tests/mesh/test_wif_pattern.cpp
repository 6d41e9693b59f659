#include <gtest/gtest.h>

#include <filesystem>
#include <numeric>
#include <string>
#include <vector>

#include "stitchmesh/pattern.hpp"
#include "stitchmesh/wif_pattern.hpp"
#include "testing.hpp"

using namespace skein;
using skein::testing::error_of;

namespace {
/// A draft's drawdown as text, bottom pick first: one line per pick, 1 where the weft is over the warp.
std::string rows_text(const mesh::Pattern& p) {
  std::string out;
  for (const auto& row : p.over) {
    for (const char c : row) out += c ? '1' : '0';
    out += '\n';
  }
  return out;
}
const std::string kHeader = "[WIF]\nVersion=1.1\nSource Program=a test\n";
/// A straight draw over `shafts` shafts for `threads` threads.
std::string straight_threading(int threads, int shafts) {
  std::string out = "[THREADING]\n";
  for (int t = 1; t <= threads; ++t) out += std::to_string(t) + "=" + std::to_string((t - 1) % shafts + 1) + "\n";
  return out;
}
std::string error_in(const std::string& text) {
  return error_of([&] { mesh::parse_pattern(text, "draft.wif"); });
}
}  // namespace

TEST(WifPattern, TieUpAndTreadlingWeaveTheDrawdownReducedToItsRepeat) {
  const auto p = mesh::read_pattern(std::filesystem::path(SKEIN_PATTERNS_DIR) / "wif" / "twill-2-2.wif");
  EXPECT_EQ(p.format, mesh::PatternFormat::Woven);
  EXPECT_EQ(p.name, "Twill 2/2 from a WIF draft");
  EXPECT_EQ(p.note, "a WIF draft from skein's test drafts");
  // Eight threads and picks of a four-thread twill: pick 1 raises shafts 1 and 2, so threads 1 and 2 go over
  // the weft (0), each pick one thread further; the repeat is four by four.
  EXPECT_EQ(rows_text(p), "0011\n1001\n1100\n0110\n");
}

TEST(WifPattern, ALiftPlanWeavesAsTheTieUpAndTreadlingItStandsFor) {
  const std::string tieup = "[WEAVING]\nShafts=4\nTreadles=4\n[TIEUP]\n1=1,2\n2=2,3\n3=3,4\n4=4,1\n[TREADLING]\n1=1\n2=2\n3=3\n4=4\n";
  const std::string lifts = "[WEAVING]\nShafts=4\n[LIFTPLAN]\n1=1,2\n2=2,3\n3=3,4\n4=4,1\n";
  const auto a = mesh::parse_pattern(kHeader + straight_threading(4, 4) + tieup, "a.wif");
  const auto b = mesh::parse_pattern(kHeader + straight_threading(4, 4) + lifts, "b.wif");
  EXPECT_EQ(rows_text(a), rows_text(b));
  EXPECT_EQ(a.name, "a");  // no [TEXT] Title: the file's stem
  // The bundled bird's eye: a point draw 1 2 3 4 3 2 lifted by a lift plan.
  const auto eye = mesh::read_pattern(std::filesystem::path(SKEIN_PATTERNS_DIR) / "wif" / "bird-eye.wif");
  EXPECT_EQ(rows_text(eye), "001110\n100100\n110001\n011011\n110001\n100100\n");
}

TEST(WifPattern, ASinkingShedAndTwoTreadlesAtOnceAreWovenAsTheLoomDoes) {
  const std::string weave = "[WEAVING]\nShafts=2\nTreadles=2\nRising Shed=no\n[TIEUP]\n1=1\n2=2\n[TREADLING]\n1=1\n2=2\n";
  // Sinking: the tied shaft's threads go under the weft (1), the others over (0): plain weave.
  EXPECT_EQ(rows_text(mesh::parse_pattern(kHeader + straight_threading(2, 2) + weave, "s.wif")), "10\n01\n");
  // Both treadles on pick 1 of a rising shed lift every thread: the weft goes under the whole row.
  const std::string both = "[WEAVING]\nShafts=2\nTreadles=2\n[TIEUP]\n1=1\n2=2\n[TREADLING]\n1=1,2\n2=2\n";
  EXPECT_EQ(rows_text(mesh::parse_pattern(kHeader + straight_threading(2, 2) + both, "b.wif")), "00\n10\n");
}

TEST(WifPattern, ADraftWhoseLastRepeatIsCutShortKeepsItsWholeRepeat) {
  // Nine threads and seven picks of a 1/3 twill: the repeat is still four by four.
  std::string lifts = "[WEAVING]\nShafts=4\n[LIFTPLAN]\n";
  for (int pick = 1; pick <= 7; ++pick) lifts += std::to_string(pick) + "=" + std::to_string((pick - 1) % 4 + 1) + "\n";
  const auto p = mesh::parse_pattern(kHeader + straight_threading(9, 4) + lifts, "t.wif");
  EXPECT_EQ(p.width(), 4);
  EXPECT_EQ(p.height(), 4);
  EXPECT_EQ(rows_text(p), "0111\n1011\n1101\n1110\n");
  EXPECT_GT(mesh::woven_yarn(p, 2, 2, 2.4, 0.6).points.size(), 0u);
}

TEST(WifPattern, BrokenDraftsAreRefusedNamingTheLineAndTheRule) {
  const std::string lifts = "[WEAVING]\nShafts=4\n[LIFTPLAN]\n1=1\n2=2\n";
  EXPECT_EQ(error_in(kHeader + lifts), "draft.wif: has no [THREADING] section: a WIF draft needs one to say which shafts carry which warp threads");
  EXPECT_EQ(error_in(kHeader + straight_threading(4, 4) + "[WEAVING]\nShafts=4\n[TIEUP]\n1=1\n"),
            "draft.wif: has neither a [LIFTPLAN] nor a [TIEUP] with a [TREADLING] section: nothing says which shafts rise on each pick");
  // A shaft past [WEAVING] Shafts (line 7 is "3=5").
  EXPECT_EQ(error_in(kHeader + "[THREADING]\n1=1\n2=2\n3=5\n" + lifts), "draft.wif: line 7: shaft 5 is outside 1 to 4");
  EXPECT_EQ(error_in(kHeader + "[THREADING]\n1=1\nx=2\n" + lifts), "draft.wif: line 6: expected [threading] thread as a whole number, found 'x'");
  EXPECT_EQ(error_in(kHeader + "[THREADING]\n1=1\n1=2\n" + lifts), "draft.wif: line 6: [threading] gives thread 1 twice");
  EXPECT_EQ(error_in(kHeader + "[THREADING]\n1=1\n2 2\n" + lifts), "draft.wif: line 6: expected KEY=VALUE in section [threading], found '2 2'");
  EXPECT_EQ(error_in(kHeader + "[THREADING\n1=1\n"), "draft.wif: line 4: a section header is [NAME], found '[THREADING'");
  EXPECT_EQ(error_in(kHeader + straight_threading(2, 2) + "[THREADING]\n1=1\n"), "draft.wif: line 7: section [threading] again (first on line 4)");
  EXPECT_EQ(error_in(kHeader + "[WARP]\nThreads=99999\n" + straight_threading(2, 2) + lifts),
            "draft.wif: line 5: [warp] Threads 99999 is outside 1 to 10000");
  EXPECT_EQ(error_in(kHeader + "[WEAVING]\nShafts=2\n" + straight_threading(2, 2) + "[LIFTPLAN]\n1=1\n3=2\n[WEFT]\nThreads=2\n"),
            "draft.wif: line 11: [liftplan] pick 3 is outside 1 to 2");
  // A draft that does not repeat within 256 threads: a straight draw over 300 shafts, lifted one by one.
  std::string wide = "[WEAVING]\nShafts=300\n[LIFTPLAN]\n";
  for (int pick = 1; pick <= 300; ++pick) wide += std::to_string(pick) + "=" + std::to_string(pick) + "\n";
  EXPECT_EQ(error_in(kHeader + straight_threading(300, 300) + wide),
            "draft.wif: the draft's smallest repeat is 300 threads x 300 picks; skein relaxes woven repeats up to 256 x 256");
}

TEST(WifPattern, ADraftTooLargeToWeaveIsRefusedBeforeItIsWoven) {
  EXPECT_EQ(error_in(kHeader + "[WEAVING]\nShafts=2\n[WARP]\nThreads=9000\n[WEFT]\nThreads=9000\n" + straight_threading(2, 2) + "[LIFTPLAN]\n1=1\n"),
            "draft.wif: the draft is 9000 threads x 9000 picks; skein weaves drafts of up to 4000000 cells");
}

namespace {
/// The two drawdowns weave the same cloth: tiled to a common size, one equals the other shifted cyclically.
bool same_cloth(const mesh::Pattern& a, const mesh::Pattern& b) {
  const auto h = std::lcm(a.over.size(), b.over.size()), w = std::lcm(a.over[0].size(), b.over[0].size());
  const auto at = [](const mesh::Pattern& p, size_t r, size_t c) { return p.over[r % p.over.size()][c % p.over[0].size()]; };
  for (size_t dr = 0; dr < h; ++dr)
    for (size_t dc = 0; dc < w; ++dc) {
      bool same = true;
      for (size_t r = 0; r < h && same; ++r)
        for (size_t c = 0; c < w && same; ++c) same = at(a, r, c) == at(b, r + dr, c + dc);
      if (same) return true;
    }
  return false;
}
}  // namespace

TEST(WifPattern, TheCorpusDraftsWeaveTheBundledCloths) {
  const std::filesystem::path dir(SKEIN_PATTERNS_DIR);
  for (const auto& [draft, weave] : std::vector<std::pair<std::string, std::string>>{
           {"plain-weave", "plain-weave"}, {"twill-2-1", "twill-2-1"}, {"basket-2x2", "basket-2x2"}, {"satin-5", "satin-5-2"}}) {
    SCOPED_TRACE(draft);
    const auto p = mesh::read_pattern(dir / "wif" / (draft + ".wif"));
    EXPECT_TRUE(same_cloth(p, mesh::read_pattern(dir / (weave + ".weave")))) << rows_text(p);
  }
  // A 3/1 twill by a lift plan: each weft over three warps, the warp it passes under one further each pick.
  EXPECT_EQ(rows_text(mesh::read_pattern(dir / "wif" / "twill-3-1.wif")), "0111\n1011\n1101\n1110\n");
  // The point draws: goose-eye's nested diamonds are symmetric about the point thread and the point pick, and
  // larger than bird's eye's.
  const auto goose = mesh::read_pattern(dir / "wif" / "goose-eye.wif");
  ASSERT_EQ(goose.over.size(), 14u);
  ASSERT_EQ(goose.over[0].size(), 14u);
  for (size_t r = 0; r < 14; ++r)
    for (size_t c = 0; c < 14; ++c) EXPECT_EQ(goose.over[r][c], goose.over[(14 - r) % 14][(14 - c) % 14]) << r << " " << c;
  EXPECT_FALSE(same_cloth(goose, mesh::read_pattern(dir / "wif" / "bird-eye.wif")));
  // Every draft of the corpus reads, with a title.
  for (const auto& entry : std::filesystem::directory_iterator(dir / "wif")) {
    SCOPED_TRACE(entry.path().string());
    EXPECT_FALSE(mesh::read_pattern(entry.path()).name.empty());
  }
}

TEST(WifPattern, ColoursOfWarpAndWeftComeFromTheColourTable) {
  // twill-2-2.wif: the warp all colour 2 (navy), the weft colour 1 (white); the weave's repeat stays 4 x 4.
  const auto twill = mesh::read_pattern(std::filesystem::path(SKEIN_PATTERNS_DIR) / "wif" / "twill-2-2.wif");
  ASSERT_EQ(twill.palette.size(), 2u);
  EXPECT_EQ(mesh::colour_code(twill.palette[0].srgb), "#ffffff");
  EXPECT_EQ(mesh::colour_code(twill.palette[1].srgb), "#000080");
  EXPECT_EQ(twill.warp_colours, (std::vector<int>{1, 1, 1, 1}));
  EXPECT_EQ(twill.weft_colours, (std::vector<int>{0, 0, 0, 0}));
  // Houndstooth: the same twill with four dark and four light threads each way (a 0..65535 range): the colour
  // order doubles the repeat to 8 x 8, and the woven yarn carries the colours thread by thread.
  const auto tooth = mesh::read_pattern(std::filesystem::path(SKEIN_PATTERNS_DIR) / "wif" / "houndstooth.wif");
  EXPECT_EQ(tooth.width(), 8);
  EXPECT_EQ(tooth.height(), 8);
  EXPECT_EQ(mesh::colour_code(tooth.palette[0].srgb), "#0f0f11");
  EXPECT_EQ(tooth.warp_colours, (std::vector<int>{0, 0, 0, 0, 1, 1, 1, 1}));
  EXPECT_EQ(tooth.weft_colours, (std::vector<int>{0, 0, 0, 0, 1, 1, 1, 1}));
  auto yarn = mesh::woven_yarn(tooth, 2, 1, 2.0, 0.3);
  mesh::colour_woven_yarn(yarn, tooth, 2, 1);
  ASSERT_EQ(yarn.curves(), 8 + 16);
  EXPECT_EQ(yarn.point_colour[yarn.curve_start[5]], 1);   // weft 6: light
  EXPECT_EQ(yarn.point_colour[yarn.curve_start[8 + 13]], 1);  // warp 14 (of the second repeat's 5 to 8): light
  EXPECT_EQ(yarn.point_colour[yarn.curve_start[8 + 9]], 0);   // warp 10: dark
  // A colour the table lacks, and a table entry that is not R,G,B, are refused naming the rule.
  const std::string draft = kHeader + straight_threading(4, 4) + "[TIEUP]\n1=1,2\n2=2,3\n3=3,4\n4=4,1\n[TREADLING]\n1=1\n2=2\n3=3\n4=4\n";
  EXPECT_EQ(error_in(draft + "[COLOR TABLE]\n1=0,0,0\n[WARP]\nColor=2\n"), "draft.wif: line 22: [WARP] Color 2 is outside 1 to 1");
  EXPECT_EQ(error_in(draft + "[COLOR TABLE]\n1=0,0\n"), "draft.wif: line 20: [COLOR TABLE] colour 1 is R,G,B, found '0,0'");
  EXPECT_EQ(error_in(draft + "[COLOR TABLE]\n1=0,0,300\n"), "draft.wif: line 20: [COLOR TABLE] colour 1's channel 300 is outside 0 to 255");
  EXPECT_EQ(error_in(draft + "[COLOR TABLE]\n1=0,0,0\n3=1,1,1\n[WEFT COLORS]\n2=2\n"),
            "draft.wif: [WEFT] threads use colour 2, which the [COLOR TABLE] does not give");
}
