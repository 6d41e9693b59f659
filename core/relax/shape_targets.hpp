#pragma once
// What holds a garment's yarn to its shape while it relaxes (Yuksel 2012 §6.3) and a patch to its period
// (Leaf 2018 §5): the targets and the forces and projections they make. workflow/yarn_shape builds the targets
// from a stitch mesh.
#include <vector>

#include <Eigen/Core>

#include "relax/periodic_map.hpp"

namespace skein::relax {

/// Shape preservation (Yuksel 2012 §6.3) needs to know which control points form each stitch's yarn loop
/// (the points emitted for one face), which loops lie on the border, and the garment surface around them.
struct ShapeTargets {
  /// Eq. 5: per border stitch, its control points; the sum of their positions stays at its start value.
  std::vector<std::vector<int>> boundary_loops;
  /// Eqs. 6–7: a patch of loops within a ring of faces around a centre stitch, with tent weights that fall off
  /// with the ring distance, the surface normal at the centre and the weighted sum of the start positions.
  struct Patch {
    std::vector<int> points;
    std::vector<double> weights;
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    Eigen::Vector3d start_sum = Eigen::Vector3d::Zero();
    double weight_sum = 0;
  };
  std::vector<Patch> patches;
  /// Periodic boundary conditions of a pattern's periodic patch (Leaf 2018 §5): not shape preservation, but
  /// the other constraint on how the yarn may move.
  PeriodicMap periodic;
  bool empty() const { return boundary_loops.empty() && patches.empty() && periodic.empty(); }
};

struct ShapeOptions {
  bool boundary = true;      ///< the hard moment constraint of eq. 5 on border loops
  bool patches = true;       ///< the patch-tracking forces of eqs. 6–7
  int ring = 1;              ///< patch size: faces within this many edges of the centre face
  double k_normal = 0.5;     ///< κ_N below the threshold
  double k_normal_far = 50;  ///< added κ_N beyond it: the biphasic stiffening of eq. 6
  double normal_threshold = 1.0;  ///< [r]: mean normal drift of a patch where it stiffens
  double k_tangent = 0.05;   ///< κ_T
  void validate() const;
};

/// Eq. 5 as a projection: removes from `delta` the mean displacement of each boundary loop, so the loop's
/// sum of positions does not move.
void project_boundary(const ShapeTargets& targets, Eigen::Matrix3Xd& delta);

/// Eqs. 6–7: the patch-tracking energy at `points` (radius r scales the threshold); adds its gradient to `grad`.
double patch_energy(const ShapeTargets& targets, const ShapeOptions& options, double radius, const Eigen::Matrix3Xd& points,
                    Eigen::Matrix3Xd& grad);

}  // namespace skein::relax
