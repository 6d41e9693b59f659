// skein weave: exemplars, volumes, pictures and jobs; bad designs refused
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"

using namespace skein::testing::cli;
using skein::testing::ScratchDir;

TEST(Cli, WeaveExemplarsThenAVolumeItsPictureAndAJob) {
  ScratchDir dir;
  const std::string patterns = SKEIN_PATTERNS_DIR;
  std::filesystem::create_directories(dir / "ex");
  auto r = run_skein("weave-exemplar " + patterns + "/plain-weave.weave " + patterns + "/twill-3-2.weave -o " + (dir / "ex").string() +
                     " --crossings 5 --voxels 8 --report " + (dir / "ex.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "ex" / "plain-weave.vdb") && std::filesystem::exists(dir / "ex" / "twill-3-2.vdb"));
  const auto ex = nlohmann::json::parse(slurp(dir / "ex.json"));
  ASSERT_EQ(ex["exemplars"].size(), 2u);
  EXPECT_EQ(ex["exemplars"][0]["pull_through_events"], 0);
  r = run_skein("weave-volume " + patterns + "/twill-2-1.weave --exemplars " + (dir / "ex").string() + " --size 9x6 -o " + (dir / "v.vdb").string() +
                " --png " + (dir / "v.png").string() + " --width 40 --height 30 --samples 1 --assignment " + (dir / "a.txt").string() + " --report " +
                (dir / "v.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto v = nlohmann::json::parse(slurp(dir / "v.json"));
  EXPECT_EQ(v["synthesis"]["correct"], 54);
  EXPECT_EQ(v["synthesis"]["neighbour_matches"], v["synthesis"]["best_possible_matches"]);
  EXPECT_LT(v["edge_fixing"]["seam_step_fixed_mm"].get<double>(), v["edge_fixing"]["seam_step_mm"].get<double>());
  EXPECT_EQ(v["output"]["voxels"][0], 9 * 8);
  EXPECT_EQ(slurp(dir / "v.png").substr(1, 3), "PNG");
  std::istringstream assignment(slurp(dir / "a.txt"));
  int rows = 0;
  for (std::string line; std::getline(assignment, line);) rows += !line.empty() && line[0] != '#';
  EXPECT_EQ(rows, 54);
  // The same as a job (docs/jobs.md), with the exemplars folder.
  const auto job = dir.write("w.json", "{\"weave\": {\"pattern\": \"" + patterns + "/satin-5-3.weave\", \"exemplars\": \"ex\", \"size\": \"6x6\", "
                                       "\"width\": 24, \"height\": 16, \"samples\": 1}, \"output\": \"out\"}");
  r = run_skein("run " + job.string());
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* f : {"volume.vdb", "assignment.txt", "render.png", "report.json", "job.log"}) EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << f;
  const auto bad = dir.write("b.json", "{\"weave\": {\"pattern\": \"" + patterns + "/satin-5-3.weave\", \"weaves\": [\"x\"]}}");
  const auto refused = run_skein("run " + bad.string());
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.output.find("key 'weave.weaves': is for a picture's colours"), std::string::npos) << refused.output;
}

TEST(Cli, WeaveRefusesBadDesignsAndExemplarsAndWritesNothing) {
  ScratchDir dir;
  const std::string patterns = SKEIN_PATTERNS_DIR;
  std::filesystem::create_directories(dir / "empty");
  std::filesystem::create_directories(dir / "broken");
  dir.write("broken/x.vdb", "not a volume");
  auto r = run_skein("weave-exemplar " + patterns + "/stockinette.knit -o " + dir.path().string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("stockinette.knit: is a knitting pattern; exemplars are woven"), std::string::npos) << r.output;
  expect_refused("weave-volume " + patterns + "/plain-weave.weave --exemplars " + (dir / "empty").string(), dir / "v.vdb", "holds no .vdb exemplars");
  expect_refused("weave-volume " + patterns + "/plain-weave.weave --exemplars " + (dir / "broken").string(), dir / "v.vdb",
                 "x.vdb: is not a readable OpenVDB file");
  expect_refused("weave-volume " + patterns + "/plain-weave.weave --size 0x5", dir / "v.vdb", "--size: expected WxH crossings");
  expect_refused("weave-volume --picture " + patterns + "/woven/jacquard.png", dir / "v.vdb", "--picture: needs --weaves");
  expect_refused("weave-volume --picture " + patterns + "/woven/jacquard.png --weaves " + patterns + "/plain-weave.weave", dir / "v.vdb",
                 "jacquard.png: has 3 colours and --weaves names 1 weaves");
  expect_refused("weave-volume " + patterns + "/plain-weave.weave --warp-colors red", dir / "v.vdb", "--warp-colors: expected colours as #rrggbb");
  expect_refused("weave-volume " + patterns + "/rib-2x2.knit", dir / "v.vdb", "is knitted, not woven");
}
