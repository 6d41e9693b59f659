#include <gtest/gtest.h>

#include "common/error.hpp"
#include "stitchmesh/stitch_model.hpp"
#include "stitchmesh/stitch_types.hpp"
#include "testing.hpp"

#include <fstream>
#include <sstream>

using namespace skein;
using skein::testing::error_of;

namespace {
const std::string kKnit = "stitch k\nshape 1 1\npiece\n  L\n  0.2 0.3 -1\n  T0a\npiece\n  T0b\n  0.8 0.3 -1\n  R\npiece\n  B0a\n  0.5 0.6 -1\n  B0b\n";
std::string parse_error(const std::string& text) {
  return error_of([&] { mesh::parse_stitch_model(text, "bad.stitch"); });
}
}  // namespace

TEST(StitchModel, ParsesAndPlacesCrossingsByConvention) {
  const auto m = mesh::parse_stitch_model("# a note\n" + kKnit, "k.stitch");
  EXPECT_EQ(m.name, "k");
  EXPECT_EQ(m.note, "a note");
  ASSERT_EQ(m.pieces.size(), 3u);
  EXPECT_EQ(m.pieces[0].points.front().crossing->side, mesh::Crossing::Side::Left);
  EXPECT_DOUBLE_EQ(m.pieces[0].points.front().uvh.y(), mesh::kWaleCrossing);
  EXPECT_DOUBLE_EQ(m.pieces[0].points.back().uvh.x(), mesh::kCourseSlots[0]);
  EXPECT_EQ(mesh::format_stitch_model(mesh::parse_stitch_model(mesh::format_stitch_model(m), "x")), mesh::format_stitch_model(m));
}

TEST(StitchModel, BadModelsNameTheFileAndRule) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"shape 1 1\npiece\n L\n R\n", "no 'stitch NAME'"},
      {"stitch k\npiece\n", "'shape' must come before"},
      {"stitch q\nshape 1 1\npiece\n L\n 0.5 0.5 0\n R\npiece\n B0a\n T0a\n", "no piece crosses bottom edge 0 twice (B0b)"},
      {"stitch q\nshape 1 1\npiece\n L\n T0a\npiece\n T0b\n B0a\npiece\n B0b\n 0.5 0.5 0\n", "no piece crosses the right wale edge"},
      {"stitch q\nshape 1 1\npiece\n L\n T0a\npiece\n L\n R\n", "crossing L is used twice"},
      {"stitch q\nshape 1 1\npiece\n L\n 1.5 0.5 0\n R\n", "outside the canonical polygon"},
      {"stitch q\nshape 1 1\npiece\n L\n 0.5 0.5 30\n R\n", "more than 8 yarn radii"},
      {"stitch q\nshape 1 1\npiece\n L\n 0.5 zero 0\n", "'zero' is not a number"},
      {"stitch q\nshape 1 1\npiece\n L\n T3a\n", "has 1 top edges"},
      {"stitch q\nshape 1 1\npiece\n L\n R\n B0a\n", "follows the piece's closing crossing"},
      {"stitch q\nshape 1 1\npiece\n Q7\n", "is not a crossing"},
      {"stitch q\nshape 1 1 no-wale\npiece\n L\n", "no wale edges"},
      {"stitch q\nshape 1\n", "expected 'shape BOTTOM TOP'"},
      {"stitch q\nshape 1 1\nfoo 1 2\n", "'foo' is not a keyword"},
      {"stitch q\nshape 1 1\n", "no yarn piece"},
      {"stitch q\nshape 1 1\npiece\n L\n", "fewer than 2 points"},
      {"stitch kp\nshape 1 1\npiece\n L\n T0a\npiece\n T0b\n R\npiece\n B0a\n B0b\n", "stitch type 'kp' needs shape 1 2"},
      // Found by fuzzing: a second shape line made the pieces read before it invalid, so the model did not read back.
      {"stitch q\nshape 1 1\npiece\n L\n T0a\nshape 1 1 no-wale\n", "a second 'shape' line"},
      {"stitch q\nstitch r\n", "a second 'stitch' line"},
  };
  for (const auto& [text, rule] : cases) {
    const std::string msg = parse_error(text);
    EXPECT_NE(msg.find("bad.stitch"), std::string::npos) << text << "\n→ " << msg;
    EXPECT_NE(msg.find(rule), std::string::npos) << text << "\n→ " << msg;
  }
}

TEST(StitchModel, BundledLibraryHasEveryStitchTypeAndMore) {
  const auto& lib = mesh::StitchLibrary::bundled();
  for (const auto& t : mesh::stitch_types()) {
    const auto* m = lib.find(t.name);
    ASSERT_NE(m, nullptr) << t.name;
    EXPECT_EQ(m->bottom, t.bottom) << t.name;
    EXPECT_EQ(m->top, t.top) << t.name;
  }
  for (int a = 1; a <= 3; ++a)
    for (int b = 1; b <= 3; ++b) EXPECT_NE(lib.find("cable" + std::to_string(a) + "x" + std::to_string(b)), nullptr);
  EXPECT_NE(lib.find("bind-off"), nullptr);
  EXPECT_THROW(lib.at("no-such-stitch"), Error);
}

TEST(StitchModel, LibraryFolderErrors) {
  skein::testing::ScratchDir dir;
  EXPECT_NE(error_of([&] { mesh::StitchLibrary::load(dir / "missing"); }).find("does not exist"), std::string::npos);
  EXPECT_NE(error_of([&] { mesh::StitchLibrary::load(dir.path()); }).find("holds no .stitch files"), std::string::npos);
  dir.write("knit.stitch", kKnit);
  EXPECT_NE(error_of([&] { mesh::StitchLibrary::load(dir.path()); }).find("must be called k.stitch"), std::string::npos);
}

// The committed library is what stitches/generate.cpp writes (run `build/bin/skein-stitches stitches` after changing it).
TEST(StitchModel, EveryFileReadsBackToItsOwnText) {
  for (const auto& [name, model] : mesh::StitchLibrary::bundled().models()) {
    std::ifstream in(mesh::StitchLibrary::bundled_folder() / (name + ".stitch"));
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(mesh::format_stitch_model(model), text.str()) << name;
  }
}
