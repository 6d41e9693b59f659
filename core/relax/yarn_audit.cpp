#include "relax/yarn_audit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <tuple>

#include <Eigen/Geometry>
#include <omp.h>

#include "common/error.hpp"
#include "relax/segment_distance.hpp"

namespace skein::relax {

using Eigen::Vector3d;

namespace {

/// Boxes put in every cell of a uniform grid that they overlap. A query meets each stored box that overlaps its
/// box once: in the cell that holds the lowest corner of the two boxes' overlap. Boxes over more than
/// kMostCells cells (a stray long segment in a file, or one that is not finite) are kept aside and tested
/// against every query, and such a query is tested against every box, so that no box makes a grid too large.
class BoxGrid {
public:
  /// `members`: per box, whether it is stored (empty: every box); the others can still be asked for by box(i).
  /// `boxes` must outlive the grid.
  BoxGrid(const std::vector<Eigen::AlignedBox3d>& boxes, double cell, const std::vector<char>& members = {})
      : m_boxes(boxes), m_cell(std::max(cell, 1e-12)) {
    for (int i = 0; i < static_cast<int>(m_boxes.size()); ++i) {
      if (!members.empty() && !members[i]) continue;
      m_stored.push_back(i);
      if (too_large(m_boxes[i])) m_large.push_back(i);
      else each_cell(m_boxes[i], [&](const Eigen::Vector3i& c) { m_sorted.emplace_back(key_of(c), i); });
    }
    std::sort(m_sorted.begin(), m_sorted.end());
  }
  const Eigen::AlignedBox3d& box(int i) const { return m_boxes[i]; }
  /// visit(i) for each stored box i that overlaps `query` and that want(i) asks for (asked first: it is cheaper
  /// than the boxes).
  template <class Want, class Visit> void overlapping(const Eigen::AlignedBox3d& query, Want want, Visit visit) const {
    if (too_large(query)) {
      for (int i : m_stored)
        if (want(i) && query.intersects(m_boxes[i])) visit(i);
      return;
    }
    each_cell(query, [&](const Eigen::Vector3i& home) {
      const std::uint64_t key = key_of(home);
      for (auto it = std::lower_bound(m_sorted.begin(), m_sorted.end(), std::make_pair(key, -1)); it != m_sorted.end() && it->first == key; ++it)
        if (want(it->second) && query.intersects(m_boxes[it->second]) && index(query.intersection(m_boxes[it->second]).min()) == home)
          visit(it->second);
    });
    for (int i : m_large)
      if (want(i) && query.intersects(m_boxes[i])) visit(i);
  }

private:
  static constexpr double kMostCells = 4096;
  /// The cell of a point; coordinates further out than 2^20 cells share the outermost cells (only slower).
  Eigen::Vector3i index(const Vector3d& x) const {
    return Eigen::Vector3i((x / m_cell).array().floor().cwiseMax(-1048576.0).cwiseMin(1048576.0).cast<int>());
  }
  bool too_large(const Eigen::AlignedBox3d& box) const {
    const Eigen::Array3d cells = (box.max() / m_cell).array().floor() - (box.min() / m_cell).array().floor() + 1;
    return !cells.allFinite() || cells.prod() > kMostCells;
  }
  static std::uint64_t key_of(const Eigen::Vector3i& c) {
    const auto part = [](int v) { return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v + (1 << 20)) & 0x1fffff); };
    return (part(c.x()) << 42) | (part(c.y()) << 21) | part(c.z());
  }
  template <class Visit> void each_cell(const Eigen::AlignedBox3d& box, Visit visit) const {
    const Eigen::Vector3i lo = index(box.min()), hi = index(box.max());
    for (int x = lo.x(); x <= hi.x(); ++x)
      for (int y = lo.y(); y <= hi.y(); ++y)
        for (int z = lo.z(); z <= hi.z(); ++z) visit(Eigen::Vector3i(x, y, z));
  }
  const std::vector<Eigen::AlignedBox3d>& m_boxes;
  double m_cell;
  std::vector<std::pair<std::uint64_t, int>> m_sorted;
  std::vector<int> m_stored;  ///< the boxes stored
  std::vector<int> m_large;   ///< stored boxes kept out of the grid
};

/// One piece [s0, s1] x [u0, u1] x [t0, t1] of the difference D(s, u, t) = y_a(s, t) − y_b(u, t), by its
/// Bernstein coefficients c[(i * 4 + j) * 2 + k] (degree 3 in s, 3 in u, 1 in t): D's values on the piece lie in
/// their convex hull.
struct Piece {
  Vector3d c[32];
  double s0, s1, u0, u1, t0, t1;
};

int at(int i, int j, int k) { return (i * 4 + j) * 2 + k; }

/// Is every coefficient more than `margin` along the direction n (any length; none when zero)?
bool beyond(const Piece& p, Vector3d n, double margin) {
  const double length = n.norm();
  if (!(length > 0)) return false;
  n /= length;
  for (const Vector3d& c : p.c)
    if (n.dot(c) <= margin) return false;
  return true;
}

/// Does a plane separate the hull of the coefficients from the origin by more than `margin`? The box's faces
/// first, then the plane normal to the coefficients' mean (the direction from b to a), then the plane normal to
/// both curves' chords (their common perpendicular where the two pieces are nearly straight), facing the mean.
bool proved_apart(const Piece& p, double margin, Vector3d& lo, Vector3d& hi) {
  lo = hi = p.c[0];
  Vector3d sum = Vector3d::Zero();
  for (const Vector3d& c : p.c) {
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
    sum += c;
  }
  if ((lo.array() > margin).any() || (hi.array() < -margin).any()) return true;
  if (beyond(p, sum, margin)) return true;
  // The chords at the start of the piece: a's along s (j fixed), b's along u (their difference's change along u is −b's).
  const Vector3d chord_a = p.c[at(3, 0, 0)] - p.c[at(0, 0, 0)], chord_b = p.c[at(0, 3, 0)] - p.c[at(0, 0, 0)];
  Vector3d n = chord_a.cross(chord_b);
  if (n.dot(sum) < 0) n = -n;
  return beyond(p, n, margin);
}

/// Halves a cubic's four coefficients c[first + step * m] (de Casteljau at 1/2) into the same places of left and right.
void halve_cubic(const Vector3d* c, Vector3d* left, Vector3d* right, int first, int step) {
  const Vector3d& p0 = c[first];
  const Vector3d& p1 = c[first + step];
  const Vector3d& p2 = c[first + 2 * step];
  const Vector3d& p3 = c[first + 3 * step];
  const Vector3d q0 = 0.5 * (p0 + p1), q1 = 0.5 * (p1 + p2), q2 = 0.5 * (p2 + p3), r0 = 0.5 * (q0 + q1), r1 = 0.5 * (q1 + q2), mid = 0.5 * (r0 + r1);
  left[first] = p0, left[first + step] = q0, left[first + 2 * step] = r0, left[first + 3 * step] = mid;
  right[first] = mid, right[first + step] = r1, right[first + 2 * step] = q2, right[first + 3 * step] = p3;
}

/// Splits a piece in two across s (axis 0), u (1) or t (2).
void split(const Piece& p, int axis, Piece& left, Piece& right) {
  left = right = p;
  if (axis == 0) {
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 2; ++k) halve_cubic(p.c, left.c, right.c, at(0, j, k), at(1, 0, 0));
    left.s1 = right.s0 = 0.5 * (p.s0 + p.s1);
  } else if (axis == 1) {
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 2; ++k) halve_cubic(p.c, left.c, right.c, at(i, 0, k), at(0, 1, 0));
    left.u1 = right.u0 = 0.5 * (p.u0 + p.u1);
  } else {
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        const Vector3d mid = 0.5 * (p.c[at(i, j, 0)] + p.c[at(i, j, 1)]);
        left.c[at(i, j, 1)] = right.c[at(i, j, 0)] = mid;
      }
    left.t1 = right.t0 = 0.5 * (p.t0 + p.t1);
  }
}

/// The axis along which the coefficients change most: 3 × the largest difference of neighbours along s or u
/// (a cubic's derivative bound), the largest difference along t.
int widest_axis(const Piece& p) {
  double ds = 0, du = 0, dt = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 2; ++k) {
        const Vector3d& c = p.c[at(i, j, k)];
        if (i < 3) ds = std::max(ds, (p.c[at(i + 1, j, k)] - c).squaredNorm());
        if (j < 3) du = std::max(du, (p.c[at(i, j + 1, k)] - c).squaredNorm());
        if (k == 0) dt = std::max(dt, (p.c[at(i, j, 1)] - c).squaredNorm());
      }
  ds *= 9, du *= 9;
  return ds >= du && ds >= dt ? 0 : du >= dt ? 1 : 2;
}

Vector3d bezier_point(const Vector3d b[4], double s) {
  const double r = 1 - s;
  return r * r * r * b[0] + 3 * r * r * s * b[1] + 3 * r * s * s * b[2] + s * s * s * b[3];
}

int curves_meet(const Vector3d a0[4], const Vector3d a1[4], const Vector3d b0[4], const Vector3d b1[4], double tolerance, int max_pieces,
                Vector3d* where) {
  Piece root;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      root.c[at(i, j, 0)] = a0[i] - b0[j];
      root.c[at(i, j, 1)] = a1[i] - b1[j];
    }
  root.s0 = root.u0 = root.t0 = 0;
  root.s1 = root.u1 = root.t1 = 1;
  // Proved apart: more than a quarter of the tolerance everywhere. Met: a piece whose box holds the origin within
  // that margin and is at most half the tolerance across, so |D| < tolerance there.
  const double margin = 0.25 * tolerance;
  // One stack per thread, kept between calls: the per-step audit tests thousands of pairs, most in one piece.
  thread_local std::vector<Piece> stack;
  stack.assign(1, root);
  int pieces = 0;
  Vector3d lo, hi;
  while (!stack.empty()) {
    const Piece p = stack.back();
    stack.pop_back();
    if (proved_apart(p, margin, lo, hi)) continue;
    if ((hi - lo).norm() <= 0.5 * tolerance) {
      if (where) *where = bezier_point(a0, 0.5 * (p.s0 + p.s1));
      return 1;
    }
    if (++pieces > max_pieces) {
      if (where) *where = bezier_point(a0, 0.5 * (p.s0 + p.s1));
      return -1;
    }
    Piece left, right;
    split(p, widest_axis(p), left, right);
    stack.push_back(right);
    stack.push_back(left);
  }
  return 0;
}

}  // namespace

int bezier_curves_meet_during(const Vector3d a0[4], const Vector3d a1[4], const Vector3d b0[4], const Vector3d b1[4], double tolerance, int max_pieces) {
  return curves_meet(a0, a1, b0, b1, tolerance, max_pieces, nullptr);
}

TopologyAuditor::TopologyAuditor(const YarnSystem& system, double tolerance) : m_system(system), m_tolerance(tolerance * system.radius) {
  if (!(tolerance > 0) || !std::isfinite(tolerance)) throw Error("", "audit tolerance", "must be positive, found " + std::to_string(tolerance));
}

void TopologyAuditor::restrict_to(std::vector<char> segments) {
  if (!segments.empty() && segments.size() != static_cast<size_t>(m_system.num_segments()))
    throw Error("", "audit", "the segment mask has " + std::to_string(segments.size()) + " entries for " +
                std::to_string(m_system.num_segments()) + " segments");
  m_tested = std::move(segments);
}

std::vector<TopologyAuditor::Crossing> TopologyAuditor::crossings(const Eigen::Matrix3Xd& before, const Eigen::Matrix3Xd& after) const {
  const int segments = m_system.num_segments();
  // Each segment's Bezier control points in both states (Catmull-Rom to Bezier, written out here so that the
  // auditor shares nothing with the relaxer), and the box that holds the segment all through the move.
  // The buffers are kept from call to call: fresh ones (1.5 MB on a cable's patch) cost a page fault per page.
  auto& bezier = m_scratch.bezier;
  auto& boxes = m_scratch.boxes;
  auto& moving = m_scratch.moving;
  bezier.resize(segments);
  boxes.resize(segments);
  moving.resize(segments);
  double width_sum = 0;
#pragma omp parallel for schedule(static) reduction(+ : width_sum)
  for (int s = 0; s < segments; ++s) {
    const auto& sp = m_system.segment_points[s];
    Eigen::AlignedBox3d box;
    for (int state = 0; state < 2; ++state) {
      const Eigen::Matrix3Xd& q = state == 0 ? before : after;
      const Vector3d p0 = q.col(sp[0]), p1 = q.col(sp[1]), p2 = q.col(sp[2]), p3 = q.col(sp[3]);
      Vector3d* b = bezier[s].data() + 4 * state;
      b[0] = p1, b[1] = p1 + (p2 - p0) / 6, b[2] = p2 - (p3 - p1) / 6, b[3] = p2;
      for (int k = 0; k < 4; ++k) box.extend(b[k]);
    }
    box.extend(box.min() - Vector3d::Constant(m_tolerance)).extend(box.max() + Vector3d::Constant(m_tolerance));
    boxes[s] = box;
    moving[s] = 0;
    for (int k = 0; k < 4; ++k) moving[s] |= before.col(sp[k]) != after.col(sp[k]);
    width_sum += box.sizes().maxCoeff();
  }
  const double mean_width = segments > 0 ? width_sum / segments : 0;
  // Cells three times as wide as the boxes are on average: a few long segments do not make every cell crowded.
  // Restricted, the grid holds the marked segments only and every segment asks it for its marked partners.
  const bool restricted = !m_tested.empty();
  const BoxGrid grid(boxes, 3 * mean_width, m_tested);
  std::vector<std::vector<Crossing>> found(segments > 0 ? omp_get_max_threads() : 0);
#pragma omp parallel for schedule(dynamic, 64)
  for (int a = 0; a < segments; ++a) {
    // Each pair once: from its moving segment, the lower of two moving ones; restricted, when either moves, from
    // its segment that is not marked, or the lower of two marked ones.
    if (!restricted && !moving[a]) continue;
    const auto want = [&](int b) {
      if (b == a) return false;
      if (!restricted) return !(moving[b] && b < a);
      return (moving[a] || moving[b]) && !(m_tested[a] && b < a);
    };
    grid.overlapping(grid.box(a), want, [&](int b) {
      if (m_system.adjacent(a, b)) return;
      const Vector3d* pa = bezier[a].data();
      const Vector3d* pb = bezier[b].data();
      Vector3d where;
      const int met = curves_meet(pa, pa + 4, pb, pb + 4, m_tolerance, kMaxAuditPieces, &where);
      if (met != 0) found[omp_get_thread_num()].push_back({std::min(a, b), std::max(a, b), where, met > 0});
    });
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

/// Calls visit(i, j) once for every edge i of closed polyline a and edge j of closed polyline b whose boxes,
/// a's grown by `reach`, overlap (b's edges in a BoxGrid with cells twice their mean box, plus the reach).
template <class Visit>
void near_edge_pairs(const std::vector<Vector3d>& a, const std::vector<Vector3d>& b, double reach, Visit visit) {
  const auto box_of = [](const std::vector<Vector3d>& line, size_t i, double grow) {
    const Vector3d& p = line[i];
    const Vector3d& q = line[(i + 1) % line.size()];
    return Eigen::AlignedBox3d(p.cwiseMin(q) - Vector3d::Constant(grow), p.cwiseMax(q) + Vector3d::Constant(grow));
  };
  std::vector<Eigen::AlignedBox3d> boxes(b.size());
  double width = 0;
  for (size_t j = 0; j < b.size(); ++j) width += (boxes[j] = box_of(b, j, 0)).sizes().maxCoeff();
  const BoxGrid grid(boxes, 2 * width / std::max<size_t>(b.size(), 1) + reach);
  for (size_t i = 0; i < a.size(); ++i) grid.overlapping(box_of(a, i, reach), [](int) { return true; }, [&](int j) { visit(i, static_cast<size_t>(j)); });
}

}  // namespace

std::optional<long> linking_number_by_crossings(const std::vector<Vector3d>& a, const std::vector<Vector3d>& b, int view) {
  // A generic view: the polylines rotated so that no edge is seen end on and no two crossings coincide, but for
  // inputs made to defeat it (then the caller tries another view).
  const Eigen::Matrix3d rotation = (Eigen::AngleAxisd(0.6180339887 + 1.3247179572 * view, Vector3d(0.2672612419, 0.5345224838, 0.8017837257)) *
                                    Eigen::AngleAxisd(0.4142135624 * (view + 1), Vector3d::UnitX()))
                                       .toRotationMatrix();
  std::vector<Vector3d> pa(a.size()), pb(b.size()), flat_a(a.size()), flat_b(b.size());
  for (size_t i = 0; i < a.size(); ++i) pa[i] = rotation * a[i], flat_a[i] = {pa[i].x(), pa[i].y(), 0};
  for (size_t j = 0; j < b.size(); ++j) pb[j] = rotation * b[j], flat_b[j] = {pb[j].x(), pb[j].y(), 0};
  const auto cross2 = [](const Vector3d& u, const Vector3d& v) { return u.x() * v.y() - u.y() * v.x(); };
  long over = 0;  // signed crossings where a passes over b
  bool degenerate = false;
  near_edge_pairs(flat_a, flat_b, 0.0, [&](size_t i, size_t j) {
    const Vector3d &a0 = pa[i], &a1 = pa[(i + 1) % pa.size()], &b0 = pb[j], &b1 = pb[(j + 1) % pb.size()];
    const Vector3d da = a1 - a0, db = b1 - b0;
    const double o1 = cross2(da, b0 - a0), o2 = cross2(da, b1 - a0), o3 = cross2(db, a0 - b0), o4 = cross2(db, a1 - b0);
    // An end on the other edge's line, or parallel edges, make the view's crossings ambiguous: another view.
    const double scale = 1e-12 * (da.head<2>().norm() + db.head<2>().norm()) * (da.head<2>().norm() + db.head<2>().norm() + (b0 - a0).head<2>().norm());
    if (std::abs(o1) <= scale || std::abs(o2) <= scale || std::abs(o3) <= scale || std::abs(o4) <= scale) {
      const bool apart = (o1 > scale && o2 > scale) || (o1 < -scale && o2 < -scale) || (o3 > scale && o4 > scale) || (o3 < -scale && o4 < -scale);
      degenerate |= !apart;
      return;
    }
    if ((o1 > 0) == (o2 > 0) || (o3 > 0) == (o4 > 0)) return;
    const double s = o3 / (o3 - o4), u = o1 / (o1 - o2);  // where along a and along b
    const double depth = (a0.z() + s * da.z()) - (b0.z() + u * db.z());
    if (std::abs(depth) <= 1e-12 * (a0 - b0).norm()) {
      degenerate = true;  // the curves meet here: no linking number
      return;
    }
    if (depth > 0) over += cross2(da, db) > 0 ? 1 : -1;
  });
  if (degenerate) return std::nullopt;
  return over;
}

namespace {

/// A closed Catmull-Rom curve as a polyline of `per_segment` samples per segment, and the bound on how far the
/// polyline strays from the curve: max |y''| / 8 per_segment² (the chord error of each piece).
struct SampledLoop {
  std::vector<Vector3d> line;
  double error = 0;
  Eigen::AlignedBox3d box;
};

SampledLoop sample_loop(const relax::YarnCurves& yarn, int c, int per_segment) {
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

/// Whether two closed polylines come closer than `threshold` anywhere (edge to edge).
bool polylines_closer_than(const std::vector<Vector3d>& a, const std::vector<Vector3d>& b, double threshold) {
  bool closer = false;
  near_edge_pairs(a, b, threshold, [&](size_t i, size_t j) {
    if (!closer) closer = segment_distance(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()]) < threshold;
  });
  return closer;
}

/// The linking number of two closed polylines that do not meet: by signed crossings (exact, near-linear time),
/// from another view when one is degenerate, and by the Gauss sum when every view is.
long polyline_linking_number(const std::vector<Vector3d>& a, const std::vector<Vector3d>& b) {
  for (int view = 0; view < 8; ++view)
    if (const auto n = linking_number_by_crossings(a, b, view)) return *n;
  return std::lround(linking_number(a, b));
}

}  // namespace

std::vector<Linking> linking_numbers(const relax::YarnCurves& yarn, double deviation) {
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
    out[k] = {closed[i], closed[j], polyline_linking_number(a.line, b.line)};
  }
  return out;
}

StateAudit audit_states(const relax::YarnCurves& before, const relax::YarnCurves& after, double deviation) {
  if (before.curve_start != after.curve_start || before.closed != after.closed)
    throw Error("", "", "the two states hold other curves (curve count, point counts or closed flags differ)");
  const auto system = make_yarn_system(before);
  StateAudit out;
  out.curves = system.num_curves();
  out.closed_curves = static_cast<int>(std::count(before.closed.begin(), before.closed.end(), 1));
  out.points = system.num_points();
  Eigen::Matrix3Xd moved(3, system.num_points());
  double squares = 0;
  for (int p = 0; p < system.num_points(); ++p) {
    moved.col(p) = after.points[p];
    const double d = (moved.col(p) - system.points.col(p)).norm();
    out.largest_move = std::max(out.largest_move, d);
    squares += d * d;
  }
  out.rms_move = std::sqrt(squares / system.num_points());
  out.crossings = TopologyAuditor(system).crossings(system.points, moved);
  out.segment_ends.reserve(system.segment_points.size());
  for (const auto& stencil : system.segment_points) out.segment_ends.push_back({stencil[1], stencil[2]});
  out.unresolved = std::count_if(out.crossings.begin(), out.crossings.end(), [](const auto& c) { return !c.resolved; });
  std::map<std::pair<int, int>, std::array<long, 2>> links;  // per pair: before, after (0 where a state has none)
  for (const auto& l : linking_numbers(before, deviation)) links[{l.a, l.b}][0] = l.number;
  for (const auto& l : linking_numbers(after, deviation)) links[{l.a, l.b}][1] = l.number;
  out.linked_pairs = static_cast<long>(links.size());
  for (const auto& [pair, numbers] : links)
    if (numbers[0] != numbers[1]) out.linking_changes.push_back({pair.first, pair.second, numbers[0], numbers[1]});
  return out;
}

}  // namespace skein::relax
