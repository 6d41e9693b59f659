// A knit pattern's periodic patch (Leaf 2018 §5) against the centre repeat of an n × n tiling relaxed with
// free borders: the cost of each and how far apart they end. One CSV line per pattern file given.
// Usage: bench_periodic [--tiles N] PATTERN.knit...   (FIRE, pull-through guard, no per-step audit)
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>


#include "common/error.hpp"
#include "relax/yarn_relax.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "workflow/yarn_periodic.hpp"

using namespace skein;

namespace {
struct Timed {
  relax::YarnState state;
  relax::YarnRelaxReport report;
  double seconds = 0;
};

Timed relax_timed(const relax::YarnSystem& system, const relax::YarnRelaxOptions& options, const relax::ShapeTargets& targets) {
  Timed t{relax::initial_state(system, options), {}, 0};
  const auto start = std::chrono::steady_clock::now();
  t.report = relax::make_cpu_yarn_relaxer(system, targets, options)->run(t.state);
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return t;
}
}  // namespace

int main(int argc, char** argv) {
  int n = 5;
  int first = 1;
  if (argc > 2 && std::strcmp(argv[1], "--tiles") == 0) n = std::stoi(argv[2]), first = 3;
  std::printf("pattern,real_points,periodic_points,periodic_steps,periodic_seconds,tiled_points,tiled_steps,tiled_seconds,cost_ratio,"
              "rms_r,largest_r,converged\n");
  const auto& library = mesh::StitchLibrary::bundled();
  const double r = 0.6;  // the default yarn radius: a tenth of the 6 mm stitch
  relax::YarnRelaxOptions options;
  options.audit = false;
  try {
    for (int a = first; a < argc; ++a) {
      const auto pattern = mesh::read_pattern(argv[a]);
      if (pattern.format == mesh::PatternFormat::Woven) continue;  // a woven tiling has no free-border emission
      const auto patch = workflow::periodic_patch(pattern, library, {}, r);
      relax::ShapeTargets targets;
      targets.periodic = patch.map;
      const auto periodic = relax_timed(relax::make_yarn_system(patch.yarn), options, targets);
      mesh::EmitOptions emit;
      emit.yarn_radius = r;
      const auto yarn = mesh::emit_yarn(mesh::pattern_stitch_mesh(pattern, n, n * patch.repeat[1] / pattern.height()), library, emit);
      const auto tiled = relax_timed(relax::make_yarn_system(yarn), options, {});
      const auto d = workflow::centre_repeat_difference(patch, periodic.state.points, yarn, tiled.state.points, n);
      std::printf("%s,%d,%zu,%ld,%.3f,%zu,%ld,%.3f,%.2f,%.4f,%.4f,%s\n", std::filesystem::path(argv[a]).stem().c_str(), d.points, patch.yarn.points.size(), periodic.report.steps,
                  periodic.seconds, yarn.points.size(), tiled.report.steps, tiled.seconds, tiled.seconds / periodic.seconds, d.rms / r, d.largest / r,
                  periodic.report.converged && tiled.report.converged ? "both" : periodic.report.converged ? "periodic only" : "not periodic");
      std::fflush(stdout);
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "bench_periodic: %s\n", e.what());
    return 2;
  }
  return 0;
}
