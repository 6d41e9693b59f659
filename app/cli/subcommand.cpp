#include "subcommand.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/error.hpp"

namespace skein::cli {

std::unique_ptr<Subcommand> make_stitch_command();
std::unique_ptr<Subcommand> make_label_command();
std::unique_ptr<Subcommand> make_edit_command();
std::unique_ptr<Subcommand> make_yarn_command();
std::unique_ptr<Subcommand> make_relax_mesh_command();
std::unique_ptr<Subcommand> make_relax_yarn_command();
std::unique_ptr<Subcommand> make_pattern_command();
std::unique_ptr<Subcommand> make_smock_command();
std::unique_ptr<Subcommand> make_weave_command();
std::unique_ptr<Subcommand> make_audit_command();
std::unique_ptr<Subcommand> make_run_command();
std::unique_ptr<Subcommand> make_sweep_command();
std::unique_ptr<Subcommand> make_stats_command();
std::unique_ptr<Subcommand> make_render_command();
std::unique_ptr<Subcommand> make_devices_command();

std::vector<std::unique_ptr<Subcommand>> make_subcommands() {
  std::vector<std::unique_ptr<Subcommand>> out;
  out.push_back(make_stitch_command());
  out.push_back(make_label_command());
  out.push_back(make_edit_command());
  out.push_back(make_yarn_command());
  out.push_back(make_relax_mesh_command());
  out.push_back(make_relax_yarn_command());
  out.push_back(make_pattern_command());
  out.push_back(make_smock_command());
  out.push_back(make_weave_command());
  out.push_back(make_audit_command());
  out.push_back(make_run_command());
  out.push_back(make_sweep_command());
  out.push_back(make_stats_command());
  out.push_back(make_render_command());
  out.push_back(make_devices_command());
  return out;
}

/// A number flag's check in the words every skein message uses: "expected a (whole) number, found TEXT" or "must be
/// in [LOW, HIGH] UNIT, found TEXT (WHY)"; `allows` says whether a number is in range, `range` how to name it.
CLI::Validator number_check(bool whole, std::function<bool(double)> allows, std::string range, std::string unit, std::string why) {
  const std::string shown = range + (unit.empty() ? "" : " " + unit);
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        const std::string expected = whole ? "expected a whole number, found " : "expected a number, found ";
        if (text.empty()) return expected + "nothing";
        double x = 0;
        try {
          size_t used = 0;
          x = std::stod(text, &used);
          if (used != text.size()) return expected + text;
        } catch (const std::exception&) {
          return expected + text;
        }
        if (!std::isfinite(x) || (whole && x != std::floor(x))) return expected + text;
        if (!allows(x)) return "must be in " + shown + ", found " + text + (why.empty() ? "" : " (" + why + ")");
        if (whole) text = std::to_string(static_cast<long long>(x));  // 1e3 and 3.0 as the integer the option stores
        return {};
      },
      range);
}

/// A number in [low, high] (inclusive).
CLI::Validator in_range(double low, double high, const std::string& unit) {
  const auto text = [](double v) {
    std::ostringstream out;
    out << v;
    return out.str();
  };
  return number_check(false, [=](double x) { return x >= low && x <= high; }, "[" + text(low) + ", " + text(high) + "]", unit);
}

/// A whole number in [low, high]; give it to `transform`, not `check`, so that 1e3 and 3.0 reach the option as 1000 and 3.
CLI::Validator whole_in_range(long low, long high, const std::string& unit) {
  return number_check(true, [=](double x) { return x >= low && x <= high; }, "[" + std::to_string(low) + ", " + std::to_string(high) + "]", unit);
}

/// A positive number (a radius, a size): the value named when it is not one.
CLI::Validator positive() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          size_t used = 0;
          const double x = std::stod(text, &used);
          if (used == text.size() && std::isfinite(x) && x > 0) return {};
        } catch (const std::exception&) {
        }
        return "expected a positive number, found " + text;
      },
      "> 0");
}

void add_fabric(CLI::App* cmd, FabricChoice& fabric, const char* yarn_sets, bool gauge) {
  cmd->add_option("--yarn", fabric.yarn, std::string("yarn weight (lace, fingering, sport, dk, worsted, bulky, super-bulky, jumbo or the CYC number 0-7): ") + yarn_sets);
  if (!gauge) return;
  cmd->add_option("--gauge", fabric.gauge, "stockinette gauge, stitches (x rows) in 10 cm, e.g. 18x24 (rows: 1.3 x the stitches when left out): sets the stitch size");
  cmd->add_option("--needle", fabric.needle, "needle diameter [mm], with --yarn: the gauge of that yarn knitted on it (a stitch is one wrap of yarn around the needle); sets the stitch size");
}

bool size_given(const CLI::App* cmd) { return cmd->count("--stitch-size") + cmd->count("--stitch-height") > 0; }

void check_companions(const CLI::App& app) {
  for (const CLI::App* command : app.get_subcommands()) {
    for (const CLI::Option* option : command->get_options()) {
      const std::string& help = option->get_description();
      if (option->count() == 0 || help.rfind("with --", 0) != 0) continue;
      // "with --a: ...", "with --a or --b: ...": the flags named before the colon (or the first comma or space after one).
      const std::string names = help.substr(5, help.find_first_of(":;,(", 5) - 5);
      std::vector<std::string> companions;
      for (size_t at = names.find("--"); at != std::string::npos; at = names.find("--", at + 2))
        companions.push_back(names.substr(at, names.find(' ', at) - at));
      const bool given = std::any_of(companions.begin(), companions.end(), [&](const std::string& flag) {
        const CLI::Option* companion = command->get_option_no_throw(flag);
        return companion == nullptr || companion->count() > 0;  // a name that is not this command's flag: not checked here
      });
      if (!given) {
        std::string wanted = companions.front();
        for (size_t i = 1; i < companions.size(); ++i) wanted += " or " + companions[i];
        throw Error("", option->get_name(), "goes with " + wanted + "; without it, it would change nothing");
      }
    }
  }
}

}  // namespace skein::cli
