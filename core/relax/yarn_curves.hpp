#pragma once
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace skein::relax {

/// Yarn as control points of Catmull-Rom curves (Yuksel 2012 §6.3), all curves back to back: a plain value
/// that flows from emission to relaxation and export. Every control point knows its yarn (curve), the
/// stitch face it was emitted for (-1 for border pieces) and that face's stitch type.
struct YarnCurves {
  std::vector<Eigen::Vector3d> points;   ///< [mm]
  std::vector<int> curve_start{0};       ///< curve c holds points [curve_start[c], curve_start[c+1])
  std::vector<char> closed;              ///< per curve: a closed loop (its last point joins its first)
  std::vector<int> point_face;           ///< per point
  std::vector<int> point_type;           ///< per point, index into type_names
  std::vector<std::string> type_names;   ///< stitch type names ("k", "kp", "cable2x2", "bind-off", "turn")
  /// Per point: 1 where the piece that emitted it passes through its face from the bottom edge to the top: the
  /// loop below carried up unworked, a slipped stitch's or a cable strand's "vertical material" (Leaf 2018
  /// §6.1); 0 for the row's own yarn ("horizontal": legs, sinkers, floats) and the heads. Empty when unknown.
  std::vector<char> point_vertical;
  double radius = 0;                     ///< yarn radius [mm]
  /// Yarn colours (colours.hpp): per point an index into `colours`, or empty when the yarn has one colour.
  std::vector<int> point_colour;
  struct Colour {
    std::string name;            ///< the pattern's name for it ("MC", "A")
    std::array<double, 3> srgb;  ///< 0..1
  };
  std::vector<Colour> colours;

  int curves() const { return static_cast<int>(curve_start.size()) - 1; }
  int curve_size(int c) const { return curve_start[c + 1] - curve_start[c]; }
  /// The curve a point belongs to (its yarn).
  int yarn_of(int point) const;
  /// The point whose piece holds the segment from point p to the next point of its curve (p is the curve's
  /// last point for a closed curve's closing segment): emission writes each piece's points after the crossing
  /// it shares with the piece before, so a segment belongs to its later point, except the closing one.
  int segment_owner(int p) const;
};

}  // namespace skein::relax
