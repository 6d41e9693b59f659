// skein run: run a job file: the whole pipeline from a mesh to relaxed yarn, unattended (docs/jobs.md)
#include "subcommand.hpp"

#include <cstdio>
#include <memory>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "job.hpp"

using nlohmann::json;

namespace skein::cli {
namespace {

struct RunCommand final : Subcommand {
  CLI::App* run_cmd = nullptr;
  std::string run_file, run_output;
  bool run_resume = false;
  double run_seconds = -1;

  void declare(CLI::App& app) override {
    run_cmd = app.add_subcommand("run", "run a job file: the whole pipeline from a mesh to relaxed yarn, unattended (docs/jobs.md)");
    run_cmd->add_option("JOB", run_file, "job file (.json)")->required();
    run_cmd->add_option("-o,--output", run_output, "output folder (default: the job's \"output\")");
    run_cmd->add_flag("--resume", run_resume, "go on from the yarn checkpoint in the output folder");
    run_cmd->add_option("--yarn-seconds", run_seconds, "wall-time cap of the yarn relaxation [s], in place of the job's (0: none; for overnight runs)");
  }

  bool chosen() const override { return run_cmd->parsed(); }

  int run(const Context& context) override {
    auto job = read_job(run_file);
    if (!run_output.empty()) job.output = run_output;
    if (run_seconds >= 0 && job.relax_yarn) job.relax_yarn->max_seconds = run_seconds;
    return run_job(job, run_resume, !context.quiet && isatty(fileno(stderr)));
  }
};

}  // namespace

std::unique_ptr<Subcommand> make_run_command() { return std::make_unique<RunCommand>(); }

}  // namespace skein::cli
