// Yarn emission and yarn statistics on the bundled sweater. See docs/BENCHMARKS.md.
#include <benchmark/benchmark.h>

#include <string>

#include "stitchmesh/labeling.hpp"
#include "stitchmesh/tessellation.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "workflow/yarn_io.hpp"

namespace {
const std::string kModels = SKEIN_MODELS_DIR;

skein::mesh::StitchMesh sweater() {
  const auto m = skein::mesh::load_mesh(kModels + "/sweater.obj");
  const auto l = skein::mesh::auto_label(m, skein::mesh::default_start_edge(m));
  return skein::mesh::tessellate(m, l, skein::mesh::initial_values(m, l, {}));
}

void emit_sweater(benchmark::State& state) {
  const auto s = sweater();
  const auto& library = skein::mesh::StitchLibrary::bundled();
  size_t points = 0;
  for (auto _ : state) {
    const auto y = skein::mesh::emit_yarn(s, library, {});
    points = y.points.size();
    benchmark::DoNotOptimize(y.points.data());
  }
  state.counters["control_points"] = static_cast<double>(points);
  state.counters["stitch_faces"] = static_cast<double>(s.faces.size());
}

void yarn_stats_sweater(benchmark::State& state) {
  const auto y = skein::mesh::emit_yarn(sweater(), skein::mesh::StitchLibrary::bundled(), {});
  for (auto _ : state) benchmark::DoNotOptimize(skein::workflow::yarn_stats(y).min_segment_distance);
}
}  // namespace

BENCHMARK(emit_sweater)->Unit(benchmark::kMillisecond);
BENCHMARK(yarn_stats_sweater)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
