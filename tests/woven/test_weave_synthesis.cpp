// Weave patterns and the structure-aware synthesis of Zhao 2012 §5.2-5.4.
#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "testing.hpp"
#include "woven/synthesis.hpp"
#include "woven/weave.hpp"

using namespace skein;
using namespace skein::woven;

namespace {

Weave bundled(const std::string& name) { return from_pattern(mesh::read_pattern(std::filesystem::path(SKEIN_PATTERNS_DIR) / (name + ".weave"))); }

/// The bundled exemplar set's weaves at 10 x 10 crossings (what the exemplars' relaxed yarn keeps).
std::vector<Weave> exemplar_weaves() {
  std::vector<Weave> out;
  for (const char* n : {"plain-weave", "twill-3-2", "twill-4-1", "satin-5-2", "basket-2x2"}) out.push_back(tiled(bundled(n), 10, 10));
  return out;
}

Weave random_weave(int warps, int wefts, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  Weave w = make_weave(warps, wefts);
  for (int i = 0; i < wefts; ++i)
    for (int j = 0; j < warps; ++j) w.set(i, j, random() & 1);
  return w;
}

}  // namespace

TEST(Weave, SkeinsWovenTextIsTurnedOverIntoZhaosWarpUp) {
  const auto pattern = mesh::parse_pattern("format woven\n1 0 0\n0 1 0\n", "t.weave");  // bottom row last
  const Weave w = from_pattern(pattern);
  ASSERT_EQ(w.warps, 3);
  ASSERT_EQ(w.wefts, 2);
  // Row 0 (the bottom line "0 1 0"): the weft over warp 1 only, so the warps 0 and 2 are up.
  EXPECT_TRUE(w.at(0, 0));
  EXPECT_FALSE(w.at(0, 1));
  EXPECT_TRUE(w.at(0, 2));
  EXPECT_FALSE(w.at(1, 0));
  EXPECT_EQ(from_text(to_text(w), "t"), w);
  EXPECT_EQ(to_text(w), ".##\n#.#\n");
}

TEST(Weave, BrokenWeaveTextNamesTheRow) {
  EXPECT_NE(skein::testing::error_of([] { from_text("##.\n#.\n", "x.txt"); }).find("weave row 2"), std::string::npos);
  EXPECT_NE(skein::testing::error_of([] { from_text("#x\n", "x.txt"); }).find("holds 'x'"), std::string::npos);
  EXPECT_NE(skein::testing::error_of([] { from_text("\n", "x.txt"); }).find("no rows"), std::string::npos);
}

TEST(Weave, APosterizedPictureTakesEachColoursWeave) {
  // Zhao §5.2: W(x, y) = V_p(I(x, y))(x, y). Left half colour 0 (plain), right half colour 1 (4/1 twill).
  const int width = 10, height = 5;
  std::vector<int> labels(width * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) labels[y * width + x] = x < 5 ? 0 : 1;
  const Weave plain = bundled("plain-weave"), twill = bundled("twill-4-1");
  const Weave w = weave_from_labels(labels, width, height, {plain, twill}, {0, 1});
  for (int i = 0; i < height; ++i)
    for (int j = 0; j < width; ++j) EXPECT_EQ(w.at(i, j), j < 5 ? plain.at(i % 2, j % 2) : twill.at(i % 5, j % 5)) << i << " " << j;
  EXPECT_NE(skein::testing::error_of([&] { weave_from_labels(labels, width, height, {plain}, {0}); }).find("no weave"), std::string::npos);
}

TEST(Weave, TheCrossingOrderOfWovenYarnIsItsWeave) {
  // §6.2 on yarn as woven_yarn lays it: the detected weave is the pattern's.
  const auto pattern = mesh::read_pattern(std::filesystem::path(SKEIN_PATTERNS_DIR) / "twill-3-2.weave");
  const auto yarn = mesh::woven_yarn(pattern, 2, 2, 1.2, 0.3);
  std::vector<int> wefts, warps;
  for (int i = 0; i < 2 * pattern.height(); ++i) wefts.push_back(i);
  for (int j = 0; j < 2 * pattern.width(); ++j) warps.push_back(2 * pattern.height() + j);
  EXPECT_EQ(detect_weave(yarn, warps, wefts), tiled(from_pattern(pattern), 2 * pattern.width(), 2 * pattern.height()));
}

TEST(WovenSynthesis, EveryCrossingHasTheRightYarnOnTopAndTheMostMatchingNeighbours) {
  const auto exemplars = exemplar_weaves();
  for (const Weave& target : {tiled(bundled("twill-2-1"), 30, 24), tiled(bundled("satin-5-3"), 25, 25), random_weave(20, 20, 7)}) {
    for (bool randomize : {false, true}) {
      SynthesisOptions options;
      options.randomize = randomize;
      const auto a = synthesize(target, exemplars, options);
      const auto s = score(target, exemplars, a);
      EXPECT_EQ(s.correct, s.crossings);  // principle 1
      EXPECT_EQ(s.matches, s.best_matches);  // principle 2, crossing by crossing
    }
  }
}

TEST(WovenSynthesis, AnExemplarsOwnWeaveIsCopiedWhole) {
  // The 4/1 twill from a set that holds it: consistent everywhere, and continuous almost everywhere.
  const auto exemplars = exemplar_weaves();
  const Weave target = tiled(bundled("twill-4-1"), 20, 20);
  SynthesisOptions options;
  options.randomize = false;
  const auto s = score(target, exemplars, synthesize(target, exemplars, options));
  EXPECT_EQ(s.consistent, s.crossings);
  EXPECT_GT(s.continuity, 0.8 * 2 * 20 * 19);
}

TEST(WovenSynthesis, EachColumnsDynamicProgramFindsTheMostContinuityABruteForceFinds) {
  // One warp column (no horizontal term): Eq. 1's optimum against every assignment of the candidate blocks.
  const auto exemplars = std::vector<Weave>{tiled(bundled("twill-3-2"), 6, 6), tiled(bundled("satin-5-2"), 6, 6)};
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const Weave target = random_weave(1, 6, seed);
    SynthesisOptions options;
    options.randomize = false;
    options.horizontal = false;
    const auto best = score(target, exemplars, synthesize(target, exemplars, options));
    // The candidates of each crossing: correct blocks with the most matching neighbours.
    std::vector<std::vector<Block>> candidates(target.wefts);
    for (int i = 0; i < target.wefts; ++i) {
      int most = -1;
      for (int u = 0; u < 2; ++u)
        for (int y = 0; y < 6; ++y)
          for (int x = 0; x < 6; ++x) {
            if (exemplars[u].at(y, x) != target.at(i, 0)) continue;
            const int m = neighbour_matches(target, i, 0, exemplars[u], x, y);
            if (m > most) most = m, candidates[i].clear();
            if (m == most) candidates[i].push_back({u, x, y});
          }
    }
    long brute = 0;
    std::vector<Block> chosen(target.wefts);
    std::function<void(int, long)> walk = [&](int i, long continuity) {
      if (i == target.wefts) return void(brute = std::max(brute, continuity));
      for (const auto& b : candidates[i]) {
        chosen[i] = b;
        walk(i + 1, continuity + (i > 0 && continuous(chosen[i - 1], b, 1, 0)));
      }
    };
    walk(0, 0);
    EXPECT_EQ(best.continuity, brute) << "seed " << seed;
    EXPECT_EQ(best.matches, best.best_matches);
  }
}

TEST(WovenSynthesis, RandomizationShiftsGroupsAndKeepsEveryPrinciple) {
  const auto exemplars = exemplar_weaves();
  const Weave target = tiled(bundled("twill-3-2"), 60, 60);
  SynthesisOptions fixed, random;
  fixed.randomize = false;
  const auto a = synthesize(target, exemplars, fixed), b = synthesize(target, exemplars, random);
  long moved = 0;
  for (size_t k = 0; k < a.blocks.size(); ++k) moved += !(a.blocks[k] == b.blocks[k]);
  EXPECT_GT(moved, 0.2 * a.blocks.size());
  const auto sa = score(target, exemplars, a), sb = score(target, exemplars, b);
  EXPECT_EQ(sb.correct, sb.crossings);
  EXPECT_EQ(sb.matches, sa.matches);
  EXPECT_EQ(sb.consistent, sa.consistent);
  // Continuity inside each 3 x 3 group survives the shift: at least the inner pairs of the groups.
  EXPECT_GT(sb.continuity, 0.5 * sa.continuity);
}

TEST(WovenSynthesis, AWeaveNoExemplarCanMakeIsRefused) {
  Weave all_weft = make_weave(4, 4);  // no crossing with the warp up
  const auto message = skein::testing::error_of([&] { synthesize(tiled(bundled("plain-weave"), 4, 4), {all_weft}); });
  EXPECT_NE(message.find("no exemplar has a crossing with the warp on top"), std::string::npos) << message;
}
