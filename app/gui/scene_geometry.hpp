#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "document.hpp"

namespace skein::gui {

/// One vertex as the viewport's buffers hold it.
struct Vertex {
  Eigen::Vector3f position, normal, color;
};
static_assert(sizeof(Vertex) == 9 * sizeof(float), "Vertex is uploaded as 9 packed floats");

/// What the viewport draws and picks: shaded triangles, lines on top, and the polygons a click can hit.
struct Geometry {
  std::vector<Vertex> triangles;  ///< three vertices per triangle
  std::vector<Vertex> lines;      ///< two vertices per line
  std::vector<Eigen::Vector3d> pick_points;
  std::vector<std::vector<int>> pick_faces;  ///< index = input or stitch face id; loops of pick_points
  Eigen::AlignedBox3d bounds;
};

enum class Layer { Input, Stitch, Yarn };
enum class Coloring { StitchType, Row, Stretch, YarnColour };

/// The input mesh with its labels (Yuksel 2012 Fig. 11): faces tinted by row (grey when unlabeled, red when
/// they break a labeling rule), course edges dark, wale edges in their row's colour (orange when marked for
/// increases), and an arrow per face along the wale direction.
Geometry input_geometry(const mesh::InputMesh& input, const std::optional<mesh::Labeling>& labels,
                        const std::optional<mesh::TessellationValues>& values);

/// Each stitch's colour: its stitch type, its row, or its area strain against `rest` (grey without one).
std::vector<Eigen::Vector3f> face_colors(const mesh::StitchMesh& stitch, Coloring coloring, const std::optional<RestSize>& rest);

/// The stitch mesh coloured by stitch type, row or stretch (area strain against `rest`; grey without one),
/// selected faces tinted yellow, edges dark, cable edges teal.
Geometry stitch_geometry(const mesh::StitchMesh& stitch, Coloring coloring, const std::optional<RestSize>& rest,
                         const std::vector<char>& selected);

/// How finely yarn tubes are drawn: Full for a finished shape, Live (square tubes, one sample per segment,
/// a quarter of the triangles) while a relaxation updates the view.
enum class YarnDetail { Full, Live };

/// Yarn as shaded tubes coloured by stitch type; very large yarn (over `max_tube_points` control points) as
/// lines, which keeps a sweater's yarn within graphics memory.
Geometry yarn_geometry(const relax::YarnCurves& yarn, YarnDetail detail = YarnDetail::Full, int max_tube_points = 60000);

/// What a ray from `origin` along `direction` hits first: the face and, of its loop, the edge nearest to the hit.
struct Hit {
  int face = -1;
  int local_edge = -1;  ///< edge k runs from loop vertex k to k+1
  double edge_distance = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
};
std::optional<Hit> pick(const Geometry& geometry, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction);

}  // namespace skein::gui
