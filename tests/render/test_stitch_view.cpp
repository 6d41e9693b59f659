// Stitch meshes as pictures: stitch types in their colours, neighbouring rows apart.
#include <gtest/gtest.h>

#include <set>

#include "garments.hpp"
#include "render/stitch_view.hpp"
#include "stitchmesh/edits.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/tessellation.hpp"
#include "stitch_fixtures.hpp"
#include "testing.hpp"

using namespace skein;

namespace {
double covered(const render::Image& img) {
  size_t n = 0;
  for (size_t i = 0; i < img.rgb.size(); i += 3) n += !(img.rgb[i] == 255 && img.rgb[i + 1] == 255 && img.rgb[i + 2] == 255);
  return static_cast<double>(n) / (img.width * img.height);
}
}  // namespace

TEST(Render, StitchTypesShowTheirColours) {
  const auto m = models::tube();
  const auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  auto s = mesh::tessellate(m, l, mesh::initial_values(m, l, {}));
  s = mesh::fill(s, skein::testing::all_faces(s), mesh::parse_fill("rib"));
  render::View view;
  view.panel = 300;
  const auto img = render::draw(render::stitch_polygons(s, render::ColorBy::StitchType), view);
  EXPECT_EQ(img.width, 600);
  EXPECT_GT(covered(img), 0.15);
  // Knit (cream) and purl (plum) both appear: red > blue for knit, blue > green for purl.
  bool knit = false, purl = false;
  for (size_t i = 0; i < img.rgb.size(); i += 3) {
    const int r = img.rgb[i], g = img.rgb[i + 1], b = img.rgb[i + 2];
    knit |= r > 150 && r > b + 20 && g > b;
    purl |= b > g + 25 && r > g;
  }
  EXPECT_TRUE(knit);
  EXPECT_TRUE(purl);
}

TEST(Render, RowColoursDifferBetweenNeighbours) {
  for (int r = 0; r < 200; ++r) EXPECT_GT((render::row_color(r) - render::row_color(r + 1)).norm(), 0.1f) << r;
}
