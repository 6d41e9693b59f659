// skein stitch: a mesh and its labels in, a stitch mesh out; bad meshes refused with nothing written
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"

using namespace skein::testing::cli;
using skein::testing::ScratchDir;

TEST(Cli, StitchThenStatsJson) {
  ScratchDir dir;
  const auto out = dir / "tube.skein";
  const auto r = run_skein("stitch " + kModels + "/tube.obj --auto-label -o " + out.string() + " --png " + (dir / "rows.png").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "rows.png"));
  const auto stats = run_skein("stats " + out.string() + " --json");
  ASSERT_EQ(stats.status, 0) << stats.output;
  for (const char* key : {"\"faces\"", "\"vertices\"", "\"rows\"", "\"increases\"", "\"decreases\"", "\"stitch_types\"", "\"invalid_faces\"",
                          "\"valid\": true"})
    EXPECT_NE(stats.output.find(key), std::string::npos) << key << "\n" << stats.output;
}

TEST(Cli, StoredLabelsGiveTheSameStitchMesh) {
  ScratchDir dir;
  ASSERT_EQ(run_skein("stitch " + kModels + "/beanie.obj --auto-label -o " + (dir / "a.skein").string()).status, 0);
  ASSERT_EQ(run_skein("stitch " + kModels + "/beanie.obj --labels " + kModels + "/beanie.skein -o " + (dir / "b.skein").string()).status, 0);
  EXPECT_EQ(slurp(dir / "a.skein"), slurp(dir / "b.skein"));
  const auto wrong = run_skein("stitch " + kModels + "/tube.obj --labels " + kModels + "/beanie.skein -o " + (dir / "c.skein").string());
  EXPECT_EQ(wrong.status, 2);
  EXPECT_NE(wrong.output.find("made for a different mesh"), std::string::npos) << wrong.output;
}

TEST(Cli, BadInputFailsCleanlyWithoutOutput) {
  ScratchDir dir;
  const auto bad = dir.write("bad.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  const auto out = dir / "out.skein";
  const auto r = run_skein("stitch " + bad.string() + " --auto-label -o " + out.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("bad.obj"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("zero area"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  const auto unwritable = run_skein("stitch " + kModels + "/tube.obj --auto-label -o /nonexistent/x.skein");
  EXPECT_EQ(unwritable.status, 2);
  EXPECT_NE(unwritable.output.find("does not exist"), std::string::npos) << unwritable.output;
  EXPECT_NE(run_skein("stitch " + kModels + "/tube.obj -o " + out.string()).status, 0);  // neither --auto-label nor --labels
}

TEST(Cli, RepairMendsWhatCgalCanAndSaysWhatChanged) {
  // Issue 25, part 2: a strip of three quads with the third turned round, the first twice, a degenerate face
  // and a quad touching the strip at one corner only (a bow tie).
  ScratchDir dir;
  const auto mesh = dir.write("broken.obj", R"(v 0 0 0
v 10 0 0
v 20 0 0
v 30 0 0
v 0 10 0
v 10 10 0
v 20 10 0
v 30 10 0
v 40 10 0
v 40 20 0
v 30 20 0
f 1 2 6 5
f 7 6 2 3
f 7 8 4 3
f 1 2 6 5
f 1 2 2
f 8 9 10 11
)");
  const auto out = dir / "b.skein";
  const auto refused = run_skein("stitch " + mesh.string() + " --auto-label -o " + out.string());
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.output.find("broken.obj: face 4: uses vertex 1 twice (vertices 0 1 1); --repair mends duplicate points and faces"),
            std::string::npos)
      << refused.output;
  EXPECT_FALSE(std::filesystem::exists(out));
  const auto mended = run_skein("stitch " + mesh.string() + " --auto-label --repair --stitch-size 3 --stitch-height 2.5 -o " + out.string());
  ASSERT_EQ(mended.status, 0) << mended.output;
  EXPECT_NE(mended.output.find("repaired " + mesh.string() +
                               ": removed 1 degenerate face, removed 1 duplicate face, turned 1 face round to agree with its neighbours, "
                               "split 1 point where the surface met itself"),
            std::string::npos)
      << mended.output;
  EXPECT_NE(mended.output.find("tessellated: 48 stitch faces"), std::string::npos) << mended.output;  // 4 quads of 10 mm, 3 x 2.5 mm stitches
  // A project is not a mesh file to mend.
  const auto project = run_skein("label " + out.string() + " --repair -o " + (dir / "l.skein").string());
  EXPECT_EQ(project.status, 2);
  EXPECT_NE(project.output.find("b.skein: --repair mends a mesh file, not a project"), std::string::npos) << project.output;
}

TEST(Cli, TrianglesAreNamedAsTheCauseAndTheListIsShort) {
  ScratchDir dir;
  std::string obj;
  for (int y = 0; y <= 6; ++y)
    for (int x = 0; x <= 6; ++x) obj += "v " + std::to_string(10 * x) + " " + std::to_string(10 * y) + " 0\n";
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 6; ++x) {
      const int a = y * 7 + x + 1, b = a + 1, c = a + 8, d = a + 7;
      obj += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "\nf " + std::to_string(a) + " " + std::to_string(c) +
             " " + std::to_string(d) + "\n";
    }
  const auto mesh = dir.write("tris.obj", obj);
  for (const std::string command : {"label ", "stitch --auto-label "}) {
    const auto r = run_skein(command + mesh.string() + " -o " + (dir / "t.skein").string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("... and 62 more faces like these"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("72 of these 72 faces are not quads (72 triangles): rows are labeled across quads"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("face 10:"), std::string::npos) << r.output;  // ten listed, not 72
    EXPECT_NE(r.output.find("is traced with `skein stitch MESH --field` instead"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "t.skein"));
  }
  // The way the message points to: the rows traced on the triangles, 60 / 6 = 10 stitches a row, a row
  // every 5 mm from 0.25 mm to 58.5 mm: 11 rows.
  const auto out = dir / "t.skein";
  const auto traced = run_skein("stitch " + mesh.string() + " --field -o " + out.string() + " --stats " + (dir / "s.json").string());
  ASSERT_EQ(traced.status, 0) << traced.output;
  EXPECT_NE(traced.output.find("traced 11 rows on 12 isolines of the knitting distance (farthest 60."), std::string::npos) << traced.output;
  EXPECT_NE(traced.output.find("mm): 110 faces, 1 cast-on and 1 closed-off rows"), std::string::npos) << traced.output;
  const auto stats = nlohmann::json::parse(slurp(dir / "s.json"));
  EXPECT_EQ(stats["faces"], 110);
  EXPECT_EQ(stats["valid"], true);
  EXPECT_EQ(run_skein("yarn " + out.string() + " -o " + (dir / "y.bcc").string()).status, 0);
  // Refusals: exit 2, the file and the place named, nothing written.
  std::filesystem::remove(out);
  const auto inner = run_skein("stitch " + mesh.string() + " --field --start-edge 500 -o " + out.string());  // 120 edges
  EXPECT_EQ(inner.status, 2);
  EXPECT_NE(inner.output.find("tris.obj: edge 500: is not a border edge; knitting starts on a border or at a point (--start-point)"), std::string::npos)
      << inner.output;
  const auto tetrahedron = dir.write("closed.obj", "v 0 0 0\nv 60 0 0\nv 0 60 0\nv 0 0 60\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n");
  const auto closed = run_skein("stitch " + tetrahedron.string() + " --field -o " + out.string());
  EXPECT_EQ(closed.status, 2);
  EXPECT_NE(closed.output.find("closed.obj: a closed surface has no border to start from: give --start-point X,Y,Z"), std::string::npos)
      << closed.output;
  const auto no_field = run_skein("stitch " + mesh.string() + " --auto-label --start-point 1,2,3 -o " + out.string());
  EXPECT_NE(no_field.status, 0);
  EXPECT_NE(no_field.output.find("--start-point requires --field"), std::string::npos) << no_field.output;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Cli, AMeshThatWouldMakeTooManyStitchesIsRefusedBeforeTessellating) {
  ScratchDir dir;
  // The swatch (120 x 100 mm) read as if its millimetres were stitches of 10 µm: about 1.4e8 stitches.
  auto r = run_skein("stitch " + kModels + "/swatch.obj --auto-label --stitch-size 0.01 -o " + (dir / "s.skein").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("would make about 1.44e+08 stitches of 0.01 x 0.00833333 mm (its surface is 0.012 m²), more than the limit of 5e+06 "
                          "(--max-stitches): check the mesh's units"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "s.skein"));
  r = run_skein("stitch " + kModels + "/swatch.obj --auto-label --max-stitches 100 -o " + (dir / "s.skein").string());  // 333 at 6 x 5 mm
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("more than the limit of 100"), std::string::npos) << r.output;
  r = run_skein("stitch " + kModels + "/swatch.obj --auto-label --max-stitches 1000 -o " + (dir / "s.skein").string());
  EXPECT_EQ(r.status, 0) << r.output;
}
