#pragma once
// A triangle mesh as glTF 2.0 (tinygltf): the one writer behind the yarn's tubes and the smocked fabric.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace skein {

/// Triangles of one material.
struct GltfPrimitive {
  std::vector<std::uint32_t> indices;  ///< three per triangle, into the mesh's vertices
  std::string material;                ///< the material's name; empty: none (the viewer's default)
  std::array<double, 3> linear_rgb{0.8, 0.8, 0.8};  ///< its base colour, linear (not sRGB)
  bool double_sided = false;           ///< both faces shaded (a sheet of fabric), else back faces culled
};

/// A mesh to write: vertices in mm (written in metres, glTF's unit), unit normals, one or more primitives.
struct GltfMesh {
  std::vector<std::array<double, 3>> positions;
  std::vector<std::array<double, 3>> normals;
  std::vector<GltfPrimitive> primitives;
  std::string mesh_name, node_name;
};

/// Writes `mesh` atomically as .glb (binary) or .gltf (JSON with the buffer embedded), by the path's extension.
/// Throws skein::Error naming the path when the mesh has no triangle, more vertices than 32-bit indices reach,
/// or tinygltf cannot write it.
void write_gltf_mesh(const GltfMesh& mesh, const std::filesystem::path& path);

}  // namespace skein
