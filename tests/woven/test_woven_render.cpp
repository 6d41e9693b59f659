// The woven renderer: the same picture for one seed, and the cloth in it.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "testing.hpp"
#include "woven_fixtures.hpp"
#include "woven/woven_render.hpp"

using namespace skein;
using namespace skein::woven;
using namespace skein::testing;

TEST(WovenRender, ARenderIsTheSameForOneSeedAndShowsTheCloth) {
  const auto& set = small_set();
  std::vector<Weave> weaves;
  for (const auto& e : set) weaves.push_back(e.weave);
  const Weave target = tiled(from_pattern(weave_pattern("twill-2-1")), 6, 6);
  const auto v = make_volume(set, target, synthesize(target, weaves), 15);
  WovenRenderOptions o;
  o.width = o.height = 48;
  o.samples = 2;
  const auto a = render_woven(v, o), b = render_woven(v, o);
  EXPECT_EQ(a.rgb, b.rgb);
  // The cloth fills the middle: most of its pixels are brighter than the backdrop.
  long bright = 0, total = 0;
  for (int y = 16; y < 32; ++y)
    for (int x = 16; x < 32; ++x, ++total) bright += a.rgb[3 * (y * 48 + x)] + a.rgb[3 * (y * 48 + x) + 1] + a.rgb[3 * (y * 48 + x) + 2] > 3 * 70;
  EXPECT_GT(bright, total / 3);
  o.samples = 0;
  EXPECT_NE(skein::testing::error_of([&] { render_woven(v, o); }).find("samples"), std::string::npos);
}
