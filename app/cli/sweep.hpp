#pragma once
// Sweeps (issue 31; docs/sweeps.md): one file lists patterns x yarns x gauges x gamma x take-up; every case is
// one `skein pattern --relax` run, the cases are shared among processes (skein-mpi: MPI ranks; skein sweep:
// one process) and gathered into one report, one table and one chart.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace skein::cli {

/// One case: a pattern relaxed with one yarn, gauge, gamma and take-up.
struct SweepCase {
  int index = 0;
  std::filesystem::path pattern;
  nlohmann::json yarn;   ///< a weight class name (--yarn), a radius in mm (--yarn-radius), or null: the default
  std::string gauge;     ///< "S" or "SxR" stitches (x rows) per 10 cm (--gauge); empty: the yarn's or the default
  double gamma = 1, take_up = 1;
  double width = 1;      ///< the repeat's width × its emitted width (--period Wx1): fixed, or a free period's start

  /// Names the case in logs, tables and its folder: "003-rib-2x2-dk-gauge-22x28-gamma-1-take-up-0.9".
  std::string label() const;
};

struct Sweep {
  std::filesystem::path file;    ///< the sweep file; its relative paths are relative to its folder
  std::string name;
  std::vector<SweepCase> cases;
  std::vector<std::string> relax_arguments;  ///< `skein pattern` options every case gets, from the "relax" object
  int threads = 1;               ///< OpenMP threads per case (a fixed count: the same results on any number of ranks)
  bool pictures = true;
  std::filesystem::path output;  ///< the folder every output goes to
};

/// Parses a sweep and reads each of its patterns; throws skein::Error naming `file`, the key and what was
/// expected (unknown keys included).
Sweep parse_sweep(const std::string& text, const std::filesystem::path& file);
Sweep read_sweep(const std::filesystem::path& file);

/// Makes the output folder and its cases/ folder and checks they can be written; throws skein::Error.
void prepare_sweep_output(const Sweep& sweep);

/// The `skein` command line that runs one case, writing into `folder` (argv[0] included).
std::vector<std::string> case_command(const Sweep& sweep, const SweepCase& c, const std::filesystem::path& folder);

/// Runs the cases whose index is `rank` modulo `size`, in order, in this process, and returns one result row
/// each (docs/sweeps.md). Stops early, marking the rest not run, when SIGINT or SIGTERM arrives.
std::vector<nlohmann::json> run_sweep_cases(const Sweep& sweep, int rank, int size);

/// Writes OUTPUT/sweep.json (the rows by case, with totals), sweep.csv and, when pictures are asked and
/// gnuplot is there, sweep.png; each atomically. Returns the exit status: 0 every case converged, 1 some
/// did not, 2 some failed, 128 + signal when interrupted.
int write_sweep(const Sweep& sweep, std::vector<nlohmann::json> rows, double seconds, int ranks);

}  // namespace skein::cli
