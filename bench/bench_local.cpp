// Local re-relaxation against a full one: a garment's yarn relaxed in full, then a share of its plain
// stitches repainted purl (spread evenly), and the edited yarn relaxed twice: locally from the previous result
// (workflow::relax_locally, as `skein relax-yarn --warm-start`) and in full from its emission. Prints one CSV line:
// the times, and how far apart the two results end, outside the relaxed rings and over all points, in yarn
// radii. Usage: bench_local PROJECT.skein [PERCENT=1] [RINGS=1] [HALO=1] [ACTIVE=0]   (FIRE, guard on; ACTIVE=1: both
// edited runs with the active set; the local run once more with every step audited, for its pull-through count)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "common/error.hpp"
#include "relax/yarn_relax.hpp"
#include "relax/yarn_system.hpp"
#include "stitchmesh/edits.hpp"
#include "stitchmesh/project.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "workflow/yarn_local.hpp"
#include "workflow/yarn_shape.hpp"

using namespace skein;

namespace {
double seconds_since(std::chrono::steady_clock::time_point t) { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count(); }

struct Full {
  Eigen::Matrix3Xd points;
  relax::YarnRelaxReport report;
  double seconds = 0;
};
Full relax_full(const mesh::StitchMesh& stitch, const relax::YarnCurves& yarn, const relax::YarnRelaxOptions& options) {
  const auto system = relax::make_yarn_system(yarn);
  const auto targets = workflow::shape_targets(stitch, yarn, options.shape);
  auto state = relax::initial_state(system, options);
  const auto start = std::chrono::steady_clock::now();
  Full out;
  out.report = relax::make_cpu_yarn_relaxer(system, targets, options)->run(state);
  out.seconds = seconds_since(start);
  out.points = state.points;
  return out;
}

/// The energy of `points` as the relaxer measures it (one evaluation, no step).
double energy_at(const mesh::StitchMesh& stitch, const relax::YarnCurves& yarn, const Eigen::Matrix3Xd& points, relax::YarnRelaxOptions options) {
  auto system = relax::make_yarn_system(yarn);
  options.max_steps = 0;
  options.audit = false;
  auto state = relax::initial_state(system, options);
  state.points = points;
  return relax::make_cpu_yarn_relaxer(system, workflow::shape_targets(stitch, yarn, options.shape), options)->run(state).energy;
}
}  // namespace

int main(int argc, char** argv) try {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_local PROJECT.skein [PERCENT=1] [RINGS=1] [HALO=1] [ACTIVE=0]\n");
    return 2;
  }
  const double percent = argc > 2 ? std::stod(argv[2]) : 1.0;
  workflow::LocalRelaxOptions local;
  if (argc > 3) local.rings = std::stoi(argv[3]);
  if (argc > 4) local.halo = std::stoi(argv[4]);
  const auto project = mesh::read_project(argv[1]);
  if (!project.stitch) throw Error(argv[1], "", "holds no stitch mesh");
  const auto& library = mesh::StitchLibrary::bundled();
  mesh::EmitOptions emit;
  emit.yarn_radius = 0.1 * project.stitch_size.width;
  const auto& before = *project.stitch;
  const auto yarn0 = mesh::emit_yarn(before, library, emit);
  relax::YarnRelaxOptions options;
  options.audit = false;
  const auto previous = relax_full(before, yarn0, options);
  options.active_set.enabled = argc > 5 && std::stoi(argv[5]) != 0;

  // Repaint every k-th plain stitch purl, k = 100 / percent.
  std::vector<int> plain;
  for (int f = 0; f < static_cast<int>(before.faces.size()); ++f)
    if (before.faces[f].type == "k") plain.push_back(f);
  const int stride = std::max(1, static_cast<int>(std::lround(before.faces.size() / (percent / 100.0 * before.faces.size()))));
  std::vector<int> chosen;
  for (size_t i = stride / 2; i < plain.size(); i += stride) chosen.push_back(plain[i]);
  const auto after = mesh::set_stitch_type(before, chosen, "p");
  const auto yarn1 = mesh::emit_yarn(after, library, emit);

  // Timed as the full run is, without the per-step audit; then once more audited, for its count.
  const auto start = std::chrono::steady_clock::now();
  const auto splice = workflow::splice_previous(yarn1, yarn0, previous.points);
  workflow::LocalRelaxReport report;
  const auto warm = workflow::relax_locally(after, yarn1, splice, options, local, 1.0, {}, report);
  const double warm_seconds = seconds_since(start);
  auto audited = options;
  audited.audit = true;
  workflow::LocalRelaxReport audit_report;
  workflow::relax_locally(after, yarn1, splice, audited, local, 1.0, {}, audit_report);
  report.pull_through_events = audit_report.pull_through_events;
  const auto full = relax_full(after, yarn1, options);

  // Differences, in yarn radii: outside the rings the local run relaxed, and over every point.
  const auto owner = workflow::owner_faces(yarn1);
  const auto relaxed_faces = workflow::face_rings(after, chosen, report.rings);
  double sum_out = 0, largest_out = 0, sum_all = 0, largest_all = 0;
  long n_out = 0;
  const long n = static_cast<long>(yarn1.points.size());
  for (long p = 0; p < n; ++p) {
    const double d = (warm.col(p) - full.points.col(p)).norm() / emit.yarn_radius;
    sum_all += d * d;
    largest_all = std::max(largest_all, d);
    if (owner[p] >= 0 && !relaxed_faces[owner[p]]) {
      sum_out += d * d;
      largest_out = std::max(largest_out, d);
      ++n_out;
    }
  }
  const double e_warm = energy_at(after, yarn1, warm, options), e_full = energy_at(after, yarn1, full.points, options);
  std::printf("faces,control_points,repainted,previous_seconds,warm_seconds,warm_steps,rounds,rings,relaxed_points,held_points,splice_crossings,"
              "pull_through_events,warm_stopped_by,full_seconds,full_steps,full_stopped_by,speedup,rms_outside_r,largest_outside_r,rms_all_r,"
              "largest_all_r,energy_warm,energy_full\n");
  std::printf("%zu,%ld,%zu,%.3f,%.3f,%ld,%d,%d,%d,%d,%ld,%ld,%s,%.3f,%ld,%s,%.2f,%.4f,%.4f,%.4f,%.4f,%.6g,%.6g\n", after.faces.size(), n, chosen.size(),
              previous.seconds, warm_seconds, report.steps, report.rounds, report.rings, report.relaxed_points, report.held_points,
              report.splice_crossings, report.pull_through_events, relax::to_string(report.stopped_by).c_str(), full.seconds, full.report.steps,
              relax::to_string(full.report.stopped_by).c_str(), full.seconds / warm_seconds, n_out ? std::sqrt(sum_out / n_out) : 0.0, largest_out,
              std::sqrt(sum_all / n), largest_all, e_warm, e_full);
  return 0;
} catch (const skein::Error& e) {
  std::fprintf(stderr, "bench_local: %s\n", e.what());
  return 2;
}
