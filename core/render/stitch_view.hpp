#pragma once
#include <string>
#include <vector>

#include "render/raster.hpp"
#include "stitchmesh/stitch_mesh.hpp"

namespace skein::render {

enum class ColorBy { Row, StitchType };

/// A distinct colour per row index (golden-ratio hue steps, so neighbouring rows differ).
Eigen::Vector3f row_color(int row);
/// The colour of a stitch type: knit cream, purl plum, yarn-over gold, twisted orange, increases green,
/// decreases red, slip/cross blue; cable pieces teal, bind-off slate, turns pale grey.
Eigen::Vector3f stitch_color(const std::string& type);

std::vector<Polygon> stitch_polygons(const mesh::StitchMesh& mesh, ColorBy color);

}  // namespace skein::render
