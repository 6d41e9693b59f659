#pragma once
#include <vector>

#include <Eigen/Core>

#include "woven/exemplar.hpp"
#include "woven/synthesis.hpp"

namespace skein::woven {

/// Zhao 2012 §5.5 edge fixing, kept in low rank as the paper does: each block's stacks of voxels shift along z
/// by a field that is harmonic inside the block (a 2-D discrete Laplace equation) and on the block's edges meets
/// its neighbour halfway (each side moves by half the step between the two top surfaces). The boundary values
/// of all top edges (T, bx x MN) and of all left edges without corners (L, (by - 2) x MN) are factored to rank r
/// (T ~ B_T C_T, L ~ B_L C_L); the 2r Laplace solutions of the columns of B_T and B_L are stored, and a block's
/// field is their combination with its own and its right and lower neighbours' coefficients (mirrored).
class EdgeFix {
public:
  EdgeFix() = default;
  /// `rank` 0: full rank (exact, for tests).
  EdgeFix(const std::vector<Exemplar>& exemplars, const Assignment& assignment, int rank);
  bool empty() const { return m_rank == 0; }
  /// The shift [mm] at voxel column (a, b) of the block of crossing (weft, warp).
  double shift(int weft, int warp, int a, int b) const;
  int rank() const { return m_rank; }
  /// The share of the boundary data's squared norm that rank r keeps (1 at full rank).
  double kept() const { return m_kept; }

private:
  int m_bx = 0, m_by = 0, m_rank = 0, m_warps = 0, m_wefts = 0;
  double m_kept = 1;
  /// The Laplace solutions of the basis columns, r x (bx by), column a + b bx holding voxel column (a, b) of each;
  /// and the same mirrored (top: b -> by - 1 - b, left: a -> bx - 1 - a) for the neighbours' edges. Laid out so
  /// that a lookup is four dot products of r contiguous floats (the renderer asks for every step it takes).
  Eigen::MatrixXf m_top, m_left, m_top_mirrored, m_left_mirrored;
  Eigen::MatrixXf m_ct, m_cl;                  ///< r x MN coefficients
};

/// Per exemplar, per voxel column, the height of the top surface (the highest voxel of density above 0.05, so
/// that flyaways do not count) [mm]; NaN over gaps. What edge fixing matches across block edges.
std::vector<Eigen::MatrixXf> top_surfaces(const std::vector<Exemplar>& exemplars);

/// The mean step of the top surface across the blocks' shared edges [mm] (where both sides have fibres):
/// the seams edge fixing removes. With `fix`, the shifted surfaces are compared.
double seam_step(const std::vector<Exemplar>& exemplars, const Assignment& assignment, const EdgeFix* fix = nullptr);

/// The synthesized fabric as a procedural volume (§5.3): the weave, the assignment of exemplar blocks and the
/// edge fixing, looked up voxel by voxel when asked; no voxel array of the whole fabric is made. Crossing
/// (weft i, warp j) covers [j s, (j + 1) s) x [i s, (i + 1) s) in the plane, s the exemplars' spacing.
/// Colours: per crossing, the warp's and the weft's colour index (Zhao §5.1's ID maps).
struct WovenVolume {
  const std::vector<Exemplar>* exemplars = nullptr;
  Weave weave;
  Assignment assignment;
  EdgeFix fix;
  std::vector<int> warp_color, weft_color;  ///< per crossing, row by row
  double spacing = 0, voxel = 0, z_low = 0, z_high = 0;
  int block_x = 0, block_y = 0;

  struct Sample {
    float density = 0;
    Eigen::Vector3f direction = Eigen::Vector3f::Zero();
    int color = -1;
    bool warp = false;
  };
  Sample at(const Eigen::Vector3d& p) const;
  Eigen::Vector3d size() const { return {weave.warps * spacing, weave.wefts * spacing, z_high - z_low}; }
};

/// Checks that the exemplars share one block layout (Zhao: identical resolutions; depths may differ) and builds the volume.
/// `edge_rank` 0: no edge fixing. Colour maps default to colour 0 for every warp and 1 for every weft.
WovenVolume make_volume(const std::vector<Exemplar>& exemplars, const Weave& weave, const Assignment& assignment, int edge_rank,
                        std::vector<int> warp_color = {}, std::vector<int> weft_color = {});

/// A box of the volume as a voxel grid (for .vdb export and comparisons): crossings [warp0, warp0 + warps) x
/// [weft0, weft0 + wefts), at the exemplars' voxel size.
Exemplar volume_region(const WovenVolume& volume, int warp0, int weft0, int warps, int wefts);

/// Two voxel grids of one fabric compared voxel by voxel (same voxel size and x, y layout; z matched by height):
/// how far a synthesized volume is from the directly relaxed truth.
struct VolumeDifference {
  double density_error = 0;      ///< mean |ρa - ρb| over the voxels either fills, over the mean ρ there
  double occupancy = 0;          ///< voxels both fill over voxels either fills (intersection over union)
  double orientation_deg = 0;    ///< mean angle between the fibre directions (as lines) where both fill
  double surface_error = 0;      ///< mean step between the two top surfaces where both have fibres [mm]
  double top_agreement = 0;      ///< voxel columns whose topmost fibres are of the same kind (warp or weft) in both
};
/// `warps`: yarn ids below it are warps in both grids (exemplar numbering).
VolumeDifference compare_grids(const VoxelGrid& a, const VoxelGrid& b, int warps);

}  // namespace skein::woven
