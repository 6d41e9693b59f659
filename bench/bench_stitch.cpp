// Load + label + tessellate the bundled garments (the foundation of every run). See docs/BENCHMARKS.md.
#include <benchmark/benchmark.h>

#include <string>

#include "stitchmesh/input_mesh.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/tessellation.hpp"

namespace {
const std::string kModels = SKEIN_MODELS_DIR;

void load_label_tessellate(benchmark::State& state, const std::string& name) {
  size_t faces = 0;
  for (auto _ : state) {
    const auto m = skein::mesh::load_mesh(kModels + "/" + name + ".obj");
    const auto l = skein::mesh::auto_label(m, skein::mesh::default_start_edge(m));
    const auto s = skein::mesh::tessellate(m, l, skein::mesh::initial_values(m, l, {}));
    faces = s.faces.size();
    benchmark::DoNotOptimize(s.vertices.data());
  }
  state.counters["stitch_faces"] = static_cast<double>(faces);
}

void tessellate_only(benchmark::State& state, const std::string& name) {
  const auto m = skein::mesh::load_mesh(kModels + "/" + name + ".obj");
  const auto l = skein::mesh::auto_label(m, skein::mesh::default_start_edge(m));
  const auto v = skein::mesh::initial_values(m, l, {});
  for (auto _ : state) benchmark::DoNotOptimize(skein::mesh::tessellate(m, l, v).faces.data());
}
}  // namespace

BENCHMARK_CAPTURE(load_label_tessellate, sweater, std::string("sweater"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(load_label_tessellate, mitten, std::string("mitten"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(tessellate_only, sweater, std::string("sweater"))->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
