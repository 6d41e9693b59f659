#pragma once
// Periodic boundary conditions of a yarn system (Leaf 2018 §5, Algorithm 2): which control points copy which,
// the repeat's period, and the moves and gradients that keep the copies copies. Built by workflow's
// periodic_patch; used by the relaxers, the guard and the auditor.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "relax/yarn_system.hpp"

namespace skein::relax {

/// Periodic boundary conditions (Leaf 2018 §5, Algorithm 2): each virtual control point copies a real one
/// plus a fixed offset after every step, and frozen points never move.
struct PeriodicMap {
  std::vector<int> virtual_points;        ///< iV
  std::vector<int> real_points;           ///< iR, per virtual point
  std::vector<Eigen::Vector3d> offsets;   ///< d, per virtual point [mm]: a period_x + b period_y of its cell
  std::vector<Eigen::Vector2i> cells;     ///< per virtual point: its repeat (a, b) from the real one
  std::vector<int> frozen;                ///< points held where they are (the outermost copies)
  Eigen::Vector3d period_x = Eigen::Vector3d::Zero(), period_y = Eigen::Vector3d::Zero();  ///< the repeat's offsets [mm]
  bool empty() const { return virtual_points.empty() && frozen.empty(); }
};

/// Algorithm 2 on a step: every virtual point takes its real point's move and velocity, frozen points take
/// none. Positions that start consistent (virtual = real + offset) stay so.
void apply_periodic(const PeriodicMap& map, Eigen::Matrix3Xd& delta, Eigen::Matrix3Xd& velocities);

/// A real point and its virtual copies move as one (Leaf §5), so the pull-through guard holds them together:
/// each real point that has copies gets a group id from `first` on, shared with its copies, in `groups` (per point).
void group_copies(const PeriodicMap& map, std::vector<int>& groups, int first);

/// An adjustable repeat period: the patch squeezed or stretched by `sx` along the course (x) and `sy` along the
/// wale (y), positions and offsets alike, so that every virtual point stays its real point plus its offset.
/// Take the yarn's rest lengths before (make_yarn_system on the unscaled yarn), so the yarn keeps its length.
void scale_period(PeriodicMap& map, Eigen::Matrix3Xd& points, double sx, double sy);

/// Sets the repeat's period: every virtual point is placed at its real point plus its cell's new offset
/// (a period_x + b period_y); real points stay. The variable-cell relaxation's move (yarn_cell.hpp).
void set_period(PeriodicMap& map, Eigen::Matrix3Xd& points, const Eigen::Vector3d& period_x, const Eigen::Vector3d& period_y);

/// Zeroes the gradient of virtual and frozen points: they are not degrees of freedom, so neither the
/// integrator nor the convergence test (Leaf eq. 5) may count them.
void constrain_gradient(const PeriodicMap& map, Eigen::Matrix3Xd& gradient);

/// A periodic patch's yarn per stitch of its repeat (wales x courses): the rest lengths of the segments that start
/// at a real point, over the stitches; the loop length l of Munden's constants, in the system's units.
double patch_loop_length(const YarnSystem& system, const PeriodicMap& map, const std::array<int, 2>& repeat);

}  // namespace skein::relax
