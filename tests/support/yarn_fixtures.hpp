#pragma once
// Yarn for relaxation tests: rings, and small knitted pieces emitted from the bundled models.
#include <cmath>
#include <string>

#include <Eigen/Core>

#include "garments.hpp"
#include "relax/yarn_relax.hpp"
#include "relax/yarn_system.hpp"
#include "stitchmesh/edits.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/stitch_model.hpp"
#include "stitchmesh/tessellation.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "workflow/yarn_shape.hpp"

namespace skein::testing {

/// A closed ring of `n` points of radius `radius` around `centre`, in the plane spanned by `u` and `v`.
inline void add_ring(relax::YarnCurves& yarn, const Eigen::Vector3d& centre, const Eigen::Vector3d& u, const Eigen::Vector3d& v, double radius,
                     int n) {
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    yarn.points.push_back(centre + radius * (std::cos(a) * u + std::sin(a) * v));
    yarn.point_face.push_back(-1);
    yarn.point_type.push_back(-1);
  }
  yarn.curve_start.push_back(static_cast<int>(yarn.points.size()));
  yarn.closed.push_back(1);
}

/// The control points of curve `c`.
inline std::vector<Eigen::Vector3d> curve_points(const relax::YarnCurves& y, int c) {
  return {y.points.begin() + y.curve_start[c], y.points.begin() + y.curve_start[c + 1]};
}

/// A CPU relaxation from the system's own points: its last state and its report.
struct RelaxRun {
  relax::YarnState state;
  relax::YarnRelaxReport report;
};
inline RelaxRun relaxed(const relax::YarnSystem& system, const relax::YarnRelaxOptions& options, const relax::ShapeTargets& targets = {}) {
  RelaxRun run{relax::initial_state(system, options), {}};
  run.report = relax::make_cpu_yarn_relaxer(system, targets, options)->run(run.state);
  return run;
}

/// Two rings through each other (a Hopf link), each of radius 3 mm, yarn radius r.
inline relax::YarnCurves linked_rings(double r = 0.5, int n = 24) {
  relax::YarnCurves yarn;
  yarn.radius = r;
  add_ring(yarn, {0, 0, 0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 3, n);
  add_ring(yarn, {3, 0, 0}, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(), 3, n);
  return yarn;
}

/// A stitch mesh of one of the bundled models at a coarse stitch size, with a fill ("" keeps knit).
inline mesh::StitchMesh small_piece(const mesh::InputMesh& m, const std::string& fill, mesh::StitchSize size = {15, 12.5}) {
  const auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  auto s = mesh::tessellate(m, l, mesh::initial_values(m, l, size));
  if (!fill.empty()) {
    std::vector<int> all(s.faces.size());
    for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
    s = mesh::fill(s, all, mesh::parse_fill(fill));
  }
  return s;
}

inline relax::YarnCurves yarn_of(const mesh::StitchMesh& s, double radius = 1.0) {
  mesh::EmitOptions options;
  options.yarn_radius = radius;
  return mesh::emit_yarn(s, mesh::StitchLibrary::bundled(), options);
}

/// A small knitted piece of a bundled model: its stitch mesh, yarn, system and shape targets.
struct Knitted {
  mesh::StitchMesh piece;
  relax::YarnCurves yarn;
  relax::YarnSystem system;
  relax::ShapeTargets targets;
};
inline Knitted knitted(const mesh::InputMesh& m, const std::string& fill, mesh::StitchSize size = {15, 12.5}) {
  Knitted k;
  k.piece = small_piece(m, fill, size);
  k.yarn = yarn_of(k.piece);
  k.system = relax::make_yarn_system(k.yarn);
  k.targets = workflow::shape_targets(k.piece, k.yarn, {});
  return k;
}

}  // namespace skein::testing
