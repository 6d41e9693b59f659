#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "stitchmesh/stitch_mesh.hpp"

namespace skein::surface {

/// A point of the limit surface: a ptex face (quads: one per control face; an n-gon: n sub-faces, one per
/// corner) and (u, v) in [0, 1]².
struct SurfaceCoord {
  int ptex = -1;
  double u = 0, v = 0;
};

/// Limit position and first derivatives there.
struct SurfaceSample {
  Eigen::Vector3d position = Eigen::Vector3d::Zero(), du = Eigen::Vector3d::Zero(), dv = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal() const { return du.cross(dv).normalized(); }
};

/// The Catmull-Clark limit surface of a control mesh (Yuksel 2012 §6.1), evaluated with OpenSubdiv Far:
/// adaptive refinement with Gregory end caps in double precision, border edges and corners interpolated.
/// The control mesh is a plain value (points and face loops), so this class knows nothing of OpenMesh.
class SubdivSurface {
public:
  /// @param points     control points [mm]
  /// @param faces      counter-clockwise loops of point ids, 3 or more each
  /// @param isolation  adaptive refinement level around extraordinary vertices (derivatives there depend on it)
  SubdivSurface(const std::vector<Eigen::Vector3d>& points, const std::vector<std::vector<int>>& faces, int isolation = 4);
  ~SubdivSurface();
  SubdivSurface(SubdivSurface&&) noexcept;
  SubdivSurface& operator=(SubdivSurface&&) noexcept;

  int num_ptex_faces() const;
  /// The first ptex face of control face f and how many it has (1 for a quad, n for an n-gon).
  int ptex_of(int face) const;
  int ptex_count(int face) const;
  /// The control face a ptex face belongs to.
  int face_of_ptex(int ptex) const;

  SurfaceSample evaluate(const SurfaceCoord& at) const;

private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// A fine triangle approximation of the limit surface: every ptex face sampled on an n × n grid and split into
/// triangles, samples shared along ptex edges welded. Used to project points onto the surface (Yuksel §6.1).
struct SurfaceTriangles {
  std::vector<Eigen::Vector3d> positions;      ///< on the limit surface
  std::vector<Eigen::Vector3i> triangles;
  std::vector<int> triangle_ptex;              ///< every triangle lies in one ptex face
  std::vector<std::array<Eigen::Vector2d, 3>> triangle_uv;  ///< its corners' (u, v) in that ptex face
  std::vector<std::pair<int, int>> border;     ///< edges on the surface border (vertex ids)
  std::vector<int> border_triangle;            ///< the triangle each border edge belongs to
};
SurfaceTriangles triangulate(const SubdivSurface& surface, int samples_per_edge = 8);

/// Where a point lands on the surface: the closest point of the fine triangles, then the exact limit there.
struct Attachment {
  SurfaceCoord coord;
  int triangle = -1;                                   ///< of the fine approximation, to start the next search from
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< on the limit surface at coord
  double distance = 0;                                 ///< from the point projected [mm]
};

/// Projects points onto the surface (Yuksel §6.1: through the fine triangle approximation, barycentric
/// coordinates giving the surface coordinates). Points flagged `on_border` go to the closest border edge.
class SurfaceProjector {
public:
  SurfaceProjector(const SubdivSurface& surface, SurfaceTriangles triangles);
  Attachment attach(const Eigen::Vector3d& point, bool on_border = false) const;
  /// The same for a point that moved a little since it was attached at `previous`: walks the fine triangles
  /// (or border edges) from there instead of searching them all.
  Attachment reattach(const Eigen::Vector3d& point, const Attachment& previous, bool on_border) const;
  /// Moves an attachment toward `target` in the surface's own (u, v) (Gauss-Newton on the limit surface), so
  /// that small moves stay exact; a border attachment keeps its border coordinate. Leaving the ptex face (or a
  /// border corner) falls back to reattach().
  Attachment move(const Attachment& from, const Eigen::Vector3d& target, bool on_border) const;
  const SurfaceTriangles& triangles() const { return m_tris; }

private:
  const SubdivSurface& m_surface;
  SurfaceTriangles m_tris;
  double m_cell = 1;
  std::vector<std::pair<std::uint64_t, int>> m_grid;  ///< (cell key, triangle), sorted
  std::vector<std::vector<int>> m_vertex_triangles;    ///< fine triangles around each fine vertex
  std::vector<std::vector<int>> m_vertex_border;       ///< border edges at each fine vertex
  Attachment finish(const Eigen::Vector3d& point, int triangle, const Eigen::Vector3d& weights) const;
  /// The closest point of border edge e: its distance, the edge's triangle and the point's weights there.
  struct BorderHit {
    double distance;
    int triangle;
    Eigen::Vector3d weights;
  };
  BorderHit border_hit(const Eigen::Vector3d& point, int e) const;
  std::uint64_t key(const Eigen::Vector3d& p) const;
  SurfaceCoord coord_in(int triangle, const Eigen::Vector3d& barycentric) const;
};

/// Stitch-mesh vertices attached to the limit surface (Yuksel 2012 §6.1): vertices on the stitch mesh's
/// border go to the surface border, the rest to the closest point.
struct StitchAttachment {
  std::vector<SurfaceCoord> coords;
  std::vector<Eigen::Vector3d> positions;  ///< on the limit surface [mm]
  std::vector<int> triangles;              ///< fine triangle of each
  std::vector<char> on_border;
  double max_distance = 0;                 ///< largest move from the stitch mesh's own positions [mm]
};
StitchAttachment attach_stitch_mesh(const mesh::StitchMesh& stitch, const SurfaceProjector& projector);

}  // namespace skein::surface
