#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "stitchmesh/pattern.hpp"
#include "woven/weave.hpp"

namespace skein::woven {

/// A voxel grid of woven fabric (Zhao 2012 §4 and §6): per voxel the fibre density (a volume fraction, 0 to 1),
/// the local fibre direction (unit, zero where empty) and the yarn it belongs to (-1 where empty).
struct VoxelGrid {
  int nx = 0, ny = 0, nz = 0;
  double voxel = 0;                                  ///< edge [mm]
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< lower corner of voxel (0, 0, 0) [mm]
  std::vector<float> density;
  std::vector<Eigen::Vector3f> orientation;
  std::vector<std::int16_t> yarn;

  size_t index(int x, int y, int z) const { return (static_cast<size_t>(z) * ny + y) * nx + x; }
  size_t size() const { return static_cast<size_t>(nx) * ny * nz; }
  void allocate();  ///< sizes the three arrays: empty voxels
};

/// An exemplar (Zhao §4): a voxel grid over a few yarn crossings, registered to the weaving grid (§6.5) so that
/// crossing (weft i, warp j) is block (j, i): voxels [j bx, (j + 1) bx) x [i by, (i + 1) by) x all z, the
/// crossing at the block's centre. Yarn ids 0 .. warps - 1 are the warps left to right, the rest the wefts
/// bottom to top.
struct Exemplar {
  std::string name;
  Weave weave;               ///< the exemplar's weave pattern S_u, detected from its yarn (§6.2)
  int block_x = 0, block_y = 0;
  VoxelGrid grid;
  double spacing = 0, radius = 0;  ///< crossing spacing and yarn radius [mm]
  bool is_warp(int yarn) const { return yarn >= 0 && yarn < weave.warps; }
};

/// How exemplars are made from relaxed yarn: skein has no micro-CT scans, but it relaxes woven yarn.
struct ExemplarOptions {
  int crossings = 10;       ///< the exemplar's crossings along each side (the pattern tiled to cover them)
  double radius = 0.3;      ///< yarn radius [mm]
  double spacing = 0;       ///< crossing spacing [mm]; 0: 3 r (a closer weave than `skein pattern`'s 4 r, as cloth is)
  int voxels_per_crossing = 24;  ///< block_x = block_y
  /// Non-periodic relaxation: every emitted control point moves by up to this share of the spacing in the
  /// plane (along each axis) before the yarn's rest lengths are taken, and each yarn's voxelized radius varies by
  /// the same share of itself,
  /// so that no two crossings of the exemplar are alike and blocks copied side by side leave real seams.
  double jitter = 0.04;
  /// The loom's tension: every yarn's rest length is its emitted length times 1 - tension, so that the yarn,
  /// its ends held, lies taut as on the loom instead of sliding along the floats (twills skew without it).
  double tension = 0.03;
  int plies = 3;            ///< plies per yarn, twisted around its centreline
  double twist = 0;         ///< one ply's turn along the yarn [mm]; 0: 8 r
  double flyaways = 0.02;   ///< density of the loose fibres around a yarn's surface, a share of the core's
  double migration = 0.3;   ///< how far fibres migrate in and out across a ply over a ply turn, a share of its radius
  std::uint64_t seed = 1;
  long max_steps = 1500;    ///< relaxation steps (L-BFGS, force stop rule, the yarns' ends held)
};

struct ExemplarReport {
  long steps = 0;
  bool converged = false;
  std::string stopped_by;
  long pull_through_events = 0;
  double relax_seconds = 0, voxel_seconds = 0;
  double sag = 0;           ///< the largest height of the local middle plane taken out of the relaxed patch [mm]
  double filled = 0;        ///< share of voxels with fibres
};

/// Relaxes the pattern's yarn over crossings + 2 crossings each way (a margin of one, whose ends are held),
/// takes the patch's sag and wrinkles out (heights relative to the local middle plane),
/// checks the relaxed yarn's crossing order against the pattern (§6.2; throws skein::Error if a yarn slipped
/// to the other side), gives each yarn twisted plies, and voxelizes density, fibre direction and yarn id
/// over the inner crossings x crossings (§6.3: each voxel goes to the nearest centreline).
Exemplar make_exemplar(const mesh::Pattern& pattern, const ExemplarOptions& options = {}, ExemplarReport* report = nullptr);

/// Voxelizes relaxed woven yarn as make_exemplar does: `warp_curves` and `weft_curves` the yarns in order, the
/// window's lower corner at `corner` (x, y; the crossing of warp 0 and weft 0 half a spacing inside it).
Exemplar voxelize(const relax::YarnCurves& yarn, const std::vector<int>& warp_curves, const std::vector<int>& weft_curves,
                  const Eigen::Vector2d& corner, const ExemplarOptions& options);

/// OpenVDB files: grids "density" (float), "orientation" (vec3s) and "yarn" (int32) on a transform of the voxel
/// size, and file metadata for the weave, the blocks and the yarn. Written atomically.
void write_exemplar(const Exemplar& exemplar, const std::filesystem::path& path);
/// Throws skein::Error naming the file and what is missing or broken.
Exemplar read_exemplar(const std::filesystem::path& path);
/// Every .vdb in a folder, in name order; throws skein::Error when the folder holds none.
std::vector<Exemplar> read_exemplars(const std::filesystem::path& folder);

}  // namespace skein::woven
