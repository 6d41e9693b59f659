#pragma once
#include "relax/shape_targets.hpp"
#include "relax/yarn_curves.hpp"
#include "stitchmesh/stitch_mesh.hpp"

namespace skein::workflow {

/// Targets from the stitch mesh the yarn was emitted from (`yarn.point_face` names each point's face).
relax::ShapeTargets shape_targets(const mesh::StitchMesh& mesh, const relax::YarnCurves& yarn, const relax::ShapeOptions& options);

}  // namespace skein::workflow
