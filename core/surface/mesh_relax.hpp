#pragma once
#include <atomic>
#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "stitchmesh/stitch_mesh.hpp"
#include "surface/subdiv_surface.hpp"

namespace skein::surface {

/// Settings of the mesh-based relaxation (Yuksel 2012 §6.1); validate() is called once before work.
struct MeshRelaxOptions {
  double alpha = 0.9;        ///< rest-size scale: N r_wale r_course = α A (0 < α ≤ 1)
  double aspect = 1.0;       ///< a = r_wale / r_course
  double k_stretch = 2.0, k_shear = 0.2, k_wale = 2.0;
  double k_fold = 10.0;      ///< keeps stitches from turning over (0 = off); not in Yuksel 2012
  double fold_area = 0.25;   ///< the guard acts below this fraction of the rest corner area
  double time_step = 0;      ///< h of backward Euler [mm]; 0 = 1000 r_course (so large that steps are Newton steps)
  int max_steps = 200;
  double tolerance = 0.01;   ///< stop when no vertex moves more than tolerance × r_course in a step
  double max_move = 2;       ///< no vertex moves more than this × r_course in one step (a trust region)
  int cg_iterations = 80;    ///< an inexact Newton step: more rarely pays
  double cg_tolerance = 1e-4;  ///< relative residual of the modified CG
  int samples_per_edge = 8;    ///< fine triangles: samples along each ptex face edge
  /// When set and it turns true, run() returns after the step in progress (the app's stop button).
  const std::atomic<bool>* interrupt = nullptr;
  void validate() const;       ///< throws skein::Error naming the option
};

struct MeshRelaxStep {
  int step = 0;
  double energy = 0;
  double max_displacement = 0;  ///< [mm]
  int cg_iterations = 0;
  double time_step = 0;         ///< h actually used (halved while the energy would rise)
};

struct MeshRelaxReport {
  std::vector<MeshRelaxStep> steps;
  bool converged = false;  ///< not converging is a result, not an error
  double r_course = 0, r_wale = 0;
  double initial_energy = 0;
  int turned_over_before = 0, turned_over_after = 0;  ///< see MeshRelaxer::turned_over()
};

/// Relaxes a stitch mesh on the Catmull-Clark limit surface of its input mesh (Yuksel 2012 §6.1): stretch
/// springs (eq. 2) on wale and course edges and sub-quad diagonals, shear on every sub-quad corner (eq. 3),
/// wale struts (eq. 4); backward Euler (eq. 1) with a time step so large that steps are Newton steps, solved
/// by conjugate gradients in each vertex's free directions (Baraff & Witkin 1998's constraint filter: the
/// surface's tangents; along the border for border vertices); vertices stay on the limit surface. A step
/// that would raise the energy is retried with half the time step.
class MeshRelaxer {
public:
  /// @param control_points, control_faces  the input mesh (plain values)
  MeshRelaxer(const std::vector<Eigen::Vector3d>& control_points, const std::vector<std::vector<int>>& control_faces,
              const mesh::StitchMesh& stitch, const MeshRelaxOptions& options = {});
  ~MeshRelaxer();

  double energy() const;
  MeshRelaxStep step();
  /// Steps until converged or max_steps; `on_step` sees every step (progress, logs).
  MeshRelaxReport run(const std::function<void(const MeshRelaxStep&)>& on_step = {});

  const std::vector<Eigen::Vector3d>& positions() const;
  const std::vector<SurfaceCoord>& coords() const;
  const std::vector<char>& on_border() const;
  const SubdivSurface& surface() const;
  double r_course() const;
  double r_wale() const;
  /// Stitches turned over: faces whose normal, by the order of their corners, points against the surface's.
  int turned_over() const;
  /// The stitch mesh with the relaxed positions.
  mesh::StitchMesh relaxed() const;

private:
  struct Impl;
  std::unique_ptr<Impl> m;
};

/// Per-face stretch against the rest shape: the mean edge strain (|e| / rest − 1 over the face's edges) and the
/// area strain (area / (sub-quads × r_course × r_wale) − 1).
struct FaceStretch {
  std::vector<double> edge_strain, area_strain;
};
FaceStretch face_stretch(const mesh::StitchMesh& stitch, double r_course, double r_wale);

}  // namespace skein::surface
