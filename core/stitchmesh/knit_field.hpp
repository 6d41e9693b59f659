#pragma once
// Stitch meshes from any surface (issue 25, part 1): instead of labeling the artist's quads (Yuksel 2012 §5),
// a knitting-time field is computed on the surface (the geodesic distance from where knitting starts, by the
// heat method) and rows are traced as its isolines one stitch height apart, as Stitch Meshing (Wu et al. 2018)
// and AutoKnit (Narayanan et al. 2018) do. Each row is sampled at the stitch width and neighbouring rows are
// joined into faces of one stitch each: quads, and where a row is longer or shorter than the one below, faces
// with two top or two bottom course edges (Yuksel Table 1's increases and decreases), spread along the row.
// Triangles, n-gons, poles and closed surfaces all go through; the result is an ordinary labeled mesh that
// the rest of the pipeline (tessellation, relaxation, yarn) takes as it takes a labeled quad mesh.
#include <optional>

#include <Eigen/Core>

#include "stitchmesh/input_mesh.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/tessellation.hpp"

namespace skein::mesh {

/// Where knitting starts (or ends). A border: the run of border edges through `border_edge` up to the corners where the
/// border turns by more than kFieldCornerDegrees (a tube's end: its whole loop). A point: the vertex nearest
/// to it, knitting in the round outwards from a small ring around it (a hat's crown, a sphere's pole).
struct KnitStart {
  int border_edge = -1;                  ///< used when `point` is not set; -1: the lowest border edge
  std::optional<Eigen::Vector3d> point;  ///< the mesh's units
};

/// A row's second continuation shorter than this share of the first is a sliver the field's error cut off at a
/// border, dropped; a longer one is a branch.
inline constexpr double kFieldSliver = 0.25;

/// A border turning by more than this [degrees] ends a start run.
inline constexpr double kFieldCornerDegrees = 60;

/// The traced rows as a labeled mesh of one face per stitch, with tessellation values of 1 everywhere (so that
/// tessellate() keeps its faces as they are), and what the trace saw.
struct TracedRows {
  InputMesh mesh;
  Labeling labels;
  TessellationValues values;
  int levels = 0;          ///< isolines traced
  double field_max = 0;    ///< the farthest point's knitting distance [mesh units]
  int row_starts = 0;      ///< rows with no row below them (cast-ons)
  int row_ends = 0;        ///< rows with no row above them (closed off)
};

/// Border edges of `start`'s run, in order along the border (the surface to their left, seen from outside).
std::vector<int> field_start_run(const InputMesh& surface, int border_edge);

/// Traces a stitch mesh on `surface` from `start` at `size` (the mesh's units are millimetres). With `end` (a
/// border or a point, as a start is given), the field runs from 0 on the start to its largest on the end, so
/// that the rows turn from the start's shape to the end's and the last row lies along the end. Rows that split
/// or merge (a thumb, sleeves, a hole) are joined run by run (docs/stitch-a-garment.md). Throws skein::Error
/// naming the mesh and the place for: a start that is not a border edge, a piece of the surface that the start
/// does not reach, a field the heat method could not compute, rows that split and merge at once or meet
/// unevenly, joins that would break a rule of meshes, and a surface too small for a row.
TracedRows trace_stitch_mesh(const InputMesh& surface, const KnitStart& start, const StitchSize& size, const std::optional<KnitStart>& end = {});

}  // namespace skein::mesh
