// skein smock: smocking patterns gathered in the plane and as cloth, by command and by job
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"

using namespace skein::testing::cli;
using skein::testing::ScratchDir;

TEST(Cli, SmockGathersAPatternAndWritesItsEmbeddingPicturesAndReport) {
  ScratchDir dir;
  const std::string pattern = std::string(SKEIN_PATTERNS_DIR) + "/smocking/zigzag.smock";
  const auto r = run_skein("smock " + pattern + " -o " + (dir / "z.json").string() + " --obj " + (dir / "z.obj").string() + " --png " +
                           (dir / "z.png").string() + " --chart-png " + (dir / "c.png").string() + " --snapshots 0.6 --report " + (dir / "r.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto report = nlohmann::json::parse(slurp(dir / "r.json"));
  EXPECT_EQ(report["stopped_by"], "reached");
  EXPECT_EQ(report["style"], "italian");
  EXPECT_LE(report["shrinkage"].get<double>(), 0.3 * 1.05);
  EXPECT_LE(report["largest_fabric_stretch"].get<double>(), 1.001e-3);
  const auto out = nlohmann::json::parse(slurp(dir / "z.json"));
  EXPECT_EQ(out["positions"].size(), 21u * 11u);
  EXPECT_EQ(out["stitches_lifted"].size(), 100u);
  EXPECT_EQ(out["snapshots"].size(), 1u);
  EXPECT_TRUE(std::filesystem::file_size(dir / "z.png") > 1000 && std::filesystem::file_size(dir / "c.png") > 1000);
  std::istringstream obj(slurp(dir / "z.obj"));
  int lines = 0;
  for (std::string line; std::getline(obj, line);) lines += line.rfind("l ", 0) == 0;
  EXPECT_EQ(lines, 2 * 100);  // each stitch down or up to its midpoint and on
}

TEST(Cli, SmockRefusesBadPatternsAndSaysWhenTheThreadsStall) {
  ScratchDir dir;
  const auto bad = dir.write("bad.smock", "format smocking\ngrid 4 4\npath 0,0 5,0\n");
  expect_refused("smock " + bad.string(), dir / "out.json", "bad.smock: line 3: point 2 (5,0) is off the grid of 4 x 4 points");
  const auto vertical = dir.write("v.smock", "format smocking\ngrid 3 4\npath 1,0 1,1 1,2 1,3\n");
  const auto stalled = run_skein("smock " + vertical.string() + " --report -");
  EXPECT_EQ(stalled.status, 1) << stalled.output;
  EXPECT_NE(stalled.output.find("\"stopped_by\": \"stalled\""), std::string::npos) << stalled.output;
  EXPECT_EQ(run_skein("smock " + vertical.string() + " --pull 1,x").status, 2);
  EXPECT_EQ(run_skein("smock " + vertical.string() + " --pull along").status, 0);
}

TEST(Cli, SmockClothWritesTheFabricIn3dCertifiedAndRefusesBadSubdivisions) {
  ScratchDir dir;
  const auto small = dir.write("z.smock", "format smocking\ngrid 9 5\nwalk front 0,1 1,-1 1,1 x8\nwalk front 0,3 1,-1 1,1 x8\ngamma 0.4\n");
  const auto r = run_skein("smock " + small.string() + " --cloth " + (dir / "c.obj").string() + " --cloth-png " + (dir / "c.png").string() + " --report " +
                           (dir / "r.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto cloth = nlohmann::json::parse(slurp(dir / "r.json")).at("cloth");
  EXPECT_EQ(cloth.at("intersections"), 0);
  EXPECT_EQ(cloth.at("points"), 17 * 9);
  EXPECT_GT(cloth.at("smallest_distance_mm").get<double>(), 0);
  std::istringstream obj(slurp(dir / "c.obj"));
  int faces = 0;
  for (std::string line; std::getline(obj, line);) faces += line.rfind("f ", 0) == 0;
  EXPECT_EQ(faces, 16 * 8 * 2);
  EXPECT_GT(std::filesystem::file_size(dir / "c.png"), 1000u);
  expect_refused("smock " + small.string() + " --subdivisions 3 --cloth " + (dir / "odd.obj").string(), dir / "odd.obj",
                 "subdivisions: must be even, 2 to 32");
  // As glTF: the same triangles, smooth normals, a two-sided fabric material; other formats refused before any work.
  ASSERT_EQ(run_skein("smock " + small.string() + " --cloth " + (dir / "c.gltf").string()).status, 0);
  const auto gltf = nlohmann::json::parse(slurp(dir / "c.gltf"));
  const auto& primitive = gltf.at("meshes").at(0).at("primitives").at(0);
  EXPECT_EQ(gltf.at("accessors").at(primitive.at("attributes").at("POSITION").get<int>()).at("count"), 17 * 9);
  EXPECT_EQ(gltf.at("accessors").at(primitive.at("attributes").at("NORMAL").get<int>()).at("count"), 17 * 9);
  EXPECT_EQ(gltf.at("accessors").at(primitive.at("indices").get<int>()).at("count"), 16 * 8 * 2 * 3);
  EXPECT_EQ(gltf.at("materials").at(primitive.at("material").get<int>()).at("doubleSided"), true);
  expect_refused("smock " + small.string() + " --cloth " + (dir / "c.stl").string(), dir / "c.stl", "--cloth: writes .obj, .glb or .gltf, found '.stl'");
  // A path through a plain file names the file; a subdivision count out of range names the option and the count.
  const auto through = run_skein("smock " + small.string() + " --cloth " + (small / "c.glb").string());
  EXPECT_EQ(through.status, 2);
  EXPECT_NE(through.output.find(small.string() + " is a file, not a folder"), std::string::npos) << through.output;
  expect_refused("smock " + small.string() + " --subdivisions 40 --cloth " + (dir / "big.obj").string(), dir / "big.obj",
                 "--subdivisions: must be even, 2 to 32 (stitch midpoints must be fine vertices), found 40");
  expect_refused("smock " + small.string() + " --cloth-png " + (dir / "c.jpg").string(), dir / "c.jpg", "--cloth-png: writes a PNG picture: name it .png, found '.jpg'");
}

TEST(Cli, ASmockingJobGathersItsPatternIntoTheOutputFolder) {
  ScratchDir dir;
  const std::string pattern = std::string(SKEIN_PATTERNS_DIR) + "/smocking/canadian-lattice.smock";
  const auto job = dir.write("s.json", "{\"smocking\": {\"pattern\": \"" + pattern + "\", \"pull\": \"along\", \"snapshots\": [0.5]}, \"output\": \"out\"}");
  const auto r = run_skein("run " + job.string());
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"embedding.json", "threads.obj", "smocking.png", "shrinkage.png", "job.log"}) EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << f;
  const auto report = nlohmann::json::parse(slurp(dir / "out" / "report.json"));
  EXPECT_EQ(report["status"], "done");
  EXPECT_EQ(report["smocking"]["style"], "canadian");
  EXPECT_EQ(report["smocking"]["pull"], "along");
  const auto bad = dir.write("b.json", "{\"smocking\": {\"pattern\": \"" + pattern + "\", \"pull\": [1]}, \"mesh\": \"x.obj\"}");
  const auto refused = run_skein("run " + bad.string());
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.output.find("key 'mesh': is not a key here (known: name, output, pictures, smocking)"), std::string::npos) << refused.output;
  const auto bad_pull = dir.write("p.json", "{\"smocking\": {\"pattern\": \"" + pattern + "\", \"pull\": [1]}}");
  EXPECT_NE(run_skein("run " + bad_pull.string()).output.find("key 'smocking.pull': expected [X, Y] (the pulling direction) or \"along\", found [1]"),
            std::string::npos);
  // With "cloth": the 3-D fabric too, as glTF and a picture.
  const auto small = dir.write("z.smock", "format smocking\ngrid 9 5\nwalk front 0,1 1,-1 1,1 x8\ngamma 0.4\n");
  const auto cloth_job = dir.write("c.json", "{\"smocking\": {\"pattern\": \"z.smock\", \"cloth\": true}, \"output\": \"cloth\"}");
  const auto c = run_skein("run " + cloth_job.string());
  ASSERT_EQ(c.status, 0) << c.output;
  for (const char* f : {"cloth.glb", "cloth.png"}) EXPECT_TRUE(std::filesystem::exists(dir / "cloth" / f)) << f;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir / "cloth" / "report.json"))["smocking"]["cloth"]["intersections"], 0);
  const auto odd = dir.write("o.json", "{\"smocking\": {\"pattern\": \"z.smock\", \"cloth\": true, \"cloth_subdivisions\": 3}}");
  EXPECT_NE(run_skein("run " + odd.string()).output.find("key 'smocking.cloth_subdivisions': must be even"), std::string::npos);
  // cloth_frames caps the frames, as --frames does; it needs the cloth.
  const auto few = dir.write("f.json", "{\"smocking\": {\"pattern\": \"z.smock\", \"cloth\": true, \"cloth_frames\": 3}, \"output\": \"few\"}");
  ASSERT_EQ(run_skein("run " + few.string()).status, 0);
  EXPECT_EQ(nlohmann::json::parse(slurp(dir / "few" / "report.json"))["smocking"]["cloth"]["frames"], 3);
  const auto flat = dir.write("n.json", "{\"smocking\": {\"pattern\": \"z.smock\", \"cloth_frames\": 3}}");
  EXPECT_NE(run_skein("run " + flat.string()).output.find("key 'smocking.cloth_frames': needs \"cloth\": true"), std::string::npos);
}

TEST(Cli, SmockReadsADrawingAndWritesWhatItReadAsText) {
  ScratchDir dir;
  const auto drawing = dir.write("d.svg", "<svg xmlns=\"http://www.w3.org/2000/svg\">\n<g transform=\"translate(5,5)\">\n"
                                          "<line x1=\"0\" y1=\"20\" x2=\"20\" y2=\"0\"/>\n<line x1=\"20\" y1=\"0\" x2=\"40\" y2=\"20\" stroke-dasharray=\"3 2\"/>\n"
                                          "<line x1=\"40\" y1=\"20\" x2=\"60\" y2=\"0\"/>\n</g>\n</svg>\n");
  const auto r = run_skein("smock " + drawing.string() + " --write-smock " + (dir / "d.smock").string() + " --report -");
  ASSERT_EQ(r.status, 0) << r.output;
  // Three grid squares across and one down, a square of fabric around.
  EXPECT_NE(slurp(dir / "d.smock").find("grid 6 4\nspacing 10\ngamma 0.3\npath front 1,2 2,1 3,2 4,1\n"), std::string::npos) << slurp(dir / "d.smock");
  const auto own_style = run_skein("smock " + (dir / "d.smock").string() + " --style canadian");
  EXPECT_EQ(own_style.status, 2) << own_style.output;
  EXPECT_NE(own_style.output.find("--style: is for an .svg drawing"), std::string::npos) << own_style.output;
  const auto knots = run_skein("smock " + drawing.string() + " --style canadian");  // its dashed line is a back stitch
  EXPECT_NE(knots.output.find("d.svg: line 4: Canadian smocking is stitched on the front only"), std::string::npos) << knots.output;
}
