// The 3-D fabric of Zhou 2024 §4.2: guided to the lifted embedding, never through itself, certified exactly.
#include <cmath>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "smocking/smocking_cloth.hpp"
#include "testing.hpp"

using namespace skein;
using namespace skein::smocking;
using skein::testing::error_of;

namespace {
SmockingPattern pattern_of(const std::string& text) { return parse_smocking_pattern("format smocking\n" + text, "test.smock"); }

/// A pattern gathered to `gamma` and lifted: what smock_cloth takes.
struct Gathered {
  SmockingPattern pattern;
  Embedding embedding;
  Lift lifted;
};
Gathered gathered(const std::string& text, double gamma) {
  Gathered g{pattern_of(text), {}, {}};
  EmbedOptions eo;
  eo.gamma = gamma;
  g.embedding = embed(g.pattern, eo);
  g.lifted = lift(g.embedding);
  return g;
}

const char* const kTwoZigzags = "grid 9 5\nspacing 10\nwalk front 0,1 1,-1 1,1 x8\nwalk front 0,3 1,-1 1,1 x8\n";

/// Two flat triangles, the second lifted by `lift` mm and pushed through the first when `through`.
Cloth two_triangles(double lift, bool through) {
  Cloth c;
  c.positions.resize(3, 6);
  c.positions << 0, 10, 0, 2, 2, 2,  //
      0, 0, 10, 2, 3, 3,             //
      0, 0, 0, lift, lift, lift;
  if (through) c.positions(2, 3) = -lift;  // one corner below the first triangle, two above: it crosses it
  c.triangles = {{0, 1, 2}, {3, 4, 5}};
  return c;
}
}  // namespace

TEST(SmockingCloth, TheExactTestFindsACrossingAndNoneAtAMicrometre) {
  EXPECT_EQ(exact_intersections(two_triangles(1e-3, false)), 0);  // 1 µm above: apart
  EXPECT_EQ(exact_intersections(two_triangles(1e-3, true)), 1);   // 1 µm through: crossing
  EXPECT_EQ(exact_intersections(two_triangles(1, true)), 1);
  // Neighbours sharing a corner are not crossings of the fabric through itself.
  Cloth fan = two_triangles(0, false);
  fan.triangles = {{0, 1, 2}, {0, 3, 4}};
  EXPECT_EQ(exact_intersections(fan), 0);
}

TEST(SmockingCloth, AZigzagGathersIntoPleatsWithoutPassingThroughItself) {
  // Two zigzag threads on a 9 x 5 grid, pulled to 0.4 of their length.
  const auto [p, e, l] = gathered(kTwoZigzags, 0.4);
  ASSERT_EQ(e.stopped, EmbedStop::Reached);
  ClothOptions o;
  const Cloth c = smock_cloth(p, e, l, o);
  EXPECT_EQ(c.positions.cols(), (8 * 2 + 1) * (4 * 2 + 1));
  EXPECT_EQ(exact_intersections(c), 0);
  EXPECT_GT(c.smallest_distance, 0);
  // The fabric gathered: its width across the threads' pull is well under the flat 80 mm, and it left the plane.
  const double width = c.positions.row(0).maxCoeff() - c.positions.row(0).minCoeff();
  const double depth = c.positions.row(2).maxCoeff() - c.positions.row(2).minCoeff();
  EXPECT_LT(width, 0.8 * 80) << width;
  EXPECT_GT(depth, 2) << depth;
  // Every stitching point near its lifted place (eq. 11).
  EXPECT_LT(c.target_error, 3.0);
  // Deterministic.
  const Cloth again = smock_cloth(p, e, l, o);
  EXPECT_EQ((again.positions - c.positions).cwiseAbs().maxCoeff(), 0);
}

TEST(SmockingCloth, TheEnergiesGradientMatchesFiniteDifferences) {
  // Every term at once: the fabric crumpled at random and squeezed to 0.3 of its width, so that springs
  // stretch and shorten, bending is far from flat, the guided points are off their places and hundreds of
  // point-triangle and edge-edge pairs lie within the barrier's reach.
  const auto [p, e, l] = gathered("grid 5 3\nspacing 10\nwalk front 0,1 1,-1 1,1 x4\n", 0.5);
  ClothOptions o;
  o.reach = 2;
  const int points = (4 * 2 + 1) * (2 * 2 + 1);
  Eigen::Matrix3Xd x(3, points);
  std::srand(7);
  for (int v = 0; v < points; ++v) {
    const int i = v % 9, j = v / 9;
    x.col(v) = Eigen::Vector3d(0.3 * 5 * i, -5.0 * j, 0.6 * std::sin(1.7 * i + 0.9 * j)) + 0.2 * Eigen::Vector3d::Random();
  }
  Eigen::Matrix3Xd grad;
  const double energy = first_frame_potential(p, e, l, o, x, &grad);
  ASSERT_TRUE(std::isfinite(energy));
  int checked = 0;
  for (int v = 0; v < points; v += 3)
    for (int c = 0; c < 3; ++c) {
      const double step = 1e-6;
      Eigen::Matrix3Xd plus = x, minus = x;
      plus(c, v) += step;
      minus(c, v) -= step;
      const double fd = (first_frame_potential(p, e, l, o, plus, nullptr) - first_frame_potential(p, e, l, o, minus, nullptr)) / (2 * step);
      // Within 0.2 %: a pair's distance has a kink where its closest features tie (crumpled edges nearly
      // parallel), so central differences across one are a little off; a wrong term is off by far more.
      EXPECT_NEAR(grad(c, v), fd, 2e-3 * std::max(1.0, std::abs(fd))) << "point " << v << " axis " << c;
      ++checked;
    }
  EXPECT_GT(checked, 40);
}

TEST(SmockingCloth, RefusesBadOptions) {
  ClothOptions o;
  o.subdivisions = 3;
  EXPECT_EQ(error_of([&] { o.validate(); }), "subdivisions: must be even, 2 to 32 (stitch midpoints must be fine vertices), found 3");
  o = {};
  o.k_bend = -1;
  EXPECT_EQ(error_of([&] { o.validate(); }), "k_bend: must be a positive number");
}

TEST(SmockingCloth, TheAdditiveCcdStopsEveryHeadOnPassageInTimeAndLetsSlidingPass) {
  // A point driven through a triangle and an edge driven across another, each meeting half-way through the step
  // (t = 0.5), in random poses, with random common motion and a little sideways drift; gaps from 1 µm to 2 mm.
  std::srand(11);
  const auto random_rotation = [] { return Eigen::Quaterniond(Eigen::Vector4d::Random().normalized()).toRotationMatrix(); };
  for (int trial = 0; trial < 400; ++trial) {
    const bool point_triangle = trial % 2 == 0;
    const double gap = std::pow(10.0, -3 + 3.3 * (0.5 + 0.5 * Eigen::Vector2d::Random()(0)));  // 1e-3 .. 2 mm
    const Eigen::Matrix3d rot = random_rotation();
    const Eigen::Vector3d shift = 10 * Eigen::Vector3d::Random(), common = 3 * Eigen::Vector3d::Random();
    const Eigen::Vector3d drift(0.2 * Eigen::Vector2d::Random()(0), 0.2 * Eigen::Vector2d::Random()(1), 0);
    std::array<Eigen::Vector3d, 4> x, dir;
    if (point_triangle) {
      x = {Eigen::Vector3d(0.3, 0.3, gap), {0, 0, 0}, {1.5, 0, 0}, {0, 1.5, 0}};
      dir = {Eigen::Vector3d(0, 0, -2 * gap) + drift, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    } else {
      x = {Eigen::Vector3d(-1, 0.1, gap), {1, 0.1, gap}, {0.2, -1, 0}, {0.2, 1, 0}};
      dir = {Eigen::Vector3d(0, 0, -2 * gap) + drift, Eigen::Vector3d(0, 0, -2 * gap) + drift, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    }
    for (int k = 0; k < 4; ++k) x[k] = rot * x[k] + shift, dir[k] = rot * dir[k] + common;
    const double t = additive_ccd(x, dir, point_triangle);
    // The drift keeps the closest points inside both elements, so the distance is gap (1 - 2t) until they meet at
    // t = 0.5: a tenth of the gap is left at t = 0.45.
    EXPECT_LE(t, 0.45 + 1e-9) << "trial " << trial << " gap " << gap;
    EXPECT_GT(t, 0.3) << "trial " << trial << " gap " << gap;  // and not needlessly short
  }
  // Sliding past: a point gliding over a triangle, level, the whole step.
  const std::array<Eigen::Vector3d, 4> x{Eigen::Vector3d(0.2, 0.2, 0.01), {0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::array<Eigen::Vector3d, 4> slide{Eigen::Vector3d(0.5, 0.1, 0), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  EXPECT_EQ(additive_ccd(x, slide, true), 1);
  // Still elements, or elements moving together, never meet.
  const std::array<Eigen::Vector3d, 4> together{Eigen::Vector3d(0, 0, -5), {0, 0, -5}, {0, 0, -5}, {0, 0, -5}};
  EXPECT_EQ(additive_ccd(x, together, true), 1);
}

TEST(SmockingCloth, TheBarrierStiffensWhenGuidedPointsPressTheFabricTogether) {
  // Two zigzag threads pulled hard (γ 0.3), their points held ten times more strongly than the default: the
  // guidance presses folds together. With κ held at its start the run jams, every step cut short by the collision
  // bound and a pair pressed to a micrometre; the adaptive κ (IPC) pushes back and the fabric reaches its places.
  const auto [p, e, l] = gathered(kTwoZigzags, 0.3);
  ClothOptions o;
  o.w_pos = 100;
  o.k_barrier_max = 1;
  const Cloth held = smock_cloth(p, e, l, o);
  EXPECT_EQ(held.barrier_stiffness, 1);
  EXPECT_LT(held.smallest_distance, 1e-3 * held.reach);
  EXPECT_GT(held.ccd_limited_steps, held.newton_iterations / 2);
  EXPECT_GT(held.target_error, 3.0);
  o.k_barrier_max = ClothOptions{}.k_barrier_max;
  const Cloth c = smock_cloth(p, e, l, o);
  EXPECT_GT(c.barrier_stiffness, 1);
  EXPECT_LE(c.barrier_stiffness, o.k_barrier_max);
  EXPECT_GT(c.smallest_distance, 0.1 * c.reach);
  EXPECT_LT(c.target_error, 1.0);
  EXPECT_LT(c.ccd_limited_steps, c.newton_iterations / 4);
  EXPECT_EQ(exact_intersections(held), 0);
  EXPECT_EQ(exact_intersections(c), 0);
}

TEST(SmockingCloth, StopsWhenAskedAtItsNextNewtonStep) {
  const auto p = pattern_of("grid 5 3\nspacing 10\nwalk front 0,1 1,-1 1,1 x4\n");
  const auto e = embed(p, {});
  const std::atomic<bool> stop{true};
  EXPECT_EQ(error_of([&] { smock_cloth(p, e, lift(e), {}, &stop); }), "frame 0: stopped before the fabric was finished");
}
