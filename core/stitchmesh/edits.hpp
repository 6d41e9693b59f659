#pragma once
#include <string>
#include <vector>

#include "stitchmesh/stitch_mesh.hpp"

namespace skein::mesh {

/// Stitch-mesh edits (Yuksel 2012 §5.3, Fig. 13). Each takes a valid mesh and returns the edited copy, or
/// throws skein::Error with the reason when the edit would break a rule of validate(); the input is never
/// changed, so undo is keeping the previous value.

/// Sets the stitch type of the given faces; the type must fit each face's shape.
StitchMesh set_stitch_type(const StitchMesh& mesh, const std::vector<int>& faces, const std::string& type);

/// Splits the course edge u-v at its middle: the stitch below gains a top edge (an increase), the stitch
/// above gains a bottom edge (a decrease). Faces whose type no longer fits get the default of their shape.
StitchMesh split_course_edge(const StitchMesh& mesh, int u, int v);
/// Collapses the course edge u-v onto one of its ends (the one no wale edge meets): the inverse of a split.
StitchMesh collapse_course_edge(const StitchMesh& mesh, int u, int v);

/// Adds a wale edge through face f, splitting it into two stitches; a side with a single course edge is
/// split at its middle first (which makes the neighbour across it an increase or decrease).
StitchMesh add_wale_edge(const StitchMesh& mesh, int face);
/// Removes the wale edge u-v, merging its two stitches, and collapses the course edges that its ends
/// leave free, so that the merged face keeps a stitch shape (the inverse of add_wale_edge).
StitchMesh remove_wale_edge(const StitchMesh& mesh, int u, int v);

enum class WaleEnd { Bottom, Top };
/// Moves one end of the wale edge u-v one vertex along its course line (+1 right, -1 left, seen along the
/// wale direction of the face on the edge's left), handing a course edge from one stitch to the other.
StitchMesh shift_wale_edge(const StitchMesh& mesh, int u, int v, WaleEnd end, int direction);

/// Marks a run of consecutive course edges between the same two rows as cable edges (Yuksel §4.5);
/// `path` lists the run's vertices in order. Unmark with unmark_cable.
StitchMesh mark_cable(const StitchMesh& mesh, const std::vector<int>& path, int shift, int order);
StitchMesh unmark_cable(const StitchMesh& mesh, const std::vector<int>& path);

/// Where each stitch sits in the knitted fabric: its row counted bottom-up (`level`) and its column, lined up
/// with the stitches it is worked into (the second stitch above an increase takes the next column).
struct StitchGrid {
  std::vector<long> level, column;  ///< per face
};
StitchGrid stitch_grid(const StitchMesh& mesh);
/// The lowest, then leftmost, of `faces` in the stitch grid: where a tiled pattern starts unless told.
/// Throws skein::Error when `faces` is empty.
int lowest_left(const StitchMesh& mesh, const std::vector<int>& faces);

/// Fills over a set of faces with a knit/purl pattern (Yuksel §5.3). Only plain stitches (one bottom and
/// one top edge) change; increases and decreases keep their type.
enum class FillKind { Stockinette, ReverseStockinette, Rib, Garter, Seed, Moss };
struct Fill {
  FillKind kind = FillKind::Rib;
  int knits = 1;  ///< rib: knit columns per repeat
  int purls = 1;  ///< rib: purl columns per repeat
};
/// Parses "stockinette", "reverse", "rib", "rib2x2", "rib3x1", "garter", "seed", "moss"; throws skein::Error.
Fill parse_fill(const std::string& text);
StitchMesh fill(const StitchMesh& mesh, const std::vector<int>& faces, const Fill& pattern);

/// Faces within `rows` stitch rows of a border course edge (cast-on and bind-off edges: hems, cuffs,
/// necklines), counted across course edges; the usual place for ribbing.
std::vector<int> faces_near_border(const StitchMesh& mesh, int rows);

}  // namespace skein::mesh
