// Weave patterns and the structure-aware synthesis of Zhao 2012 §5.2-5.4.
#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "testing.hpp"
#include "woven_fixtures.hpp"
#include "woven/synthesis.hpp"
#include "woven/weave.hpp"

using namespace skein;
using namespace skein::woven;
using namespace skein::testing;

namespace {

/// The bundled exemplar set's weaves at 10 x 10 crossings (what the exemplars' relaxed yarn keeps).
std::vector<Weave> exemplar_weaves() {
  std::vector<Weave> out;
  for (const char* n : {"plain-weave", "twill-3-2", "twill-4-1", "satin-5-2", "basket-2x2"}) out.push_back(tiled(bundled_weave(n), 10, 10));
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

TEST(WovenSynthesis, EveryCrossingHasTheRightYarnOnTopAndTheMostMatchingNeighbours) {
  const auto exemplars = exemplar_weaves();
  for (const Weave& target : {tiled(bundled_weave("twill-2-1"), 30, 24), tiled(bundled_weave("satin-5-3"), 25, 25), random_weave(20, 20, 7)}) {
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
  const Weave target = tiled(bundled_weave("twill-4-1"), 20, 20);
  SynthesisOptions options;
  options.randomize = false;
  const auto s = score(target, exemplars, synthesize(target, exemplars, options));
  EXPECT_EQ(s.consistent, s.crossings);
  EXPECT_GT(s.continuity, 0.8 * 2 * 20 * 19);
}

TEST(WovenSynthesis, EachColumnsDynamicProgramFindsTheMostContinuityABruteForceFinds) {
  // One warp column (no horizontal term): Eq. 1's optimum against every assignment of the candidate blocks.
  const auto exemplars = std::vector<Weave>{tiled(bundled_weave("twill-3-2"), 6, 6), tiled(bundled_weave("satin-5-2"), 6, 6)};
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
  const Weave target = tiled(bundled_weave("twill-3-2"), 60, 60);
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
  const auto message = skein::testing::error_of([&] { synthesize(tiled(bundled_weave("plain-weave"), 4, 4), {all_weft}); });
  EXPECT_NE(message.find("no exemplar has a crossing with the warp on top"), std::string::npos) << message;
}
