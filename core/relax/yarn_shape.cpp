#include "relax/yarn_shape.hpp"

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

ShapeTargets shape_targets(const mesh::StitchMesh& mesh, const mesh::YarnCurves& yarn, const ShapeOptions& options) {
  options.validate();
  const int faces = static_cast<int>(mesh.faces.size());
  std::vector<std::vector<int>> loop(faces);
  for (int p = 0; p < static_cast<int>(yarn.points.size()); ++p) {
    const int f = p < static_cast<int>(yarn.point_face.size()) ? yarn.point_face[p] : -1;
    if (f >= 0 && f < faces) loop[f].push_back(p);
  }
  const auto table = mesh::edge_table(mesh);
  std::vector<std::vector<int>> neighbours(faces);
  std::vector<char> border(faces, 0);
  for (const auto& [key, uses] : table) {
    if (uses.count == 1) border[uses.use[0].face] = 1;
    if (uses.count == 2) {
      neighbours[uses.use[0].face].push_back(uses.use[1].face);
      neighbours[uses.use[1].face].push_back(uses.use[0].face);
    }
  }
  ShapeTargets out;
  if (options.boundary)
    for (int f = 0; f < faces; ++f)
      if (border[f] && !loop[f].empty()) out.boundary_loops.push_back(loop[f]);
  if (!options.patches) return out;
  for (int centre = 0; centre < faces; ++centre) {
    if (loop[centre].empty()) continue;
    // Faces within `ring` edges, breadth first; tent weight 1 - distance / (ring + 1) (Yuksel §6.3).
    std::map<int, int> distance{{centre, 0}};
    std::vector<int> frontier{centre};
    for (int d = 1; d <= options.ring; ++d) {
      std::vector<int> next;
      for (int f : frontier)
        for (int g : neighbours[f])
          if (distance.emplace(g, d).second) next.push_back(g);
      frontier = std::move(next);
    }
    ShapeTargets::Patch patch;
    for (const auto& [f, d] : distance) {
      const double w = 1.0 - static_cast<double>(d) / (options.ring + 1);
      for (int p : loop[f]) {
        patch.points.push_back(p);
        patch.weights.push_back(w);
        patch.start_sum += w * yarn.points[p];
        patch.weight_sum += w;
      }
    }
    // Newell normal of the centre face.
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    const auto& face = mesh.faces[centre];
    for (int k = 0; k < face.size(); ++k) normal += mesh.vertices[face.vertex(k)].cross(mesh.vertices[face.vertex(k + 1)]);
    if (normal.norm() > 0) patch.normal = normal.normalized();
    out.patches.push_back(std::move(patch));
  }
  return out;
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
