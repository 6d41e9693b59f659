#pragma once
// Repair of meshes from other tools (issue 25, part 2), by CGAL's Polygon Mesh Processing on the polygon soup the
// reader returns: what it can mend is mended and counted, so that `--repair` can say what it changed.
#include <string>

#include "stitchmesh/input_mesh.hpp"

namespace skein::mesh {

/// What repair_mesh_soup changed.
struct RepairReport {
  long non_finite_faces = 0;    ///< faces with a NaN or infinite corner, removed
  long merged_points = 0;       ///< points at the same position as another, merged into it
  long degenerate_faces = 0;    ///< faces with fewer than 3 distinct corners or zero area, removed
  long duplicate_faces = 0;     ///< faces with the same corners as another, removed
  long reversed_faces = 0;      ///< faces turned round to agree with their neighbours
  long split_points = 0;        ///< points duplicated where the surface met itself (a bow tie, an edge of 3+ faces)
  long unused_points = 0;       ///< points no face uses any more, removed
  bool changed() const;
  std::string summary() const;  ///< "merged 3 duplicate points, removed 1 degenerate face, ..." or "nothing to repair"
};

/// The soup repaired: non-finite and degenerate faces removed, duplicate points merged, duplicate faces
/// removed, faces oriented consistently and the points where the surface meets itself split (CGAL
/// repair_polygon_soup's steps and orient_polygon_soup), unused points dropped.
MeshSoup repair_mesh_soup(MeshSoup soup, RepairReport& report);

}  // namespace skein::mesh
