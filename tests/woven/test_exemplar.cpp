// Exemplars from relaxed woven yarn (Zhao 2012 §4, §6): the weave kept, fibres along the yarn, seeds, and OpenVDB files.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "testing.hpp"
#include "woven_fixtures.hpp"
#include "woven/exemplar.hpp"

using namespace skein;
using namespace skein::woven;
using namespace skein::testing;

TEST(WovenExemplar, RelaxedYarnKeepsItsWeaveAndItsFibresRunAlongTheYarn) {
  ExemplarReport report;
  const auto ex = make_exemplar(weave_pattern("twill-3-2"), small(), &report);
  EXPECT_EQ(report.pull_through_events, 0);
  EXPECT_EQ(ex.weave, tiled(from_pattern(weave_pattern("twill-3-2")), 6, 6));  // checked inside too (§6.2)
  EXPECT_GT(report.filled, 0.15);
  EXPECT_LT(report.filled, 0.7);
  // Warp voxels' fibres run mostly along y, weft voxels' along x (plies and fibres twist a little off it).
  double warp_y = 0, weft_x = 0;
  long warps = 0, wefts = 0;
  const auto& g = ex.grid;
  for (size_t k = 0; k < g.size(); ++k) {
    if (g.yarn[k] < 0) continue;
    EXPECT_GT(g.density[k], 0.0f);
    EXPECT_LE(g.density[k], 1.0f);
    EXPECT_NEAR(g.orientation[k].norm(), 1.0f, 1e-4f);
    if (ex.is_warp(g.yarn[k])) warp_y += std::abs(g.orientation[k].y()), ++warps;
    else weft_x += std::abs(g.orientation[k].x()), ++wefts;
  }
  ASSERT_GT(warps, 0);
  ASSERT_GT(wefts, 0);
  EXPECT_GT(warp_y / warps, 0.8);
  EXPECT_GT(weft_x / wefts, 0.8);
}

TEST(WovenExemplar, TheSameSeedMakesTheSameExemplarAndAnotherSeedAnotherOne) {
  const auto a = make_exemplar(weave_pattern("plain-weave"), small()), b = make_exemplar(weave_pattern("plain-weave"), small());
  auto o = small();
  o.seed = 2;
  const auto c = make_exemplar(weave_pattern("plain-weave"), o);
  EXPECT_EQ(a.grid.density, b.grid.density);
  EXPECT_NE(a.grid.density, c.grid.density);
}

TEST(WovenExemplar, OpenVdbFilesRoundTripAndBrokenOnesAreNamed) {
  skein::testing::ScratchDir dir;
  const auto& ex = small_set()[1];
  write_exemplar(ex, dir / "twill.vdb");
  const auto back = read_exemplar(dir / "twill.vdb");
  EXPECT_EQ(back.name, ex.name);
  EXPECT_EQ(back.weave, ex.weave);
  EXPECT_EQ(back.block_x, ex.block_x);
  EXPECT_EQ(back.grid.nz, ex.grid.nz);
  EXPECT_NEAR(back.grid.origin.z(), ex.grid.origin.z(), 1e-12);
  EXPECT_EQ(back.grid.yarn, ex.grid.yarn);
  EXPECT_EQ(back.grid.density, ex.grid.density);
  for (size_t k = 0; k < ex.grid.size(); ++k) ASSERT_EQ(back.grid.orientation[k], ex.grid.orientation[k]);
  EXPECT_FALSE(std::filesystem::exists(dir / "twill.vdb.part"));

  const auto text = dir.write("not.vdb", "format woven\n1 0\n");
  EXPECT_NE(skein::testing::error_of([&] { read_exemplar(text); }).find("not.vdb: is not a readable OpenVDB file"), std::string::npos);
  std::ifstream in(dir / "twill.vdb", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto cut = dir.write("cut.vdb", bytes.substr(0, bytes.size() / 2));
  EXPECT_NE(skein::testing::error_of([&] { read_exemplar(cut); }).find("cut.vdb"), std::string::npos);
  EXPECT_NE(skein::testing::error_of([&] { read_exemplar(dir / "missing.vdb"); }).find("missing.vdb"), std::string::npos);
  // A length in the metadata made huge: OpenVDB would allocate it; in its child process that is an error.
  std::string huge = bytes;
  const auto at = huge.find("skein_exemplar");
  ASSERT_NE(at, std::string::npos);
  huge[at + 14 + 4 + 6 + 3] = '\x7f';  // past the name, the type name's length and "string": the value's length, top byte
  const auto blown = dir.write("huge.vdb", huge);
  ::setenv("SKEIN_READER_GB", "0.5", 1);
  const auto message = skein::testing::error_of([&] { read_exemplar(blown); });
  ::unsetenv("SKEIN_READER_GB");
  EXPECT_NE(message.find("huge.vdb: is not a readable OpenVDB file"), std::string::npos) << message;
  std::filesystem::create_directories(dir / "empty");
  EXPECT_NE(skein::testing::error_of([&] { read_exemplars(dir / "empty"); }).find("holds no .vdb exemplars"), std::string::npos);
  EXPECT_NE(skein::testing::error_of([&] { write_exemplar(ex, dir / "no-folder" / "x.vdb"); }).find("could not be written"), std::string::npos);
}
