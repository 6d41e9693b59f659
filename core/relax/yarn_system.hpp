#pragma once
#include <array>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Core>

#include "relax/yarn_curves.hpp"
#include "relax/yarn_segment.hpp"

namespace skein::relax {

/// The yarn as the relaxers see it: a structure of arrays over control points and spline segments.
/// Segment i joins control points (p1, p2) = segment_points[i][1..2] with neighbours p0 and p3; an open
/// yarn's end segments repeat their end point as the missing neighbour. Built once; topology never changes.
struct YarnSystem {
  Eigen::Matrix3Xd points;                       ///< [mm], column per control point
  std::vector<int> curve_start{0};               ///< curve c holds points [curve_start[c], curve_start[c+1])
  std::vector<char> closed;                      ///< per curve
  std::vector<std::array<int, 4>> segment_points;  ///< per segment: p0 p1 p2 p3
  std::vector<int> segment_curve;                ///< per segment
  std::vector<double> rest_length;               ///< per segment [mm]
  std::vector<double> arc_start;                 ///< per segment: rest arc length from its curve's start [mm]
  std::vector<double> curve_length;              ///< per curve: rest length [mm]
  std::vector<double> mass;                      ///< per point: half the rest length of its segments
  std::vector<int> point_segments_start;         ///< CSR: point p touches segments point_segments[start[p] .. start[p+1])
  std::vector<int> point_segments;               ///< with the slot (0..3) in the lowest two bits
  double radius = 0;                             ///< yarn radius r [mm]
  std::vector<int> contact_samples;              ///< per segment: sphere samples (ContactSampling)
  std::vector<int> sample_start;                 ///< per segment: its first sample in a flat list of all samples

  int num_points() const { return static_cast<int>(points.cols()); }
  int num_segments() const { return static_cast<int>(segment_points.size()); }
  int num_curves() const { return static_cast<int>(curve_start.size()) - 1; }
  /// One piece of yarn: segments less than 2r apart along one yarn (rest arc strictly between them), so
  /// that the yarn's tube already overlaps itself there. Passing through each other means nothing for such
  /// pieces; the pull-through guard and the auditor watch every other pair.
  bool adjacent(int a, int b) const;
  /// Segments that share a control-point end: the same segment or consecutive ones along a yarn. Every
  /// other pair can touch and pass through each other (Kaldor's |i - j| > 1).
  bool consecutive(int a, int b) const;
};

/// Arc length of one Catmull-Rom segment (p0 p1 p2 p3) [mm].
double spline_length(const Eigen::Matrix3Xd& points, const std::array<int, 4>& segment);

/// How many contact samples each segment gets (Leaf 2018 §3.1; issue 10's adaptive sampling).
struct ContactSampling {
  /// 0: Leaf's rule per segment, an odd count more than its rest length / 2r. Above 0 (adaptive): the fewest
  /// samples (2, or an odd count) that leave no gap of rest arc longer than `spacing` r between two consecutive
  /// samples, measured with the segment's own parameter speed: short segments get 2 (the trapezoid rule), unevenly
  /// parametrised ones more. Up to kMaxCoveringSpacing, where every crossing of two centrelines still has two
  /// samples closer than 2r, so contact is felt before one yarn can pass another.
  double spacing = 0;
  /// Two chains of samples g apart that cross at the worst place keep samples sqrt(g² / 2) apart: under 2r while g < 2√2 r.
  static constexpr double kMaxCoveringSpacing = 2.8284271247461903;
  void validate() const;  ///< throws skein::Error for a spacing outside [0, 2√2]
};

/// A system from emitted or loaded curves; rest lengths are the current segments' arc lengths times `take_up`,
/// and times `take_up_by_type[name]` for the segments of a stitch (or weft, warp) of that type (Leaf 2018 §6.1:
/// more or less yarn for slip stitches, or along the warp or the weft); `name:vertical` and `name:horizontal`
/// scale only that stitch's vertical or horizontal material (relax::YarnCurves::point_vertical), on top of
/// `name`'s factor. A segment belongs to the piece of its owner point (segment_owner). Throws skein::Error when the
/// yarn has no segment, a non-positive radius or take-up, coincident control points, or a take-up names a
/// type the yarn does not have. `sampling` sets each segment's contact samples, from its shape as given.
YarnSystem make_yarn_system(const relax::YarnCurves& curves, double take_up = 1.0, const std::map<std::string, double>& take_up_by_type = {},
                            const ContactSampling& sampling = {});

/// The system `rest` (its segments, rest lengths and samples) with its points moved to those of `curves`, the same
/// yarn in another shape: a swatch bent after relaxing flat keeps the flat yarn's lengths as its rest lengths,
/// where make_yarn_system(curves) would take the bent lengths (relax-yarn --rest-lengths). Throws skein::Error,
/// naming `where`, when the two do not hold the same curves (count, points per curve, open or closed).
YarnSystem with_rest_lengths_of(YarnSystem rest, const relax::YarnCurves& curves, const std::string& where);

/// The curves with only the points where `keep` is set: a curve is cut where it loses points (a closed curve
/// that loses some opens there, just after a lost point) and pieces of fewer than two points are dropped; the
/// pieces keep their order, and the points their faces, types and colours. `index`: per input point its index in the result, or -1.
relax::YarnCurves cut_curves(const relax::YarnCurves& curves, const std::vector<char>& keep, std::vector<int>& index);

/// Points that are not `placed` move as the nearest placed point of their yarn (by count of points along it,
/// the earlier one on a tie): to their position in `base` plus that point's move from `base` into `points`.
/// On a yarn with no placed point they take their `base` position.
void follow_placed(const relax::YarnCurves& yarn, const std::vector<char>& placed, const Eigen::Matrix3Xd& base, Eigen::Matrix3Xd& points);

/// A point's position rounded to 0.1 µm. Emission puts the same points at the same places, so this matches
/// points across emissions: a tiling and its periodic patch, a garment before and after an edit.
using PositionKey = std::tuple<long long, long long, long long>;
PositionKey position_key(const Eigen::Vector3d& p);

/// Writes the system's control points back into a copy of `curves` (same structure).
relax::YarnCurves with_points(const relax::YarnCurves& curves, const Eigen::Matrix3Xd& points);

/// The system's segment arrays as the shared per-segment math (yarn_segment.hpp) reads them; valid while
/// `system` lives and is not resized.
model::SegmentView<double> segment_view(const YarnSystem& system);

/// A bound on the largest distance any point of any yarn moves when the control points move by `delta`:
/// the largest Bezier control point of each segment's displacement curve (the curve lies in their hull).
double largest_sample_move(const YarnSystem& system, const Eigen::Matrix3Xd& delta);

}  // namespace skein::relax
