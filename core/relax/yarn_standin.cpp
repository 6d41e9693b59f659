#include "relax/yarn_standin.hpp"

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

/// Per face: whether it may stand in (a 1-1 quad inside the garment, no cable mark on its course edges, every
/// face around its corners of its type).
std::vector<char> eligible_faces(const mesh::StitchMesh& mesh) {
  const int faces = static_cast<int>(mesh.faces.size());
  std::vector<std::vector<int>> faces_of(mesh.vertices.size());
  std::map<std::pair<int, int>, int> edge_uses;
  for (int f = 0; f < faces; ++f) {
    const auto& face = mesh.faces[f];
    for (int v : face.vertices) faces_of[v].push_back(f);
    for (int k = 0; k < face.size(); ++k) ++edge_uses[std::minmax(face.vertex(k), face.vertex(k + 1))];
  }
  std::vector<char> out(faces, 0);
  for (int f = 0; f < faces; ++f) {
    const auto& face = mesh.faces[f];
    if (face.bottom != 1 || face.top() != 1) continue;
    bool ok = true;
    for (int k = 0; k < 4 && ok; ++k) {
      const std::pair<int, int> edge = std::minmax(face.vertex(k), face.vertex(k + 1));
      ok = edge_uses[edge] == 2 && (face.is_wale(k) || !mesh.cables.count(edge));
      for (int g : faces_of[face.vertex(k)]) ok = ok && mesh.faces[g].type == face.type && mesh.faces[g].bottom == 1 && mesh.faces[g].top() == 1;
    }
    out[f] = ok;
  }
  return out;
}

/// A stitch type's periodic patch relaxed: its real points in the centre face's frame (u, v, h) and their moves
/// in relaxation (a, b, c) in the same frame, the patch's drift (the mean move) removed.
struct RelaxedStitch {
  std::vector<Vector3d> where, move;
  long steps = 0;
  bool converged = false;
};
RelaxedStitch relax_stitch(const std::string& type, const mesh::StitchLibrary& library, const mesh::StitchSize& size, double radius,
                           const YarnRelaxOptions& options) {
  mesh::Pattern pattern;
  pattern.name = type;
  pattern.rows = {{type}};
  auto patch = periodic_patch(pattern, library, size, radius);
  const auto system = make_yarn_system(patch.yarn);
  const auto tiles = mesh::pattern_stitch_mesh(pattern, patch.tiles, patch.tiles, size);
  // The forces the garment's relaxation feels: the patch-tracking ones too (the patch has no border loops).
  auto shape = options.shape;
  shape.boundary = false;
  ShapeTargets targets = shape_targets(tiles, patch.yarn, shape);
  targets.periodic = patch.map;
  YarnState state = initial_state(system, options);
  const auto run = make_cpu_yarn_relaxer(system, targets, options)->run(state);
  if (run.stopped_by == "diverged") throw Error("", "stand-in for " + type, "the periodic patch's relaxation diverged");
  // The centre face: the face most real points were emitted for.
  std::map<int, int> votes;
  std::vector<int> real;
  for (int p = 0; p < system.num_points(); ++p)
    if (patch.ring[p] == 0) real.push_back(p), ++votes[patch.yarn.point_face[p]];
  int centre = -1;
  for (const auto& [f, count] : votes)
    if (f >= 0 && (centre < 0 || count > votes[centre])) centre = f;
  if (centre < 0) throw Error("", "stand-in for " + type, "the periodic patch has no real point on a face");
  const Bilinear frame(tiles, centre);
  Vector3d drift = Vector3d::Zero();
  for (int p : real) drift += state.points.col(p) - system.points.col(p);
  drift /= static_cast<double>(real.size());
  RelaxedStitch out;
  for (int p : real) {
    const Vector3d uvh = frame.local(system.points.col(p));
    out.where.push_back(uvh);
    out.move.push_back(frame.split(state.points.col(p) - system.points.col(p) - drift, uvh.x(), uvh.y()));
  }
  out.steps = run.steps;
  out.converged = run.converged;
  return out;
}

}  // namespace

void StandInOptions::validate() const {
  if (min_faces < 1) throw Error("", "stand-in", "the fewest faces of a type must be at least 1, found " + std::to_string(min_faces));
}

Eigen::Matrix3Xd stand_in_preview(const mesh::StitchMesh& stitch, const mesh::YarnCurves& yarn, const mesh::StitchLibrary& library,
                                  const YarnRelaxOptions& options, const StandInOptions& stand_in,
                                  StandInReport& report) {
  const auto started = std::chrono::steady_clock::now();
  stand_in.validate();
  const int n = static_cast<int>(yarn.points.size());
  if (static_cast<int>(yarn.point_face.size()) != n) throw Error("", "stand-in", "the yarn does not say which face each point was emitted for");
  const auto eligible = eligible_faces(stitch);
  std::map<std::string, std::vector<int>> by_type;
  for (int f = 0; f < static_cast<int>(stitch.faces.size()); ++f)
    if (eligible[f]) by_type[stitch.faces[f].type].push_back(f);
  Eigen::Matrix3Xd base(3, n);
  for (int p = 0; p < n; ++p) base.col(p) = yarn.points[p];
  Eigen::Matrix3Xd out = base;
  std::vector<char> placed(n, 0);
  std::vector<std::vector<int>> points_of(stitch.faces.size());
  for (int p = 0; p < n; ++p)
    if (yarn.point_face[p] >= 0 && yarn.point_face[p] < static_cast<int>(stitch.faces.size())) points_of[yarn.point_face[p]].push_back(p);
  report = {};
  const double r = yarn.radius;
  for (const auto& region : by_type) {
    const std::string& type = region.first;
    const std::vector<int>& faces = region.second;  // a plain reference: OpenMP regions cannot capture a structured binding
    if (static_cast<int>(faces.size()) < stand_in.min_faces) continue;
    const auto t0 = std::chrono::steady_clock::now();
    // The patch at the region's mean stitch size: its yarn as long as the region's.
    mesh::StitchSize mean{0, 0};
    for (int f : faces) {
      const Bilinear q(stitch, f);
      mean.width += 0.5 * ((q.c[1] - q.c[0]).norm() + (q.c[2] - q.c[3]).norm()) / static_cast<double>(faces.size());
      mean.height += 0.5 * ((q.c[3] - q.c[0]).norm() + (q.c[2] - q.c[1]).norm()) / static_cast<double>(faces.size());
    }
    spdlog::info("stand-in {}: mean stitch {:.3f} x {:.3f} mm", type, mean.width, mean.height);
    const auto relaxed = relax_stitch(type, library, mean, r, options);
    StandInType entry{type, static_cast<int>(faces.size()), relaxed.steps, relaxed.converged,
                      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()};
    // Each point to the real point at its place in the stitch, modulo the period: lengths in the patch's
    // stitch (u along the course times its width, v along the wale times its height, h as it is).
    const auto distance = [&](const Vector3d& a, const Vector3d& b, int i, int j) {
      return Vector3d((a.x() - b.x() - i) * mean.width, (a.y() - b.y() - j) * mean.height, a.z() - b.z()).norm();
    };
#pragma omp parallel for schedule(dynamic, 16)
    for (int k = 0; k < static_cast<int>(faces.size()); ++k) {
      const Bilinear frame(stitch, faces[k]);
      for (int p : points_of[faces[k]]) {
        const Vector3d uvh = frame.local(base.col(p));
        double best = r;  // no match farther than one yarn radius
        int match = -1;
        for (size_t q = 0; q < relaxed.where.size(); ++q)
          for (int i = -1; i <= 1; ++i)
            for (int j = -1; j <= 1; ++j)
              if (const double d = distance(uvh, relaxed.where[q], i, j); d < best) best = d, match = static_cast<int>(q);
        if (match < 0) continue;
        out.col(p) = base.col(p) + frame.carry(uvh, relaxed.move[match]);
        placed[p] = 1;
      }
    }
    spdlog::info("stand-in {}: its periodic patch relaxed in {} steps ({}), mapped over {} faces", type, relaxed.steps,
                 relaxed.converged ? "converged" : "not converged", faces.size());
    report.types.push_back(entry);
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
