#include "relax/yarn_audit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <unordered_map>

#include <Eigen/Geometry>
#include <omp.h>

#include "common/error.hpp"
#include "relax/segment_distance.hpp"
#include "relax/segment_distance.hpp"

namespace skein::relax {

using Eigen::Vector3d;

bool edges_meet_during(const Vector3d a0[2], const Vector3d a1[2], const Vector3d b0[2], const Vector3d b1[2], double tolerance) {
  const auto at = [&](double t, Vector3d out[4]) {
    out[0] = a0[0] + t * (a1[0] - a0[0]);
    out[1] = a0[1] + t * (a1[1] - a0[1]);
    out[2] = b0[0] + t * (b1[0] - b0[0]);
    out[3] = b0[1] + t * (b1[1] - b0[1]);
  };
  const auto distance_at = [&](double t) {
    Vector3d p[4];
    at(t, p);
    return segment_distance(p[0], p[1], p[2], p[3]);
  };
  // Points of the edges move at most as far as their farthest end: edges further apart than both moves
  // together cannot meet.
  const double reach = std::max((a1[0] - a0[0]).norm(), (a1[1] - a0[1]).norm()) + std::max((b1[0] - b0[0]).norm(), (b1[1] - b0[1]).norm());
  if (segment_distance(a0[0], a0[1], b0[0], b0[1]) > reach + tolerance) return false;
  // Two moving edges can only meet when their four ends are coplanar: V(t) = e1 . (e2 x e3) = 0, a cubic.
  const Vector3d u1 = a0[1] - a0[0], u2 = b0[0] - a0[0], u3 = b0[1] - a0[0];
  const Vector3d w1 = (a1[1] - a1[0]) - u1, w2 = (b1[0] - a1[0]) - u2, w3 = (b1[1] - a1[0]) - u3;
  const double c0 = u1.dot(u2.cross(u3));
  const double c1 = w1.dot(u2.cross(u3)) + u1.dot(u2.cross(w3) + w2.cross(u3));
  const double c2 = w1.dot(u2.cross(w3) + w2.cross(u3)) + u1.dot(w2.cross(w3));
  const double c3 = w1.dot(w2.cross(w3));
  const auto volume = [&](double t) { return ((c3 * t + c2) * t + c1) * t + c0; };
  // Monotone pieces of [0, 1] between the cubic's turning points; a root in each is found by bisection.
  std::array<double, 4> cuts{0, 1, 1, 1};
  int count = 1;
  const double qa = 3 * c3, qb = 2 * c2, qc = c1;
  if (std::abs(qa) > 1e-300) {
    const double disc = qb * qb - 4 * qa * qc;
    if (disc >= 0) {
      const double sq = std::sqrt(disc);
      for (double t : {(-qb - sq) / (2 * qa), (-qb + sq) / (2 * qa)})
        if (t > 0 && t < 1) cuts[count++] = t;
    }
  } else if (std::abs(qb) > 1e-300) {
    const double t = -qc / qb;
    if (t > 0 && t < 1) cuts[count++] = t;
  }
  cuts[count++] = 1;
  std::sort(cuts.begin(), cuts.begin() + count);
  const double scale = std::max({std::abs(c0), std::abs(c1), std::abs(c2), std::abs(c3)});
  if (scale <= 1e-300) {  // coplanar throughout the move: look along it
    for (int i = 0; i <= 64; ++i)
      if (distance_at(i / 64.0) <= tolerance) return true;
    return false;
  }
  for (int i = 0; i + 1 < count; ++i) {
    double lo = cuts[i], hi = cuts[i + 1];
    double vlo = volume(lo), vhi = volume(hi);
    if (distance_at(lo) <= tolerance || distance_at(hi) <= tolerance) return true;
    if ((vlo > 0) == (vhi > 0)) continue;
    for (int k = 0; k < 100 && hi - lo > 1e-15; ++k) {
      const double mid = 0.5 * (lo + hi), vm = volume(mid);
      if ((vm > 0) == (vlo > 0)) {
        lo = mid;
        vlo = vm;
      } else {
        hi = mid;
      }
    }
    if (distance_at(0.5 * (lo + hi)) <= tolerance) return true;
  }
  return false;
}

TopologyAuditor::TopologyAuditor(const YarnSystem& system, double deviation) : m_system(system), m_deviation(deviation * system.radius) {
  if (!(deviation > 0) || !std::isfinite(deviation)) throw Error("", "audit deviation", "must be positive, found " + std::to_string(deviation));
}

Vector3d TopologyAuditor::curve_point(const Eigen::Matrix3Xd& points, int segment, double t) const {
  // Catmull-Rom basis, written out here so that the auditor shares nothing with the relaxer.
  const auto& sp = m_system.segment_points[segment];
  const double t2 = t * t, t3 = t2 * t;
  return 0.5 * ((-t3 + 2 * t2 - t) * points.col(sp[0]) + (3 * t3 - 5 * t2 + 2) * points.col(sp[1]) + (-3 * t3 + 4 * t2 + t) * points.col(sp[2]) +
                (t3 - t2) * points.col(sp[3]));
}

std::vector<double> TopologyAuditor::second_derivative_bounds(const Eigen::Matrix3Xd& before, const Eigen::Matrix3Xd& after) const {
  std::vector<double> bounds(m_system.num_segments());
#pragma omp parallel for schedule(static)
  for (int s = 0; s < m_system.num_segments(); ++s) {
    // y'' of a cubic is linear in t, and linear in the control points along the move: its largest length
    // over the segment and the move is at one of its ends in one of the two states.
    const auto& sp = m_system.segment_points[s];
    double largest = 0;
    for (const Eigen::Matrix3Xd* points : {&before, &after}) {
      const auto p = [&](int k) { return points->col(sp[k]); };
      largest = std::max({largest, (2 * p(0) - 5 * p(1) + 4 * p(2) - p(3)).norm(), (-p(0) + 4 * p(1) - 5 * p(2) + 2 * p(3)).norm()});
    }
    bounds[s] = largest;
  }
  return bounds;
}

std::vector<int> TopologyAuditor::edges_per_segment(const Eigen::Matrix3Xd& before, const Eigen::Matrix3Xd& after) const {
  constexpr int kMostEdges = 64;
  const auto bounds = second_derivative_bounds(before, after);
  std::vector<int> edges(bounds.size());
  for (size_t s = 0; s < bounds.size(); ++s)
    edges[s] = std::clamp(static_cast<int>(std::ceil(std::sqrt(bounds[s] / (8 * m_deviation)))), 1, kMostEdges);
  return edges;
}

bool TopologyAuditor::segments_meet_finely(int a, int b, const Eigen::Matrix3Xd& before, const Eigen::Matrix3Xd& after, double tolerance) const {
  constexpr int kFine = 64;
  std::array<Vector3d, kFine + 1> a0, a1, b0, b1;
  for (int k = 0; k <= kFine; ++k) {
    const double t = static_cast<double>(k) / kFine;
    a0[k] = curve_point(before, a, t);
    a1[k] = curve_point(after, a, t);
    b0[k] = curve_point(before, b, t);
    b1[k] = curve_point(after, b, t);
  }
  const auto box = [](const Vector3d& p, const Vector3d& q, const Vector3d& r, const Vector3d& s) {
    Eigen::AlignedBox3d out(p);
    return out.extend(q).extend(r).extend(s);
  };
  for (int i = 0; i < kFine; ++i) {
    const auto box_a = box(a0[i], a0[i + 1], a1[i], a1[i + 1]);
    for (int j = 0; j < kFine; ++j) {
      if (!box_a.intersects(box(b0[j], b0[j + 1], b1[j], b1[j + 1]))) continue;
      const Vector3d ea0[2] = {a0[i], a0[i + 1]}, ea1[2] = {a1[i], a1[i + 1]}, eb0[2] = {b0[j], b0[j + 1]}, eb1[2] = {b1[j], b1[j + 1]};
      if (edges_meet_during(ea0, ea1, eb0, eb1, tolerance)) return true;
    }
  }
  return false;
}

std::vector<TopologyAuditor::Crossing> TopologyAuditor::crossings(const Eigen::Matrix3Xd& before, const Eigen::Matrix3Xd& after) const {
  // Polylines: segment s has edges [first[s], first[s + 1]) and points [first[s] + s, first[s + 1] + s].
  const int segments = m_system.num_segments();
  const auto per = edges_per_segment(before, after);
  std::vector<long> first(segments + 1, 0);
  for (int s = 0; s < segments; ++s) first[s + 1] = first[s] + per[s];
  const long edges = first[segments];
  std::vector<int> segment_of(edges);
  Eigen::Matrix3Xd p0(3, edges + segments), p1(3, edges + segments);
#pragma omp parallel for schedule(static)
  for (int s = 0; s < segments; ++s)
    for (int k = 0; k <= per[s]; ++k) {
      const double t = static_cast<double>(k) / per[s];
      p0.col(first[s] + s + k) = curve_point(before, s, t);
      p1.col(first[s] + s + k) = curve_point(after, s, t);
      if (k < per[s]) segment_of[first[s] + k] = s;
    }
  const auto ends = [&](long e) {
    const long i = e + segment_of[e];
    return std::array<long, 2>{i, i + 1};
  };
  // Swept boxes of the edges, bucketed in a grid whose cells are as wide as the widest box.
  // Two edges that both stay put cannot meet during the move: only pairs with a moving edge are tested.
  std::vector<Eigen::AlignedBox3d> boxes(edges);
  std::vector<char> moving(edges);
  double widest = 0;
#pragma omp parallel for schedule(static) reduction(max : widest)
  for (long e = 0; e < edges; ++e) {
    const auto [i, j] = ends(e);
    Eigen::AlignedBox3d box(p0.col(i));
    box.extend(Vector3d(p0.col(j))).extend(Vector3d(p1.col(i))).extend(Vector3d(p1.col(j)));
    boxes[e] = box;
    moving[e] = p0.col(i) != p1.col(i) || p0.col(j) != p1.col(j);
    widest = std::max(widest, box.sizes().maxCoeff());
  }
  const double cell = std::max(widest, 1e-9);
  const auto key_of = [&](const Vector3d& c, int dx, int dy, int dz) {
    const auto part = [](double v, int d) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v)) + d + (1 << 20)) & 0x1fffff; };
    return (part(c.x() / cell, dx) << 42) | (part(c.y() / cell, dy) << 21) | part(c.z() / cell, dz);
  };
  std::vector<std::pair<std::uint64_t, long>> sorted(edges);
  for (long e = 0; e < edges; ++e) sorted[e] = {key_of(boxes[e].center(), 0, 0, 0), e};
  std::sort(sorted.begin(), sorted.end());
  std::unordered_map<std::uint64_t, std::pair<long, long>> cells;  // key -> range in `sorted`
  for (long i = 0; i < edges;) {
    long j = i;
    while (j < edges && sorted[j].first == sorted[i].first) ++j;
    cells.emplace(sorted[i].first, std::make_pair(i, j));
    i = j;
  }
  const double tolerance = 1e-9 * m_system.radius;
  std::vector<std::vector<Crossing>> found(edges > 0 ? omp_get_max_threads() : 0);
#pragma omp parallel for schedule(dynamic, 256)
  for (long e = 0; e < edges; ++e) {
    if (!moving[e]) continue;
    const Vector3d c = boxes[e].center();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto cell = cells.find(key_of(c, dx, dy, dz));
          if (cell == cells.end()) continue;
          for (long i = cell->second.first; i < cell->second.second; ++i) {
            const long f = sorted[i].second;
            // Each pair once: a pair of moving edges from its first edge, a moving edge and a still one from the moving one.
            if (f == e || (moving[f] && f < e) || !boxes[e].intersects(boxes[f]) ||
                m_system.adjacent(segment_of[e], segment_of[f]))
              continue;
            const auto [ei, ej] = ends(e);
            const auto [fi, fj] = ends(f);
            const Vector3d a0[2] = {p0.col(ei), p0.col(ej)}, a1[2] = {p1.col(ei), p1.col(ej)};
            const Vector3d b0[2] = {p0.col(fi), p0.col(fj)}, b1[2] = {p1.col(fi), p1.col(fj)};
            // A meeting of the coarse polylines is confirmed on 64 points per segment: where two centrelines
            // come closer than the coarse polylines' own error, the coarse edges can cross when the curves do not.
            const int sa = segment_of[e], sb = segment_of[f];
            if (edges_meet_during(a0, a1, b0, b1, tolerance) && segments_meet_finely(sa, sb, before, after, tolerance))
              found[omp_get_thread_num()].push_back({sa, sb, 0.5 * (a0[0] + b0[0])});
          }
        }
  }
  std::vector<Crossing> all;
  for (const auto& part : found) all.insert(all.end(), part.begin(), part.end());
  std::sort(all.begin(), all.end(), [](const Crossing& x, const Crossing& y) {
    return std::tie(x.segment_a, x.segment_b) < std::tie(y.segment_a, y.segment_b);
  });
  return all;
}

double linking_number(const std::vector<Vector3d>& a, const std::vector<Vector3d>& b) {
  constexpr double kPi = 3.14159265358979323846;
  double total = 0;
  const size_t na = a.size(), nb = b.size();
  for (size_t i = 0; i < na; ++i) {
    const Vector3d& a0 = a[i];
    const Vector3d& a1 = a[(i + 1) % na];
    for (size_t j = 0; j < nb; ++j) {
      const Vector3d& b0 = b[j];
      const Vector3d& b1 = b[(j + 1) % nb];
      // Klenin & Langowski 2000: the solid angle the edge pair subtends, from the four corner normals.
      const Vector3d r13 = b0 - a0, r14 = b1 - a0, r23 = b0 - a1, r24 = b1 - a1;
      Vector3d n[4] = {r13.cross(r14), r14.cross(r24), r24.cross(r23), r23.cross(r13)};
      bool degenerate = false;
      for (auto& v : n) {
        const double len = v.norm();
        if (len <= 1e-300) degenerate = true;
        else v /= len;
      }
      if (degenerate) continue;
      double omega = 0;
      for (int k = 0; k < 4; ++k) omega += std::asin(std::clamp(n[k].dot(n[(k + 1) % 4]), -1.0, 1.0));
      const double side = ((b1 - b0).cross(a1 - a0)).dot(r13);
      total += (side > 0 ? omega : side < 0 ? -omega : 0.0);
    }
  }
  return total / (4 * kPi);
}

namespace {

/// A closed Catmull-Rom curve as a polyline of `per_segment` samples per segment, and the bound on how far the
/// polyline strays from the curve: max |y''| / 8 per_segment² (the chord error of each piece).
struct SampledLoop {
  std::vector<Vector3d> line;
  double error = 0;
  Eigen::AlignedBox3d box;
};

SampledLoop sample_loop(const mesh::YarnCurves& yarn, int c, int per_segment) {
  SampledLoop out;
  const int begin = yarn.curve_start[c], n = yarn.curve_size(c);
  const auto point = [&](int k) -> const Vector3d& { return yarn.points[begin + ((k % n) + n) % n]; };
  double curvature = 0;  // max |y''| over the curve; y'' is linear on a segment, so its ends bound it
  for (int k = 0; k < n; ++k) {
    const Vector3d d0 = 2 * point(k - 1) - 5 * point(k) + 4 * point(k + 1) - point(k + 2);   // y''(0)
    const Vector3d d1 = -point(k - 1) + 4 * point(k) - 5 * point(k + 1) + 2 * point(k + 2);  // y''(1)
    curvature = std::max({curvature, d0.norm(), d1.norm()});
    for (int m = 0; m < per_segment; ++m) {
      const double t = static_cast<double>(m) / per_segment, t2 = t * t, t3 = t2 * t;
      const Vector3d p = 0.5 * ((-t3 + 2 * t2 - t) * point(k - 1) + (3 * t3 - 5 * t2 + 2) * point(k) + (-3 * t3 + 4 * t2 + t) * point(k + 1) +
                                (t3 - t2) * point(k + 2));
      out.line.push_back(p);
      out.box.extend(p);
    }
  }
  out.error = curvature / (8.0 * per_segment * per_segment);
  out.box.extend(out.box.min() - Vector3d::Constant(out.error));
  out.box.extend(out.box.max() + Vector3d::Constant(out.error));
  return out;
}

/// Whether two closed polylines come closer than `threshold` anywhere (edge to edge); edges whose boxes are
/// farther apart than that are skipped without a distance.
bool polylines_closer_than(const std::vector<Vector3d>& a, const std::vector<Vector3d>& b, double threshold) {
  for (size_t i = 0; i < a.size(); ++i) {
    const Vector3d& a0 = a[i];
    const Vector3d& a1 = a[(i + 1) % a.size()];
    const Vector3d lo = a0.cwiseMin(a1) - Vector3d::Constant(threshold), hi = a0.cwiseMax(a1) + Vector3d::Constant(threshold);
    for (size_t j = 0; j < b.size(); ++j) {
      const Vector3d& b0 = b[j];
      const Vector3d& b1 = b[(j + 1) % b.size()];
      if ((b0.cwiseMax(b1).array() < lo.array()).any() || (b0.cwiseMin(b1).array() > hi.array()).any()) continue;
      if (segment_distance(a0, a1, b0, b1) < threshold) return true;
    }
  }
  return false;
}

}  // namespace

std::vector<Linking> linking_numbers(const mesh::YarnCurves& yarn, double deviation) {
  std::vector<int> closed;
  for (int c = 0; c < yarn.curves(); ++c)
    if (yarn.closed[c] && yarn.curve_size(c) > 2) closed.push_back(c);
  // Each closed curve first with enough samples to stay within `deviation` r of itself (at least 4 a segment).
  const double tolerance = deviation * (yarn.radius > 0 ? yarn.radius : 1.0);
  std::vector<int> per_segment(closed.size(), 4);
  std::vector<SampledLoop> loops(closed.size());
  for (size_t i = 0; i < closed.size(); ++i) {
    loops[i] = sample_loop(yarn, closed[i], 4);
    const int m = static_cast<int>(std::ceil(std::sqrt(16 * loops[i].error / tolerance)));  // the error goes as 1/m², 4² at m = 4
    if (m > 4) loops[i] = sample_loop(yarn, closed[i], per_segment[i] = std::min(m, kMaxLinkingSamples));
  }
  std::vector<std::pair<int, int>> candidates;
  for (size_t i = 0; i < closed.size(); ++i)
    for (size_t j = i + 1; j < closed.size(); ++j)
      if (loops[i].box.intersects(loops[j].box)) candidates.emplace_back(static_cast<int>(i), static_cast<int>(j));
  std::vector<Linking> out(candidates.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (long k = 0; k < static_cast<long>(candidates.size()); ++k) {
    const auto [i, j] = candidates[k];
    // The polylines' linking number is the curves' when neither polyline strays from its curve by as much as
    // half their gap: moving each polyline onto its curve then never makes them meet. Refine until it holds.
    SampledLoop a = loops[i], b = loops[j];
    for (int ma = per_segment[i], mb = per_segment[j];;) {
      if (!polylines_closer_than(a.line, b.line, 2 * (a.error + b.error)) || (ma >= kMaxLinkingSamples && mb >= kMaxLinkingSamples)) break;
      if (a.error >= b.error && ma < kMaxLinkingSamples) a = sample_loop(yarn, closed[i], ma = std::min(2 * ma, kMaxLinkingSamples));
      else b = sample_loop(yarn, closed[j], mb = std::min(2 * mb, kMaxLinkingSamples));
    }
    out[k] = {closed[i], closed[j], std::lround(linking_number(a.line, b.line))};
  }
  return out;
}

}  // namespace skein::relax
