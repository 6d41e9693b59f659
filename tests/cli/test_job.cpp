// skein run: job files checked key by key, killed and resumed, garments of a yarn weight
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stitchmesh/fabric.hpp"
#include "workflow/yarn_io.hpp"
#include "workflow/yarn_options.hpp"
#include "cli_support.hpp"

using namespace skein::testing::cli;
using skein::testing::ScratchDir;

TEST(Job, YarnOptionsHaveTheRangesTheCommandLineGivesThem) {
  // One schema (relax/yarn_options.hpp): a value past an option's range is refused by relax-yarn's flag and by a
  // job's relax_yarn key alike, each naming the same range.
  ScratchDir dir;
  const std::set<std::string> job_keys{"max_steps", "max_seconds", "tolerance", "stall", "force_tolerance", "stall_window", "energy_stall", "jam_steps",
                                       "jam_drop", "max_move", "contact_spacing", "checkpoint_every", "checkpoint_minutes", "k_bend", "k_stretch",
                                       "k_length", "k_contact"};
  int checked = 0;
  for (const auto& option : skein::workflow::yarn_options()) {
    if (!job_keys.count(option.key)) continue;
    SCOPED_TRACE(option.key);
    const std::string too_big = option.kind == skein::workflow::YarnOption::Kind::Integer ? std::to_string(static_cast<long>(option.high) + 1) : "1e12";
    auto r = run_skein("relax-yarn none.bcc " + option.flag() + " " + too_big + " -o " + (dir / "x.bcc").string());
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find(option.flag() + ": must be in " + option.range()), std::string::npos) << r.output;
    r = run_skein("run " + dir.write(option.key + ".json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "relax_yarn": {")" + option.key + "\": " + too_big + "}}")
                              .string());
    EXPECT_EQ(r.status, 2);
    EXPECT_NE(r.output.find("key 'relax_yarn." + option.key + "'"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("number in " + option.range()), std::string::npos) << r.output;
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(job_keys.size()));
  // A whole number written as a fraction is refused alike; JSON's 1e3 is a whole number.
  auto r = run_skein("relax-yarn none.bcc --max-steps 1.5 -o " + (dir / "x.bcc").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--max-steps: expected a whole number, found 1.5"), std::string::npos) << r.output;
  r = run_skein("run " + dir.write("half.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "relax_yarn": {"max_steps": 1.5}})").string());
  EXPECT_NE(r.output.find("expected a whole number, found 1.5"), std::string::npos) << r.output;
  r = run_skein("run " + dir.write("big.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "relax_yarn": {"max_steps": 2e9}})").string());
  EXPECT_NE(r.output.find("expected a whole number in [0, 1e+09], found 2000000000.0"), std::string::npos) << r.output;
  // A stitch type's take-up is a take-up: the same range.
  r = run_skein("pattern " + kPatterns + "/honeycomb.knit --relax --take-up-stitch s=20 -o " + (dir / "x.bcc").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--take-up-stitch 's=20': the factor must be in [0.1, 10], as --take-up's"), std::string::npos) << r.output;
  // A part of a stitch's yarn (Leaf 2018 §6.1): taken from a pattern, refused by name when misspelt.
  r = run_skein("pattern " + kPatterns + "/honeycomb.knit --relax --no-audit --max-steps 20 --take-up-stitch s:vertical=0.3 -o " + (dir / "v.bcc").string());
  EXPECT_EQ(r.status, 0) << r.output;
  r = run_skein("pattern " + kPatterns + "/honeycomb.knit --relax --no-audit --max-steps 20 --take-up-stitch s:up=0.3 -o " + (dir / "u.bcc").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("take-up of s:up: the part after ':' must be vertical or horizontal"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "u.bcc"));
  // Every flag with a range speaks as the schema's do (not CLI11's "Value abc not in range 64 to 4096"), and the
  // active set's settings are refused without it rather than ignored.
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"pattern " + kPatterns + "/seed.knit --png-size abc --png p.png", "--png-size: expected a whole number, found abc"},
           {"pattern " + kPatterns + "/seed.knit --png-size 10 --png p.png", "--png-size: must be in [64, 4096], found 10"},
           {"pattern " + kPatterns + "/seed.knit --relax --gamma 9", "--gamma: must be in [0.25, 4], found 9"},
           {"relax-yarn none.bcc --sleep-force 1", "--sleep-force: goes with the active set"},
           {"relax-yarn none.bcc --active-set --wake-move -3", "--wake-move: expected a positive number, found -3"}}) {
    r = run_skein(args + " -o " + (dir / "x.bcc").string());
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
  }
  // A whole number may be written as one: 1e1 steps are 10 steps.
  r = run_skein("pattern " + kPatterns + "/seed.knit --relax --no-audit --max-steps 1e1 -o " + (dir / "x.bcc").string() + " --report " + (dir / "r.json").string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir / "r.json"))["steps"], 10);
  // Not a schema option, but no longer taken silently as the default either.
  r = run_skein("relax-yarn none.bcc --yarn-radius -1 -o " + (dir / "x.bcc").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--yarn-radius: expected a positive number, found -1"), std::string::npos) << r.output;
}

TEST(Job, ErrorsNameTheKeyAndWhatWasExpected) {
  ScratchDir dir;
  const auto error_for = [&](const std::string& name, const std::string& text) {
    const auto r = run_skein("run " + dir.write(name, text).string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << name;  // refused before any work
    return r.output;
  };
  const std::string base = swatch_job();
  const auto with = [&](const std::string& extra) { return base.substr(0, base.size() - 1) + extra + "}"; };
  std::string msg = error_for("typo.json", with(R"(, "relax_yarns": {})"));
  EXPECT_NE(msg.find("key 'relax_yarns'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("known: "), std::string::npos) << msg;
  msg = error_for("type.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "relax_yarn": {"max_steps": "many"}})");
  EXPECT_NE(msg.find("key 'relax_yarn.max_steps'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected a whole number, found \"many\""), std::string::npos) << msg;
  msg = error_for("active.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "relax_yarn": {"active_set": "yes"}})");
  EXPECT_NE(msg.find("key 'relax_yarn.active_set'"), std::string::npos) << msg;
  msg = error_for("spacing.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "relax_yarn": {"contact_spacing": 4}})");
  EXPECT_NE(msg.find("key 'relax_yarn.contact_spacing'"), std::string::npos) << msg;
  msg = error_for("method.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "relax_yarn": {"method": "rk4"}})");
  EXPECT_NE(msg.find("expected \"fire\", \"euler\" or \"lbfgs\", found \"rk4\""), std::string::npos) << msg;
  msg = error_for("rule.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "relax_yarn": {"stop_rule": "relative"}})");
  EXPECT_NE(msg.find("key 'relax_yarn.stop_rule'"), std::string::npos) << msg;
  msg = error_for("force.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "relax_yarn": {"stop_rule": "force", "force_tolerance": 0}})");
  EXPECT_NE(msg.find("key 'relax_yarn.force_tolerance'"), std::string::npos) << msg;
  msg = error_for("gauge.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "gauge": {"stitches": 18}, "stitch_size": {"width": 5}})");
  EXPECT_NE(msg.find("key 'gauge': sets the stitch size"), std::string::npos) << msg;
  msg = error_for("rows.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "gauge": {"rows": 18}})");
  EXPECT_NE(msg.find("key 'gauge.stitches': is missing"), std::string::npos) << msg;
  msg = error_for("weight.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "yarn": {"weight": "wool"}})");
  EXPECT_NE(msg.find("key 'yarn.weight': is not a yarn weight"), std::string::npos) << msg;
  msg = error_for("radius.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "yarn": {"weight": "dk", "radius": 1}})");
  EXPECT_NE(msg.find("key 'yarn.weight': sets the radius"), std::string::npos) << msg;
  msg = error_for("needle.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "yarn": {"needle": 4.5}})");
  EXPECT_NE(msg.find("key 'yarn.needle': needs the yarn knitted on it"), std::string::npos) << msg;
  msg = error_for("needle-gauge.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "gauge": {"stitches": 18}, "yarn": {"weight": "dk", "needle": 4.5}})");
  EXPECT_NE(msg.find("key 'yarn.needle': sets the stitch size: give gauge or the needle, not both"), std::string::npos) << msg;
  msg = error_for("needle-size.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "yarn": {"weight": "dk", "needle": 0}})");
  EXPECT_NE(msg.find("key 'yarn.needle': expected a number in [0.001, 50]"), std::string::npos) << msg;
  msg = error_for("max.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "max_stitches": 0})");
  EXPECT_NE(msg.find("key 'max_stitches'"), std::string::npos) << msg;
  msg = error_for("nomesh.json", R"({"name": "x"})");
  EXPECT_NE(msg.find("key 'mesh'"), std::string::npos) << msg;
  msg = error_for("missing.json", R"({"mesh": "no-such.obj"})");
  EXPECT_NE(msg.find("does not exist"), std::string::npos) << msg;
  msg = error_for("both.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "edits": [{"fill": "rib", "pattern": "x.knit"}]})");
  EXPECT_NE(msg.find("key 'edits[0].fill'"), std::string::npos) << msg;
  msg = error_for("fill.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "edits": [{"fill": "ribbon"}]})");
  EXPECT_NE(msg.find("key 'edits[0].fill'"), std::string::npos) << msg;
  msg = error_for("range.json", R"({"mesh": ")" + kModels + R"(/swatch.obj", "relax_mesh": {"alpha": 3}})");
  EXPECT_NE(msg.find("key 'relax_mesh.alpha'"), std::string::npos) << msg;
  msg = error_for("json.json", R"({"mesh": )");
  EXPECT_NE(msg.find("not valid JSON"), std::string::npos) << msg;
  msg = error_for("overflow.json", R"({"name": 1e99999})");  // found by fuzzing
  EXPECT_NE(msg.find("not valid JSON"), std::string::npos) << msg;
  const auto r = run_skein("run " + (dir / "none.json").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("none.json"), std::string::npos) << r.output;
}

TEST(Job, AnUnwritableOutputIsRefusedBeforeAnyWork) {
  ScratchDir dir;
  dir.write("file", "not a folder");
  const auto job = dir.write("job.json", swatch_job(R"(, "output": "file/out")"));
  const auto r = run_skein("run " + job.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("output folder cannot be made"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("load and label"), std::string::npos) << r.output;  // no stage started
}

TEST(Job, KilledThenResumedEndsAsAnUninterruptedRun) {
  ScratchDir dir;
  const auto job = dir.write("job.json", swatch_job());
  const auto whole = run_skein("-q run " + job.string() + " -o " + (dir / "whole").string());
  ASSERT_EQ(whole.status, 0) << whole.output;
  const auto report = slurp(dir / "whole" / "report.json");
  EXPECT_NE(report.find("\"status\": \"done\""), std::string::npos) << report;
  for (const char* stage : {"load and label", "tessellate and edit", "relax the stitch mesh", "emit yarn", "relax the yarn"})
    EXPECT_NE(report.find(stage), std::string::npos) << stage;
  // SIGKILL after the first checkpoint; --resume goes on from it.
  const pid_t pid = spawn_skein({"-q", "run", job.string(), "-o", (dir / "killed").string()}, dir / "killed.log");
  ASSERT_TRUE(wait_for(dir / "killed" / "yarn.ckp", 120));
  ::kill(pid, SIGKILL);
  EXPECT_EQ(exit_code(pid), 128 + SIGKILL);
  EXPECT_FALSE(std::filesystem::exists(dir / "killed" / "yarn-relaxed.bcc"));
  const auto resumed = run_skein("run " + job.string() + " -o " + (dir / "killed").string() + " --resume");
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming the yarn from"), std::string::npos) << resumed.output;
  EXPECT_EQ(slurp(dir / "killed" / "yarn-relaxed.bcc"), slurp(dir / "whole" / "yarn-relaxed.bcc"));
}

TEST(Job, AYarnWeightRelaxesAGarmentAtItsCompressedContactAndMundensLoopLength) {
  // Issue 24: as `skein pattern --yarn` relaxes a repeat, a garment of a yarn weight is emitted and relaxed at
  // kYarnCompression of the weight's radius, each stitch's yarn cut to Munden's loop length for the project's
  // stitch width (Kw w), and written at the weight's full radius; both `relax-yarn --yarn` and a job's yarn.weight.
  ScratchDir dir;
  const double full = 25.4 / 13 / 2, munden = skein::mesh::kMundenKw * 12;  // dk; the job's 12 mm stitches
  const auto job = dir.write("job.json", swatch_job(R"(, "yarn": {"weight": "dk"})", 10));
  auto r = run_skein("-q run " + job.string() + " -o " + (dir / "job").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto report = nlohmann::json::parse(slurp(dir / "job" / "report.json"));
  const auto& fabric = report.at("fabric");
  EXPECT_NEAR(fabric.at("contact_radius_mm").get<double>(), skein::mesh::kYarnCompression * full, 1e-9);
  EXPECT_NEAR(fabric.at("munden_loop_length_mm").get<double>(), munden, 1e-9);
  EXPECT_NEAR(fabric.at("yarn_per_stitch_mm").get<double>(), munden, 1e-6 * munden);
  const double to_munden = fabric.at("take_up_to_munden").get<double>();
  EXPECT_GT(std::abs(to_munden - 1), 0.05) << "the emitted loops are Munden's already: the test shows nothing";
  for (const char* file : {"yarn.bcc", "yarn-relaxed.bcc"}) EXPECT_NEAR(skein::workflow::read_bcc(dir / "job" / file).radius, full, 1e-9) << file;
  // The same through relax-yarn on the job's project; a take-up given is kept.
  const auto project = (dir / "job" / "relaxed.skein").string();
  r = run_skein("relax-yarn " + project + " --yarn dk --max-steps 0 --no-audit -o " + (dir / "r.bcc").string() + " --report " + (dir / "r.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  auto relaxed = nlohmann::json::parse(slurp(dir / "r.json"));
  EXPECT_NEAR(relaxed.at("fabric").at("take_up_to_munden").get<double>(), to_munden, 1e-9);
  EXPECT_NEAR(skein::workflow::read_bcc(dir / "r.bcc").radius, full, 1e-9);
  r = run_skein("relax-yarn " + project + " --yarn dk --take-up 0.95 --max-steps 0 --no-audit -o " + (dir / "t.bcc").string() + " --report " +
                (dir / "t.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  relaxed = nlohmann::json::parse(slurp(dir / "t.json"));
  EXPECT_FALSE(relaxed.at("fabric").contains("take_up_to_munden"));
  EXPECT_NEAR(relaxed.at("fabric").at("yarn_per_stitch_mm").get<double>(), 0.95 * munden / to_munden, 1e-6 * munden);
  // Refused where a weight's compressed contact cannot hold: a preview that keeps the emitted radius.
  expect_refused("relax-yarn " + project + " --yarn dk --stand-in", dir / "s.bcc", "--yarn: relaxes a whole garment");
  // A weight the app saved with the project (set yarn.weight) is taken as --yarn, with Munden's take-up over its saved one.
  auto text = slurp(project);
  text.insert(text.rfind("end"), "set yarn.weight dk\nset yarn.take_up 0.8\n");
  const auto saved = dir.write("saved.skein", text);
  r = run_skein("relax-yarn " + saved.string() + " --max-steps 0 --no-audit -o " + (dir / "w.bcc").string() + " --report " + (dir / "w.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("--yarn"), std::string::npos) << r.output;
  relaxed = nlohmann::json::parse(slurp(dir / "w.json"));
  EXPECT_EQ(relaxed.at("fabric").at("yarn").get<std::string>(), "dk");
  EXPECT_NEAR(relaxed.at("fabric").at("take_up_to_munden").get<double>(), to_munden, 1e-9);
  EXPECT_NEAR(skein::workflow::read_bcc(dir / "w.bcc").radius, full, 1e-9);
  // A saved weight cannot hold where --yarn cannot: the error names the project's line.
  expect_refused("relax-yarn " + saved.string() + " --stand-in", dir / "s.bcc", "set yarn.weight dk: relaxes a whole garment");
  // Other saved settings do not stop --yarn from cutting the yarn to Munden's loop length (a saved take-up is the app's,
  // which it does not use with a weight).
  text = slurp(project);
  text.insert(text.rfind("end"), "set yarn.tolerance 0.01\nset yarn.take_up 0.8\n");
  const auto other = dir.write("other.skein", text);
  r = run_skein("relax-yarn " + other.string() + " --yarn dk --max-steps 0 --no-audit -o " + (dir / "o.bcc").string() + " --report " +
                (dir / "o.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NEAR(nlohmann::json::parse(slurp(dir / "o.json")).at("fabric").at("take_up_to_munden").get<double>(), to_munden, 1e-9);
  // The command line's own radius wins over the saved weight.
  r = run_skein("relax-yarn " + saved.string() + " --yarn-radius 1 --max-steps 0 --no-audit -o " + (dir / "x.bcc").string() + " --report " +
                (dir / "x.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(nlohmann::json::parse(slurp(dir / "x.json")).contains("fabric"));
  EXPECT_NE(r.output.find("saves the yarn weight dk: not used, the command line gives --yarn-radius"), std::string::npos) << r.output;
}

TEST(Job, LabelsFromTheFieldKnitATriangleMeshThroughToRelaxedYarn) {
  // Issue 25: "labels": "field" traces the rows on any surface, here the bundled swatch fanned into triangles.
  ScratchDir dir;
  const std::string obj = fanned_into_triangles(slurp(kModels + "/swatch.obj"));
  const auto mesh = dir.write("swatch-triangles.obj", obj);
  const auto job = dir.write("job.json", R"({"name": "field", "mesh": ")" + mesh.string() + R"(", "labels": "field",
    "stitch_size": {"width": 12, "height": 10}, "relax_yarn": {"max_steps": 40}, "pictures": false})");
  const auto r = run_skein("-q run " + job.string() + " -o " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto report = nlohmann::json::parse(slurp(dir / "out" / "report.json"));
  EXPECT_EQ(report.at("status"), "done");
  // 120 x 100 mm at 12 x 10 mm stitches: 10 stitches a row, 9 rows (the last row's top short of the far border).
  EXPECT_EQ(report.at("stitch_mesh").at("faces"), 90) << report.dump(1);
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "yarn-relaxed.bcc"));
}

TEST(Job, FieldRowsStartWhereTheJobSays) {
  // Issue 25: "start": {"point": [x, y, z]} knits in the round from a surface point, as skein stitch --start-point does.
  ScratchDir dir;
  const std::string obj = fanned_into_triangles(slurp(kModels + "/swatch.obj"));
  const auto mesh = dir.write("t.obj", obj);
  ASSERT_EQ(run_skein("-q stitch " + mesh.string() + " --field --start-point 60,40,0 --stitch-size 12 --stitch-height 10 -o " + (dir / "p.skein").string()).status, 0);
  const auto stats = nlohmann::json::parse(run_skein("stats " + (dir / "p.skein").string() + " --json").output);
  const auto job = dir.write("job.json", R"({"mesh": ")" + mesh.string() + R"(", "labels": "field", "start": {"point": [60, 40, 0]},
    "stitch_size": {"width": 12, "height": 10}, "relax_mesh": false, "relax_yarn": false, "pictures": false})");
  const auto r = run_skein("-q run " + job.string() + " -o " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto report = nlohmann::json::parse(slurp(dir / "out" / "report.json"));
  EXPECT_EQ(report.at("stitch_mesh").at("faces"), stats.at("faces")) << stats.dump(1);
  EXPECT_GT(stats.at("increases"), 0);  // rings that grow outwards from the point
  const auto refused = [&](const std::string& start, const std::string& labels, const std::string& message) {
    const auto bad = dir.write("bad.json", R"({"mesh": ")" + mesh.string() + R"(", "labels": )" + labels + R"(, "start": )" + start + "}");
    const auto out = run_skein("run " + bad.string() + " -o " + (dir / "bad").string());
    EXPECT_EQ(out.status, 2);
    EXPECT_NE(out.output.find(message), std::string::npos) << out.output;
  };
  refused(R"({"edge": 3, "point": [0, 0, 0]})", R"("field")", "key 'start': give \"edge\" (a border edge) or \"point\"");
  refused(R"({"point": [0, 0]})", R"("field")", "key 'start.point': expected [x, y, z] in the mesh's units, found [0,0]");
  refused(R"({"point": [0, 0, 0]})", R"("auto")", "key 'start.point': is for \"labels\": \"field\"");

  // "end" as skein stitch --end-point: the rows close round the far border's middle.
  ASSERT_EQ(run_skein("-q stitch " + mesh.string() + " --field --end-point 60,100,0 --stitch-size 12 --stitch-height 10 -o " + (dir / "e.skein").string()).status, 0);
  const auto end_stats = nlohmann::json::parse(run_skein("stats " + (dir / "e.skein").string() + " --json").output);
  const auto end_job = dir.write("end.json", R"({"mesh": ")" + mesh.string() + R"(", "labels": "field", "end": {"point": [60, 100, 0]},
    "stitch_size": {"width": 12, "height": 10}, "relax_mesh": false, "relax_yarn": false, "pictures": false})");
  const auto e = run_skein("-q run " + end_job.string() + " -o " + (dir / "end").string());
  ASSERT_EQ(e.status, 0) << e.output;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir / "end" / "report.json")).at("stitch_mesh").at("faces"), end_stats.at("faces"));
  EXPECT_GT(end_stats.at("decreases"), 0);  // the rows shorten as they close round the end
  const auto bad_end = dir.write("bad-end.json", R"({"mesh": ")" + mesh.string() + R"(", "labels": "auto", "end": {"edge": 3}})");
  const auto out = run_skein("run " + bad_end.string() + " -o " + (dir / "bad").string());
  EXPECT_EQ(out.status, 2);
  EXPECT_NE(out.output.find("key 'end': is for \"labels\": \"field\""), std::string::npos) << out.output;
}

TEST(Job, SigtermLeavesACheckpointToResumeFrom) {
  ScratchDir dir;
  const auto job = dir.write("job.json", swatch_job("", 1000000));  // runs until stopped
  const pid_t pid = spawn_skein({"run", job.string(), "-o", (dir / "out").string()}, dir / "run.log");
  ASSERT_TRUE(wait_for(dir / "out" / "yarn.ckp", 120));  // the yarn has relaxed 20 steps
  ::kill(pid, SIGTERM);
  EXPECT_EQ(exit_code(pid), 128 + SIGTERM) << slurp(dir / "run.log");
  const auto report = slurp(dir / "out" / "report.json");
  EXPECT_NE(report.find("\"status\": \"interrupted\""), std::string::npos) << report;
  EXPECT_NE(report.find("--resume"), std::string::npos) << report;
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "yarn.ckp"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "yarn-relaxed.bcc"));
  // The checkpoint is whole: a resumed run reads it and goes on.
  const pid_t again = spawn_skein({"run", job.string(), "-o", (dir / "out").string(), "--resume"}, dir / "resumed.log");
  for (int i = 0; i < 2400 && slurp(dir / "resumed.log").find("resuming the yarn from") == std::string::npos; ++i) ::usleep(50000);
  ::kill(again, SIGTERM);
  EXPECT_EQ(exit_code(again), 128 + SIGTERM);
  EXPECT_NE(slurp(dir / "resumed.log").find("resuming the yarn from"), std::string::npos) << slurp(dir / "resumed.log");
}
