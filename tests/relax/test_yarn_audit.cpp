// The exact continuous crossing test (issue 27): Bezier curves moving on straight lines, against references
// that can be computed exactly: a straight yarn swept through a plane curve (it meets the curve where its 2-D
// path crosses it), yarn passing over a plane curve at a gap from a millimetre down to a nanometre, and yarn
// dropped through it by as little.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "common/error.hpp"

#include "relax/yarn_audit.hpp"
#include "relax/yarn_system.hpp"
#include "testing.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;
using Eigen::Vector2d;
using Eigen::Vector3d;
using skein::testing::curve_points;

namespace {

/// A cubic Bezier curve's point.
Vector3d bezier(const Vector3d b[4], double s) {
  const double r = 1 - s;
  return r * r * r * b[0] + 3 * r * r * s * b[1] + 3 * r * s * s * b[2] + s * s * s * b[3];
}

/// A straight segment from p to q as Bezier control points (evenly spaced).
void straight(const Vector3d& p, const Vector3d& q, Vector3d out[4]) {
  for (int i = 0; i < 4; ++i) out[i] = p + (q - p) * (i / 3.0);
}

/// Where along p0-p1 (0..1) the 2-D segment q0-q1 crosses it, or -1.
double crossing(const Vector2d& p0, const Vector2d& p1, const Vector2d& q0, const Vector2d& q1) {
  const auto cross = [](const Vector2d& u, const Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
  const Vector2d d = p1 - p0, e = q1 - q0;
  const double den = cross(d, e);
  if (den == 0) return -1;
  const double t = cross(q0 - p0, e) / den, u = cross(q0 - p0, d) / den;
  return t >= 0 && t <= 1 && u >= 0 && u <= 1 ? t : -1;
}

double point_segment_distance(const Vector2d& x, const Vector2d& p, const Vector2d& q) {
  const double t = std::clamp((x - p).dot(q - p) / (q - p).squaredNorm(), 0.0, 1.0);
  return (p + t * (q - p) - x).norm();
}

}  // namespace

TEST(ExactAudit, AStraightYarnSweptThroughAPlaneCurveMeetsItExactlyWhenItsPathCrossesTheCurve) {
  // Curve a: random control points in the plane z = 0, still. Yarn b: a straight segment along z through the
  // plane, carried from P to Q. They meet iff the path P-Q crosses a's curve in the plane; the reference
  // intersects P-Q with a's curve sampled at 20,000 points and skips cases closer than 1 µm to tangency.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  int meets = 0, misses = 0, compared = 0;
  for (int trial = 0; trial < 400; ++trial) {
    Vector3d a[4], b0[4], b1[4];
    for (auto& p : a) p = {coordinate(random), coordinate(random), 0};
    const Vector2d P(coordinate(random), coordinate(random)), Q(coordinate(random), coordinate(random));
    straight({P.x(), P.y(), -1}, {P.x(), P.y(), 1}, b0);
    straight({Q.x(), Q.y(), -1}, {Q.x(), Q.y(), 1}, b1);
    // The reference: a's curve as 20,000 pieces crossed with P-Q. Too close to call (skipped): the curve passes
    // within 1 µm of P or Q, grazes P-Q without crossing, or crosses it twice within 1 µm (a tangency).
    constexpr int kSamples = 20000;
    std::vector<double> along;
    double graze = INFINITY, ends = INFINITY;
    for (int i = 0; i < kSamples; ++i) {
      const Vector2d c0 = bezier(a, static_cast<double>(i) / kSamples).head<2>(), c1 = bezier(a, static_cast<double>(i + 1) / kSamples).head<2>();
      if (const double t = crossing(P, Q, c0, c1); t >= 0) along.push_back(t * (Q - P).norm());
      graze = std::min(graze, point_segment_distance(c0, P, Q));
      ends = std::min({ends, point_segment_distance(P, c0, c1), point_segment_distance(Q, c0, c1)});
    }
    std::sort(along.begin(), along.end());
    bool tangency = false;
    for (size_t i = 1; i < along.size(); ++i) tangency |= along[i] - along[i - 1] < 1e-3;
    if (ends < 1e-3 || (along.empty() && graze < 1e-3) || tangency) continue;
    const bool crosses = !along.empty();
    ++compared;
    const int met = bezier_curves_meet_during(a, a, b0, b1, 1e-9);
    ASSERT_NE(met, -1) << "trial " << trial;
    EXPECT_EQ(met == 1, crosses) << "trial " << trial;
    (crosses ? meets : misses) += 1;
  }
  EXPECT_GT(compared, 250);
  EXPECT_GT(meets, 50);
  EXPECT_GT(misses, 50);
}

TEST(ExactAudit, YarnPassingOverACurveAtAnyGapIsApartAndAtNoGapMeets) {
  // Curve a in the plane z = 0; yarn b a straight segment parallel to the plane at height g, swept across the
  // whole curve. The closest they come is g: apart for every g > 0 down to 1 nm (the polylines of the old
  // auditor could not see below 0.1 r), met at g = 0.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> coordinate(-2.0, 2.0);
  for (int trial = 0; trial < 40; ++trial) {
    Vector3d a[4], b0[4], b1[4];
    for (auto& p : a) p = {coordinate(random), coordinate(random), 0};
    for (double gap : {1.0, 1e-3, 1e-6, 1e-9, 0.0}) {
      straight({-3, -3, gap}, {-3, 3, gap}, b0);
      straight({3, -3, gap}, {3, 3, gap}, b1);
      EXPECT_EQ(bezier_curves_meet_during(a, a, b0, b1, 1e-12), gap > 0 ? 0 : 1) << "trial " << trial << ", gap " << gap;
      // Dropped from g above the plane to g below it, over the curve's middle: it passes through, however small the move.
      const Vector3d m = bezier(a, 0.5);
      straight({m.x() - 0.1, m.y() - 3, gap}, {m.x() + 0.1, m.y() + 3, gap}, b0);
      straight({m.x() - 0.1, m.y() - 3, -gap}, {m.x() + 0.1, m.y() + 3, -gap}, b1);
      if (gap > 0) {
        EXPECT_EQ(bezier_curves_meet_during(a, a, b0, b1, 1e-12), 1) << "trial " << trial << ", through at gap " << gap;
      }
    }
  }
}

TEST(ExactAudit, TwoCurvesThatKeepAGapAllTheWayAreApartThoughTheyMove) {
  // Both move: b follows a at a fixed offset of 1 µm, a sliding along a diagonal. Parallel curves this close
  // take many pieces to separate; they are settled, not counted as meeting.
  Vector3d a0[4] = {{0, 0, 0}, {1, 1, 0}, {2, -1, 0}, {3, 0, 0}}, a1[4], b0[4], b1[4];
  const Vector3d offset(0, 0, 1e-3), slide(0.4, 0.3, 0.2);
  for (int i = 0; i < 4; ++i) {
    a1[i] = a0[i] + slide;
    b0[i] = a0[i] + offset;
    b1[i] = a1[i] + offset;
  }
  EXPECT_EQ(bezier_curves_meet_during(a0, a1, b0, b1, 1e-9), 0);
  // Offset along the path's normal by less than the tolerance: they count as meeting.
  for (int i = 0; i < 4; ++i) b0[i] = a0[i] + 1e-10 * Vector3d::UnitZ(), b1[i] = a1[i] + 1e-10 * Vector3d::UnitZ();
  EXPECT_EQ(bezier_curves_meet_during(a0, a1, b0, b1, 1e-9), 1);
}

TEST(ExactAudit, ARingDraggedThroughAnotherIsCaughtAndASlideIsNot) {
  // Ring B dragged off ring A through its yarn: caught, every pair settled. A slide along the yarn: nothing.
  const auto yarn = skein::testing::linked_rings(0.5, 24);
  const auto system = make_yarn_system(yarn);
  const TopologyAuditor auditor(system);
  Eigen::Matrix3Xd after = system.points;
  for (int p = yarn.curve_start[1]; p < yarn.curve_start[2]; ++p) after(0, p) += 8;
  const auto crossed = auditor.crossings(system.points, after);
  ASSERT_FALSE(crossed.empty());
  for (const auto& c : crossed) EXPECT_TRUE(c.resolved);
  Eigen::Matrix3Xd slide = system.points;
  for (int p = yarn.curve_start[1]; p < yarn.curve_start[2]; ++p) slide(1, p) += 0.1;
  EXPECT_TRUE(auditor.crossings(system.points, slide).empty());
  EXPECT_THROW(TopologyAuditor(system, 0.0), skein::Error);
}

TEST(ExactAudit, AStrayPointKilometresAwayIsAuditedWithoutAHugeGrid) {
  // A file with one control point far out (a unit mistake, a blow-up): its segments' boxes span more cells than
  // any grid should hold, so they are tested against every segment instead, and the audit ends at once. The
  // stray segments sweep through ring A's yarn on the way out.
  const auto yarn = skein::testing::linked_rings();
  const auto system = make_yarn_system(yarn);
  Eigen::Matrix3Xd after = system.points;
  after.col(yarn.curve_start[1]) = Vector3d(1e6, -1e6, 1e6);
  const auto crossings = TopologyAuditor(system).crossings(system.points, after);
  EXPECT_FALSE(crossings.empty());
  Eigen::Matrix3Xd nowhere = system.points;
  nowhere.col(yarn.curve_start[1]) = Vector3d::Constant(std::numeric_limits<double>::infinity());
  EXPECT_NO_THROW(TopologyAuditor(system).crossings(system.points, nowhere));
}

TEST(ExactAudit, LinkingByCrossingsEqualsTheGaussSumSignIncluded) {
  // Curve B winds k times round curve A's circle (k = -3..3), both jittered and turned at random, sampled at
  // random counts: the crossing count gives the Gauss sum's integer, sign included, from every view.
  std::mt19937 random(5);
  std::uniform_real_distribution<double> jitter(-0.04, 0.04), angle(0, 6.283185307179586);
  std::uniform_int_distribution<int> count(40, 400);
  for (int trial = 0; trial < 30; ++trial) {
    const int k = trial % 7 - 3, na = count(random), nb = count(random) + 20 * std::abs(k);
    const Eigen::Matrix3d turn = (Eigen::AngleAxisd(angle(random), Vector3d::UnitZ()) * Eigen::AngleAxisd(angle(random), Vector3d::UnitX())).toRotationMatrix();
    std::vector<Vector3d> a, b;
    for (int i = 0; i < na; ++i) {
      const double t = 6.283185307179586 * i / na;
      a.push_back(turn * Vector3d(std::cos(t) + jitter(random), std::sin(t) + jitter(random), jitter(random)));
    }
    for (int i = 0; i < nb; ++i) {
      const double t = 6.283185307179586 * i / nb, rho = 0.3;
      b.push_back(turn * Vector3d((1 + rho * std::cos(k * t)) * std::cos(t), (1 + rho * std::cos(k * t)) * std::sin(t), rho * std::sin(k * t)));
    }
    const double gauss = linking_number(a, b);
    ASSERT_NEAR(gauss, std::round(gauss), 1e-6) << "trial " << trial;
    EXPECT_EQ(std::abs(std::lround(gauss)), std::abs(k));
    for (int view = 0; view < 3; ++view) {
      const auto crossings = linking_number_by_crossings(a, b, view);
      ASSERT_TRUE(crossings.has_value()) << "trial " << trial << ", view " << view;
      EXPECT_EQ(*crossings, std::lround(gauss)) << "trial " << trial << ", view " << view;
    }
    // B carried away from A: unlinked.
    for (auto& p : b) p += Vector3d(5, 0, 0);
    EXPECT_EQ(linking_number_by_crossings(a, b), 0);
  }
}

TEST(StateAudit, ARingPulledOffAnotherChangesItsLinkingAndCrossesAndAnUnmovedYarnChangesNothing) {
  const auto before = skein::testing::linked_rings(0.5, 24);
  auto after = before;
  for (int p = before.curve_start[1]; p < before.curve_start[2]; ++p) after.points[p].x() += 8;  // ring B off ring A
  const auto pulled = audit_states(before, after);
  EXPECT_EQ(pulled.curves, 2);
  EXPECT_EQ(pulled.closed_curves, 2);
  EXPECT_EQ(pulled.points, 48);
  EXPECT_NEAR(pulled.largest_move, 8, 1e-12);
  EXPECT_NEAR(pulled.rms_move, std::sqrt(0.5 * 64), 1e-12);  // half the points moved 8 mm
  EXPECT_FALSE(pulled.crossings.empty());
  EXPECT_EQ(pulled.unresolved, 0);
  ASSERT_EQ(pulled.linking_changes.size(), 1u);
  EXPECT_EQ(std::abs(pulled.linking_changes[0].before), 1);
  EXPECT_EQ(pulled.linking_changes[0].after, 0);
  EXPECT_FALSE(pulled.unchanged());
  const auto still = audit_states(before, before);
  EXPECT_TRUE(still.unchanged());
  EXPECT_EQ(still.largest_move, 0);
  EXPECT_EQ(still.linked_pairs, 1);
  auto fewer = before;
  fewer.closed[1] = 0;
  EXPECT_NE(skein::testing::error_of([&] { audit_states(before, fewer); }).find("hold other curves"), std::string::npos);
}

TEST(YarnAudit, LinkingNumbersOfLinkedAndSeparateRings) {
  const auto linked = skein::testing::linked_rings();
  EXPECT_NEAR(std::abs(linking_number(curve_points(linked, 0), curve_points(linked, 1))), 1.0, 1e-9);
  auto apart = linked;
  for (int p = apart.curve_start[1]; p < apart.curve_start[2]; ++p) apart.points[p].z() += 10;
  EXPECT_NEAR(linking_number(curve_points(apart, 0), curve_points(apart, 1)), 0.0, 1e-9);
  const auto all = linking_numbers(linked);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(std::abs(all[0].number), 1);
}

TEST(YarnAudit, LinkingNumbersSeeARingHookedCloserThanFourSamplesASegmentResolve) {
  // A: a closed Catmull-Rom curve through the four corners of a diamond (a rounded square, 5 mm). B: a ring of
  // radius 0.02 mm around A's curve where four samples a segment cut the corner by three times that, so B
  // hooks the curve but not the coarse polyline; the fixed 4-sample rule called this pair unlinked.
  relax::YarnCurves y;
  y.radius = 0.3;
  y.points = {{5, 0, 0}, {0, 5, 0}, {-5, 0, 0}, {0, -5, 0}};
  const auto cr = [](const Vector3d& p0, const Vector3d& p1, const Vector3d& p2, const Vector3d& p3, double t) {
    const double t2 = t * t, t3 = t2 * t;
    return Vector3d(0.5 * ((-t3 + 2 * t2 - t) * p0 + (3 * t3 - 5 * t2 + 2) * p1 + (-3 * t3 + 4 * t2 + t) * p2 + (t3 - t2) * p3));
  };
  const auto& P = y.points;
  const Vector3d centre = cr(P[3], P[0], P[1], P[2], 0.625), before = cr(P[3], P[0], P[1], P[2], 0.5), after = cr(P[3], P[0], P[1], P[2], 0.75);
  ASSERT_GT((centre - 0.5 * (before + after)).norm(), 0.06);  // the coarse polyline passes 0.06 mm and more away
  const Vector3d tangent = (after - before).normalized(), u = tangent.unitOrthogonal(), v = tangent.cross(u);
  for (int k = 0; k < 8; ++k) {
    const double a = 2 * M_PI * k / 8;
    y.points.push_back(centre + 0.02 * (std::cos(a) * u + std::sin(a) * v));
  }
  y.curve_start = {0, 4, 12};
  y.closed = {1, 1};
  y.point_face.assign(y.points.size(), -1);
  std::vector<Vector3d> coarse;  // A as the fixed rule sampled it: four samples a segment
  for (int k = 0; k < 4; ++k)
    for (int m = 0; m < 4; ++m) coarse.push_back(cr(P[(k + 3) % 4], P[k], P[(k + 1) % 4], P[(k + 2) % 4], m / 4.0));
  EXPECT_NEAR(linking_number(coarse, curve_points(y, 1)), 0.0, 1e-9);
  const auto links = linking_numbers(y);
  ASSERT_EQ(links.size(), 1u);
  EXPECT_EQ(std::abs(links[0].number), 1);
  // Moved off the curve by 0.3 mm (outside the corner), the ring is free: 0.
  for (int p = 4; p < 12; ++p) y.points[p] += 0.3 * (centre - 0.5 * (before + after)).normalized();
  EXPECT_EQ(linking_numbers(y)[0].number, 0);
}

TEST(YarnAudit, AuditorCountsARingPulledThroughAnother) {
  const auto yarn = skein::testing::linked_rings();
  const auto system = make_yarn_system(yarn);
  Eigen::Matrix3Xd after = system.points;
  for (int p = yarn.curve_start[1]; p < yarn.curve_start[2]; ++p) after(0, p) += 8;  // drag ring B off ring A
  EXPECT_GT(TopologyAuditor(system).crossings(system.points, after).size(), 0u);
  Eigen::Matrix3Xd lifted = system.points;
  for (int p = yarn.curve_start[1]; p < yarn.curve_start[2]; ++p) lifted(1, p) += 0.1;  // a small slide
  EXPECT_TRUE(TopologyAuditor(system).crossings(system.points, lifted).empty());
}
