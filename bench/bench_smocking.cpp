// The smocking embedding (Zhou 2024 Algorithm 1, with eq. 1b projected; docs/smocking.md): each bundled pattern
// at its own gamma, and zigzags grown to the paper's grid sizes (Table 2: 288 to 1,363 grid points) and past them.
#include <filesystem>
#include <string>

#include <benchmark/benchmark.h>

#include "smocking/smocking_embed.hpp"

using namespace skein::smocking;

namespace {

void embed_file(benchmark::State& state, const std::string& name) {
  const auto pattern = read_smocking_pattern(std::filesystem::path(SKEIN_PATTERNS_DIR) / "smocking" / (name + ".smock"));
  EmbedOptions options;
  options.gamma = pattern.gamma;
  options.pull_along_stitches = name == "spiral";
  Embedding e;
  for (auto _ : state) benchmark::DoNotOptimize(e = embed(pattern, options));
  state.counters["grid_points"] = pattern.num_points();
  state.counters["stitches"] = pattern.num_stitches();
  state.counters["iterations"] = e.iterations;
  state.counters["shrinkage"] = e.shrinkage();
}

/// A zigzag thread every second row of a columns x rows grid (10 mm apart), pulled to 0.3 at a thickness of 1 mm
/// (the default, 1 % of the longer side, would pull the larger grids' threads taut above 0.3).
void embed_zigzag(benchmark::State& state) {
  const int columns = static_cast<int>(state.range(0)), rows = static_cast<int>(state.range(1));
  const std::string text = "format smocking\ngrid " + std::to_string(columns) + " " + std::to_string(rows) + "\nwalk 0,1 1,-1 1,1 x" +
                           std::to_string(columns - 1) + "\nrepeat 0,2 x" + std::to_string((rows - 1) / 2) + "\n";
  const auto pattern = parse_smocking_pattern(text, "zigzag");
  EmbedOptions options;
  options.thickness = 1;
  Embedding e;
  for (auto _ : state) benchmark::DoNotOptimize(e = embed(pattern, options));
  state.counters["grid_points"] = pattern.num_points();
  state.counters["stitches"] = pattern.num_stitches();
  state.counters["iterations"] = e.iterations;
  state.counters["settle_sweeps"] = e.settle_iterations;
  state.counters["shrinkage"] = e.shrinkage();
}

}  // namespace

#define SKEIN_SMOCKING_FILE(name) BENCHMARK_CAPTURE(embed_file, name, #name)->Unit(benchmark::kMillisecond);
SKEIN_SMOCKING_FILE(zigzag)
SKEIN_SMOCKING_FILE(diamonds)
SKEIN_SMOCKING_FILE(castle)
SKEIN_SMOCKING_FILE(waves)
SKEIN_SMOCKING_FILE(spiral)
SKEIN_SMOCKING_FILE(english-pleats)
SKEIN_SMOCKING_FILE(canadian-lattice)
SKEIN_SMOCKING_FILE(canadian-braid)
BENCHMARK(embed_zigzag)->Args({19, 16})->Args({40, 22})->Args({47, 29})->Args({101, 101})->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
