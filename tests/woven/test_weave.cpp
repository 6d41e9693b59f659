// Weave patterns: skein's woven text turned into Zhao 2012's warp-up matrix, broken text named, pictures
// posterized into weaves, and the crossing order of woven yarn.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "common/error.hpp"
#include "testing.hpp"
#include "woven_fixtures.hpp"
#include "woven/weave.hpp"

using namespace skein;
using namespace skein::woven;
using namespace skein::testing;

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
  const Weave plain = bundled_weave("plain-weave"), twill = bundled_weave("twill-4-1");
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

// A posterized picture's pixels get their colours' indices in the order the colours first appear, top row first.
TEST(Weave, APicturesColoursAreNumberedInTheOrderTheyFirstAppear) {
  render::Image image(3, 2);
  const std::array<std::array<std::uint8_t, 3>, 6> pixels{{{9, 9, 9}, {200, 0, 0}, {9, 9, 9}, {0, 0, 255}, {200, 0, 0}, {0, 0, 255}}};
  for (size_t k = 0; k < pixels.size(); ++k)
    for (int c = 0; c < 3; ++c) image.rgb[3 * k + c] = pixels[k][c];
  int colours = 0;
  EXPECT_EQ(picture_labels(image, colours), (std::vector<int>{0, 1, 0, 2, 1, 2}));
  EXPECT_EQ(colours, 3);
}
