// skein sweep: relax each case of a sweep file (patterns x yarns x gauges x gamma x take-up) in this process: one report, 
#include "subcommand.hpp"

#include <memory>

#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "sweep.hpp"

using nlohmann::json;

namespace skein::cli {
namespace {

struct SweepCommand final : Subcommand {
  CLI::App* sweep_cmd = nullptr;
  std::string sweep_file, sweep_output;

  void declare(CLI::App& app) override {
    sweep_cmd = app.add_subcommand("sweep", "relax each case of a sweep file (patterns x yarns x gauges x gamma x take-up) in this process: one report, "
                                                  "table and chart (docs/sweeps.md; skein-mpi sweep shares the cases among MPI ranks)");
    sweep_cmd->add_option("SWEEP", sweep_file, "sweep file (.json)")->required();
    sweep_cmd->add_option("-o,--output", sweep_output, "output folder (default: the sweep's \"output\")");
  }

  bool chosen() const override { return sweep_cmd->parsed(); }

  int run(const Context&) override {
    auto sweep = read_sweep(sweep_file);
    if (!sweep_output.empty()) sweep.output = sweep_output;
    prepare_sweep_output(sweep);
    Stopwatch t;
    auto rows = run_sweep_cases(sweep, 0, 1);
    return write_sweep(sweep, std::move(rows), t.seconds(), 1);
  }
};

}  // namespace

std::unique_ptr<Subcommand> make_sweep_command() { return std::make_unique<SweepCommand>(); }

}  // namespace skein::cli
