#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

#include "relax/yarn_relax.hpp"
#include "stitchmesh/stitch_mesh.hpp"
#include "stitchmesh/stitch_model.hpp"
#include "stitchmesh/tessellation.hpp"
#include "stitchmesh/yarn_curves.hpp"

namespace skein::relax {

struct StandInOptions {
  int min_faces = 12;  ///< fewest stand-in faces of one stitch type for the type to get a patch
  void validate() const;
};

/// One stitch type that got a stand-in.
struct StandInType {
  std::string type;
  int faces = 0;        ///< garment faces it was mapped over
  long patch_steps = 0;
  bool converged = false;
  double patch_seconds = 0;
};

struct StandInReport {
  std::vector<StandInType> types;
  int placed = 0;     ///< control points placed from a relaxed patch
  int following = 0;  ///< the rest: they follow the nearest placed point of their yarn
  int taken_back = 0; ///< points placed at first, then taken back to following for the certificate
  double seconds = 0;
};

/// A preview of a garment's relaxed yarn from periodic stand-ins (issue 10; Leaf 2018 §5): where the garment
/// is one stitch type over a region, that type's 1 x 1 periodic patch, at the region's mean stitch width and
/// height, is relaxed once (relax::periodic_patch, with `options` and the patch-tracking forces) and its relaxed
/// yarn mapped over the region's faces, so the garment itself is not relaxed.
/// A face stands in when it is a 1-1 quad inside the garment (every edge shared, no cable mark) whose faces
/// around every corner have its type. On such a face each emitted point is found in the face's bilinear frame
/// (u, v along course and wale, h along the normal), matched to the patch's real point at the same place of
/// its stitch (modulo the period) and moved as that point moved in relaxation, the move carried from the
/// patch's frame to the face's. Every other point follows the nearest placed point of its yarn
/// (follow_placed). On the straight path from the emission to the preview no yarn passes through another (the
/// topology auditor): faces whose points would are taken back to following. `yarn`: the garment's emitted yarn
/// (mesh::emit_yarn of `stitch` with `library`). Returns the positions [mm].
Eigen::Matrix3Xd stand_in_preview(const mesh::StitchMesh& stitch, const mesh::YarnCurves& yarn, const mesh::StitchLibrary& library,
                                  const YarnRelaxOptions& options, const StandInOptions& stand_in,
                                  StandInReport& report);

}  // namespace skein::relax
