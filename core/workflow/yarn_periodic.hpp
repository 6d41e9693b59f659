#pragma once
#include <array>
#include <vector>

#include <Eigen/Core>

#include "relax/periodic_map.hpp"
#include "relax/yarn_curves.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/stitch_model.hpp"

namespace skein::workflow {

/// A pattern's periodic patch: its yarn tiled (2k + 3) x (2k + 3) times, the centre repeat real and the k
/// rings around it virtual (at least two stitches or yarns wide, so that every real point sees the
/// neighbourhood it would have in an endless fabric). The outermost ring only makes the virtual stitches
/// interior ones at emission and is dropped (curves are cut there); virtual points that match no real one are
/// frozen.
struct PeriodicPatch {
  relax::YarnCurves yarn;
  relax::PeriodicMap map;
  std::vector<int> ring;               ///< per point: its repeat's distance from the centre (0: real; 1 for a centre point that copies another across its edge)
  Eigen::Vector3d period_x, period_y;  ///< the repeat's offsets [mm]
  int tiles = 0;                       ///< repeats along each side, the dropped ring included
  /// The patch's repeat in stitches (wales x courses): the pattern's, with its rows twice over when a knit has an
  /// odd number of them. A tiling's rows alternate in direction (the yarn turns at the sides), so its yarn repeats
  /// every two rows; a repeat of one row copied a row up would tie points of a left-going row to a right-going one.
  std::array<int, 2> repeat{};
};
/// Knits and tiles (wovens: periodic_woven_patch): from the stitch mesh of the tiled pattern, emitted with `library`. A virtual point is
/// matched to the centre point at its position less the repeat's offset; emitted points that match none
/// (stitches at the borders) are frozen. A knit of an odd number of rows repeats twice up (PeriodicPatch::repeat).
PeriodicPatch periodic_patch(const mesh::Pattern& pattern, const mesh::StitchLibrary& library, const mesh::StitchSize& size, double radius);
/// Wovens: crossings `spacing` apart.
PeriodicPatch periodic_woven_patch(const mesh::Pattern& pattern, double spacing, double radius);

/// A tiled preview of a relaxed periodic patch: the yarn `tiled` of an N x M tiling of the same pattern
/// (mesh::pattern_stitch_mesh and emission with the patch's library, size and radius), each point placed where
/// the relaxed real point it copies lies plus its repeat's offset. Points are matched where they were emitted
/// (as the patch matches its virtual points); the tiling's border stitches (cast-on, bind-off, turns), which
/// no real point copies, move as the nearest matched point along their yarn. `period_scale`: the repeat's
/// period scale along x and y (scale_period), 1 x 1 when none; `period`, when given, the relaxed repeat's period
/// (px, py) of a free-period run, which replaces the scaled one (the tiling is sheared with it). Returns the positions [mm].
struct TiledPreview {
  Eigen::Matrix3Xd points;
  int matched = 0;  ///< points placed from a real point (the rest follow their yarn)
};
TiledPreview tile_relaxed_patch(const PeriodicPatch& patch, const Eigen::Matrix3Xd& relaxed, const relax::YarnCurves& tiled,
                                const Eigen::Vector2d& period_scale = {1, 1}, const Eigen::Matrix<double, 3, 2>* period = nullptr);

/// The periodic patch's relaxed real points against the matching points of the relaxed centre repeat of an
/// n × n tiling of the patch's repeat (its stitch mesh from mesh::pattern_stitch_mesh(pattern, n, n × the patch's
/// rows over the pattern's: PeriodicPatch::repeat), emitted
/// with the same library and radius), the common translation removed. Points are matched where they were
/// emitted: the tiling's repeat ((n − 1)/2, (n − 1)/2) sits where the patch's centre repeat does, less an
/// offset. Throws skein::Error when a real point has no match (the two were not emitted alike).
struct PatchDifference {
  double rms = 0, largest = 0;  ///< [mm]
  int points = 0;               ///< real points compared
};
PatchDifference centre_repeat_difference(const PeriodicPatch& patch, const Eigen::Matrix3Xd& patch_relaxed, const relax::YarnCurves& tiled,
                                         const Eigen::Matrix3Xd& tiled_relaxed, int n);

}  // namespace skein::workflow
