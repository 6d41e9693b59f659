#include "workflow/yarn_local.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <set>

#include <spdlog/spdlog.h>

#include "common/error.hpp"
#include "relax/yarn_audit.hpp"
#include "relax/yarn_system.hpp"
#include "workflow/yarn_shape.hpp"

namespace skein::workflow {

int Splice::changed() const { return static_cast<int>(std::count(matched.begin(), matched.end(), 0)); }

Splice splice_previous(const relax::YarnCurves& emitted, const relax::YarnCurves& previous_emitted, const Eigen::Matrix3Xd& previous_relaxed) {
  if (previous_relaxed.cols() != static_cast<Eigen::Index>(previous_emitted.points.size()))
    throw Error("", "warm start", "the previous relaxed yarn has " + std::to_string(previous_relaxed.cols()) + " control points, its emission " +
                                      std::to_string(previous_emitted.points.size()));
  std::map<relax::PositionKey, int> previous;
  for (int q = 0; q < static_cast<int>(previous_emitted.points.size()); ++q) previous.emplace(relax::position_key(previous_emitted.points[q]), q);
  const int n = static_cast<int>(emitted.points.size());
  Splice out;
  out.points.resize(3, n);
  out.matched.assign(n, 0);
  for (int p = 0; p < n; ++p)
    if (const auto it = previous.find(relax::position_key(emitted.points[p])); it != previous.end()) {
      out.points.col(p) = previous_relaxed.col(it->second);
      out.matched[p] = 1;
    }
  // The rest move as the nearest matched point of their yarn.
  Eigen::Matrix3Xd base(3, n);
  for (int p = 0; p < n; ++p) base.col(p) = emitted.points[p];
  relax::follow_placed(emitted, out.matched, base, out.points);
  return out;
}

Splice splice_previous(const relax::YarnCurves& emitted, const relax::YarnCurves& previous_emitted, const relax::YarnCurves& previous_relaxed) {
  if (previous_relaxed.curve_start != previous_emitted.curve_start)
    throw Error("", "warm start", "the previous relaxed yarn holds other curves than the previous project's (curve or point counts differ): it was not relaxed from it");
  Eigen::Matrix3Xd points(3, previous_relaxed.points.size());
  for (size_t p = 0; p < previous_relaxed.points.size(); ++p) points.col(p) = previous_relaxed.points[p];
  return splice_previous(emitted, previous_emitted, points);
}

std::vector<int> owner_faces(const relax::YarnCurves& yarn) {
  std::vector<int> owner(yarn.point_face.begin(), yarn.point_face.end());
  for (int c = 0; c < yarn.curves(); ++c) {
    const int begin = yarn.curve_start[c], end = yarn.curve_start[c + 1];
    for (int p = begin; p < end; ++p) {
      if (yarn.point_face[p] >= 0) continue;
      for (int d = 1; d < end - begin && owner[p] < 0; ++d)
        for (const int r : {p - d, p + d})
          if (owner[p] < 0 && r >= begin && r < end && yarn.point_face[r] >= 0) owner[p] = yarn.point_face[r];
    }
  }
  return owner;
}

std::vector<char> face_rings(const mesh::StitchMesh& mesh, const std::vector<int>& seeds, int rings) {
  std::vector<std::vector<int>> faces_of(mesh.vertices.size());
  for (int f = 0; f < static_cast<int>(mesh.faces.size()); ++f)
    for (int v : mesh.faces[f].vertices) faces_of[v].push_back(f);
  std::vector<char> in(mesh.faces.size(), 0);
  std::vector<int> front;
  for (int f : seeds)
    if (f >= 0 && f < static_cast<int>(in.size()) && !in[f]) in[f] = 1, front.push_back(f);
  for (int k = 0; k < rings; ++k) {
    std::vector<int> next;
    for (int f : front)
      for (int v : mesh.faces[f].vertices)
        for (int g : faces_of[v])
          if (!in[g]) in[g] = 1, next.push_back(g);
    front = std::move(next);
  }
  return in;
}

void LocalRelaxOptions::validate() const {
  if (rings < 0 || halo < 1 || max_rings < rings || max_rings > 64 || !(boundary_move > 0))
    throw Error("", "local relaxation", "needs 0 <= rings <= max rings <= 64, a halo of at least 1 ring and a positive boundary move");
}

Eigen::Matrix3Xd relax_locally(const mesh::StitchMesh& mesh, const relax::YarnCurves& emitted, const Splice& splice, const relax::YarnRelaxOptions& options,
                               const LocalRelaxOptions& local, double take_up, const std::map<std::string, double>& take_up_by_type,
                               LocalRelaxReport& report) {
  local.validate();
  const auto clock = std::chrono::steady_clock::now();
  const auto seconds = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count(); };
  const int n = static_cast<int>(emitted.points.size());
  if (splice.points.cols() != n) throw Error("", "warm start", "the splice does not belong to this yarn");
  report = {};
  Eigen::Matrix3Xd points = splice.points;
  const auto owner = owner_faces(emitted);
  std::set<int> seeds;
  for (int p = 0; p < n; ++p)
    if (!splice.matched[p]) {
      ++report.changed_points;
      if (owner[p] >= 0) seeds.insert(owner[p]);
    }
  report.changed_stitches = static_cast<int>(seeds.size());
  report.converged = true;
  report.stopped_by = relax::StopReason::NothingChanged;
  if (report.changed_points == 0) return points;
  const std::vector<int> seed_list(seeds.begin(), seeds.end());
  report.pull_through_events = options.audit ? 0 : -1;
  // The stop rule's scale (Leaf eq. 5's |∇E_0|): the whole garment's as emitted, as a full relaxation measures
  // it. Measured on the few rings that relax, from a start that is relaxed almost everywhere, it would be far
  // smaller and ask for a far smaller residual.
  double scale = 0;
  {
    const relax::YarnSystem whole = relax::make_yarn_system(emitted, take_up, take_up_by_type, options.sampling);
    relax::YarnRelaxOptions probe = options;
    probe.max_steps = 0;
    probe.audit = false;
    probe.checkpoint.clear();
    relax::YarnState state = relax::initial_state(whole, probe);
    relax::make_cpu_yarn_relaxer(whole, shape_targets(mesh, emitted, options.shape), probe)->run(state);
    scale = state.residual0;
  }
  for (int rings = local.rings;; ++rings) {
    // This round's points: the relaxed rings' and the halo's, the curves cut where they leave both.
    const auto active = face_rings(mesh, seed_list, rings), kept = face_rings(mesh, seed_list, rings + local.halo);
    const auto inner = rings > 0 ? face_rings(mesh, seed_list, rings - 1) : std::vector<char>(mesh.faces.size(), 0);
    std::vector<char> keep(n, 0);
    for (int p = 0; p < n; ++p) keep[p] = owner[p] < 0 ? !splice.matched[p] : kept[owner[p]];
    std::vector<int> index;
    const auto piece = relax::cut_curves(emitted, keep, index);
    std::vector<int> global(piece.points.size());
    for (int p = 0; p < n; ++p)
      if (index[p] >= 0) global[index[p]] = p;
    const auto relaxes = [&](int p) { return owner[p] < 0 ? !splice.matched[p] : active[owner[p]] != 0; };
    relax::YarnSystem system = relax::make_yarn_system(piece, take_up, take_up_by_type, options.sampling);  // rest lengths from the emission
    const Eigen::Matrix3Xd start = system.points;
    for (int i = 0; i < system.num_points(); ++i) system.points.col(i) = points.col(global[i]);
    if (report.rounds == 0) {
      // The splice's certificate: no new yarn crosses another on the way from the new emission to it. Two
      // pieces of unchanged yarn are not tested: the previous relaxation (audited) took them from these very
      // emitted positions to these relaxed ones, and the straight move between the two is not the way it went.
      const auto is_new = [&](int segment) {
        for (int k = 0; k < 4; ++k)
          if (!splice.matched[global[system.segment_points[segment][k]]]) return true;
        return false;
      };
      for (const auto& crossing : relax::TopologyAuditor(system).crossings(start, system.points))
        report.splice_crossings += is_new(crossing.segment_a) || is_new(crossing.segment_b);
      if (report.splice_crossings > 0) {
        report.converged = false;
        report.stopped_by = relax::StopReason::UnsafeSplice;
        report.wall_seconds = seconds();
        return points;
      }
    }
    relax::ShapeTargets targets = shape_targets(mesh, piece, options.shape);
    report.relaxed_points = report.held_points = 0;
    for (int i = 0; i < system.num_points(); ++i) {
      if (relaxes(global[i])) ++report.relaxed_points;
      else ++report.held_points, targets.periodic.frozen.push_back(i);
    }
    // Eq. 5 on a border loop partly held: the held points do not move, so the loop's sum stays put when the
    // sum of its other points does.
    std::vector<char> held(system.num_points(), 0);
    for (int i : targets.periodic.frozen) held[i] = 1;
    for (auto& loop : targets.boundary_loops) loop.erase(std::remove_if(loop.begin(), loop.end(), [&](int i) { return held[i] != 0; }), loop.end());
    std::erase_if(targets.boundary_loops, [](const std::vector<int>& loop) { return loop.empty(); });
    relax::YarnState state = relax::initial_state(system, options);
    state.residual0 = scale;
    const Eigen::Matrix3Xd before = system.points;
    const auto run = relax::make_cpu_yarn_relaxer(system, targets, options)->run(state);
    ++report.rounds;
    report.rings = rings;
    report.steps += run.steps;
    report.converged = run.converged;
    report.stopped_by = run.stopped_by;
    if (run.pull_through_events > 0) report.pull_through_events += run.pull_through_events;
    // Write the relaxed points back; measure how far the outermost relaxed ring moved.
    double boundary = 0;
    for (int i = 0; i < system.num_points(); ++i) {
      const int p = global[i];
      if (!relaxes(p)) continue;
      points.col(p) = state.points.col(i);
      if (owner[p] >= 0 && !inner[owner[p]]) boundary = std::max(boundary, (state.points.col(i) - before.col(i)).norm() / system.radius);
    }
    report.last_boundary_move = boundary;
    spdlog::info("local relaxation: {} rings, {} points relaxed and {} held, {} after {} steps; the outermost ring moved {:.3g} r", rings,
                 report.relaxed_points, report.held_points, to_string(run.stopped_by), run.steps, boundary);
    if (!run.converged || boundary <= local.boundary_move || rings >= local.max_rings) break;
  }
  report.wall_seconds = seconds();
  return points;
}

}  // namespace skein::workflow
