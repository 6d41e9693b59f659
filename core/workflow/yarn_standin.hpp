#pragma once
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "relax/yarn_curves.hpp"
#include "relax/yarn_relax.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/stitch_mesh.hpp"
#include "stitchmesh/stitch_model.hpp"
#include "stitchmesh/tessellation.hpp"

namespace skein::workflow {

struct StandInOptions {
  int min_faces = 12;   ///< fewest faces of one repeat for it to get a patch
  int max_period = 8;   ///< longest repeat looked for, in stitches along the row and along the wale (mesh::find_repeats)
  int reach = 2;        ///< rings of stitches of the pattern's type that join a region beyond it (mesh::find_repeats)
  double take_up = 1.0; ///< the patches' rest lengths, as the garment's relaxation takes them (make_yarn_system)
  std::map<std::string, double> take_up_by_type;
  /// Patterns tiled onto the garment by re-meshing (cables, lace, increases, decreases: mesh::remeshes) whose
  /// whole repeats get stand-ins too (mesh::find_tiled_repeats); the others are read back from the stitch types.
  std::vector<mesh::Pattern> patterns;
  void validate() const;
};

/// One repeat that got a stand-in.
struct StandInRepeat {
  std::string pattern;  ///< mesh::repeat_text: its rows, top first
  int across = 1, up = 1;
  int faces = 0;        ///< garment faces it was mapped over
  long patch_steps = 0;
  bool converged = false;
  double patch_seconds = 0;
};

struct StandInReport {
  std::vector<StandInRepeat> repeats;
  int placed = 0;     ///< control points placed from a relaxed patch
  int following = 0;  ///< the rest: they follow the nearest placed point of their yarn
  int taken_back = 0; ///< points placed at first, then taken back to following for the certificate
  double seconds = 0;
};

/// A preview of a garment's relaxed yarn from periodic stand-ins (issue 10; Leaf 2018 §5): where the garment
/// is knitted in one repeating pattern over a region (mesh::find_repeats: stockinette, a rib, seed stitch,
/// any repeat of plain stitches up to `max_period` wide and high, `reach` rings beyond; and the whole repeats of
/// the re-meshing patterns named in `stand_in.patterns`: cables, lace, increases, decreases), that repeat's
/// periodic patch, at the region's mean stitch width and height, is relaxed once (workflow::periodic_patch, with `options` and the
/// patch-tracking forces) and its relaxed yarn mapped over the region's faces, so the garment itself is not
/// relaxed. On a face of a region each emitted point (a cable's yarn, made at emission between faces: on the
/// nearest face along its yarn) is found in the face's bilinear frame (u, v along course and wale, h along
/// the normal), matched to the patch's point emitted for the same stitch type at the same place around the
/// same stitch of the repeat, and moved as that point moved in relaxation, the move carried from the patch's
/// frame to the face's. Every other point (stitches within one of another pattern, of no repeat, border
/// pieces) follows the nearest placed point of its yarn (follow_placed). On the straight path from the
/// emission to the preview no yarn passes through another (the topology auditor): faces whose points would
/// are taken back to following. `yarn`: the garment's emitted yarn (mesh::emit_yarn of `stitch` with
/// `library`). Returns the positions [mm].
Eigen::Matrix3Xd stand_in_preview(const mesh::StitchMesh& stitch, const relax::YarnCurves& yarn, const mesh::StitchLibrary& library,
                                  const relax::YarnRelaxOptions& options, const StandInOptions& stand_in,
                                  StandInReport& report);

}  // namespace skein::workflow
