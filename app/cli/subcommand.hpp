#pragma once
// One `skein` subcommand (a file each: stitch_command.cpp, relax_yarn_command.cpp, ...) and what their flags
// share: checks that speak as the yarn options' schema does, the schema's own flags, the yarn and gauge flags.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "workflow/yarn_options.hpp"

namespace skein::cli {

/// What every subcommand's run sees of the command line above it.
struct Context {
  bool quiet = false;  ///< -q: warnings and errors only (and no progress bar)
};

/// A subcommand: its flags declared on skein's CLI::App, and its run when the command line chose it. Thin: it
/// parses, calls the library and prints what happened.
class Subcommand {
public:
  virtual ~Subcommand() = default;
  virtual void declare(CLI::App& app) = 0;  ///< adds the subcommand (or two) and its flags to `app`
  virtual bool chosen() const = 0;          ///< after parsing: the command line named it
  virtual int run(const Context& context) = 0;  ///< the exit status (command_line.hpp); throws skein::Error
};

/// Every subcommand, in the order `skein --help` lists them.
std::vector<std::unique_ptr<Subcommand>> make_subcommands();

/// A number flag's check in the words every skein message uses: "expected a (whole) number, found TEXT" or "must be
/// in RANGE UNIT, found TEXT (WHY)"; `allows` says whether a number is in range, `range` how to name it.
CLI::Validator number_check(bool whole, std::function<bool(double)> allows, std::string range, std::string unit = "", std::string why = "");
/// A number in [low, high] (inclusive).
CLI::Validator in_range(double low, double high, const std::string& unit = "");
/// A whole number in [low, high]; give it to `transform`, not `check`, so that 1e3 and 3.0 reach the option as 1000 and 3.
CLI::Validator whole_in_range(long low, long high, const std::string& unit = "");
/// A positive number (a radius, a size): the value named when it is not one.
CLI::Validator positive();
/// --yarn, and with `gauge` --gauge and --needle: the yarn and the fabric as a knitter gives them (docs/yarn.md).
void add_fabric(CLI::App* cmd, FabricChoice& fabric, const char* yarn_sets, bool gauge);
/// Whether --stitch-size or --stitch-height was given to `cmd`.
bool size_given(const CLI::App* cmd);
/// A flag whose help begins "with --other: ..." (or "with --a or --b: ...") given without its companion: a skein::Error
/// naming both, rather than a flag that silently changes nothing.
void check_companions(const CLI::App& app);

/// A yarn option's flag as the schema declares it (relax/yarn_options.hpp): its help, unit and range, the same as
/// in jobs, sweeps, projects and the app. `prefix` says when it applies ("with --relax: "), `suffix` adds what only this command does.
template <class T>
CLI::Option* add_yarn_option(CLI::App* app, const std::string& key, T& target, const std::string& prefix = "", const std::string& suffix = "") {
  const auto& spec = workflow::yarn_option(key);
  const std::string unit = spec.unit.empty() ? "" : " [" + spec.unit + "]";
  auto* option = app->add_option(spec.flag(), target, prefix + spec.help + unit + suffix);
  if (spec.kind == workflow::YarnOption::Kind::Choice) return option->check(CLI::IsMember(spec.choices))->capture_default_str();
  const bool whole = spec.kind == workflow::YarnOption::Kind::Integer;
  const auto check = number_check(whole, [&spec](double x) { return spec.allows(x); }, spec.range(), spec.unit, spec.help);
  whole ? option->transform(check) : option->check(check);  // a transform may hand 1e3 on as 1000
  return option->capture_default_str();
}

}  // namespace skein::cli
