// skein-mpi: a sweep's cases shared among Open MPI ranks (issue 31; docs/sweeps.md). Every rank reads the
// sweep file (each finds the same error, if any, so none waits for another); rank 0 makes the output folder and
// says whether it could; case i runs on rank i mod N, each through skein's own command line; the rows are
// gathered to rank 0, which writes the report, the table and the chart after MPI is finalized.
#include <string>
#include <vector>

#include <mpi.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "commands.hpp"
#include "common/cpu_threads.hpp"
#include "common/error.hpp"
#include "skein/config.hpp"
#include "sweep.hpp"

using nlohmann::json;
using namespace skein;

namespace {

/// Rank 0 receives every rank's rows (each rank's JSON array as text).
std::vector<json> gather_rows(const std::vector<json>& mine, int rank, int size) {
  const std::string text = json(mine).dump();
  int length = static_cast<int>(text.size());
  std::vector<int> lengths(rank == 0 ? size : 0), offsets(rank == 0 ? size : 0);
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::string all;
  if (rank == 0) {
    for (int r = 1; r < size; ++r) offsets[r] = offsets[r - 1] + lengths[r - 1];
    all.resize(static_cast<size_t>(offsets[size - 1] + lengths[size - 1]));
  }
  MPI_Gatherv(text.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0, MPI_COMM_WORLD);
  std::vector<json> rows;
  for (int r = 0; rank == 0 && r < size; ++r)
    for (auto& row : json::parse(all.substr(offsets[r], lengths[r]))) rows.push_back(std::move(row));
  return rows;
}

}  // namespace

int main(int argc, char** argv) {
  skein::wait_passively(argv);  // issue 28: before MPI_Init, so that the program executed again is the one MPI meets
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  spdlog::set_default_logger(spdlog::stderr_color_mt("skein"));
  spdlog::set_pattern("[%H:%M:%S.%e] %^%l%$ %v");

  CLI::App app{"skein-mpi: skein's sweeps shared among MPI ranks (mpirun -np N skein-mpi sweep FILE; docs/sweeps.md)"};
  app.set_version_flag("--version", SKEIN_VERSION);
  app.require_subcommand(1);
  auto* sweep_cmd = app.add_subcommand("sweep", "relax each case of a sweep file, case i on rank i mod N: one report, table and chart");
  std::string file, output;
  sweep_cmd->add_option("SWEEP", file, "sweep file (.json)")->required();
  sweep_cmd->add_option("-o,--output", output, "output folder (default: the sweep's \"output\")");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int status = rank == 0 ? app.exit(e) : (e.get_exit_code() != 0 ? e.get_exit_code() : 0);
    MPI_Finalize();
    return status;
  }

  cli::Sweep sweep;
  std::string error;
  try {
    sweep = cli::read_sweep(file);
    if (!output.empty()) sweep.output = output;
  } catch (const Error& e) {
    error = e.what();
  }
  int ready = error.empty() ? 1 : 0;
  if (rank == 0 && ready) {
    try {
      cli::prepare_sweep_output(sweep);
    } catch (const Error& e) {
      error = e.what(), ready = 0;
    }
  }
  MPI_Bcast(&ready, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (!ready) {
    if (rank == 0) spdlog::error("{}", error);
    MPI_Finalize();
    return 2;
  }
  if (rank == 0) spdlog::info("sweep {}: {} cases on {} rank{}, {} thread{} each", sweep.name, sweep.cases.size(), size, size == 1 ? "" : "s",
                              sweep.threads, sweep.threads == 1 ? "" : "s");
  cli::Stopwatch clock;
  const auto mine = cli::run_sweep_cases(sweep, rank, size);
  auto rows = gather_rows(mine, rank, size);
  const double seconds = clock.seconds();
  MPI_Finalize();
  if (rank != 0) return cli::interrupt_signal() ? 128 + cli::interrupt_signal() : 0;
  return cli::write_sweep(sweep, std::move(rows), seconds, size);
}
