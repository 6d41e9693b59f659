#pragma once
#include <vector>

#include "render/raster.hpp"
#include "stitchmesh/yarn_curves.hpp"

namespace skein::render {

enum class YarnColor { StitchType, Yarn };

/// Yarn as shaded tubes (Catmull-Rom sampled, `sides`-gon cross-section) for draw().
std::vector<Polygon> yarn_polygons(const mesh::YarnCurves& yarn, YarnColor color, int sides = 6, int samples_per_segment = 2);

}  // namespace skein::render
