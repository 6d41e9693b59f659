// Sweeps (docs/sweeps.md): `skein sweep` in one process and `skein-mpi sweep` on 2 and 4 Open MPI ranks.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "testing.hpp"

using nlohmann::json;
using skein::testing::run_command;
using skein::testing::ScratchDir;

namespace {
const std::string kPatterns = SKEIN_PATTERNS_DIR;

std::string mpirun(int ranks) {
  return std::string(SKEIN_MPIEXEC) + " --allow-run-as-root --oversubscribe -np " + std::to_string(ranks) + " " + SKEIN_MPI_BIN;
}
std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
/// A small sweep: two patterns x two yarn radii x two take-ups, each relaxation capped at 150 steps.
std::string small_sweep(const std::string& output) {
  return R"({"name": "small", "patterns": [")" + kPatterns + R"(/stockinette.knit", ")" + kPatterns +
         R"(/rib-1x1.knit"], "yarns": [0.5, "dk"], "take_up": [1, 0.95],
             "relax": {"max_steps": 150, "free_period": "x"}, "output": ")" + output + R"("})";
}
/// The rows with what depends on the run (rank, time) taken out.
json comparable(const json& report) {
  json rows = report.at("rows");
  for (auto& r : rows) r.erase("rank"), r.erase("wall_seconds");
  return rows;
}
}  // namespace

TEST(Sweep, FileMistakesAreRefusedBeforeAnyWorkNamingTheKey) {
  ScratchDir dir;
  const std::string stock = kPatterns + "/stockinette.knit";
  for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
           {R"({"patterns": [")" + stock + R"("], "yarn": ["dk"]})", "key 'yarn': is not a key here"},
           {R"({"yarns": ["dk"]})", "key 'patterns': is required"},
           {R"({"patterns": ["nowhere.knit"]})", "nowhere.knit, which does not exist"},
           {R"({"patterns": [")" + stock + R"("], "yarns": ["chunky-ish"]})", "key 'yarns'"},
           {R"({"patterns": [")" + stock + R"("], "yarns": [-1]})", "key 'yarns': expected a yarn weight"},
           {R"({"patterns": [")" + stock + R"("], "gauges": ["many"]})", "key 'gauges'"},
           {R"({"patterns": [")" + stock + R"("], "take_up": [0]})", "key 'take_up': expected numbers in [0.1, 10] (as --take-up)"},
           {R"({"patterns": [")" + stock + R"("], "widths": [0.05]})", "key 'widths': expected numbers in [0.1, 10] (as --period's width)"},
           {R"({"patterns": [")" + stock + R"("], "relax": {"method": "rk4"}})", "key 'relax.method'"},
           {R"({"patterns": [")" + stock + R"("], "relax": {"steps": 5}})", "key 'relax.steps': is not a key here"},
           {R"({"patterns": [")" + stock + R"("], "relax": {"period_tolerance": 0.01}})", "key 'relax.period_tolerance': is the free period's stop rule"},
           {R"({"patterns": [")" + stock + R"("], "relax": {"period_method": "bracket"}})", "key 'relax.period_method': is how the free period relaxes"},
           {R"({"patterns": [")" + stock + R"("], "relax": {"free_period": "x", "period_method": "newton"}})", "key 'relax.period_method'"},
           {R"({"patterns": [")" + stock + R"("], "relax": {"free_period": "xy", "period_method": "bracket"}})", "bracket finds one free length"},
           {R"({"patterns": [")" + stock + R"("], "relax": {"free_period": "x", "period_method": "bracket", "stop_rule": "leaf"}})",
            "bracket judges each width by the force stop rule"},
           {R"({"patterns": [")" + stock + R"(", )", "is not valid JSON"},
           {R"({"patterns": [")" + stock + R"("], "gamma": [1E400]})", "number overflow"},  // found by CI's fuzzing
       }) {
    const auto file = dir.write("bad.json", text);
    const auto out = dir / "out";
    const auto r = run_command(std::string(SKEIN_BIN) + " sweep " + file.string() + " -o " + out.string());
    EXPECT_EQ(r.status, 2) << text << "\n" << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << text << "\n" << r.output;
    EXPECT_NE(r.output.find(file.string()), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << text;
    // On MPI ranks: every rank finds the same mistake, one says it, none waits for another.
    if (message == "key 'patterns': is required") {
      const auto m = run_command("timeout 60 " + mpirun(2) + " sweep " + file.string() + " -o " + out.string());
      EXPECT_NE(m.output.find(message), std::string::npos) << m.output;
      EXPECT_EQ(m.output.find(message), m.output.rfind(message)) << "said once\n" << m.output;
      EXPECT_NE(m.status, 0);
      EXPECT_NE(m.status, 124) << "hung";
      EXPECT_FALSE(std::filesystem::exists(out));
    }
  }
}

TEST(Sweep, OneProcessAndTwoAndFourRanksRelaxEveryCaseToTheSameResult) {
  ScratchDir dir;
  const auto one = dir.write("one.json", small_sweep((dir / "one").string()));
  const auto r1 = run_command(std::string(SKEIN_BIN) + " sweep " + one.string());
  ASSERT_EQ(r1.status, 1) << "capped at 150 steps: not converged\n" << r1.output;
  const json report1 = json::parse(slurp(dir / "one" / "sweep.json"));
  ASSERT_EQ(report1.at("cases"), 8);
  ASSERT_EQ(report1.at("rows").size(), 8u);
  EXPECT_EQ(report1.at("ranks"), 1);
  EXPECT_EQ(report1.at("audited"), 8);
  EXPECT_EQ(report1.at("pull_through_events"), 0);
  for (const auto& row : report1.at("rows")) {
    EXPECT_EQ(row.at("stopped_by"), "step cap") << row.dump();
    EXPECT_EQ(row.at("steps"), 150);
    EXPECT_GT(row.at("stitches_per_10cm").get<double>(), 10) << row.dump();  // a free width: the relaxed gauge
    EXPECT_TRUE(std::filesystem::exists(dir / "one" / "cases" / row.at("label").get<std::string>() / "preview.png"));
  }
  // The table: a header and one line per case; the chart.
  std::istringstream csv(slurp(dir / "one" / "sweep.csv"));
  std::string line;
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  EXPECT_EQ(lines, 9);
  EXPECT_GT(std::filesystem::file_size(dir / "one" / "sweep.png"), 1000u);

  for (int ranks : {2, 4}) {
    const std::string name = "ranks" + std::to_string(ranks);
    const auto file = dir.write(name + ".json", small_sweep((dir / name).string()));
    const auto r = run_command("timeout 300 " + mpirun(ranks) + " sweep " + file.string());
    EXPECT_NE(r.status, 124) << "hung\n" << r.output;
    const json report = json::parse(slurp(dir / name / "sweep.json"));
    EXPECT_EQ(report.at("ranks"), ranks);
    EXPECT_EQ(comparable(report), comparable(report1)) << ranks << " ranks";
    std::set<int> used;
    for (const auto& row : report.at("rows")) {
      used.insert(row.at("rank").get<int>());
      EXPECT_EQ(row.at("rank"), row.at("case").get<int>() % ranks);
      // The same relaxed yarn, byte for byte (one thread per case, whatever the rank count).
      const std::string label = row.at("label");
      EXPECT_EQ(slurp(dir / name / "cases" / label / "relaxed.bcc"), slurp(dir / "one" / "cases" / label / "relaxed.bcc")) << label;
    }
    EXPECT_EQ(static_cast<int>(used.size()), ranks);
  }
}

// A sweep over repeat widths (docs/sweeps.md, `widths`): each case relaxes the repeat held at its width (`--period
// Wx1`), named in its label, and its row gives one repeat's energy and stress there; with a free period the width
// is where each case starts.
TEST(Sweep, WidthsHoldTheRepeatAtEachWidthOrStartItThere) {
  ScratchDir dir;
  const auto file = dir.write("widths.json", R"({"patterns": [")" + kPatterns + R"(/stockinette.knit"], "widths": [0.9, 1],
      "relax": {"max_steps": 60, "audit": false}, "pictures": false, "output": ")" + (dir / "w").string() + R"("})");
  const auto r = run_command(std::string(SKEIN_BIN) + " sweep " + file.string());
  ASSERT_LE(r.status, 1) << r.output;
  const json rows = json::parse(slurp(dir / "w" / "sweep.json")).at("rows");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("width"), 0.9);
  EXPECT_NE(rows[0].at("label").get<std::string>().find("width-0.9"), std::string::npos) << rows[0].dump();
  EXPECT_EQ(rows[1].at("label").get<std::string>().find("width"), std::string::npos) << "the default width is not named";
  EXPECT_EQ(rows[0].at("period"), "fixed");
  EXPECT_NEAR(rows[0].at("repeat_mm")[0].get<double>(), 0.9 * rows[1].at("repeat_mm")[0].get<double>(), 1e-9);  // held where asked
  EXPECT_TRUE(rows[0].at("repeat_energy").is_number());
  EXPECT_EQ(rows[0].at("stress_over_bending").size(), 3u);
  // With a free period the width is the start: the relaxed width moves from it (here by the bracket search, which
  // converges under tension).
  const auto free_file = dir.write("free.json", R"({"patterns": [")" + kPatterns + R"(/stockinette.knit"], "widths": 0.85, "take_up": 0.8,
      "relax": {"max_steps": 8000, "audit": false, "free_period": "x", "period_method": "bracket"}, "pictures": false, "output": ")" +
      (dir / "f").string() + R"("})");
  ASSERT_LE(run_command(std::string(SKEIN_BIN) + " sweep " + free_file.string()).status, 1);
  const json free_row = json::parse(slurp(dir / "f" / "sweep.json")).at("rows").at(0);
  EXPECT_EQ(free_row.at("period"), "free");
  EXPECT_EQ(free_row.at("stopped_by"), "converged");
  EXPECT_NE(free_row.at("repeat_mm")[0].get<double>(), 0.85 * rows[1].at("repeat_mm")[0].get<double>());
}
