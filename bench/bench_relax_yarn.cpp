// The parts of one yarn-relaxation step on emitted (unrelaxed) yarn of the bundled models: forces, contact
// pairs, the pull-through guard and the auditor. Whole runs are measured with `skein relax-yarn` (docs/BENCHMARKS.md).
#include <benchmark/benchmark.h>

#include <map>
#include <string>

#include "relax/pull_through_guard.hpp"
#include "relax/yarn_audit.hpp"
#include "relax/yarn_relax.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/tessellation.hpp"
#include "stitchmesh/yarn_emission.hpp"

namespace {
using namespace skein;
const std::string kModels = SKEIN_MODELS_DIR;
const char* kNames[] = {"swatch", "mitten", "sweater"};

/// The model's emitted yarn; `spacing` > 0: adaptive contact samples (relax::ContactSampling).
const relax::YarnSystem& system_of(int model, double spacing = 0) {
  static std::map<std::pair<int, double>, relax::YarnSystem> cache;
  if (!cache.count({model, spacing})) {
    const auto m = mesh::load_mesh(kModels + "/" + kNames[model] + ".obj");
    const auto l = mesh::auto_label(m, mesh::default_start_edge(m));
    const auto s = mesh::tessellate(m, l, mesh::initial_values(m, l, {}));
    cache.emplace(std::make_pair(model, spacing), relax::make_yarn_system(mesh::emit_yarn(s, mesh::StitchLibrary::bundled(), {}), 1.0, {}, {spacing}));
  }
  return cache.at({model, spacing});
}

void label(benchmark::State& state, const relax::YarnSystem& system) {
  state.SetLabel(kNames[state.range(0)]);
  state.counters["control_points"] = system.num_points();
  state.counters["us_per_point"] = benchmark::Counter(static_cast<double>(system.num_points()) * state.iterations(),
                                                      benchmark::Counter::kIsRate | benchmark::Counter::kInvert, benchmark::Counter::kIs1000);
}

/// range(1): contact spacing in tenths of r (0: Leaf's rule).
void forces(benchmark::State& state) {
  const auto& system = system_of(static_cast<int>(state.range(0)), state.range(1) / 10.0);
  const relax::YarnRelaxOptions options;
  const auto pairs = relax::find_contact_pairs(system, system.points, options.contact_margin * system.radius);
  Eigen::Matrix3Xd grad, damping, velocities = Eigen::Matrix3Xd::Zero(3, system.num_points());
  for (auto _ : state) benchmark::DoNotOptimize(relax::yarn_energy(system, options.params, pairs, system.points, grad, &velocities, &damping));
  state.counters["contact_pairs"] = static_cast<double>(pairs.pairs());
  state.counters["contact_samples"] = system.sample_start.back() + system.contact_samples.back();
  label(state, system);
}

void contact_pairs(benchmark::State& state) {
  const auto& system = system_of(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(relax::find_contact_pairs(system, system.points, system.radius).partner.data());
  label(state, system);
}

/// One guard check of a step that moves every point by up to ε r in a fixed pseudo-random direction;
/// range(1) = 1 keeps the safe bounds (later steps skip), 0 tests every pair every step.
void guard(benchmark::State& state) {
  const auto& system = system_of(static_cast<int>(state.range(0)));
  relax::GuardOptions options;
  options.safe_bounds = state.range(1) != 0;
  relax::PullThroughGuard guard(system, options);
  guard.reset(relax::find_contact_pairs(system, system.points, system.radius));
  Eigen::Matrix3Xd step = Eigen::Matrix3Xd::Random(3, system.num_points()) * (0.05 * system.radius);
  for (auto _ : state) {
    Eigen::Matrix3Xd delta = step;
    benchmark::DoNotOptimize(guard.accept(system.points, delta));
    step = -step;  // back and forth, so the yarn stays where it is
  }
  state.counters["pairs_tested_per_step"] = static_cast<double>(guard.counters().pairs_tested) / guard.counters().steps;
  label(state, system);
}

/// The exact auditor (yarn_audit.hpp) on a step of random moves of 0.05 r.
void audit(benchmark::State& state) {
  const auto& system = system_of(static_cast<int>(state.range(0)));
  const Eigen::Matrix3Xd after = system.points + Eigen::Matrix3Xd::Random(3, system.num_points()) * (0.05 * system.radius);
  relax::TopologyAuditor auditor(system);
  for (auto _ : state) benchmark::DoNotOptimize(auditor.crossings(system.points, after).size());
  label(state, system);
}
}  // namespace

BENCHMARK(forces)->ArgsProduct({{0, 1, 2}, {0, 25}})->Unit(benchmark::kMillisecond);
BENCHMARK(contact_pairs)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(guard)->ArgsProduct({{0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond);
BENCHMARK(audit)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
