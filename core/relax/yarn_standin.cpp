#include "relax/yarn_standin.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include <Eigen/Dense>
#include <spdlog/spdlog.h>

#include "common/error.hpp"
#include "relax/yarn_audit.hpp"
#include "relax/yarn_local.hpp"
#include "relax/yarn_periodic.hpp"
#include "relax/yarn_system.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/repeats.hpp"

namespace skein::relax {
namespace {

using Eigen::Vector3d;

/// A quad face's bilinear surface: corners at (u, v) = (0, 0), (1, 0), (1, 1), (0, 1), the stitch face's
/// order (bottom-left, bottom-right, top-right, top-left; stitch_mesh.hpp).
struct Bilinear {
  Vector3d c[4];
  Bilinear(const mesh::StitchMesh& mesh, int f) {
    for (int k = 0; k < 4; ++k) c[k] = mesh.vertices[mesh.faces[f].vertex(k)];
  }
  Vector3d at(double u, double v) const { return (1 - u) * (1 - v) * c[0] + u * (1 - v) * c[1] + u * v * c[2] + (1 - u) * v * c[3]; }
  Vector3d du(double v) const { return (1 - v) * (c[1] - c[0]) + v * (c[2] - c[3]); }
  Vector3d dv(double u) const { return (1 - u) * (c[3] - c[0]) + u * (c[2] - c[1]); }
  Vector3d normal(double u, double v) const { return du(v).cross(dv(u)).normalized(); }
  /// (u, v, h): the foot of `p` on the surface (Gauss-Newton) and its distance h along the normal.
  Vector3d local(const Vector3d& p) const {
    double u = 0.5, v = 0.5;
    for (int i = 0; i < 30; ++i) {
      Eigen::Matrix<double, 3, 2> J;
      J << du(v), dv(u);
      const Eigen::Vector2d step = (J.transpose() * J).ldlt().solve(J.transpose() * (at(u, v) - p));
      u -= step.x();
      v -= step.y();
      if (step.norm() < 1e-12) break;
    }
    return {u, v, (p - at(u, v)).dot(normal(u, v))};
  }
  /// A move `d` at (u, v) in this frame: d = a ∂u + b ∂v + c n.
  Vector3d split(const Vector3d& d, double u, double v) const {
    Eigen::Matrix3d m;
    m << du(v), dv(u), normal(u, v);
    return m.lu().solve(d);
  }
  /// The move (a, b, c) in this frame at (u, v, h) as a displacement [mm].
  Vector3d carry(const Vector3d& uvh, const Vector3d& move) const {
    const double u = uvh.x(), v = uvh.y();
    return at(u + move.x(), v + move.y()) - at(u, v) + move.z() * normal(u, v);
  }
};

/// A repeat's periodic patch relaxed: per place in the repeat (row * width + column), the patch's points
/// around one stitch at that place (its own and its neighbours', as far as one stitch beyond its face) at
/// (u, v, h) in that stitch's frame, and their moves in relaxation (a, b, c) in the same frame, the patch's
/// drift (the mean move of its real points) removed.
struct RelaxedRepeat {
  std::vector<std::vector<Vector3d>> where, move;
  long steps = 0;
  bool converged = false;
};
RelaxedRepeat relax_repeat(const mesh::Pattern& repeat, const mesh::StitchLibrary& library, const mesh::StitchSize& size, double radius,
                           const YarnRelaxOptions& options, const StandInOptions& stand_in) {
  const std::string what = "stand-in for " + mesh::repeat_text(repeat);
  auto patch = periodic_patch(repeat, library, size, radius);
  // The garment's take-up, for the stitch types this patch has.
  std::map<std::string, double> take_up_by_type;
  for (const auto& [type, factor] : stand_in.take_up_by_type)
    if (std::count(patch.yarn.type_names.begin(), patch.yarn.type_names.end(), type)) take_up_by_type[type] = factor;
  const auto system = make_yarn_system(patch.yarn, stand_in.take_up, take_up_by_type, options.sampling);
  const auto tiles = mesh::pattern_stitch_mesh(repeat, patch.tiles, patch.tiles, size);
  // The forces the garment's relaxation feels: the patch-tracking ones too (the patch has no border loops).
  auto shape = options.shape;
  shape.boundary = false;
  ShapeTargets targets = shape_targets(tiles, patch.yarn, shape);
  targets.periodic = patch.map;
  YarnState state = initial_state(system, options);
  const auto run = make_cpu_yarn_relaxer(system, targets, options)->run(state);
  if (run.stopped_by == "diverged") throw Error("", what, "the periodic patch's relaxation diverged");
  Vector3d drift = Vector3d::Zero();
  int real = 0;
  for (int p = 0; p < system.num_points(); ++p)
    if (patch.ring[p] == 0) drift += state.points.col(p) - system.points.col(p), ++real;
  if (real == 0) throw Error("", what, "the periodic patch has no real point");
  drift /= real;
  // Each place's stitch nearest the patch's middle, found as the garment's are.
  const auto found = mesh::find_repeats(tiles, stand_in.max_period);
  const auto it = std::find_if(found.repeats.begin(), found.repeats.end(), [&](const mesh::Pattern& p) { return p.rows == repeat.rows; });
  if (it == found.repeats.end()) throw Error("", what, "the periodic patch's own stitch mesh does not show the repeat");
  const int r = static_cast<int>(it - found.repeats.begin()), width = repeat.width();
  Vector3d middle = Vector3d::Zero();
  for (const auto& v : tiles.vertices) middle += v / static_cast<double>(tiles.vertices.size());
  const auto centroid = [&](int f) { return Bilinear(tiles, f).at(0.5, 0.5); };
  std::vector<int> stitch(width * repeat.height(), -1);
  for (int f = 0; f < static_cast<int>(tiles.faces.size()); ++f) {
    if (found.repeat[f] != r) continue;
    int& best = stitch[found.row[f] * width + found.column[f]];
    if (best < 0 || (centroid(f) - middle).norm() < (centroid(best) - middle).norm()) best = f;
  }
  RelaxedRepeat out;
  const double nearby = 2 * (size.width + size.height);  // a cheap test before the frame's
  for (int f : stitch) {
    if (f < 0) throw Error("", what, "the periodic patch lacks a stitch of the repeat");
    const Bilinear frame(tiles, f);
    std::vector<Vector3d> where, move;
    for (int p = 0; p < system.num_points(); ++p) {
      if ((system.points.col(p) - centroid(f)).norm() > nearby) continue;
      const Vector3d uvh = frame.local(system.points.col(p));
      if (uvh.x() < -1 || uvh.x() > 2 || uvh.y() < -1 || uvh.y() > 2) continue;
      where.push_back(uvh);
      move.push_back(frame.split(state.points.col(p) - system.points.col(p) - drift, uvh.x(), uvh.y()));
    }
    out.where.push_back(std::move(where));
    out.move.push_back(std::move(move));
  }
  out.steps = run.steps;
  out.converged = run.converged;
  return out;
}

}  // namespace

void StandInOptions::validate() const {
  if (min_faces < 1) throw Error("", "stand-in", "the fewest faces of a repeat must be at least 1, found " + std::to_string(min_faces));
  if (max_period < 1 || max_period > 16) throw Error("", "stand-in", "the longest repeat must be 1 to 16 stitches, found " + std::to_string(max_period));
  if (reach < 0) throw Error("", "stand-in", "the rings beyond a region must be 0 or more, found " + std::to_string(reach));
}

Eigen::Matrix3Xd stand_in_preview(const mesh::StitchMesh& stitch, const mesh::YarnCurves& yarn, const mesh::StitchLibrary& library,
                                  const YarnRelaxOptions& options, const StandInOptions& stand_in,
                                  StandInReport& report) {
  const auto started = std::chrono::steady_clock::now();
  stand_in.validate();
  const int n = static_cast<int>(yarn.points.size());
  if (static_cast<int>(yarn.point_face.size()) != n) throw Error("", "stand-in", "the yarn does not say which face each point was emitted for");
  const auto regions = mesh::find_repeats(stitch, stand_in.max_period, stand_in.reach);
  spdlog::info("stand-in: {} repeating patterns found in {:.2f} s", regions.repeats.size(),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  std::vector<std::vector<int>> faces_of(regions.repeats.size());
  for (int f = 0; f < static_cast<int>(stitch.faces.size()); ++f)
    if (regions.repeat[f] >= 0) faces_of[regions.repeat[f]].push_back(f);
  Eigen::Matrix3Xd base(3, n);
  for (int p = 0; p < n; ++p) base.col(p) = yarn.points[p];
  Eigen::Matrix3Xd out = base;
  std::vector<char> placed(n, 0);
  std::vector<std::vector<int>> points_of(stitch.faces.size());
  for (int p = 0; p < n; ++p)
    if (yarn.point_face[p] >= 0 && yarn.point_face[p] < static_cast<int>(stitch.faces.size())) points_of[yarn.point_face[p]].push_back(p);
  report = {};
  const double r = yarn.radius;
  for (size_t k = 0; k < regions.repeats.size(); ++k) {
    const mesh::Pattern& repeat = regions.repeats[k];
    const std::vector<int>& faces = faces_of[k];
    if (static_cast<int>(faces.size()) < stand_in.min_faces) continue;
    const auto t0 = std::chrono::steady_clock::now();
    // The patch at the region's mean stitch size: its yarn as long as the region's.
    mesh::StitchSize mean{0, 0};
    for (int f : faces) {
      const Bilinear q(stitch, f);
      mean.width += 0.5 * ((q.c[1] - q.c[0]).norm() + (q.c[2] - q.c[3]).norm()) / static_cast<double>(faces.size());
      mean.height += 0.5 * ((q.c[3] - q.c[0]).norm() + (q.c[2] - q.c[1]).norm()) / static_cast<double>(faces.size());
    }
    const std::string text = mesh::repeat_text(repeat);
    spdlog::info("stand-in {}: {} faces, mean stitch {:.3f} x {:.3f} mm", text, faces.size(), mean.width, mean.height);
    const auto relaxed = relax_repeat(repeat, library, mean, r, options, stand_in);
    StandInRepeat entry{text, repeat.width(), repeat.height(), static_cast<int>(faces.size()), relaxed.steps, relaxed.converged,
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()};
    // Each point to the patch's point at its place around the same stitch of the repeat: lengths in the
    // patch's stitch (u along the course times its width, v along the wale times its height, h as it is).
    const auto distance = [&](const Vector3d& a, const Vector3d& b) {
      return Vector3d((a.x() - b.x()) * mean.width, (a.y() - b.y()) * mean.height, a.z() - b.z()).norm();
    };
#pragma omp parallel for schedule(dynamic, 16)
    for (int i = 0; i < static_cast<int>(faces.size()); ++i) {
      const int f = faces[i], place = regions.row[f] * repeat.width() + regions.column[f];
      const auto& where = relaxed.where[place];
      const Bilinear frame(stitch, f);
      for (int p : points_of[f]) {
        const Vector3d uvh = frame.local(base.col(p));
        double best = r;  // no match farther than one yarn radius
        int match = -1;
        for (size_t q = 0; q < where.size(); ++q)
          if (const double d = distance(uvh, where[q]); d < best) best = d, match = static_cast<int>(q);
        if (match < 0) continue;
        out.col(p) = base.col(p) + frame.carry(uvh, relaxed.move[place][match]);
        placed[p] = 1;
      }
    }
    spdlog::info("stand-in {}: its periodic patch relaxed in {} steps ({}), mapped over {} faces", text, relaxed.steps,
                 relaxed.converged ? "converged" : "not converged", faces.size());
    report.repeats.push_back(entry);
  }
  // The certificate (as for a warm start's splice): on the straight path from the emission to the preview no
  // yarn may pass through another. The faces of segments that would are taken back to following their yarn
  // until none do; with every face taken back the preview is the emission moved along, which passes that test.
  const Eigen::Matrix3Xd mapped = out;
  const auto system = make_yarn_system(yarn);
  const TopologyAuditor auditor(system);
  const auto owner = owner_faces(yarn);
  for (int rings = 1;;) {
    out = base;
    for (int p = 0; p < n; ++p)
      if (placed[p]) out.col(p) = mapped.col(p);
    follow_placed(yarn, placed, base, out);
    const auto crossings = auditor.crossings(base, out);
    if (crossings.empty()) break;
    // The faces of the segments that cross and `rings` rings around them (followers move with placed points
    // nearby); when that takes nothing back, one ring more.
    std::vector<int> seeds;
    for (const auto& c : crossings)
      for (int s : {c.segment_a, c.segment_b})
        for (int p : system.segment_points[s]) seeds.push_back(owner[p]);
    const auto drop = face_rings(stitch, seeds, rings);
    int dropped = 0;
    for (int p = 0; p < n; ++p)
      if (placed[p] && drop[yarn.point_face[p]]) placed[p] = 0, ++dropped;
    report.taken_back += dropped;
    if (dropped == 0) ++rings;
  }
  report.placed = static_cast<int>(std::count(placed.begin(), placed.end(), 1));
  report.following = n - report.placed;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace skein::relax
