#include "relax/yarn_system.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "relax/yarn_model.hpp"

namespace skein::relax {

double spline_length(const Eigen::Matrix3Xd& points, const std::array<int, 4>& segment) {
  // The same Simpson quadrature as the length penalty (Leaf eq. 1), so a fresh system starts at rest.
  model::Vec3<double> p[4];
  for (int k = 0; k < 4; ++k) p[k] = {points(0, segment[k]), points(1, segment[k]), points(2, segment[k])};
  double length = 0;
  for (int i = 0; i < model::kIntrinsicSamples; ++i) {
    double w[4];
    model::basis_d1(static_cast<double>(i) / (model::kIntrinsicSamples - 1), w);
    length += model::simpson_weight<double>(i, model::kIntrinsicSamples) * model::norm(model::combine(w, p));
  }
  return length;
}

void ContactSampling::validate() const {
  if (!(spacing >= 0 && spacing <= kMaxCoveringSpacing))
    throw Error("", "contact spacing", "must be 0 (Leaf's rule) or at most 2√2 ≈ 2.828 yarn radii, so that crossing yarns always feel contact; found " +
                                           std::to_string(spacing));
}

namespace {

/// Leaf 2018 §3.1: an odd number of contact samples, more than L / 2r (Leaf takes the shortest segment's count
/// for all; per segment keeps long segments covered and short ones cheap).
int leaf_samples(double rest_length, double radius) {
  int n = static_cast<int>(std::floor(rest_length / (2 * radius))) + 1;
  if (n % 2 == 0) ++n;
  return std::max(3, n);
}

/// The fewest samples (2, or odd) at uniform parameter steps that leave no gap of rest arc longer than
/// `spacing` r between two of them: the segment's parameter speed |y'| measured on its shape as given, scaled to
/// its rest length, so uneven speed (unevenly spaced control points) gets more samples. Arc, not chord: the
/// length penalty holds the arc, and no bending can make a chord longer. kMaxContactSamples + 1 when none is enough.
int adaptive_samples(const Eigen::Matrix3Xd& points, const std::array<int, 4>& segment, double rest_length, double radius, double spacing) {
  model::Vec3<double> p[4];
  for (int k = 0; k < 4; ++k) p[k] = {points(0, segment[k]), points(1, segment[k]), points(2, segment[k])};
  // Arc from t = 0 to t = k / kFine, by the midpoint rule.
  constexpr int kFine = 64;
  std::array<double, kFine + 1> arc{};
  for (int k = 0; k < kFine; ++k) {
    double w[4];
    model::basis_d1((k + 0.5) / kFine, w);
    arc[k + 1] = arc[k] + model::norm(model::combine(w, p)) / kFine;
  }
  const double scale = rest_length / arc[kFine];
  const auto arc_at = [&](double t) {
    const double x = t * kFine;
    const int k = std::min(static_cast<int>(x), kFine - 1);
    return arc[k] + (x - k) * (arc[k + 1] - arc[k]);
  };
  for (int n = 2; n <= model::kMaxContactSamples; n += (n == 2 ? 1 : 2)) {
    double widest = 0;
    for (int i = 0; i + 1 < n; ++i) widest = std::max(widest, arc_at(static_cast<double>(i + 1) / (n - 1)) - arc_at(static_cast<double>(i) / (n - 1)));
    if (widest * scale <= spacing * radius) return n;
  }
  return model::kMaxContactSamples + 1;
}

}  // namespace

bool YarnSystem::adjacent(int a, int b) const { return model::adjacent(segment_view(*this), a, b); }

bool YarnSystem::consecutive(int a, int b) const { return model::consecutive(segment_view(*this), a, b); }

YarnSystem make_yarn_system(const relax::YarnCurves& curves, double take_up, const std::map<std::string, double>& take_up_by_type,
                            const ContactSampling& sampling) {
  sampling.validate();
  if (!(curves.radius > 0) || !std::isfinite(curves.radius)) throw Error("", "", "the yarn radius must be positive, found " + std::to_string(curves.radius));
  if (!(take_up > 0) || !std::isfinite(take_up)) throw Error("", "", "the yarn take-up must be positive, found " + std::to_string(take_up));
  // Per stitch type: the take-up of its segments, of its vertical ones and of its horizontal ones (Leaf 2018
  // §6.1: "TYPE", "TYPE:vertical", "TYPE:horizontal"; YarnCurves::point_vertical says which is which).
  const size_t types = curves.type_names.size();
  std::vector<double> type_take_up(types, 1.0), vertical_take_up(types, 1.0), horizontal_take_up(types, 1.0);
  for (const auto& [key, factor] : take_up_by_type) {
    if (!(factor > 0) || !std::isfinite(factor)) throw Error("", "take-up of " + key, "must be positive, found " + std::to_string(factor));
    const auto colon = key.find(':');
    const std::string name = key.substr(0, colon), part = colon == std::string::npos ? "" : key.substr(colon + 1);
    if (name.empty()) throw Error("", "take-up of " + key, "expected a stitch type before ':' (s:vertical)");
    if (colon != std::string::npos && part != "vertical" && part != "horizontal")
      throw Error("", "take-up of " + key, "the part after ':' must be vertical or horizontal (Leaf 2018 §6.1), found '" + part + "'");
    if (curves.type_names.empty())
      throw Error("", "take-up of " + key, "this yarn knows no stitch types (yarn read from a file keeps none); relax it from its project or pattern");
    if (!part.empty() && curves.point_vertical.size() != curves.points.size())
      throw Error("", "take-up of " + key, "this yarn does not say which of its material is vertical (yarn read from a file keeps no stitch pieces); "
                                          "relax it from its project or pattern, or give " + name + "=F for all of the stitch's yarn");
    const auto it = std::find(curves.type_names.begin(), curves.type_names.end(), name);
    if (it == curves.type_names.end()) {
      std::string known;
      for (const auto& t : curves.type_names) known += (known.empty() ? "" : " ") + t;
      throw Error("", "take-up of " + key, "the yarn has no stitch of that type; it has: " + known);
    }
    const int type = static_cast<int>(it - curves.type_names.begin());
    if (!part.empty()) {  // the stitch must have that part somewhere, or the factor would be taken and do nothing
      bool found = false;
      for (size_t p = 0; p < curves.points.size() && !found; ++p)
        found = curves.point_type[p] == type && (curves.point_vertical[p] != 0) == (part == "vertical");
      if (!found)
        throw Error("", "take-up of " + key, "stitch " + name + " has no " + part + " yarn here (" +
                                                (part == "vertical" ? "only slipped stitches and cables carry a loop up through their row" : "a cable face holds only its crossing strands") + ")");
    }
    auto& table = part.empty() ? type_take_up : part == "vertical" ? vertical_take_up : horizontal_take_up;
    table[type] = factor;
  }
  // A segment's factor is its piece's: the piece that wrote the segment's owner point.
  const auto factor_at = [&](int point) {
    const int owner = curves.segment_owner(point);
    const int type = owner < static_cast<int>(curves.point_type.size()) ? curves.point_type[owner] : -1;
    if (type < 0 || type >= static_cast<int>(types)) return 1.0;
    const bool vertical = owner < static_cast<int>(curves.point_vertical.size()) && curves.point_vertical[owner];
    return type_take_up[type] * (vertical ? vertical_take_up[type] : horizontal_take_up[type]);
  };
  YarnSystem s;
  s.radius = curves.radius;
  s.closed = curves.closed;
  s.curve_start = curves.curve_start;
  const int n = static_cast<int>(curves.points.size());
  s.points.resize(3, n);
  for (int p = 0; p < n; ++p) s.points.col(p) = curves.points[p];
  s.mass.assign(n, 0.0);
  s.curve_length.assign(curves.curves(), 0.0);
  for (int c = 0; c < curves.curves(); ++c) {
    const int begin = curves.curve_start[c], size = curves.curve_size(c);
    const bool closed = curves.closed[c] && size > 2;
    const int segments = closed ? size : size - 1;
    const auto at = [&](int k) {
      if (closed) return begin + ((k % size) + size) % size;
      return begin + std::clamp(k, 0, size - 1);
    };
    for (int k = 0; k < segments; ++k) {
      s.segment_points.push_back({at(k - 1), at(k), at(k + 1), at(k + 2)});
      s.segment_curve.push_back(c);
      if (!((s.points.col(at(k + 1)) - s.points.col(at(k))).norm() > 0))
        throw Error("", "curve " + std::to_string(c) + " points " + std::to_string(at(k)) + " and " + std::to_string(at(k + 1)),
                    "two consecutive control points coincide");
      s.rest_length.push_back(spline_length(s.points, s.segment_points.back()) * take_up * factor_at(at(k)));
      s.arc_start.push_back(s.curve_length[c]);
      s.curve_length[c] += s.rest_length.back();
      s.mass[at(k)] += 0.5 * s.rest_length.back();
      s.mass[at(k + 1)] += 0.5 * s.rest_length.back();
    }
  }
  if (s.num_segments() == 0) throw Error("", "", "the yarn has no segment (every curve has fewer than two points)");
  for (int seg = 0; seg < s.num_segments(); ++seg) {
    const double l = s.rest_length[seg];
    const int n = sampling.spacing > 0 ? adaptive_samples(s.points, s.segment_points[seg], l, s.radius, sampling.spacing) : leaf_samples(l, s.radius);
    if (n > model::kMaxContactSamples)
      throw Error("", "segment " + std::to_string(seg),
                  "a segment " + std::to_string(l) + " mm long needs more than " + std::to_string(model::kMaxContactSamples) +
                      " contact samples: resample the yarn more finely" +
                      (sampling.spacing > 0 ? ", or give a larger contact spacing (it is " + std::to_string(sampling.spacing) + " r)" : std::string()));
    s.sample_start.push_back(seg == 0 ? 0 : s.sample_start.back() + s.contact_samples.back());
    s.contact_samples.push_back(n);
  }
  // Point -> segment stencil (Leaf §3.2): every segment whose four control points include the point.
  std::vector<int> count(n + 1, 0);
  for (const auto& sp : s.segment_points)
    for (int slot = 0; slot < 4; ++slot) ++count[sp[slot] + 1];
  for (int p = 0; p < n; ++p) count[p + 1] += count[p];
  s.point_segments_start = count;
  s.point_segments.resize(count[n]);
  for (int seg = 0; seg < s.num_segments(); ++seg)
    for (int slot = 0; slot < 4; ++slot) s.point_segments[count[s.segment_points[seg][slot]]++] = seg * 4 + slot;
  for (int p = 0; p < n; ++p)
    if (s.mass[p] <= 0) throw Error("", "point " + std::to_string(p), "a control point on no segment (a curve of one point)");
  return s;
}

YarnSystem with_rest_lengths_of(YarnSystem rest, const relax::YarnCurves& curves, const std::string& where) {
  if (curves.curves() != rest.num_curves())
    throw Error(where, "", "holds " + std::to_string(curves.curves()) + " yarns where the yarn relaxed holds " + std::to_string(rest.num_curves()));
  for (int c = 0; c < rest.num_curves(); ++c) {
    const int size = rest.curve_start[c + 1] - rest.curve_start[c];
    if (curves.curve_size(c) != size || (curves.closed[c] != 0) != (rest.closed[c] != 0))
      throw Error(where, "yarn " + std::to_string(c),
                  "has " + std::to_string(curves.curve_size(c)) + (curves.closed[c] ? " points, closed," : " points, open,") +
                      " where the yarn relaxed has " + std::to_string(size) + (rest.closed[c] ? " points, closed" : " points, open"));
  }
  for (int p = 0; p < rest.num_points(); ++p) rest.points.col(p) = curves.points[p];
  return rest;
}

relax::YarnCurves with_points(const relax::YarnCurves& curves, const Eigen::Matrix3Xd& points) {
  relax::YarnCurves out = curves;
  for (int p = 0; p < static_cast<int>(out.points.size()); ++p) out.points[p] = points.col(p);
  return out;
}

model::SegmentView<double> segment_view(const YarnSystem& system) {
  return {system.segment_points.front().data(), system.segment_curve.data(), system.curve_start.data(), system.rest_length.data(), system.arc_start.data(),
          system.curve_length.data(), system.closed.data(), system.contact_samples.data(), system.sample_start.data(), system.radius};
}

double largest_sample_move(const YarnSystem& system, const Eigen::Matrix3Xd& delta) {
  const int* segment_points = system.segment_points.front().data();
  const auto move = [&](int p) { return model::Vec3<double>{delta(0, p), delta(1, p), delta(2, p)}; };
  double largest = 0;
#pragma omp parallel for reduction(max : largest) schedule(static)
  for (int seg = 0; seg < system.num_segments(); ++seg) largest = std::max(largest, model::segment_largest_move<double>(segment_points, seg, move));
  return largest;
}

PositionKey position_key(const Eigen::Vector3d& p) {
  return {std::llround(p.x() * 1e4), std::llround(p.y() * 1e4), std::llround(p.z() * 1e4)};
}

void follow_placed(const relax::YarnCurves& yarn, const std::vector<char>& placed, const Eigen::Matrix3Xd& base, Eigen::Matrix3Xd& points) {
  for (int c = 0; c < yarn.curves(); ++c) {
    const int begin = yarn.curve_start[c], end = yarn.curve_start[c + 1];
    // The nearest placed point before each point, then after it where that is strictly nearer.
    std::vector<int> nearest(end - begin, -1);
    for (int p = begin, last = -1; p < end; ++p) {
      if (placed[p]) last = p;
      else nearest[p - begin] = last;
    }
    for (int p = end - 1, next = -1; p >= begin; --p) {
      if (placed[p]) next = p;
      else if (next >= 0 && (nearest[p - begin] < 0 || next - p < p - nearest[p - begin])) nearest[p - begin] = next;
    }
    for (int p = begin; p < end; ++p) {
      if (placed[p]) continue;
      const int q = nearest[p - begin];
      points.col(p) = base.col(p);
      if (q >= 0) points.col(p) += points.col(q) - base.col(q);
    }
  }
}

relax::YarnCurves cut_curves(const relax::YarnCurves& in, const std::vector<char>& keep, std::vector<int>& index) {
  const int n = static_cast<int>(in.points.size());
  relax::YarnCurves out;
  out.radius = in.radius;
  out.type_names = in.type_names;
  out.colours = in.colours;
  const bool coloured = in.point_colour.size() == in.points.size();
  index.assign(n, -1);
  for (int c = 0; c < in.curves(); ++c) {
    const int begin = in.curve_start[c], end = in.curve_start[c + 1];
    const bool whole = std::all_of(keep.begin() + begin, keep.begin() + end, [](char k) { return k != 0; });
    // A closed curve that loses points opens where it does: start the walk just after a lost point.
    int first = begin;
    if (in.closed[c] && !whole)
      while (keep[first]) ++first;
    std::vector<int> piece;
    const auto flush = [&](bool closed) {
      if (piece.size() >= 2) {
        for (int p : piece) {
          index[p] = static_cast<int>(out.points.size());
          out.points.push_back(in.points[p]);
          out.point_face.push_back(in.point_face[p]);
          out.point_type.push_back(in.point_type[p]);
          if (in.point_vertical.size() == in.points.size()) out.point_vertical.push_back(in.point_vertical[p]);
          if (coloured) out.point_colour.push_back(in.point_colour[p]);
        }
        out.curve_start.push_back(static_cast<int>(out.points.size()));
        out.closed.push_back(closed);
      }
      piece.clear();
    };
    for (int k = 0; k < end - begin; ++k) {
      const int p = begin + (first - begin + k) % (end - begin);
      if (keep[p]) piece.push_back(p);
      else flush(false);
    }
    flush(in.closed[c] && whole);
  }
  return out;
}

}  // namespace skein::relax
