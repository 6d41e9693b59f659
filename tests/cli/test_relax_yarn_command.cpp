// skein relax-yarn: reports, logs, checkpoints, warm starts, stand-ins and the project's yarn settings
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <tuple>

#include "workflow/yarn_io.hpp"
#include "cli_support.hpp"

using namespace skein::testing::cli;
using skein::testing::ScratchDir;

TEST(Cli, RelaxYarnAndPatternWriteTheStitchIdsToo) {  // and pattern's chart picture
  ScratchDir dir;
  const auto project = (dir / "s.skein").string();
  ASSERT_EQ(run_skein("stitch " + kModels + "/swatch.obj --auto-label --stitch-size 15 -o " + project).status, 0);
  // relax-yarn: the same side file as the emission's (the relaxed yarn keeps its points' order).
  ASSERT_EQ(run_skein("yarn " + project + " -o " + (dir / "e.bcc").string() + " --ids " + (dir / "e.csv").string()).status, 0);
  auto r = run_skein("relax-yarn " + project + " -o " + (dir / "r.bcc").string() + " --ids " + (dir / "r.csv").string() + " --max-steps 3 --no-audit");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(slurp(dir / "r.csv"), slurp(dir / "e.csv"));
  EXPECT_GT(slurp(dir / "r.csv").size(), 100u);
  expect_refused("relax-yarn " + (dir / "e.bcc").string() + " --ids " + (dir / "b.csv").string(), dir / "b.bcc",
                 "--ids: names each control point's stitch face: give a .skein project");
  EXPECT_FALSE(std::filesystem::exists(dir / "b.csv"));
  // --rest-lengths: the same yarn in another shape relaxes; a different yarn is refused before any work.
  ASSERT_EQ(run_skein("relax-yarn " + (dir / "e.bcc").string() + " --rest-lengths " + (dir / "r.bcc").string() + " --max-steps 3 --no-audit -o " +
                      (dir / "rl.bcc").string()).status, 0);
  ASSERT_EQ(run_skein("pattern " + std::string(SKEIN_PATTERNS_DIR) + "/rib-1x1.knit --tile 2x2 -o " + (dir / "other.bcc").string()).status, 0);
  expect_refused("relax-yarn " + (dir / "e.bcc").string() + " --rest-lengths " + (dir / "other.bcc").string(), dir / "rl2.bcc",
                 (dir / "other.bcc").string() + ": ");
  // pattern: a row per control point of the tiling, its faces the tiling's, knit and purl as the rib has them.
  r = run_skein("pattern " + std::string(SKEIN_PATTERNS_DIR) + "/rib-1x1.knit --tile 2x3 -o " + (dir / "p.bcc").string() + " --ids " +
                (dir / "p.csv").string() + " --chart-png " + (dir / "chart.png").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "chart.png"));
  long points = 0;
  std::set<std::string> types;
  std::set<int> faces;
  for (const auto& id : read_ids(dir / "p.csv")) {
    EXPECT_EQ(id.point, points++);
    if (id.face >= 0) faces.insert(id.face), types.insert(id.type);
  }
  EXPECT_EQ(points, static_cast<long>(skein::workflow::read_bcc(dir / "p.bcc").points.size()));
  EXPECT_EQ(faces.size(), 12u);  // 2 x 3 repeats of 2 x 1 stitches
  EXPECT_EQ(types, (std::set<std::string>{"k", "p"}));
  expect_refused("pattern " + std::string(SKEIN_PATTERNS_DIR) + "/rib-1x1.knit --relax --ids " + (dir / "q.csv").string(), dir / "q.bcc",
                 "--ids: names each control point's stitch face in a tiling: the periodic patch is one repeat and its copies (add --tiled)");
  expect_refused("pattern " + std::string(SKEIN_PATTERNS_DIR) + "/plain-weave.weave --ids " + (dir / "q.csv").string(), dir / "q.bcc",
                 "--ids: names each control point's stitch face, and a woven pattern has none");
  EXPECT_FALSE(std::filesystem::exists(dir / "q.csv"));
  expect_refused("pattern " + std::string(SKEIN_PATTERNS_DIR) + "/plain-weave.weave --chart-png " + (dir / "q.png").string(), dir / "q.bcc",
                 "chart: a woven pattern has no knitting chart: draw its yarn with --png");
  EXPECT_FALSE(std::filesystem::exists(dir / "q.png"));
  // A yarn name the writer refuses is refused before the relaxation (a long run is not lost to it), the report not written either.
  expect_refused("pattern " + std::string(SKEIN_PATTERNS_DIR) + "/rib-2x2.knit --relax --free-period --max-steps 1000000 --report " +
                     (dir / "q.json").string(),
                 dir / "q.yarn", "q.yarn: yarn is written as .bcc or .obj (polylines)");
  expect_refused("pattern " + std::string(SKEIN_PATTERNS_DIR) + "/rib-2x2.knit --relax --preview " + (dir / "v.txt").string(), dir / "q.bcc",
                 "v.txt: yarn is written as .bcc or .obj (polylines)");
  expect_refused("relax-yarn " + (dir / "p.bcc").string() + " --max-steps 1000000", dir / "r.yarn", "r.yarn: yarn is written as .bcc or .obj (polylines)");
  EXPECT_FALSE(std::filesystem::exists(dir / "q.json"));
}

TEST(Cli, RelaxYarnWritesYarnReportLogAndCheckpointAndResumes) {
  ScratchDir dir;
  const auto project = dir / "swatch.skein";
  ASSERT_EQ(run_skein("stitch " + kModels + "/swatch.obj --auto-label --stitch-size 15 -o " + project.string()).status, 0);
  ASSERT_EQ(run_skein("edit " + project.string() + " --fill rib -o " + project.string()).status, 0);
  const auto out = dir / "relaxed.bcc", report = dir / "report.json", log = dir / "log.csv", ckp = dir / "run.ckp";
  auto r = run_skein("relax-yarn " + project.string() + " -o " + out.string() + " --report " + report.string() + " --log " + log.string() +
                     " --checkpoint " + ckp.string() + " --checkpoint-every 20 --max-steps 40");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(out));
  EXPECT_TRUE(std::filesystem::exists(ckp));
  const auto json = slurp(report);
  for (const char* key : {"\"converged\"", "\"steps\": 40", "\"wall_seconds\"", "\"residual\"", "\"guard_events\"", "\"pull_through_events\": 0"})
    EXPECT_NE(json.find(key), std::string::npos) << key << "\n" << json;
  EXPECT_NE(slurp(log).find("step,energy,residual"), std::string::npos);
  // Resume from step 40 for 10 more steps.
  r = run_skein("relax-yarn " + project.string() + " -o " + (dir / "more.bcc").string() + " --resume " + ckp.string() + " --max-steps 50");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("resuming"), std::string::npos) << r.output;
  // The audit between the emitted and the relaxed yarn finds nothing pulled through.
  ASSERT_EQ(run_skein("yarn " + project.string() + " -o " + (dir / "start.bcc").string()).status, 0);
  r = run_skein("audit " + (dir / "start.bcc").string() + " " + out.string());
  EXPECT_NE(r.output.find("centreline crossings"), std::string::npos) << r.output;
}

TEST(Cli, RelaxYarnWarmStartRelaxesOnlyWhatAnEditChanged) {
  ScratchDir dir;
  const auto before = dir / "before.skein", after = dir / "after.skein", relaxed = dir / "before.bcc";
  ASSERT_EQ(run_skein("stitch " + kModels + "/swatch.obj --auto-label --stitch-size 15 -o " + before.string()).status, 0);
  ASSERT_EQ(run_skein("relax-yarn " + before.string() + " -o " + relaxed.string() + " --no-audit").status, 0);
  ASSERT_EQ(run_skein("edit " + before.string() + " --set-type p --faces 40 -o " + after.string()).status, 0);
  const auto out = dir / "after.bcc", report = dir / "r.json";
  auto r = run_skein("relax-yarn " + after.string() + " -o " + out.string() + " --report " + report.string() + " --warm-start " +
                     relaxed.string() + " --warm-project " + before.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto json = slurp(report);
  for (const char* key : {"\"converged\": true", "\"changed_stitches\": 1", "\"splice_crossings\": 0", "\"pull_through_events\": 0"})
    EXPECT_NE(json.find(key), std::string::npos) << key << "\n" << json;
  // A warm start needs the project it came from, and yarn relaxed from that project.
  const auto none = dir / "none.bcc";
  r = run_skein("relax-yarn " + after.string() + " -o " + none.string() + " --warm-start " + relaxed.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--warm-start: relaxes a .skein project"), std::string::npos) << r.output;
  ASSERT_EQ(run_skein("stitch " + kModels + "/tube.obj --auto-label -o " + (dir / "tube.skein").string()).status, 0);
  r = run_skein("relax-yarn " + after.string() + " -o " + none.string() + " --warm-start " + relaxed.string() + " --warm-project " +
                (dir / "tube.skein").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("holds other curves than the yarn of"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(none));
}

TEST(Cli, RelaxYarnStandInWritesAMarkedPreviewAndTheActiveSetRelaxes) {
  ScratchDir dir;
  const auto project = dir / "swatch.skein", preview = dir / "preview.bcc", report = dir / "r.json";
  ASSERT_EQ(run_skein("stitch " + kModels + "/swatch.obj --auto-label --stitch-size 15 -o " + project.string()).status, 0);
  auto r = run_skein("relax-yarn " + project.string() + " --stand-in --stand-in-min-faces 4 -o " + preview.string() + " --report " + report.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("stand-in preview (not a relaxation)"), std::string::npos) << r.output;
  const auto json = slurp(report);
  for (const char* key : {"\"preview\": \"stand-in\"", "\"pull_through_events\": 0", "\"pattern\": \"k\""})
    EXPECT_NE(json.find(key), std::string::npos) << key << "\n" << json;
  EXPECT_NE(slurp(preview).find("skein preview, radius"), std::string::npos);
  const auto refused = dir / "refused.bcc";
  r = run_skein("relax-yarn " + project.string() + " --stand-in --stand-in-max-period 17 -o " + refused.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("the longest repeat must be 1 to 16 stitches, found 17"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(refused));
  r = run_skein("relax-yarn " + project.string() + " --stand-in --stand-in-reach -1 -o " + refused.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("the rings beyond a region must be 0 or more, found -1"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(refused));
  // A lace tiled onto the swatch re-meshes its stitches: named, its whole repeats get their stand-in too.
  const std::string patterns = SKEIN_PATTERNS_DIR;
  const auto lace = dir / "lace.skein";
  ASSERT_EQ(run_skein("pattern " + patterns + "/eyelet-lace.knit --onto " + project.string() + " -o " + lace.string()).status, 0);
  r = run_skein("relax-yarn " + lace.string() + " --stand-in --stand-in-min-faces 4 --stand-in-pattern " + patterns + "/eyelet-lace.knit -o " +
                preview.string() + " --report " + report.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("whole repeats of Eyelet lace found"), std::string::npos) << r.output;
  for (const char* key : {"\"pattern\": \"Eyelet lace\"", "\"pull_through_events\": 0"}) EXPECT_NE(slurp(report).find(key), std::string::npos) << key;
  // A pattern file that is not one, or a weave, is refused with its name.
  const auto broken = dir / "broken.knit";
  std::ofstream(broken) << "format knit\nk zz k\n";
  for (const auto& [file, rule] : {std::pair{broken.string(), std::string("zz")}, {patterns + "/twill-2-1.weave", std::string("is woven")}}) {
    r = run_skein("relax-yarn " + lace.string() + " --stand-in --stand-in-pattern " + file + " -o " + refused.string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find(rule), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(refused));
  }
  // Stand-ins map over stitch faces: bare yarn has none.
  const auto bare = dir / "bare.bcc", none = dir / "none.bcc";
  ASSERT_EQ(run_skein("yarn " + project.string() + " -o " + bare.string()).status, 0);
  r = run_skein("relax-yarn " + bare.string() + " --stand-in -o " + none.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--stand-in maps patches over a project's stitch faces"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(none));
  // The active set and the clipped stop scale: relaxations that report what they did, and only on the CPU.
  const auto relaxed = dir / "relaxed.bcc", report_file = dir / "cpu-only.json";
  for (const auto& [flags, key, refusal] : {std::tuple{std::string("--active-set"), std::string("\"integrated_share\""), std::string("the active set runs on the CPU only")},
                                            {"--stop-scale clipped", "\"stop_scale\": \"clipped\"", "runs on the CPU only"},
                                            {"--stop-rule force", "\"stop_rule\": \"force\"", "runs on the CPU only"}}) {
    r = run_skein("relax-yarn " + project.string() + " " + flags + " --max-steps 20 --no-audit -o " + relaxed.string() + " --report " + report_file.string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(slurp(report_file).find(key), std::string::npos) << key;
    r = run_skein("relax-yarn " + project.string() + " " + flags + " --backend cuda -o " + none.string());
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find(refusal), std::string::npos) << r.output;
  }
  r = run_skein("relax-yarn " + project.string() + " --stop-scale median -o " + none.string());
  EXPECT_NE(r.status, 0);
  EXPECT_FALSE(std::filesystem::exists(none));
  r = run_skein("relax-yarn " + project.string() + " --stop-rule force --force-tolerance -1 -o " + none.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--force-tolerance: must be in (0, 1e+06] B/r³, found -1"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(none));
}

TEST(Cli, RelaxYarnTakesAdaptiveContactSamplesAndRefusesASpacingThatLetsYarnSlipThrough) {
  ScratchDir dir;
  const auto project = dir / "swatch.skein", relaxed = dir / "relaxed.bcc", leaf = dir / "leaf.json", adaptive = dir / "adaptive.json";
  ASSERT_EQ(run_skein("stitch " + kModels + "/swatch.obj --auto-label --stitch-size 15 -o " + project.string()).status, 0);
  auto r = run_skein("relax-yarn " + project.string() + " --max-steps 0 -o " + relaxed.string() + " --report " + leaf.string());
  ASSERT_EQ(r.status, 0) << r.output;
  r = run_skein("relax-yarn " + project.string() + " --max-steps 0 --contact-spacing 2.8 -o " + relaxed.string() + " --report " + adaptive.string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto samples = [](const std::string& json) { return std::stol(json.substr(json.find("\"contact_samples\": ") + 19)); };
  EXPECT_LT(samples(slurp(adaptive)), samples(slurp(leaf)));
  EXPECT_NE(slurp(adaptive).find("\"contact_spacing_r\": 2.8"), std::string::npos);
  const auto none = dir / "none.bcc";
  r = run_skein("relax-yarn " + project.string() + " --contact-spacing 3 -o " + none.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("so that crossing yarns always feel contact"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(none));
  r = run_skein("relax-yarn " + project.string() + " --jam-steps -1 -o " + none.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--jam-steps: must be in [0, 1e+09] steps, found -1"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(none));
}

TEST(Cli, RelaxYarnTakesTheYarnSettingsSavedWithTheProjectUnlessTheCommandLineGivesThem) {
  ScratchDir dir;
  const auto plain = dir / "plain.skein", project = dir / "set.skein", bad = dir / "bad.skein", out = dir / "y.bcc", report = dir / "r.json";
  ASSERT_EQ(run_skein("stitch " + kModels + "/swatch.obj --auto-label --stitch-size 15 -o " + plain.string()).status, 0);
  std::string text = slurp(plain);
  const auto after_header = text.find('\n') + 1;
  std::ofstream(project) << text.substr(0, after_header) + "set yarn.max_steps 3\nset yarn.method euler\n" + text.substr(after_header);
  auto r = run_skein("relax-yarn " + project.string() + " --no-audit -o " + out.string() + " --report " + report.string());
  ASSERT_EQ(r.status, 0) << r.output;
  // Only the keys the project sets stand in for flags.
  EXPECT_NE(r.output.find("carries yarn settings (saved by the app): using them for --method --max-steps\n"), std::string::npos) << r.output;
  for (const char* key : {"\"steps\": 3", "\"stopped_by\": \"step cap\"", "\"method\": \"euler\""}) EXPECT_NE(slurp(report).find(key), std::string::npos) << key;
  r = run_skein("relax-yarn " + project.string() + " --no-audit --max-steps 5 -o " + out.string() + " --report " + report.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(slurp(report).find("\"steps\": 5"), std::string::npos);
  // A setting this skein does not know is refused, with the file and the line, and nothing is written.
  std::ofstream(bad) << text.substr(0, after_header) + "set yarn.colour red\n" + text.substr(after_header);
  const auto none = dir / "none.bcc";
  r = run_skein("relax-yarn " + bad.string() + " -o " + none.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("line 2"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'yarn.colour' is not a setting this skein knows"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(none));
}

TEST(Cli, RelaxYarnRejectsADamagedCheckpointAndForeignYarn) {
  ScratchDir dir;
  const auto bad = dir.write("bad.ckp", "SKEINCKP and then nothing useful");
  const auto project = dir / "tube.skein";
  ASSERT_EQ(run_skein("stitch " + kModels + "/tube.obj --auto-label --stitch-size 15 -o " + project.string()).status, 0);
  auto r = run_skein("relax-yarn " + project.string() + " -o " + (dir / "out.bcc").string() + " --resume " + bad.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("bad.ckp"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.bcc"));
  r = run_skein("relax-yarn " + kModels + "/tube.obj -o " + (dir / "out.bcc").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("reads a .skein project or .bcc yarn"), std::string::npos) << r.output;
  ASSERT_EQ(run_skein("yarn " + project.string() + " -o " + (dir / "a.bcc").string()).status, 0);
  ASSERT_EQ(run_skein("stitch " + kModels + "/swatch.obj --auto-label --stitch-size 15 -o " + (dir / "s.skein").string()).status, 0);
  ASSERT_EQ(run_skein("yarn " + (dir / "s.skein").string() + " -o " + (dir / "b.bcc").string()).status, 0);
  r = run_skein("audit " + (dir / "a.bcc").string() + " " + (dir / "b.bcc").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("holds other curves"), std::string::npos) << r.output;
}
