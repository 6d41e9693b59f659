// Patterns as text: the three formats, their errors, tiled stitch meshes and woven yarn, and every bundled
// pattern.
#include <set>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "stitchmesh/edits.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/stitch_model.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "stitch_fixtures.hpp"
#include "testing.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::mesh;

namespace {
std::string error_in(const std::string& text) {
  return skein::testing::error_of([&] { parse_pattern(text, "test.knit"); });
}
std::vector<std::filesystem::path> bundled_patterns() {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(SKEIN_PATTERNS_DIR))
    if (e.path().extension() == ".knit" || e.path().extension() == ".weave") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}
}  // namespace

TEST(Pattern, KnitRowsAreReadBottomRowFirstWithNameAndSource) {
  const auto p = parse_pattern("# name: Seed\n# source: a test\nformat knit\n\np k   # the top row\nk p\n", "seed.knit");
  EXPECT_EQ(p.name, "Seed");
  EXPECT_EQ(p.note, "a test");
  ASSERT_EQ(p.rows.size(), 2u);
  EXPECT_EQ(p.rows[0], (std::vector<std::string>{"k", "p"}));  // the last line is the first row
  EXPECT_EQ(p.width(), 2);
  EXPECT_EQ(p.height(), 2);
}

TEST(Pattern, LeafTilesMapToStitchTypes) {
  const auto p = parse_pattern("format tiles\nK P F B YS 2U Y3Y\n", "t.knit");
  EXPECT_EQ(p.format, PatternFormat::Tiles);
  EXPECT_EQ(p.rows[0], (std::vector<std::string>{"k", "p", "sk", "s", "ys", "2u", "y3y"}));
  EXPECT_EQ(p.width(), 11);  // the lace tiles take 2, 2 and 3 loops
}

TEST(Pattern, WovenMatrixWithOrWithoutSpaces) {
  const auto p = parse_pattern("format woven\n1 0\n01\n", "w.weave");
  ASSERT_EQ(p.over.size(), 2u);
  EXPECT_EQ(p.over[0], (std::vector<char>{0, 1}));
  EXPECT_EQ(p.over[1], (std::vector<char>{1, 0}));
}

TEST(Pattern, ErrorsNameTheLineColumnAndRule) {
  EXPECT_NE(error_in("format knit\nk w p\n").find("line 2, column 3: unknown stitch 'w'; the stitch types are: k p"), std::string::npos)
      << error_in("format knit\nk w p\n");
  EXPECT_NE(error_in("").find("is empty"), std::string::npos);
  EXPECT_NE(error_in("# only a comment\n").find("is empty"), std::string::npos);
  EXPECT_NE(error_in("format knit\n").find("holds no rows"), std::string::npos);
  EXPECT_NE(error_in("k p\n").find("line 1, column 1: expected the format first"), std::string::npos);
  EXPECT_NE(error_in("format woven\n101\n10\n").find("line 2: has 3 columns but line 3 has 2"), std::string::npos) << error_in("format woven\n101\n10\n");
  EXPECT_NE(error_in("format woven\n1x\n").find("line 2, column 2: expected 0"), std::string::npos);
  EXPECT_NE(error_in("format tiles\nK Y2\n").find("line 2, column 3: unknown tile 'Y2'; the tiles are K P F B YS 2U Y3Y"), std::string::npos);
  EXPECT_NE(error_in("format tiles\nK k\n").find("unknown tile 'k'"), std::string::npos);
  // kp makes two loops from one: the row above must take two.
  EXPECT_NE(error_in("format knit\nk\nkp\n").find("line 2: this row takes 1 loop but the row below it (line 3) makes 2"), std::string::npos)
      << error_in("format knit\nk\nkp\n");
  EXPECT_NE(error_in("format knit\nk k\nkp\n").find("the first row takes 1 loop but the last row (line 2) makes 2"), std::string::npos)
      << error_in("format knit\nk k\nkp\n");
  const std::string missing = skein::testing::error_of([] { read_pattern("/no/such/pattern.knit"); });
  EXPECT_NE(missing.find("/no/such/pattern.knit: does not exist"), std::string::npos) << missing;
}

TEST(Pattern, TiledStitchMeshIsValidWithIncreasesAndDecreases) {
  const auto p = parse_pattern("format knit\nk k k k k\nkyk d123k k\n", "eyelet.knit");
  const auto mesh = pattern_stitch_mesh(p, 3, 2, {6, 5});
  const auto report = validate(mesh);
  EXPECT_TRUE(report.valid()) << report.summary();
  EXPECT_EQ(mesh.faces.size(), 3u * 2u * (5u + 3u));
  EXPECT_THROW(pattern_stitch_mesh(p, 0, 2), Error);
}

TEST(Pattern, WovenYarnCrossingsAreAYarnDiameterApart) {
  const auto p = parse_pattern("format woven\n10\n01\n", "plain.weave");
  const double r = 0.5;
  const auto yarn = woven_yarn(p, 2, 3, 4 * r, r);
  EXPECT_EQ(yarn.curves(), 3 * 2 + 2 * 2);  // weft rows + warp columns
  // Weft 0 and warp 0 cross at the origin; row 0 is the last line, "01": the warp lies over the weft there.
  EXPECT_NEAR(yarn.points[1].z(), -r, 1e-12);
  const int warp0 = yarn.curve_start[6];
  EXPECT_NEAR(yarn.points[warp0 + 1].z(), r, 1e-12);
  EXPECT_NEAR((yarn.points[1] - yarn.points[warp0 + 1]).norm(), 2 * r, 1e-12);
}

TEST(Pattern, EveryBundledPatternReadsTilesAndEmits) {
  const auto files = bundled_patterns();
  int knits = 0, wovens = 0;
  for (const auto& f : files) {
    SCOPED_TRACE(f.filename().string());
    const auto p = read_pattern(f);
    EXPECT_FALSE(p.note.empty()) << "every bundled pattern says where it comes from";
    if (p.format == PatternFormat::Woven) {
      ++wovens;
      EXPECT_GT(woven_yarn(p, 2, 2, 2.4, 0.6).points.size(), 0u);
      continue;
    }
    ++knits;
    const auto mesh = pattern_stitch_mesh(p, 2, 2);
    ASSERT_TRUE(validate(mesh).valid()) << validate(mesh).summary();
    EXPECT_GT(emit_yarn(mesh, StitchLibrary::bundled(), {}).points.size(), 0u);
  }
  EXPECT_GE(knits, 20);
  EXPECT_GE(wovens, 8);
}

TEST(Pattern, TilingOntoAStitchMeshPlacesTheRepeatFromTheOriginFace) {
  const auto piece = skein::testing::small_piece(models::tube(), "");
  const auto faces = skein::testing::all_faces(piece);
  const auto grid = stitch_grid(piece);
  // Origin: a stitch of the lowest row and leftmost column, where fill's rib starts too.
  int origin = -1;
  for (int f : faces)
    if (piece.faces[f].bottom == 1 && piece.faces[f].top() == 1 && grid.column[f] == 0 && (origin < 0 || grid.level[f] < grid.level[origin])) origin = f;
  ASSERT_GE(origin, 0);
  ASSERT_EQ(grid.level[origin], 0);
  const auto rib = parse_pattern("format knit\nk p\n", "rib.knit");
  const auto tiled = tile_pattern(piece, faces, rib, origin);
  EXPECT_TRUE(validate(tiled).valid());
  EXPECT_EQ(tiled, fill(piece, faces, parse_fill("rib")));  // the same as the built-in 1x1 rib fill
  // Seed from another origin: each stitch's type follows its row and column from there.
  const auto seed = parse_pattern("format knit\np k\nk p\n", "seed.knit");
  const int other = faces[faces.size() / 2];
  const auto seeded = tile_pattern(piece, faces, seed, other);
  for (int f : faces) {
    if (piece.faces[f].bottom != 1 || piece.faces[f].top() != 1) continue;
    const long parity = ((grid.level[f] - grid.level[other]) + (grid.column[f] - grid.column[other])) % 2;
    EXPECT_EQ(seeded.faces[f].type, parity == 0 ? "k" : "p") << "face " << f;
  }
}

TEST(Pattern, TilingInColourBringsThePatternsPaletteIntoTheMeshs) {
  const auto piece = skein::testing::small_piece(models::tube(), "");
  const auto faces = skein::testing::all_faces(piece);
  const auto grid = stitch_grid(piece);
  const int origin = faces.front();
  // Two-row stripes repaint the plain stitches: each takes its row's colour from the origin; the mesh gets the palette.
  const auto stripes = parse_pattern("format knit\ncolour MC: cream\ncolour CC: navy\nk\nk\ncolours\nCC\nMC\n", "s.knit");
  const auto striped = tile_pattern(piece, faces, stripes, origin);
  ASSERT_EQ(striped.palette, stripes.palette);
  for (int f : faces) {
    if (piece.faces[f].bottom == 1 && piece.faces[f].top() == 1) {
      EXPECT_EQ(striped.faces[f].colour, ((grid.level[f] - grid.level[origin]) % 2 + 2) % 2 == 0 ? 0 : 1) << "face " << f;
    }
  }
  // A second pattern's colours join by name: its CC is the mesh's CC, its new colour is added after it.
  const auto dots = parse_pattern("format knit\ncolour CC: red\ncolour D: gold\nk k\ncolours\nCC D\n", "d.knit");
  const auto dotted = tile_pattern(striped, faces, dots, origin);
  ASSERT_EQ(dotted.palette.size(), 3u);
  EXPECT_EQ(dotted.palette[1].description, "navy");  // the mesh's CC keeps its colour
  EXPECT_EQ(dotted.palette[2].name, "D");
  EXPECT_EQ(dotted.faces[origin].colour, 1);
  // A pattern that re-meshes gives its new faces their colours too; one without colours keeps the stitches' own.
  const auto cable = parse_pattern("format knit\ncolour A: red\ncolour B: white\nk k k k\ncable2x2+\ncolours\nA\nB\n", "c.knit");
  const auto cabled = tile_pattern(striped, faces, cable, origin);
  EXPECT_EQ(cabled.palette.size(), 4u);  // MC, CC, A, B
  EXPECT_GT(std::count_if(cabled.faces.begin(), cabled.faces.end(), [](const StitchFace& f) { return f.colour == 2; }), 0);
  const auto plain = tile_pattern(striped, faces, parse_pattern("format knit\np p\n", "p.knit"), origin);
  EXPECT_EQ(plain.palette, striped.palette);
  for (int f : faces) EXPECT_EQ(plain.faces[f].colour, striped.faces[f].colour);
}

TEST(Pattern, TilingRefusesWhatItCannotPlace) {
  const auto piece = skein::testing::small_piece(models::tube(), "");
  const auto faces = skein::testing::all_faces(piece);
  const auto rib = parse_pattern("format knit\nk p\n", "rib.knit");
  EXPECT_NE(skein::testing::error_of([&] { tile_pattern(piece, faces, rib, -1); }).find("face -1: does not exist"), std::string::npos);
  const auto weave = parse_pattern("format woven\n10\n01\n", "w.weave");
  EXPECT_THROW(tile_pattern(piece, faces, weave, 0), Error);
  // A re-meshing pattern needs whole repeats of plain stitches, from a plain stitch.
  const auto eyelet = parse_pattern("format knit\nk k k k k\nkyk d123k k\n", "eyelet.knit");
  EXPECT_NE(skein::testing::error_of([&] { tile_pattern(piece, {0, 1, 2}, eyelet, 0); }).find("none fits among the chosen stitches from face 0"),
            std::string::npos);
  const auto shaped = split_course_edge(piece, piece.faces[0].vertex(2), piece.faces[0].vertex(3));  // face 0 becomes an increase
  EXPECT_NE(skein::testing::error_of([&] { tile_pattern(shaped, faces, eyelet, 0); }).find("face 0: is not a plain stitch"), std::string::npos);
}

namespace {
/// A stitch mesh as what can be compared across face and vertex numbering: per face its type, row and corner
/// positions (rounded to 1e-6 mm), and the cable marks as position pairs.
struct Geometry {
  std::multiset<std::string> faces;
  std::multiset<std::string> cables;
  bool operator==(const Geometry&) const = default;
};
Geometry geometry(const StitchMesh& m) {
  const auto key = [&](int v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.6f %.6f %.6f)", m.vertices[v].x(), m.vertices[v].y(), m.vertices[v].z());
    return std::string(buf);
  };
  Geometry g;
  for (const auto& f : m.faces) {
    std::string s = f.type + " " + std::to_string(f.row) + " " + std::to_string(f.bottom);
    for (int v : f.vertices) s += key(v);
    g.faces.insert(s);
  }
  for (const auto& [e, mark] : m.cables) {
    const auto a = key(e.first), b = key(e.second);
    g.cables.insert(std::min(a, b) + std::max(a, b) + std::to_string(mark.shift) + std::to_string(mark.order));
  }
  return g;
}
}  // namespace

TEST(Pattern, TilingReMeshesWholeRepeatsAsThePatternsOwnMeshHasThem) {
  // Yuksel §5.3: tiled over a plain sheet, a pattern with increases, decreases, lace or cables gives the very
  // stitch mesh the pattern makes by itself (pattern_stitch_mesh), face for face, vertex for vertex.
  for (const char* text : {"format knit\nk k k k k\nkyk d123k k\n",                 // eyelet: 1 to 3, then 3 to 1
                           "format knit\nk k k k k\nd123k kyk k\n",                 // fewer loops inside the repeat first
                           "format tiles\nK K K K K\nYS Y3Y\n2U K K K\n",          // Leaf's lace tiles
                           "format knit\np k k k k p\np cable2x2- p\n"}) {           // a cable
    SCOPED_TRACE(text);
    const auto pattern = parse_pattern(text, "p.knit");
    auto row = parse_pattern("format knit\nk\n", "k.knit");
    row.rows[0].assign(pattern.width(), "k");
    const auto sheet = pattern_stitch_mesh(row, 2, 2 * pattern.height());
    TileReport report;
    const auto tiled = tile_pattern(sheet, skein::testing::all_faces(sheet), pattern, 0, &report);
    ASSERT_TRUE(validate(tiled).valid()) << validate(tiled).summary();
    EXPECT_EQ(report.repeats, 4);
    EXPECT_EQ(report.stitches, 4 * pattern.width() * pattern.height());
    EXPECT_EQ(geometry(tiled), geometry(pattern_stitch_mesh(pattern, 2, 2)));
    EXPECT_EQ(tiled.vertices.size(), pattern_stitch_mesh(pattern, 2, 2).vertices.size());  // no vertex left unused
  }
}

TEST(Pattern, TilingReMeshesOnlyWholeRepeatsOfChosenPlainStitches) {
  const auto eyelet = parse_pattern("format knit\nk k k k k\nkyk d123k k\n", "eyelet.knit");
  auto row = parse_pattern("format knit\nk\n", "k.knit");
  const auto sheet = pattern_stitch_mesh(row, 12, 5);  // 12 x 5 plain stitches: 2 x 2 whole repeats fit
  TileReport report;
  const auto tiled = tile_pattern(sheet, skein::testing::all_faces(sheet), eyelet, 0, &report);
  ASSERT_TRUE(validate(tiled).valid()) << validate(tiled).summary();
  EXPECT_EQ(report.repeats, 4);
  const auto stats = stitch_stats(tiled);
  EXPECT_EQ(stats.stitch_types.at("kyk"), 4);
  EXPECT_EQ(stats.stitch_types.at("d123k"), 4);
  EXPECT_EQ(stats.stitch_types.at("k"), 60 - 4 * 10 + 4 * 6);  // outside the repeats, and the repeats' own k
  // On a curved piece with ring rows the repeats go round and the yarn still joins up.
  const auto piece = skein::testing::small_piece(models::tube(), "");
  const auto on_tube = tile_pattern(piece, skein::testing::all_faces(piece), eyelet, 0, &report);
  ASSERT_TRUE(validate(on_tube).valid()) << validate(on_tube).summary();
  EXPECT_GT(report.repeats, 0);
  const auto yarn = emit_yarn(on_tube, StitchLibrary::bundled(), {});
  EXPECT_GT(yarn.points.size(), 0u);
}

TEST(Pattern, CablesBecomeCableMarksAboveTheirStitches) {
  const auto p = parse_pattern("format knit\np k k k k p\np cable2x2- p\n", "cable.knit");
  ASSERT_EQ(p.cables.size(), 1u);
  EXPECT_EQ(p.cables[0].row, 0);
  EXPECT_EQ(p.cables[0].first_loop, 1);
  EXPECT_EQ(p.cables[0].order, -1);
  EXPECT_EQ(p.rows[0], (std::vector<std::string>{"p", "k", "k", "k", "k", "p"}));
  const auto mesh = pattern_stitch_mesh(p, 2, 2);
  EXPECT_TRUE(validate(mesh).valid()) << validate(mesh).summary();
  EXPECT_EQ(mesh.cables.size(), 2u * 2u * 4u);  // two copies across, in rows 0 and 2 (row 3 is the top: nothing above it)
  for (const auto& [edge, mark] : mesh.cables) {
    EXPECT_EQ(mark.shift, 2);
    EXPECT_EQ(mark.order, -1);
  }
  mesh::EmitReport report;
  emit_yarn(mesh, StitchLibrary::bundled(), {}, &report);
  EXPECT_EQ(report.cables, 4);
  EXPECT_NE(error_in("format knit\ncable4x1\n").find("a cable is cableAxB"), std::string::npos);
  EXPECT_NE(error_in("format knit\ncable2x2*\n").find("a cable is cableAxB"), std::string::npos);
}

TEST(Pattern, AFileSavedWithAByteOrderMarkOrWindowsLineEndsReadsTheSame) {
  const auto plain = mesh::parse_pattern("format knit\nk p\np k\n", "rib.knit");
  for (const std::string text : {"\xEF\xBB\xBF" "format knit\nk p\np k\n", "format knit\r\nk p\r\np k\r\n"}) {
    const auto read = mesh::parse_pattern(text, "rib.knit");
    EXPECT_EQ(read.rows, plain.rows);
  }
}
