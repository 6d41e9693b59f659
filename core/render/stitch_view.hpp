#pragma once
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "render/raster.hpp"
#include "stitchmesh/stitch_mesh.hpp"

namespace skein::render {

/// What a stitch face's colour shows: its row, its stitch type, or its yarn's colour (the mesh's palette; as
/// StitchType for a mesh without one).
enum class ColorBy { Row, StitchType, Colour };

/// A distinct colour per row index (golden-ratio hue steps, so neighbouring rows differ).
Eigen::Vector3f row_color(int row);
/// The colour of a stitch type: knit cream, purl plum, yarn-over gold, twisted orange, increases green,
/// decreases red, slip/cross blue; cable pieces teal, bind-off slate, turns pale grey.
Eigen::Vector3f stitch_color(const std::string& type);

/// A palette colour (sRGB 0..1) as the rasterizer draws: linear.
Eigen::Vector3f linear_color(const std::array<double, 3>& srgb);

std::vector<Polygon> stitch_polygons(const mesh::StitchMesh& mesh, ColorBy color);

/// Diverging colour for a strain: blue when compressed, white at rest, red when stretched; ±`range` saturates.
Eigen::Vector3f strain_color(double strain, double range = 0.5);
/// Polygons of a stitch mesh with one colour per face.
std::vector<Polygon> stitch_polygons(const mesh::StitchMesh& mesh, const std::vector<Eigen::Vector3f>& face_colors);

/// A PLY (ASCII) of the stitch mesh with a colour per face and named float values per face, atomically.
void write_ply(const mesh::StitchMesh& mesh, const std::vector<Eigen::Vector3f>& face_colors,
               const std::vector<std::pair<std::string, std::vector<double>>>& face_values, const std::filesystem::path& path);

}  // namespace skein::render
