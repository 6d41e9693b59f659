#include "workflow/yarn_standin.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include <Eigen/Dense>
#include <spdlog/spdlog.h>

#include "common/error.hpp"
#include "relax/yarn_audit.hpp"
#include "relax/yarn_system.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/repeats.hpp"
#include "workflow/yarn_local.hpp"
#include "workflow/yarn_periodic.hpp"
#include "workflow/yarn_shape.hpp"

namespace skein::workflow {
namespace {

using Eigen::Vector3d;

/// A stitch face's bilinear surface through its corners at (u, v) = (0, 0), (1, 0), (1, 1), (0, 1): bottom-left,
/// bottom-right, top-right, top-left (stitch_mesh.hpp; the vertices between them along a course are left out).
struct Bilinear {
  Vector3d c[4];
  Bilinear(const mesh::StitchMesh& mesh, int f) {
    const auto& face = mesh.faces[f];
    int k = 0;
    for (int corner : {0, face.bottom, face.bottom + 1, face.size() - 1}) c[k++] = mesh.vertices[face.vertex(corner)];
  }
  double width() const { return 0.5 * ((c[1] - c[0]).norm() + (c[2] - c[3]).norm()); }
  double height() const { return 0.5 * ((c[3] - c[0]).norm() + (c[2] - c[1]).norm()); }
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
  /// A move `d` at (u, v) in this frame: the (a, b, c) that `carry` takes back to d (Newton's method from
  /// d = a ∂u + b ∂v + c n, which is exact where the face is a parallelogram).
  Vector3d split(const Vector3d& d, double u, double v) const {
    Eigen::Matrix3d m;
    m << du(v), dv(u), normal(u, v);
    Vector3d abc = m.lu().solve(d);
    const Vector3d uvh(u, v, 0);
    for (int i = 0; i < 10; ++i) {
      const Vector3d residual = carry(uvh, abc) - d;
      if (residual.norm() < 1e-12 * (1 + d.norm())) break;
      m << du(v + abc.y()), dv(u + abc.x()), normal(u, v);
      abc -= m.lu().solve(residual);
    }
    return abc;
  }
  /// The move (a, b, c) in this frame at (u, v, h) as a displacement [mm].
  Vector3d carry(const Vector3d& uvh, const Vector3d& move) const {
    const double u = uvh.x(), v = uvh.y();
    return at(u + move.x(), v + move.y()) - at(u, v) + move.z() * normal(u, v);
  }
};

/// Whether point p is of the yarn that emission makes for a cable's crossing, between the stitch faces.
bool on_cable(const relax::YarnCurves& yarn, int p) {
  return yarn.point_face[p] < 0 && yarn.point_type[p] >= 0 && yarn.type_names[yarn.point_type[p]].starts_with("cable");
}

/// A region of the garment knitted in one repeat: its faces and each one's place in the repeat (numbered as
/// mesh::repeat_face numbers them).
struct Region {
  const mesh::Pattern* repeat;
  std::string name;
  std::vector<int> faces, place;
};

/// The regions: repeats of plain stitches read back from the stitch types (mesh::find_repeats), and repeats of
/// the patterns that re-mesh, where `stand_in.patterns` names them (mesh::find_tiled_repeats), which take
/// their faces from the former.
std::vector<Region> regions_of(const mesh::StitchMesh& stitch, const StandInOptions& stand_in, const mesh::RepeatRegions& plain,
                               const mesh::TiledRepeats& tiled) {
  std::vector<Region> out;
  for (size_t k = 0; k < plain.repeats.size(); ++k) out.push_back({&plain.repeats[k], mesh::repeat_text(plain.repeats[k]), {}, {}});
  for (size_t k = 0; k < tiled.patterns.size(); ++k) out.push_back({&tiled.patterns[k], tiled.patterns[k].name, {}, {}});
  for (int f = 0; f < static_cast<int>(stitch.faces.size()); ++f) {
    if (tiled.pattern[f] >= 0) {
      auto& region = out[plain.repeats.size() + tiled.pattern[f]];
      region.faces.push_back(f), region.place.push_back(tiled.place[f]);
    } else if (plain.repeat[f] >= 0) {
      auto& region = out[plain.repeat[f]];
      region.faces.push_back(f), region.place.push_back(plain.row[f] * region.repeat->width() + plain.column[f]);
    }
  }
  std::erase_if(out, [&](const Region& r) { return static_cast<int>(r.faces.size()) < stand_in.min_faces; });
  return out;
}

/// The region's stitch size: the width from its faces' course spans against those of the pattern's own faces
/// at the same places; the height from their wale edges, each less the lean the pattern's own edge has along
/// the course at that width (a lace's wale edges lean: its stitches are not all alike), against the pattern's
/// rows, one stitch high each. On stitches of plain rectangles: their mean width and height.
mesh::StitchSize mean_stitch_size(const mesh::StitchMesh& stitch, const Region& region) {
  const auto unit = mesh::pattern_stitch_mesh(*region.repeat, 1, 1, {1, 1});
  double spans = 0, unit_spans = 0;
  for (size_t i = 0; i < region.faces.size(); ++i) {
    const Bilinear garment(stitch, region.faces[i]), own(unit, region.place[i]);
    spans += (garment.c[1] - garment.c[0]).norm() + (garment.c[2] - garment.c[3]).norm();
    unit_spans += (own.c[1] - own.c[0]).norm() + (own.c[2] - own.c[3]).norm();
  }
  const double width = spans / unit_spans;
  double height = 0;
  for (size_t i = 0; i < region.faces.size(); ++i) {
    const Bilinear garment(stitch, region.faces[i]), own(unit, region.place[i]);
    for (const auto& [a, b] : {std::pair{0, 3}, {1, 2}}) {
      const double lean = width * (own.c[b] - own.c[a]).x();
      height += 0.5 * std::sqrt(std::max(0.0, (garment.c[b] - garment.c[a]).squaredNorm() - lean * lean));
    }
  }
  return {width, height / static_cast<double>(region.faces.size())};
}

/// A repeat's periodic patch relaxed: per place in the repeat, the patch's points around its stitch at that
/// place in the middle repeat (its own and its neighbours', as far as one stitch beyond its face) at (u, v, h)
/// in that stitch's frame, and their moves in relaxation (a, b, c) in the same frame, the patch's drift (the
/// mean move of its real points) removed; and that stitch's width and height.
struct RelaxedRepeat {
  std::vector<std::vector<Vector3d>> where, move;
  std::vector<std::vector<char>> cable;  ///< whether the point is of a cable's crossing yarn (on_cable)
  std::vector<Eigen::Vector2d> size;
  long steps = 0;
  bool converged = false;
};
RelaxedRepeat relax_repeat(const mesh::Pattern& repeat, const std::string& name, const mesh::StitchLibrary& library, const mesh::StitchSize& size,
                           double radius, const relax::YarnRelaxOptions& options, const StandInOptions& stand_in) {
  const std::string what = "stand-in for " + name;
  auto patch = periodic_patch(repeat, library, size, radius);
  // The garment's take-up, for the stitch types this patch has.
  std::map<std::string, double> take_up_by_type;
  for (const auto& [type, factor] : stand_in.take_up_by_type)
    if (std::count(patch.yarn.type_names.begin(), patch.yarn.type_names.end(), type.substr(0, type.find(':')))) take_up_by_type[type] = factor;
  const auto system = relax::make_yarn_system(patch.yarn, stand_in.take_up, take_up_by_type, options.sampling);
  // The patch's own repeat (an odd number of rows twice over) tiled as it was emitted.
  const mesh::Pattern patch_repeat = patch.repeat[1] == repeat.height() ? repeat : mesh::stacked(repeat, 2);
  const auto tiles = mesh::pattern_stitch_mesh(patch_repeat, patch.tiles, patch.tiles, size);
  // The forces the garment's relaxation feels: the patch-tracking ones too (the patch has no border loops).
  auto shape = options.shape;
  shape.boundary = false;
  relax::ShapeTargets targets = shape_targets(tiles, patch.yarn, shape);
  targets.periodic = patch.map;
  relax::YarnState state = relax::initial_state(system, options);
  const auto run = relax::make_cpu_yarn_relaxer(system, targets, options)->run(state);
  if (run.stopped_by == relax::StopReason::Diverged) throw Error("", what, "the periodic patch's relaxation diverged");
  Vector3d drift = Vector3d::Zero();
  int real = 0;
  for (int p = 0; p < system.num_points(); ++p)
    if (patch.ring[p] == 0) drift += state.points.col(p) - system.points.col(p), ++real;
  if (real == 0) throw Error("", what, "the periodic patch has no real point");
  drift /= real;
  // Each place's stitch in the middle repeat, the real one (of a stacked repeat, its lower copy).
  const int middle = patch.tiles / 2;
  const int places = repeat.stitches();
  RelaxedRepeat out;
  const double nearby = 2 * (size.width + size.height);  // a cheap test before the frame's
  for (int place = 0; place < places; ++place) {
    const int f = mesh::repeat_face(patch_repeat, patch.tiles, middle, middle, place);
    const Bilinear frame(tiles, f);
    const Vector3d centroid = frame.at(0.5, 0.5);
    std::vector<Vector3d> where, move;
    std::vector<char> cable;
    for (int p = 0; p < system.num_points(); ++p) {
      if ((system.points.col(p) - centroid).norm() > nearby) continue;
      const Vector3d uvh = frame.local(system.points.col(p));
      if (uvh.x() < -1 || uvh.x() > 2 || uvh.y() < -1 || uvh.y() > 2) continue;
      where.push_back(uvh);
      cable.push_back(on_cable(patch.yarn, p));
      move.push_back(frame.split(state.points.col(p) - system.points.col(p) - drift, uvh.x(), uvh.y()));
    }
    out.where.push_back(std::move(where));
    out.cable.push_back(std::move(cable));
    out.move.push_back(std::move(move));
    out.size.emplace_back(frame.width(), frame.height());
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

Eigen::Matrix3Xd stand_in_preview(const mesh::StitchMesh& stitch, const relax::YarnCurves& yarn, const mesh::StitchLibrary& library,
                                  const relax::YarnRelaxOptions& options, const StandInOptions& stand_in,
                                  StandInReport& report) {
  const auto started = std::chrono::steady_clock::now();
  stand_in.validate();
  const int n = static_cast<int>(yarn.points.size());
  if (static_cast<int>(yarn.point_face.size()) != n || static_cast<int>(yarn.point_type.size()) != n)
    throw Error("", "stand-in", "the yarn does not say which face and stitch type each point was emitted for");
  const auto plain = mesh::find_repeats(stitch, stand_in.max_period, stand_in.reach);
  const auto tiled = mesh::find_tiled_repeats(stitch, stand_in.patterns);
  for (size_t k = 0; k < tiled.patterns.size(); ++k)
    spdlog::info("stand-in: {} whole repeats of {} found", tiled.repeats[k], tiled.patterns[k].name);
  const auto regions = regions_of(stitch, stand_in, plain, tiled);
  spdlog::info("stand-in: {} repeating patterns found in {:.2f} s", plain.repeats.size() + tiled.patterns.size(),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  Eigen::Matrix3Xd base(3, n);
  for (int p = 0; p < n; ++p) base.col(p) = yarn.points[p];
  Eigen::Matrix3Xd out = base;
  std::vector<char> placed(n, 0);
  // Each point on its face; the yarn of the cable faces made at emission on the nearest stitch along it (the
  // turns and bind-offs at borders follow theirs).
  const auto owner = owner_faces(yarn);
  std::vector<std::vector<int>> points_of(stitch.faces.size());
  for (int p = 0; p < n; ++p) {
    const int f = on_cable(yarn, p) ? owner[p] : yarn.point_face[p];
    if (f >= 0 && f < static_cast<int>(stitch.faces.size())) points_of[f].push_back(p);
  }
  report = {};
  const double r = yarn.radius;
  for (const Region& region : regions) {
    const mesh::Pattern& repeat = *region.repeat;
    const std::vector<int>& faces = region.faces;
    const auto t0 = std::chrono::steady_clock::now();
    // The patch at the region's mean stitch size: its yarn as long as the region's.
    const mesh::StitchSize mean = mean_stitch_size(stitch, region);
    const std::string& text = region.name;
    spdlog::info("stand-in {}: {} faces, mean stitch {:.3f} x {:.3f} mm", text, faces.size(), mean.width, mean.height);
    const auto relaxed = relax_repeat(repeat, text, library, mean, r, options, stand_in);
    StandInRepeat entry{text, repeat.width(), repeat.height(), static_cast<int>(faces.size()), relaxed.steps, relaxed.converged,
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()};
#pragma omp parallel for schedule(dynamic, 16)
    for (int i = 0; i < static_cast<int>(faces.size()); ++i) {
      const int f = faces[i], place = region.place[i];
      const auto& where = relaxed.where[place];
      const Bilinear frame(stitch, f);
      // Each point to the patch's point at its place around the same stitch of the repeat: lengths in the
      // patch's stitch (u along the course times its width, v along the wale times its height, h as it is).
      const Eigen::Vector2d& size = relaxed.size[place];
      const auto distance = [&](const Vector3d& a, const Vector3d& b) {
        return Vector3d((a.x() - b.x()) * size.x(), (a.y() - b.y()) * size.y(), a.z() - b.z()).norm();
      };
      for (int p : points_of[f]) {
        const Vector3d uvh = frame.local(base.col(p));
        double best = r;  // no match farther than one yarn radius
        int match = -1;
        // A cable's crossing yarn to the patch's, a stitch's to a stitch's.
        const char cable = on_cable(yarn, p);
        for (size_t q = 0; q < where.size(); ++q)
          if (const double d = distance(uvh, where[q]); d < best && relaxed.cable[place][q] == cable) best = d, match = static_cast<int>(q);
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
  const auto system = relax::make_yarn_system(yarn);
  const relax::TopologyAuditor auditor(system);
  for (int rings = 1;;) {
    out = base;
    for (int p = 0; p < n; ++p)
      if (placed[p]) out.col(p) = mapped.col(p);
    relax::follow_placed(yarn, placed, base, out);
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
      if (placed[p] && drop[owner[p]]) placed[p] = 0, ++dropped;
    report.taken_back += dropped;
    if (dropped == 0) ++rings;
  }
  report.placed = static_cast<int>(std::count(placed.begin(), placed.end(), 1));
  report.following = n - report.placed;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace skein::workflow
