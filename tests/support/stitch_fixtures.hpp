#pragma once
// Helpers for tests that work on stitch meshes.
#include <vector>

#include "stitchmesh/stitch_mesh.hpp"

namespace skein::testing {

/// Every face id of the mesh.
inline std::vector<int> all_faces(const mesh::StitchMesh& s) {
  std::vector<int> all(s.faces.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  return all;
}

/// The vertices along the top edges of stitches [from, to) of a row (left to right): a cable path.
inline std::vector<int> top_path(const mesh::StitchMesh& s, int row, int from, int to) {
  const auto rows = mesh::faces_by_row(s);
  std::vector<int> path;
  for (int i = from; i < to; ++i) {
    const auto& f = s.faces[rows[row][i]];
    if (path.empty()) path.push_back(f.vertex(f.size() - 1));
    path.push_back(f.vertex(f.bottom + 1));
  }
  return path;
}

}  // namespace skein::testing
