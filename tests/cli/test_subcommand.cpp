// What every subcommand shares: the yarn and gauge flags, and flags that go with another
#include <gtest/gtest.h>

#include <array>
#include <string>

#include <nlohmann/json.hpp>

#include "stitchmesh/fabric.hpp"
#include "workflow/yarn_io.hpp"
#include "cli_support.hpp"

using namespace skein::testing::cli;
using skein::testing::ScratchDir;

TEST(Cli, YarnWeightAndGaugeSetTheStitchSizeAndTheRadius) {
  ScratchDir dir;
  const std::string patterns = SKEIN_PATTERNS_DIR;
  // Worsted: its radius (10 wraps per inch) and its standard gauge, 18 stitches and 23.4 rows in 10 cm.
  auto r = run_skein("pattern " + patterns + "/stockinette.knit --yarn worsted -o " + (dir / "w.bcc").string() + " --report " + (dir / "w.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NEAR(skein::workflow::read_bcc(dir / "w.bcc").radius, 1.27, 1e-6);
  auto report = slurp(dir / "w.json");
  for (const char* key : {"\"weight\": \"worsted\"", "\"stitches\": 18.0", "\"munden_loop_length_mm\": 22.2", "\"stitch_mm\": [\n"})
    EXPECT_NE(report.find(key), std::string::npos) << key << "\n" << report;
  // A free period reports the relaxed gauge against the one asked for.
  r = run_skein("pattern " + patterns + "/stockinette.knit --gauge 20x25 --relax --free-period --max-steps 200 -o " + (dir / "g.bcc").string() +
                " --report " + (dir / "g.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  report = slurp(dir / "g.json");
  EXPECT_NE(report.find("\"against_asked\""), std::string::npos) << report;
  EXPECT_NEAR(skein::workflow::read_bcc(dir / "g.bcc").radius, 0.5, 1e-6);  // a tenth of the 5 mm stitch without --yarn
  // A gauge sets the tessellation's stitch size.
  r = run_skein("stitch " + kModels + "/tube.obj --auto-label --gauge 10x12.5 -o " + (dir / "t.skein").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(slurp(dir / "t.skein").find("stitch-size 10 8\n"), std::string::npos) << slurp(dir / "t.skein").substr(0, 200);
  // A needle with the yarn gives the gauge of that yarn knitted on it; outside the CYC's range, a warning.
  r = run_skein("pattern " + patterns + "/stockinette.knit --yarn worsted --needle 4 -o " + (dir / "n.bcc").string() + " --report " + (dir / "n.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("--needle 4 mm: outside the Craft Yarn Council's range for worsted yarn (4.5 to 5.5 mm)"), std::string::npos) << r.output;
  const auto fabric = nlohmann::json::parse(slurp(dir / "n.json"))["fabric"];
  const auto on_4mm = skein::mesh::needle_gauge(skein::mesh::find_yarn_weight("worsted"), 4);
  EXPECT_GT(on_4mm.stitches, 18);  // a smaller needle than worsted's middle, more stitches
  EXPECT_NEAR(fabric["gauge_per_10cm"]["stitches"].get<double>(), on_4mm.stitches, 1e-9) << fabric.dump();
  EXPECT_NEAR(fabric["stitch_mm"][0].get<double>(), 100 / on_4mm.stitches, 1e-9) << fabric.dump();
  EXPECT_EQ(fabric["needle_mm"].get<double>(), 4);
  EXPECT_FALSE(fabric["needle_in_cyc_range"].get<bool>());
  // Refused, naming the option, with nothing written.
  const std::array<std::pair<std::string, const char*>, 9> refusals = {
      {{"pattern " + patterns + "/stockinette.knit --gauge 18 --stitch-size 5", "leave out --stitch-size"},
       {"pattern " + patterns + "/stockinette.knit --needle 4.5", "--needle: needs the yarn knitted on it: give --yarn WEIGHT too"},
       {"pattern " + patterns + "/stockinette.knit --yarn dk --needle 4.5 --gauge 20", "--needle: sets the gauge: give --needle or --gauge, not both"},
       {"stitch " + kModels + "/tube.obj --auto-label --yarn dk --needle 4.5mm", "--needle '4.5mm': expected the needle's diameter in millimetres"},
       {"stitch " + kModels + "/tube.obj --auto-label --yarn dk --needle -1", "--needle -1: a needle's diameter must be a number of millimetres in (0, 50]"},
       {"pattern " + patterns + "/stockinette.knit --yarn dk --yarn-radius 1", "leave out --yarn-radius"},
       {"pattern " + patterns + "/stockinette.knit --yarn wool", "is not a yarn weight; one of lace, fingering"},
       {"pattern " + patterns + "/stockinette.knit --gauge 18x", "expected STITCHES or STITCHESxROWS"},
       {"stitch " + kModels + "/tube.obj --auto-label --gauge 0", "must be a number in (0, 1000]"}}};
  for (const auto& [args, message] : refusals) expect_refused(args, dir / "refused.skein", message);
}

// A flag whose help says "with --other" is refused without it, naming both, and nothing is written (it would
// otherwise change nothing, silently).
TEST(Cli, AFlagGivenWithoutTheFlagItGoesWithIsRefused) {
  ScratchDir dir;
  const std::string pattern = kPatterns + "/seed.knit";
  expect_refused("pattern " + pattern + " --max-steps 10", dir / "a.bcc", "--max-steps: goes with --relax");
  expect_refused("pattern " + pattern + " --free-period", dir / "b.bcc", "--free-period: goes with --relax");
  expect_refused("pattern " + pattern + " --relax --shear", dir / "c.bcc", "--shear: goes with --free-period");
  expect_refused("stitch " + kModels + "/swatch.obj --start-edge 3", dir / "d.skein", "--start-edge: goes with --auto-label or --field");
  // Given with it, the same flags are taken.
  const auto r = run_skein("pattern " + pattern + " --relax --max-steps 3 --no-audit -o " + (dir / "e.bcc").string());
  EXPECT_EQ(r.status, 0) << r.output;
}
