#include "relax/shape_targets.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include <Eigen/Geometry>

#include "common/error.hpp"
#include "relax/yarn_model.hpp"

namespace skein::relax {

void ShapeOptions::validate() const {
  const auto check = [](double v, const char* name) {
    if (!(v >= 0) || !std::isfinite(v)) throw Error("", "shape preservation", std::string(name) + " must be finite and not negative, found " + std::to_string(v));
  };
  check(k_normal, "k_normal");
  check(k_normal_far, "k_normal_far");
  check(normal_threshold, "normal_threshold");
  check(k_tangent, "k_tangent");
  if (ring < 0 || ring > 8) throw Error("", "shape preservation", "the patch ring must be in 0..8, found " + std::to_string(ring));
}

void project_boundary(const ShapeTargets& targets, Eigen::Matrix3Xd& delta) {
#pragma omp parallel for schedule(static)
  for (int l = 0; l < static_cast<int>(targets.boundary_loops.size()); ++l) {
    const auto& loop = targets.boundary_loops[l];
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int p : loop) mean += delta.col(p);
    mean /= static_cast<double>(loop.size());
    for (int p : loop) delta.col(p) -= mean;
  }
}

double patch_energy(const ShapeTargets& targets, const ShapeOptions& options, double radius, const Eigen::Matrix3Xd& points,
                    Eigen::Matrix3Xd& grad) {
  const int n = static_cast<int>(targets.patches.size());
  std::vector<Eigen::Vector3d> slope(n);
  std::vector<double> energy(n);
  const double h = options.normal_threshold * radius;
#pragma omp parallel for schedule(static)
  for (int k = 0; k < n; ++k) {
    const auto& patch = targets.patches[k];
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < patch.points.size(); ++i) sum += patch.weights[i] * points.col(patch.points[i]);
    // Eq. 7 over the weight sum: the patch's weighted mean drift.
    const Eigen::Vector3d v = (sum - patch.start_sum) / patch.weight_sum;
    model::Vec3<double> s;
    energy[k] = model::patch_tracking<double>({v.x(), v.y(), v.z()}, {patch.normal.x(), patch.normal.y(), patch.normal.z()}, patch.weight_sum,
                                              options.k_normal, options.k_normal_far, h, options.k_tangent, s);
    slope[k] = {s.x, s.y, s.z};
  }
  double total = 0;
  for (int k = 0; k < n; ++k) {
    total += energy[k];
    const auto& patch = targets.patches[k];
    for (size_t i = 0; i < patch.points.size(); ++i) grad.col(patch.points[i]) += patch.weights[i] * slope[k];
  }
  return total;
}

}  // namespace skein::relax
