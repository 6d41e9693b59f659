#pragma once
// The per-segment work of one force evaluation, written once for the CPU relaxer (double, OpenMP loop over
// segments) and the CUDA relaxer (float, a thread per segment): contact samples of a segment, then the
// segment's energy and the gradient and contact damping on its four control points (Leaf 2018 §3.1–3.2).
// Plain pointers in, no allocation (STYLE.md, "one source of truth").
#include "relax/yarn_model.hpp"

namespace skein::relax::model {

/// A yarn system's segment arrays as plain pointers (YarnSystem on the host, device buffers on the GPU).
template <class T>
struct SegmentView {
  const int* segment_points;   ///< 4 per segment: p0 p1 p2 p3
  const int* segment_curve;    ///< per segment
  const int* curve_start;      ///< per curve and one more: its first control point (and segment)
  const T* rest_length;        ///< per segment [mm]
  const T* arc_start;          ///< per segment: rest arc from its curve's start [mm]
  const T* curve_length;       ///< per curve [mm]
  const char* closed;          ///< per curve
  const int* contact_samples;  ///< per segment
  const int* sample_start;     ///< per segment
  T radius;                    ///< r [mm]
};

/// Contact samples of every segment, flat (SegmentView::sample_start): position, velocity, quadrature
/// weight times rest length, rest arc position.
template <class T>
struct SampleView {
  Vec3<T>* pos;
  Vec3<T>* vel;
  T* weight;
  T* arc;
};

/// Contact pairs as CSR from each segment to its partners (ContactPairs).
struct PairView {
  const int* start;
  const int* partner;
};

/// Largest contact-sample count of a segment (make_yarn_system keeps every segment under it).
constexpr int kMaxContactSamples = 63;

/// Distance along curve c between rest arc positions a and b (the shorter way round a closed curve).
template <class T> SKEIN_HD T arc_distance(const SegmentView<T>& v, int c, T a, T b) {
  const T along = a > b ? a - b : b - a;
  if (!v.closed[c]) return along;
  const T other = v.curve_length[c] - along;
  return other < along ? other : along;
}

/// Segments that share a control-point end: the same segment or consecutive ones along a yarn. Every other
/// pair can touch and pass through each other (Kaldor's |i - j| > 1). Segments are numbered along each curve.
template <class T> SKEIN_HD bool consecutive(const SegmentView<T>& v, int a, int b) {
  if (a == b) return true;
  const int c = v.segment_curve[a];
  if (c != v.segment_curve[b]) return false;
  const int gap = a > b ? a - b : b - a;
  if (gap == 1) return true;
  // A closed curve's last segment meets its first.
  return v.closed[c] && gap == v.curve_start[c + 1] - v.curve_start[c] - 1;
}

/// One piece of yarn: segments less than 2r apart along one yarn (rest arc strictly between them), so that
/// the yarn's tube already overlaps itself there. Passing through each other means nothing for such pieces;
/// the pull-through guard and the auditor watch every other pair.
template <class T> SKEIN_HD bool adjacent(const SegmentView<T>& v, int a, int b) {
  if (a == b) return true;
  const int c = v.segment_curve[a];
  if (c != v.segment_curve[b]) return false;
  if (a > b) {
    const int t = a;
    a = b;
    b = t;
  }
  const T limit = 2 * v.radius;
  if (v.arc_start[b] - (v.arc_start[a] + v.rest_length[a]) < limit) return true;
  return v.closed[c] && v.curve_length[c] - (v.arc_start[b] + v.rest_length[b]) + v.arc_start[a] < limit;
}

/// Writes segment s's contact samples. `point(i)` and `velocity(i)` return control point i's position and
/// velocity as Vec3<T>.
template <class T, class Point, class Velocity>
SKEIN_HD void segment_samples(const SegmentView<T>& v, int s, Point point, Velocity velocity, const SampleView<T>& out) {
  const int* sp = v.segment_points + 4 * s;
  Vec3<T> p[4], u[4];
  for (int k = 0; k < 4; ++k) {
    p[k] = point(sp[k]);
    u[k] = velocity(sp[k]);
  }
  const int n = v.contact_samples[s], first = v.sample_start[s];
  for (int i = 0; i < n; ++i) {
    T w[4];
    basis(T(i) / T(n - 1), w);
    out.pos[first + i] = combine(w, p);
    out.vel[first + i] = combine(w, u);
    out.weight[first + i] = contact_weight<T>(i, n) * v.rest_length[s];
    out.arc[first + i] = v.arc_start[s] + v.rest_length[s] * T(i) / T(n - 1);
  }
}

/// Segment s's share of the energy (its intrinsic terms, half of each contact it takes part in) with the
/// gradient on its four control points added to grad[4] and the contact damping force (eq. 12) to damp[4].
/// Samples of one yarn less than 2r apart along it are neighbours, not a contact (Kaldor's rule in lengths).
template <class T, class Point>
SKEIN_HD T segment_forces(const SegmentView<T>& v, const SampleView<T>& samples, const PairView& pairs, const IntrinsicParams<T>& intrinsic,
                          const ContactParams<T>& contact, int s, Point point, Vec3<T> grad[4], Vec3<T> damp[4]) {
  const int* sp = v.segment_points + 4 * s;
  // The intrinsic terms see only derivatives: about p1 they lose no precision to the garment's size (float).
  const Vec3<T> origin = point(sp[1]);
  Vec3<T> p[4];
  for (int k = 0; k < 4; ++k) p[k] = point(sp[k]) - origin;
  const T energy = segment_intrinsic(p, v.rest_length[s], intrinsic, grad);
  const int first = v.sample_start[s], n = v.contact_samples[s], curve = v.segment_curve[s];
  const Vec3<T> zero{0, 0, 0};
  T contact_energy = 0;
  for (int i = 0; i < n; ++i) {
    Vec3<T> g = zero, d = zero;
    const Vec3<T> ya = samples.pos[first + i], ua = samples.vel[first + i];
    const T wa = samples.weight[first + i], arc_a = samples.arc[first + i];
    for (int k = pairs.start[s]; k < pairs.start[s + 1]; ++k) {
      const int t = pairs.partner[k], other = v.sample_start[t], m = v.contact_samples[t];
      const bool same_yarn = v.segment_curve[t] == curve;
      for (int j = 0; j < m; ++j)
        if (!same_yarn || arc_distance(v, curve, arc_a, samples.arc[other + j]) >= 2 * v.radius)
          contact_energy += sample_contact(ya, samples.pos[other + j], ua, samples.vel[other + j], wa * samples.weight[other + j], contact, g, d);
    }
    // The sample's gradient and damping to the control points through the basis.
    T w[4];
    basis(T(i) / T(n - 1), w);
    for (int k = 0; k < 4; ++k) {
      grad[k] += g * w[k];
      damp[k] += d * w[k];
    }
  }
  return energy + T(0.5) * contact_energy;  // each pair is seen from both sides
}

/// The largest distance any point of segment s moves when its control points move by delta(i): the
/// largest Bezier control point of the Catmull-Rom segment of the displacements (the curve lies in their hull).
template <class T, class Delta> SKEIN_HD T segment_largest_move(const int* segment_points, int s, Delta delta) {
  const int* sp = segment_points + 4 * s;
  const Vec3<T> d0 = delta(sp[0]), d1 = delta(sp[1]), d2 = delta(sp[2]), d3 = delta(sp[3]);
  const T m[4] = {norm(d1), norm(d2), norm(d1 + (d2 - d0) * (T(1) / 6)), norm(d2 - (d3 - d1) * (T(1) / 6))};
  T largest = m[0];
  for (int k = 1; k < 4; ++k) largest = m[k] > largest ? m[k] : largest;
  return largest;
}

}  // namespace skein::relax::model
