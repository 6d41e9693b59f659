#pragma once
#include <vector>

#include "relax/yarn_curves.hpp"
#include "render/raster.hpp"

namespace skein::render {

/// What a tube's colour shows: its stitch type, which yarn it is, or the yarn's own colour (a pattern's
/// palette, YarnCurves::point_colour; as StitchType for yarn without colours).
enum class YarnColor { StitchType, Yarn, Colour };

/// Yarn as shaded tubes (Catmull-Rom sampled, `sides`-gon cross-section) for draw().
std::vector<Polygon> yarn_polygons(const relax::YarnCurves& yarn, YarnColor color, int sides = 6, int samples_per_segment = 2);

}  // namespace skein::render
