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

}  // namespace skein::testing
