#pragma once
// The smocked fabric in 3-D (Zhou, Ren and Sorkine-Hornung 2024, §4.2): a fine triangle mesh of the fabric,
// its stitching points and stitch midpoints guided to the lifted embedding (eqs. 9-11), with stretching and
// bending of the fabric and contact by a barrier (the IPC idea, Li et al. 2020): each Newton step's line search
// is capped by a conservative continuous-collision bound, so no step lets the fabric pass through itself. The
// result is certified at the end by an exact triangle-triangle test (CGAL's exact predicates).
#include <array>
#include <atomic>
#include <vector>

#include <Eigen/Core>

#include "smocking/smocking_embed.hpp"
#include "smocking/smocking_pattern.hpp"

namespace skein::smocking {

/// The 3-D stage's settings. Lengths in mm; energies per mm of the flat fabric's spacing (see the .cpp).
struct ClothOptions {
  int subdivisions = 2;        ///< fine grid squares per side of a pattern square (even: stitch midpoints are vertices)
  double k_stretch = 100;      ///< edge springs of the fabric (membrane)
  double k_bend = 30;          ///< quadratic bending (Bergou et al. 2006) of the flat fabric: 1 crumples it, 30 folds it in pleats
  double w_pos = 10;           ///< eq. 11: stitching points and midpoints toward their lifted places
  double w_sew = 1;            ///< eq. 10: each stitch toward its lifted length
  double inertia = 1;          ///< proximal weight of each frame (the incremental potential's mass / Δt²), per mm² of fabric
  double reach = -1;           ///< the barrier's reach d̂ [mm]; below 0: the embedding's fabric thickness τ
  double k_barrier = 1;        ///< the barrier's stiffness κ at the start (IPC's adaptive κ doubles it as pairs press in)
  double k_barrier_max = 1e4;  ///< κ doubles up to this times k_barrier (1: κ held at k_barrier)
  int frames = 100;            ///< as the paper's 100 frames at most
  int newton_per_frame = 20;
  double tolerance = 1e-2;     ///< a frame has settled when a Newton step moves no point more than this × the fine spacing

  /// Throws skein::Error naming the option and the rule broken.
  void validate() const;
};

struct Cloth {
  Eigen::Matrix3Xd rest;                   ///< the flat fabric, z = 0 [mm]
  Eigen::Matrix3Xd positions;              ///< the smocked fabric [mm]
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> grid_vertex;            ///< per pattern grid point, its fine vertex
  int frames = 0, newton_iterations = 0;
  double reach = 0;                        ///< d̂ used
  double barrier_stiffness = 0;            ///< κ at the end (it doubles while a pair keeps closing in deep in the reach)
  double energy = 0;                       ///< the last frame's incremental potential at the end, with the final κ
  double smallest_distance = 0;            ///< between non-adjacent triangles' closest elements at the end [mm]
  double largest_stretch = 0;              ///< max over fabric edges of length / rest - 1
  double target_error = 0;                 ///< RMS distance of the guided points from their lifted places [mm]
  long ccd_limited_steps = 0;              ///< line searches the collision bound cut short
  long shifted_steps = 0;                  ///< Newton steps whose factorization broke down and took a diagonal shift
};

/// Drapes the fine fabric from flat to the lifted embedding of `pattern` (embed() then lift()). When `stop` is
/// given and becomes true, throws skein::Error ("stopped") at the next Newton step.
Cloth smock_cloth(const SmockingPattern& pattern, const Embedding& embedding, const Lift& lift, const ClothOptions& options,
                  const std::atomic<bool>* stop = nullptr);

/// The barrier's reach d̂ that smock_cloth uses [mm].
double barrier_reach(const SmockingPattern& pattern, const Embedding& embedding, const ClothOptions& options);

/// The first frame's incremental potential (anchored at the flat fabric) at fine positions `x` (3 x points, as
/// Cloth::positions), and its gradient when `grad` is given: for checking the energies against finite differences.
double first_frame_potential(const SmockingPattern& pattern, const Embedding& embedding, const Lift& lift, const ClothOptions& options,
                             const Eigen::Matrix3Xd& x, Eigen::Matrix3Xd* grad);

/// Additive continuous collision detection (Li et al. 2021, C-IPC Algorithm 1, with no thickness) of two elements
/// moving along straight lines: a point x[0] and a triangle x[1..3], or two edges x[0..1] and x[2..3], each vertex
/// moving by dir[k] over the step. Returns the largest step fraction t in [0, 1] after which the two are still at
/// least a tenth of their distance at the start apart (conservative: never past a meeting).
double additive_ccd(const std::array<Eigen::Vector3d, 4>& x, const std::array<Eigen::Vector3d, 4>& dir, bool point_triangle);

/// Pairs of triangles that share no vertex and intersect, by CGAL's exact predicates (0 for a valid result).
long exact_intersections(const Cloth& cloth);

}  // namespace skein::smocking
