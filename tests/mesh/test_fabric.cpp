#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "common/error.hpp"
#include "stitchmesh/fabric.hpp"
#include "testing.hpp"

using namespace skein;
using skein::testing::error_of;

TEST(Fabric, WeightClassesRunThinToThickWithTheirGauge) {
  // Thicker yarn, fewer stitches in 10 cm and larger needles, class after class (Craft Yarn Council).
  const auto& weights = mesh::yarn_weights();
  ASSERT_EQ(weights.size(), 8u);
  std::set<std::string> names;
  for (size_t i = 0; i < weights.size(); ++i) {
    EXPECT_EQ(weights[i].category, static_cast<int>(i));
    EXPECT_TRUE(names.insert(weights[i].name).second);
    if (i == 0) continue;
    EXPECT_GT(weights[i].diameter(), weights[i - 1].diameter()) << weights[i].name;
    EXPECT_LT(weights[i].stitches_per_10cm, weights[i - 1].stitches_per_10cm) << weights[i].name;
    EXPECT_GT(weights[i].needle_mm, weights[i - 1].needle_mm) << weights[i].name;
  }
  // Worsted: 16 to 20 stitches in 10 cm on 4.5 to 5.5 mm needles, about 10 wraps per inch.
  const auto& worsted = mesh::find_yarn_weight("worsted");
  EXPECT_DOUBLE_EQ(worsted.stitches_per_10cm, 18);
  EXPECT_NEAR(worsted.diameter(), 2.54, 1e-12);
}

TEST(Fabric, NamesAliasesAndNumbersFindTheSameClass) {
  EXPECT_EQ(&mesh::find_yarn_weight("Medium"), &mesh::find_yarn_weight("worsted"));
  EXPECT_EQ(&mesh::find_yarn_weight("4"), &mesh::find_yarn_weight("aran"));
  EXPECT_EQ(&mesh::find_yarn_weight("super bulky"), &mesh::find_yarn_weight("super-bulky"));
  EXPECT_EQ(&mesh::find_yarn_weight("sock"), &mesh::find_yarn_weight("fingering"));
  EXPECT_EQ(error_of([] { mesh::find_yarn_weight("wool"); }),
            "--yarn 'wool': is not a yarn weight; one of lace, fingering, sport, dk, worsted, bulky, super-bulky, jumbo (or the Craft Yarn "
            "Council's number 0 to 7)");
}

TEST(Fabric, GaugeGivesTheStitchSizeAndMundensLoopLength) {
  const auto g = mesh::parse_gauge("20x25");
  EXPECT_DOUBLE_EQ(g.stitch_size().width, 5);
  EXPECT_DOUBLE_EQ(g.stitch_size().height, 4);
  EXPECT_DOUBLE_EQ(g.loop_length(), mesh::kMundenKw * 5);  // Kw = wales per length x loop length
  const auto s = mesh::parse_gauge("20");                  // rows by the loop shape factor Kc/Kw
  EXPECT_DOUBLE_EQ(s.rows, 26);
  const auto back = mesh::gauge_of(g.stitch_size());
  EXPECT_DOUBLE_EQ(back.stitches, 20);
  EXPECT_DOUBLE_EQ(back.rows, 25);
  const auto standard = mesh::standard_gauge(mesh::find_yarn_weight("dk"));
  EXPECT_DOUBLE_EQ(standard.stitches, 22.5);
  EXPECT_DOUBLE_EQ(standard.rows, 22.5 * 1.3);
}

TEST(Fabric, BadGaugesAreRefusedWithTheOption) {
  const std::string format = "expected STITCHES or STITCHESxROWS in 10 cm of stockinette (e.g. 18x24)";
  for (const std::string text : {"", "x", "18x", "18x24x3", "18 rows", "eighteen", "18,24"})
    EXPECT_EQ(error_of([&] { mesh::parse_gauge(text); }), "--gauge '" + text + "': " + format) << text;
  EXPECT_EQ(error_of([] { mesh::parse_gauge("-4x20"); }), "--gauge '-4x20': stitches in 10 cm must be a number in (0, 1000], got -4.000000");
  EXPECT_EQ(error_of([] { mesh::parse_gauge("18x0"); }), "--gauge '18x0': rows in 10 cm must be a number in (0, 1000], got 0.000000");
  EXPECT_NE(error_of([] { mesh::parse_gauge("1e9"); }).find("--gauge '1e9': stitches in 10 cm must be a number in (0, 1000]"), std::string::npos);
  EXPECT_EQ(error_of([] { mesh::parse_gauge("nan"); }), "--gauge 'nan': " + format);
  EXPECT_EQ(mesh::parse_gauge("1e1x2.5e1").rows, 25);
}

TEST(Fabric, ANeedleGivesTheGaugeOfItsWrap) {
  // The middle of a weight's needle range gives its standard gauge; a larger needle, fewer stitches.
  for (const auto& w : mesh::yarn_weights()) {
    const auto middle = mesh::needle_gauge(w, w.needle_mm);
    EXPECT_NEAR(middle.stitches, w.stitches_per_10cm, 1e-9) << w.name;
    EXPECT_NEAR(middle.rows, mesh::kLoopShapeFactor * w.stitches_per_10cm, 1e-9) << w.name;
    EXPECT_GT(mesh::needle_gauge(w, w.needle_mm * 0.9).stitches, middle.stitches) << w.name;
    EXPECT_TRUE(mesh::needle_in_range(w, w.needle_mm)) << w.name;
  }
  // The loop length grows with the wrap's centreline, pi (D + d): worsted (d 2.54 mm) on 7.54 - 2.54 x 2 mm.
  const auto& worsted = mesh::find_yarn_weight("worsted");
  const double d = worsted.diameter();
  EXPECT_NEAR(mesh::needle_gauge(worsted, 2 * (5 + d) - d).loop_length(), 2 * mesh::standard_gauge(worsted).loop_length(), 1e-9);
  // At the ends of the Craft Yarn Council's needle ranges, the ends of its gauge ranges within 7 %, but for
  // super-bulky's largest needle (12.75 mm: 7.8 stitches, the CYC's 7); jumbo's 12.75 mm gives at most its 6.
  for (const auto& w : mesh::yarn_weights()) {
    const double at_smallest = mesh::needle_gauge(w, w.needle_min_mm).stitches;
    if (w.name == "jumbo") {
      EXPECT_LE(at_smallest, w.stitches_max);
      continue;
    }
    EXPECT_NEAR(at_smallest / w.stitches_max, 1, 0.07) << w.name;
    EXPECT_NEAR(mesh::needle_gauge(w, w.needle_max_mm).stitches / w.stitches_min, 1, w.name == "super-bulky" ? 0.12 : 0.07) << w.name;
  }
  EXPECT_FALSE(mesh::needle_in_range(worsted, 8));
  EXPECT_TRUE(mesh::needle_in_range(mesh::find_yarn_weight("jumbo"), 25));
  EXPECT_EQ(error_of([&] { mesh::needle_gauge(worsted, 0); }), "--needle 0: a needle's diameter must be a number of millimetres in (0, 50]");
  EXPECT_EQ(error_of([&] { mesh::needle_gauge(worsted, 80, "needle"); }), "needle 80: a needle's diameter must be a number of millimetres in (0, 50]");
}
