#include "workflow/yarn_shape.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include <Eigen/Geometry>

#include "common/error.hpp"
#include "relax/yarn_model.hpp"

namespace skein::workflow {

relax::ShapeTargets shape_targets(const mesh::StitchMesh& mesh, const relax::YarnCurves& yarn, const relax::ShapeOptions& options) {
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
  relax::ShapeTargets out;
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
    relax::ShapeTargets::Patch patch;
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

}  // namespace skein::workflow
