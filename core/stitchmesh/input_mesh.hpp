#pragma once
#include <filesystem>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include "common/contained.hpp"

namespace skein::mesh {

struct MeshTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
};
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<MeshTraits>;

/// One use of an edge by a face: the face and the edge's place k in the face loop
/// (local edge k runs from face vertex k to face vertex k+1).
struct EdgeUse {
  int face = -1;
  int local = -1;
};

/// The garment's polygon mesh: manifold, consistently oriented, polygons kept as they were drawn.
/// Face and edge ids are the OpenMesh indices; the face loops are kept in the order of the file.
class InputMesh {
public:
  /// Builds and validates a mesh. Throws skein::Error naming `source` and the face/vertex/edge at fault
  /// for: no faces, non-finite coordinates, faces with < 3 or repeated vertices, zero area,
  /// edges shared by more than two faces or with inconsistent orientation, non-manifold vertices.
  InputMesh(std::vector<Eigen::Vector3d> points, std::vector<std::vector<int>> faces, std::string source);

  const std::string& source() const { return m_source; }
  const PolyMesh& poly() const { return m_mesh; }
  int num_vertices() const { return static_cast<int>(m_points.size()); }
  int num_faces() const { return static_cast<int>(m_faces.size()); }
  int num_edges() const { return static_cast<int>(m_edge_vertices.size()); }

  const Eigen::Vector3d& point(int v) const { return m_points[v]; }
  const std::vector<Eigen::Vector3d>& points() const { return m_points; }
  const std::vector<int>& face(int f) const { return m_faces[f]; }
  const std::vector<std::vector<int>>& faces() const { return m_faces; }
  /// Edge id of local edge k of face f.
  int face_edge(int f, int k) const { return m_face_edges[f][k]; }
  const std::vector<int>& face_edges(int f) const { return m_face_edges[f]; }
  /// The two ends of edge e, lower vertex id first.
  std::pair<int, int> edge_vertices(int e) const { return m_edge_vertices[e]; }
  /// The faces using edge e (one on the border, two inside).
  const std::vector<EdgeUse>& edge_uses(int e) const { return m_edge_uses[e]; }
  bool is_border(int e) const { return m_edge_uses[e].size() == 1; }
  /// Edge between u and v, or -1.
  int find_edge(int u, int v) const;
  double edge_length(int e) const;
  /// Length of the bounding box diagonal (the model size).
  double bounding_diagonal() const;

private:
  std::string m_source;
  std::vector<Eigen::Vector3d> m_points;
  std::vector<std::vector<int>> m_faces;
  std::vector<std::vector<int>> m_face_edges;
  std::vector<std::pair<int, int>> m_edge_vertices;
  std::vector<std::vector<EdgeUse>> m_edge_uses;
  std::unordered_map<std::uint64_t, int> m_edge_of;
  PolyMesh m_mesh;
};

/// An InputMesh of the points the faces use, in the order they are first used (points no face uses are
/// dropped, the faces renumbered).
InputMesh with_used_points(const std::vector<Eigen::Vector3d>& points, std::vector<std::vector<int>> faces, std::string source);

/// What a mesh file holds, before any rule is checked: positions (welded across the file's meshes) and polygons.
struct MeshSoup {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> faces;
};

/// Reads a mesh file as load_mesh does (assimp in a child process under `limits`, points no face uses dropped)
/// without building the mesh, for repair (mesh_repair.hpp). Throws skein::Error as load_mesh does for the file.
MeshSoup read_mesh_soup(const std::filesystem::path& path, const ContainedLimits& limits = ContainedLimits::from_environment());

/// Reads any format assimp reads (OBJ, PLY, glTF, FBX, ...) without triangulating; identical vertices are
/// welded across all meshes of the file. assimp runs in a child process under `limits` (run_contained), so a
/// file that crashes it or makes it take all memory or time is an error, not the end of skein. Throws
/// skein::Error naming the file for a missing or unreadable file, an unknown format, a crash or a limit
/// reached in the reader, and every rule of InputMesh.
InputMesh load_mesh(const std::filesystem::path& path, const ContainedLimits& limits = ContainedLimits::from_environment());

/// Writes the mesh as OBJ with its polygons (atomically).
void write_obj(const InputMesh& mesh, const std::filesystem::path& path);

}  // namespace skein::mesh
