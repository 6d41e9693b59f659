#include "sweep.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <omp.h>
#include <unistd.h>

#include <spdlog/spdlog.h>

#include "command_line.hpp"
#include "commands.hpp"
#include "common/atomic_file.hpp"
#include "common/cpu_threads.hpp"
#include "common/error.hpp"
#include "common/input_file.hpp"
#include "json_keys.hpp"
#include "relax/yarn_relax.hpp"
#include "stitchmesh/fabric.hpp"
#include "stitchmesh/pattern.hpp"

namespace skein::cli {
namespace {

std::string number_text(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

/// A key's value as a list: an array as it is, one value as a list of one.
std::vector<json> list_of(const Keys& k, const std::string& key) {
  if (!k.has(key)) return {};
  const json& v = k.at(key);
  if (v.is_array()) {
    if (v.empty()) k.fail(k.name(key), "expected at least one value, found []");
    return {v.begin(), v.end()};
  }
  return {v};
}

std::vector<double> numbers(const Keys& k, const std::string& key, double low, double high, const std::string& as = "") {
  std::vector<double> out;
  for (const json& v : list_of(k, key)) {
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < low || v.get<double>() > high)
      k.fail(k.name(key), "expected numbers in [" + number_text(low) + ", " + number_text(high) + "]" + (as.empty() ? "" : " (as " + as + ")") + ", found " + v.dump());
    out.push_back(v.get<double>());
  }
  if (out.empty()) out.push_back(1);
  return out;
}

/// The "relax" object as `skein pattern` options (docs/sweeps.md lists the keys).
std::vector<std::string> relax_arguments(const Keys& k) {
  k.only({"method", "stop_rule", "free_period", "max_steps", "max_seconds", "tolerance", "force_tolerance", "period_tolerance", "period_method",
          "audit", "k_bend", "k_contact", "contact_spacing"});
  std::vector<std::string> args;
  const auto option = [&](const std::string& key, const std::string& flag, const std::string& value) {
    if (k.has(key)) args.insert(args.end(), {flag, value});
  };
  option("method", "--method", k.choice("method", "lbfgs", workflow::yarn_option("method").choices));
  option("stop_rule", "--stop-rule", k.choice("stop_rule", "force", workflow::yarn_option("stop_rule").choices));
  if (k.has("free_period") && !(k.at("free_period").is_boolean() && !k.at("free_period").get<bool>()))
    args.insert(args.end(), {"--free-period", k.choice("free_period", "x", {"x", "y", "xy"})});
  option("max_steps", "--max-steps", std::to_string(static_cast<long>(k.option("max_steps", 0))));
  option("max_seconds", "--max-seconds", number_text(k.option("max_seconds", 0)));
  option("tolerance", "--tolerance", number_text(k.option("tolerance", 0)));
  option("force_tolerance", "--force-tolerance", number_text(k.option("force_tolerance", 0)));
  if (k.has("period_tolerance") && std::find(args.begin(), args.end(), "--free-period") == args.end())
    k.fail(k.name("period_tolerance"), "is the free period's stop rule: give free_period too");
  option("period_tolerance", "--period-tolerance", number_text(k.number("period_tolerance", 0, 0, 1e6)));
  if (k.has("period_method") && std::find(args.begin(), args.end(), "--free-period") == args.end())
    k.fail(k.name("period_method"), "is how the free period relaxes: give free_period too");
  option("period_method", "--period-method", k.choice("period_method", "frame", {"frame", "bracket"}));
  if (k.has("period_method")) {
    // The combination checked by the relaxer's own rules, so that the file is refused before any case runs.
    relax::YarnRelaxOptions combination;
    combination.stop_rule = relax::parse_stop_rule(k.choice("stop_rule", "force", workflow::yarn_option("stop_rule").choices));
    const std::string axes = k.choice("free_period", "x", {"x", "y", "xy"});
    combination.period.free = true;
    combination.period.free_x = axes != "y";
    combination.period.free_y = axes != "x";
    combination.period.method = k.choice("period_method", "frame", {"frame", "bracket"}) == "bracket" ? relax::PeriodOptions::Method::Bracket
                                                                                                       : relax::PeriodOptions::Method::Frame;
    try {
      combination.validate();
    } catch (const Error& e) {
      k.fail(k.name("period_method"), e.place() + " " + e.rule());
    }
  }
  if (!k.flag("audit", true)) args.push_back("--no-audit");
  option("k_bend", "--k-bend", number_text(k.option("k_bend", 0)));
  option("k_contact", "--k-contact", number_text(k.option("k_contact", 0)));
  option("contact_spacing", "--contact-spacing", number_text(k.option("contact_spacing", 0)));
  return args;
}

std::string slug(const std::string& s) {
  std::string out;
  for (char c : s) out += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' ? c : '-';
  return out;
}

json read_report(const fs::path& path) {
  std::ifstream in(path);
  if (!in) return nullptr;
  try {
    return json::parse(in);
  } catch (const json::exception&) {
    return nullptr;
  }
}

/// The row of one case: what it asked and what its report says.
json case_row(const SweepCase& c, const std::string& label, int rank, int status, const json& report) {
  json row = {{"case", c.index}, {"label", label}, {"pattern", c.pattern.string()}, {"yarn", c.yarn}, {"gauge", c.gauge.empty() ? json(nullptr) : json(c.gauge)},
              {"gamma", c.gamma}, {"take_up", c.take_up}, {"width", c.width}, {"rank", rank}, {"exit_status", status}};
  if (report.is_null()) {
    row["stopped_by"] = status == -1 ? "not run" : "failed";
    return row;
  }
  for (const char* key : {"stopped_by", "converged", "steps", "energy", "force_residual", "pull_through_events", "wall_seconds", "control_points"})
    row[key] = report.value(key, json(nullptr));
  for (const char* period : {"free_period", "fixed_period"}) {
    if (!report.contains(period)) continue;
    const json& p = report[period];
    row["period"] = period == std::string("free_period") ? "free" : "fixed";
    for (const char* key : {"repeat_mm", "repeat_energy", "stress_over_bending", "loop_length_mm", "Kc", "Kw", "rows_apart"}) row[key] = p.value(key, json(nullptr));
    if (report.contains("periodic")) row["repeat"] = report["periodic"].value("repeat", json(nullptr));  // the relaxed repeat's stitches
    if (p.contains("gauge_per_10cm")) row["stitches_per_10cm"] = p["gauge_per_10cm"]["stitches"], row["rows_per_10cm"] = p["gauge_per_10cm"]["rows"];
    if (p.contains("against_asked")) row["stitches_against_gauge"] = p["against_asked"]["stitches"];  // the relaxed over the yarn's or given gauge
  }
  return row;
}

std::string csv_field(const json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) {
    std::string s = v.get<std::string>();
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return q + "\"";
  }
  if (v.is_array()) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : " x ") + csv_field(x);
    return s;
  }
  return v.dump();
}

const std::vector<std::string> kCsvColumns = {"case", "label", "width", "rank", "stopped_by", "converged", "steps", "wall_seconds", "energy", "repeat_energy", "stress_over_bending", "force_residual",
                                              "pull_through_events", "repeat_mm", "stitches_per_10cm", "stitches_against_gauge", "rows_per_10cm", "Kw", "Kc",
                                              "loop_length_mm"};

/// sweep.png by gnuplot (scripts/install-deps.sh installs gnuplot-nox): per case, the stitches per 10 cm of a
/// free period (or one repeat's energy of a fixed one) above, the time each took below, coloured by rank.
bool draw_chart(const Sweep& sweep, const std::vector<json>& rows, const fs::path& png) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    spdlog::warn("gnuplot is not installed: no {} (sweep.csv holds the figures)", png.string());
    return false;
  }
  bool gauge = false;
  for (const auto& r : rows) gauge |= r.value("period", "") == "free";  // a fixed period's gauge is the one imposed
  // Each bar is named by what varies in the sweep.
  std::map<std::string, std::set<std::string>> values;
  for (const auto& r : rows)
    for (const char* key : {"pattern", "yarn", "gauge", "gamma", "take_up", "width"}) values[key].insert(r.value(key, json(nullptr)).dump());
  const auto short_label = [&](const json& r) {
    std::string s;
    const auto add = [&](const char* key, const std::string& text) {
      if (values[key].size() > 1) s += (s.empty() ? "" : " ") + text;
    };
    add("pattern", fs::path(r["pattern"].get<std::string>()).stem().string());
    add("yarn", r["yarn"].is_string() ? r["yarn"].get<std::string>() : r["yarn"].is_number() ? "r " + number_text(r["yarn"].get<double>()) : "default yarn");
    add("gauge", r["gauge"].is_string() ? "gauge " + r["gauge"].get<std::string>() : "default gauge");
    add("gamma", "gamma " + number_text(r["gamma"].get<double>()));
    add("take_up", "take-up " + number_text(r["take_up"].get<double>()));
    add("width", "width " + number_text(r.value("width", 1.0)));
    return s.empty() ? std::to_string(r["case"].get<int>()) : s;
  };
  char dir_template[] = "/tmp/skein-sweep-XXXXXX";
  if (!mkdtemp(dir_template)) return false;
  const fs::path dir = dir_template, data = dir / "rows.dat", script = dir / "chart.gp", out = dir / "chart.png";
  {
    std::ofstream d(data);
    for (const auto& r : rows) {
      const json& top = gauge ? r.value("stitches_per_10cm", json(nullptr)) : r.value("repeat_energy", json(nullptr));
      const json& time = r.value("wall_seconds", json(nullptr));
      d << r["case"].get<int>() << " \"" << short_label(r) << "\" " << (top.is_number() ? top.dump() : "NaN") << " "
        << (time.is_number() ? time.dump() : "NaN") << " " << r["rank"].get<int>() << "\n";
    }
    std::ofstream g(script);
    g << "set terminal pngcairo size " << std::max(900, 60 * static_cast<int>(rows.size()) + 200) << ",900 font 'sans,10'\n"
      << "set output '" << out.string() << "'\nset multiplot layout 2,1 title '" << sweep.name << ": " << rows.size() << " cases'\n"
      << "set style fill solid 0.8\nset boxwidth 0.7\nset grid ytics\nunset key\nset xtics rotate by -40 left\n"
      << "set palette defined (0 '#4477aa', 1 '#ee6677', 2 '#228833', 3 '#ccbb44', 4 '#66ccee', 5 '#aa3377', 6 '#bbbbbb', 7 '#000000')\n"
      << "set cbrange [0:7]\nunset colorbox\nset bmargin 7\n"
      // A gauge as bars from 0; energies, which differ by tenths of a percent across a scan of widths, as points on
      // an axis of their own range.
      << (gauge ? "set yrange [0:*]\nset ylabel 'stitches per 10 cm (free period)'\nplot '" + data.string() + "' using 1:3:5:xtic(2) with boxes lc palette\n"
                : "set yrange [*:*]\nset offsets 0.5, 0.5, 0, 0\nset ylabel 'energy of one repeat (fixed period)'\nplot '" + data.string() +
                      "' using 1:3:5:xtic(2) with points pt 7 ps 1.5 lc palette\n")
      << "set offsets 0, 0, 0, 0\nset yrange [0:*]\nset ylabel 'seconds (colour: rank)'\nplot '" << data.string() << "' using 1:4:5:xtic(2) with boxes lc palette\nunset multiplot\n";
  }
  const bool ok = std::system(("gnuplot '" + script.string() + "' 2>" + (dir / "gnuplot.err").string()).c_str()) == 0 && fs::exists(out);
  if (ok) {
    write_file_atomically(png, [&](std::ostream& o) { o << std::ifstream(out, std::ios::binary).rdbuf(); });
  } else {
    spdlog::warn("gnuplot could not draw {} (see {})", png.string(), (dir / "gnuplot.err").string());
  }
  if (ok) fs::remove_all(dir);
  return ok;
}

}  // namespace

std::string SweepCase::label() const {
  char index_text[16];
  std::snprintf(index_text, sizeof index_text, "%03d", index);
  std::string s = std::string(index_text) + "-" + pattern.stem().string();
  if (yarn.is_string()) s += "-" + yarn.get<std::string>();
  if (yarn.is_number()) s += "-r" + number_text(yarn.get<double>());
  if (!gauge.empty()) s += "-gauge-" + gauge;
  s += "-gamma-" + number_text(gamma) + "-take-up-" + number_text(take_up);
  if (width != 1) s += "-width-" + number_text(width);
  return slug(s);
}

Sweep parse_sweep(const std::string& text, const fs::path& file) {
  const json j = parse_user_json(text, file);
  const Keys k(j, "", file);
  k.only({"name", "patterns", "yarns", "gauges", "gamma", "take_up", "widths", "relax", "threads", "pictures", "output"});
  Sweep s;
  s.file = file;
  s.name = k.text("name", file.stem().string());
  if (!k.has("patterns")) k.fail("patterns", "is required: the pattern files to relax");
  std::vector<fs::path> patterns;
  for (const json& p : list_of(k, "patterns")) {
    if (!p.is_string() || p.get<std::string>().empty()) k.fail("patterns", "expected pattern file names, found " + p.dump());
    const fs::path path = (file.parent_path() / p.get<std::string>()).lexically_normal();
    std::error_code error;
    if (!fs::exists(path, error)) k.fail("patterns", "names " + path.string() + ", which " + (error ? "cannot be read: " + error.message() : "does not exist"));
    const auto pattern = mesh::read_pattern(path);  // its own errors name its file and line
    if (pattern.format == mesh::PatternFormat::Woven && (k.has("yarns") || k.has("gauges")))
      k.fail("patterns", path.string() + " is woven: its yarn spacing is 4 yarn radii, so yarns and gauges do not apply");
    patterns.push_back(path);
  }
  std::vector<json> yarns = list_of(k, "yarns");
  for (const json& y : yarns) {
    if (y.is_string()) {
      try {
        mesh::find_yarn_weight(y.get<std::string>());
      } catch (const Error& e) {
        k.fail("yarns", e.rule());
      }
    } else if (!y.is_number() || !(y.get<double>() > 0 && y.get<double>() < 100)) {
      k.fail("yarns", "expected a yarn weight (\"dk\", \"worsted\", ...) or a radius in mm, found " + y.dump());
    }
  }
  if (yarns.empty()) yarns.push_back(nullptr);
  std::vector<std::string> gauges;
  for (const json& g : list_of(k, "gauges")) {
    if (!g.is_string()) k.fail("gauges", "expected gauges as text, stitches (x rows) per 10 cm (\"22\" or \"22x30\"), found " + g.dump());
    try {
      mesh::parse_gauge(g.get<std::string>(), "gauges");
    } catch (const Error& e) {
      k.fail("gauges", e.rule());
    }
    gauges.push_back(g.get<std::string>());
  }
  if (gauges.empty()) gauges.push_back("");
  const auto& take_up = workflow::yarn_option("take_up");  // the schema's range, as --take-up's
  const auto gammas = numbers(k, "gamma", relax::kMinGamma, relax::kMaxGamma, "--gamma"),
             take_ups = numbers(k, "take_up", take_up.low, take_up.high, take_up.flag());
  const auto widths = numbers(k, "widths", 0.1, 10, "--period's width");
  if (k.has("relax")) s.relax_arguments = relax_arguments(Keys(k.at("relax"), "relax", file));
  s.threads = static_cast<int>(k.integer("threads", 1, 1, 1024));
  s.pictures = k.flag("pictures", true);
  s.output = k.has("output") ? (file.parent_path() / k.text("output", "")).lexically_normal() : file.parent_path() / "out" / s.name;
  for (const auto& p : patterns)
    for (const auto& y : yarns)
      for (const auto& g : gauges)
        for (double gamma : gammas)
          for (double t : take_ups)
            for (double w : widths) s.cases.push_back({static_cast<int>(s.cases.size()), p, y, g, gamma, t, w});
  if (s.cases.size() > 100000) k.fail("patterns", std::to_string(s.cases.size()) + " cases: more than 100,000");
  return s;
}

Sweep read_sweep(const fs::path& file) {
  check_input_file(file, 16u << 20);
  std::ifstream in(file);
  if (!in) throw Error(file.string(), "", "cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  return parse_sweep(text.str(), file);
}

void prepare_sweep_output(const Sweep& sweep) {
  std::error_code error;
  fs::create_directories(sweep.output / "cases", error);
  if (error) throw Error(sweep.output.string(), "", "cannot be made: " + error.message());
  check_writable(sweep.output / "sweep.json");
  check_writable(sweep.output / "cases" / "x");
}

std::vector<std::string> case_command(const Sweep& sweep, const SweepCase& c, const fs::path& folder) {
  std::vector<std::string> args = {"skein", "-q", "pattern", c.pattern.string(), "--relax", "-o", (folder / "relaxed.bcc").string(),
                                   "--report", (folder / "report.json").string()};
  if (c.yarn.is_string()) args.insert(args.end(), {"--yarn", c.yarn.get<std::string>()});
  if (c.yarn.is_number()) args.insert(args.end(), {"--yarn-radius", number_text(c.yarn.get<double>())});
  if (!c.gauge.empty()) args.insert(args.end(), {"--gauge", c.gauge});
  args.insert(args.end(), {"--gamma", number_text(c.gamma), "--take-up", number_text(c.take_up)});
  if (c.width != 1) args.insert(args.end(), {"--period", number_text(c.width) + "x1"});
  args.insert(args.end(), sweep.relax_arguments.begin(), sweep.relax_arguments.end());
  if (sweep.pictures) args.insert(args.end(), {"--preview-png", (folder / "preview.png").string(), "--png-size", "400"});
  return args;
}

std::vector<json> run_sweep_cases(const Sweep& sweep, int rank, int size) {
  std::vector<json> rows;
  install_interrupt_handlers();  // between cases too: the rest are marked not run
  follow_free_cores(false);  // the sweep's threads per case, whatever else runs
  omp_set_num_threads(sweep.threads);
  for (const auto& c : sweep.cases) {
    if (c.index % size != rank) continue;
    const std::string label = c.label();
    if (interrupt_signal() != 0) {
      rows.push_back(case_row(c, label, rank, -1, nullptr));
      continue;
    }
    const fs::path folder = sweep.output / "cases" / label;
    fs::create_directories(folder);
    fs::remove(folder / "report.json");  // a report left by an earlier sweep is not this run's
    auto args = case_command(sweep, c, folder);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const auto level = spdlog::get_level();  // the case runs quiet (-q); the sweep's own log goes on as it was
    const int status = run_command_line(static_cast<int>(args.size()), argv.data());
    spdlog::set_level(level);
    json row = case_row(c, label, rank, status, read_report(folder / "report.json"));
    spdlog::info("case {} of {} on rank {}: {}: {}{}", c.index + 1, sweep.cases.size(), rank, label, row["stopped_by"].get<std::string>(),
                 row.contains("steps") ? fmt::format(" after {} steps, {:.1f} s", row["steps"].dump(), row.value("wall_seconds", 0.0)) : "");
    rows.push_back(std::move(row));
  }
  return rows;
}

int write_sweep(const Sweep& sweep, std::vector<json> rows, double seconds, int ranks) {
  std::sort(rows.begin(), rows.end(), [](const json& a, const json& b) { return a["case"].get<int>() < b["case"].get<int>(); });
  int converged = 0, failed = 0, not_run = 0, audited = 0;
  long pull_through = 0;
  for (const auto& r : rows) {
    const std::string by = r.value("stopped_by", "");
    converged += by == "converged";
    failed += by == "failed" || by == "diverged";
    not_run += by == "not run" || by == "interrupted";
    if (r.value("pull_through_events", json(nullptr)).is_number()) pull_through += r["pull_through_events"].get<long>(), ++audited;
  }
  const int signal = interrupt_signal();
  const std::string status = signal ? "interrupted" : failed ? "failed" : converged == static_cast<int>(rows.size()) ? "converged" : "done";
  json report = {{"sweep", sweep.name}, {"file", sweep.file.string()}, {"status", status}, {"ranks", ranks}, {"threads_per_case", sweep.threads},
                 {"cases", rows.size()}, {"converged", converged}, {"failed", failed}, {"not_run", not_run},
                 {"audited", audited}, {"pull_through_events", pull_through}, {"wall_seconds", seconds}, {"rows", rows}};
  write_json(report, (sweep.output / "sweep.json").string());
  write_file_atomically(sweep.output / "sweep.csv", [&](std::ostream& out) {
    for (size_t i = 0; i < kCsvColumns.size(); ++i) out << (i ? "," : "") << kCsvColumns[i];
    out << "\n";
    for (const auto& r : rows) {
      for (size_t i = 0; i < kCsvColumns.size(); ++i) out << (i ? "," : "") << csv_field(r.value(kCsvColumns[i], json(nullptr)));
      out << "\n";
    }
  });
  if (sweep.pictures && !rows.empty()) draw_chart(sweep, rows, sweep.output / "sweep.png");
  spdlog::info("sweep {}: {} cases on {} rank{} in {:.1f} s: {} converged, {} failed, {} not run; {} pull-through events in {} audited cases; wrote {}",
               sweep.name, rows.size(), ranks, ranks == 1 ? "" : "s", seconds, converged, failed, not_run, pull_through, audited,
               (sweep.output / "sweep.json").string());
  if (signal) return 128 + signal;
  return failed ? 2 : converged == static_cast<int>(rows.size()) ? 0 : 1;
}

}  // namespace skein::cli
