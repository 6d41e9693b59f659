// PNG files written and read back, and refused where they cannot be.
#include <gtest/gtest.h>

#include <cstdint>

#include "common/error.hpp"
#include "render/raster.hpp"
#include "testing.hpp"

using namespace skein;

TEST(Render, PngRoundTripAndErrors) {
  skein::testing::ScratchDir dir;
  render::Image img(7, 5);
  for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = static_cast<std::uint8_t>(i * 13);
  render::write_png(img, dir / "a.png");
  const auto back = render::read_png(dir / "a.png");
  EXPECT_EQ(back.width, 7);
  EXPECT_EQ(back.rgb, img.rgb);
  EXPECT_THROW(render::write_png(img, dir / "no" / "a.png"), Error);
  EXPECT_THROW(render::read_png(dir.write("bad.png", "not a png")), Error);
}
