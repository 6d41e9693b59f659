#pragma once
#include "relax/yarn_curves.hpp"
#include "stitchmesh/stitch_mesh.hpp"
#include "stitchmesh/stitch_model.hpp"

namespace skein::mesh {

struct EmitOptions {
  double yarn_radius = 0.6;  ///< [mm]; the default suits the default 6 mm stitch (a tenth of its width)
  void validate() const;     ///< throws skein::Error unless positive and finite
};

/// What emission did beyond the stitches themselves (Yuksel 2012 §4.3–4.5).
struct EmitReport {
  int cables = 0;          ///< cable faces made from marked course edges
  int cast_on = 0;         ///< first-row stitches (y+1, their bottom pieces dropped)
  int bind_off = 0;        ///< bind-off pieces over top border edges
  int turns = 0;           ///< loose ends joined at side borders (yarn turning to the next row)
  int tied_ends = 0;       ///< loose ends left tied
};

/// Emits yarn for a valid stitch mesh (Yuksel 2012 §6.2): marked cable edges become cable faces first; each
/// face's stitch model is placed on the face with mean value coordinates and the surface normal; pieces join
/// across edges into continuous yarns — open yarns, and closed loops where the structure closes (ring rows,
/// opposite wale directions); borders get cast-on stitches, bind-off pieces, turns and tied ends.
/// Throws skein::Error for an invalid mesh, a stitch type without a model, a cable without a model, or two
/// faces of one row with opposite wale directions.
relax::YarnCurves emit_yarn(const StitchMesh& mesh, const StitchLibrary& library, const EmitOptions& options, EmitReport* report = nullptr);

}  // namespace skein::mesh
