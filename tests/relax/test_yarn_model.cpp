// The yarn model's energies against finite differences, and the contact pairs against brute force.
#include <gtest/gtest.h>

#include <random>

#include "relax/yarn_contacts.hpp"
#include "relax/yarn_model.hpp"
#include "relax/yarn_relax.hpp"
#include "relax/yarn_system.hpp"
#include "stitchmesh/pattern.hpp"
#include "workflow/yarn_shape.hpp"
#include "testing.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;
using namespace skein::workflow;
using V = model::Vec3<double>;

namespace {

/// Central differences of `energy` over the 3 x n coordinates of `x`, compared with `gradient`.
template <class F>
void expect_gradient(Eigen::Matrix3Xd x, const Eigen::Matrix3Xd& gradient, F energy, double h = 1e-6, double rel = 1e-5) {
  double scale = 0;
  for (int i = 0; i < x.size(); ++i) scale = std::max(scale, std::abs(gradient.data()[i]));
  ASSERT_GT(scale, 0);
  for (int i = 0; i < x.size(); ++i) {
    const double keep = x.data()[i];
    x.data()[i] = keep + h;
    const double up = energy(x);
    x.data()[i] = keep - h;
    const double down = energy(x);
    x.data()[i] = keep;
    EXPECT_NEAR((up - down) / (2 * h), gradient.data()[i], rel * scale + 1e-9) << "coordinate " << i;
  }
}

Eigen::Matrix3Xd random_points(int n, double spread, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-spread, spread);
  Eigen::Matrix3Xd p(3, n);
  for (int i = 0; i < n; ++i) p.col(i) = Eigen::Vector3d(i * 1.0 + u(rng), u(rng), u(rng));
  return p;
}

void to_vec(const Eigen::Matrix3Xd& m, int first, V out[4]) {
  for (int k = 0; k < 4; ++k) out[k] = {m(0, first + k), m(1, first + k), m(2, first + k)};
}

}  // namespace

TEST(YarnModel, BasisSumsToOneAndPieceHullHoldsTheCurve) {
  for (double s : {0.0, 0.3, 0.5, 1.0}) {
    double w[4], d[4], dd[4];
    model::basis(s, w);
    model::basis_d1(s, d);
    model::basis_d2(s, dd);
    EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1, 1e-15);
    EXPECT_NEAR(d[0] + d[1] + d[2] + d[3], 0, 1e-15);
    EXPECT_NEAR(dd[0] + dd[1] + dd[2] + dd[3], 0, 1e-15);
  }
  const auto p = random_points(4, 2.0, 3);
  V q[4], b[4];
  to_vec(p, 0, q);
  model::piece_bezier(q, 0.2, 0.7, b);
  const V c = (b[0] + b[1] + b[2] + b[3]) * 0.25;
  double radius = 0;
  for (const auto& x : b) radius = std::max(radius, model::norm(x - c));
  for (int i = 0; i <= 50; ++i) {
    double w[4];
    model::basis(0.2 + 0.5 * i / 50.0, w);
    EXPECT_LE(model::norm(model::combine(w, q) - c), radius + 1e-12);
  }
}

TEST(YarnModel, IntrinsicGradientMatchesFiniteDifferences) {
  const model::IntrinsicParams<double> k{0.7, 3.0, 11.0};
  const auto p0 = random_points(4, 0.4, 1);
  const double rest = 1.3;
  const auto energy = [&](const Eigen::Matrix3Xd& p) {
    V q[4], g[4] = {};
    to_vec(p, 0, q);
    return model::segment_intrinsic(q, rest, k, g);
  };
  V q[4], g[4] = {};
  to_vec(p0, 0, q);
  model::segment_intrinsic(q, rest, k, g);
  Eigen::Matrix3Xd grad(3, 4);
  for (int i = 0; i < 4; ++i) grad.col(i) << g[i].x, g[i].y, g[i].z;
  expect_gradient(p0, grad, energy);
}

TEST(YarnModel, ContactGradientMatchesFiniteDifferencesIncludingTheSoftCore) {
  for (const double gap : {0.8, 0.15}) {  // ordinary overlap, and centrelines inside the linear core
    // Two open yarns of four points crossing each other `gap` apart (yarn radius 0.5).
    relax::YarnCurves yarn;
    yarn.radius = 0.5;
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0), {1, 0.1, 0}, {2, -0.1, 0.1}, {3, 0, 0}, {1.5, -1.5, gap}, {1.6, -0.5, gap + 0.05},
                                    {1.4, 0.5, gap - 0.05}, {1.5, 1.5, gap}})
      yarn.points.push_back(p);
    yarn.curve_start = {0, 4, 8};
    yarn.closed = {0, 0};
    yarn.point_face.assign(8, -1);
    yarn.point_type.assign(8, -1);
    const auto system = make_yarn_system(yarn);
    YarnParams params;
    params.k_bend = params.k_stretch = params.k_length = 0;  // contact alone
    const auto pairs = find_contact_pairs(system, system.points, 0.5);
    ASSERT_GT(pairs.pairs(), 0);
    Eigen::Matrix3Xd grad;
    EXPECT_GT(yarn_energy(system, params, pairs, system.points, grad), 0);
    expect_gradient(system.points, grad, [&](const Eigen::Matrix3Xd& x) {
      Eigen::Matrix3Xd g;
      return yarn_energy(system, params, pairs, x, g);
    });
  }
}

TEST(YarnModel, ContactDampingOpposesRelativeVelocity) {
  const model::ContactParams<double> k{1.0, 0.3, 2.0, 0.5, 0.5};
  V g{0, 0, 0}, d{0, 0, 0};
  // b sits 0.6 above a and moves away along the normal: the damping drags a along (+z), and only along z.
  model::sample_contact(V{0, 0, 0}, V{0, 0, 0.6}, V{0, 0, 0}, V{0, 0, 1}, 1.0, k, g, d);
  EXPECT_GT(d.z, 0);
  EXPECT_NEAR(d.x, 0, 1e-12);
  EXPECT_GT(g.z, 0);  // the energy grows toward b: the contact force pushes a down, away from it
}

TEST(YarnModel, StepBoundKeepsTheMoveUnderTheLimit) {
  for (double u : {0.0, 0.5, 3.0})
    for (double a : {0.0, 1.0, 100.0}) {
      if (u == 0 && a == 0) continue;
      const double dt = model::step_bound(u, a, 0.1);
      EXPECT_NEAR(u * dt + a * dt * dt, 0.1, 1e-12) << u << " " << a;
    }
}

TEST(YarnModel, WholeYarnEnergyGradientMatchesFiniteDifferences) {
  auto yarn = skein::testing::linked_rings(0.6, 12);
  for (auto& p : yarn.points) p *= 0.5;  // squeeze: the rings overlap
  const auto system = make_yarn_system(yarn, 0.9);
  YarnParams params;
  params.k_bend = 0.5;
  const auto pairs = find_contact_pairs(system, system.points, 2 * system.radius);
  ASSERT_GT(pairs.pairs(), 0);
  Eigen::Matrix3Xd grad;
  const double e = yarn_energy(system, params, pairs, system.points, grad);
  EXPECT_GT(e, 0);
  expect_gradient(system.points, grad, [&](const Eigen::Matrix3Xd& x) {
    Eigen::Matrix3Xd g;
    return yarn_energy(system, params, pairs, x, g);
  }, 1e-6, 2e-5);
}

TEST(YarnModel, PatchTrackingGradientMatchesFiniteDifferencesOnBothPhases) {
  ShapeTargets targets;
  ShapeTargets::Patch patch;
  patch.points = {0, 1, 2};
  patch.weights = {1, 0.5, 0.5};
  patch.weight_sum = 2;
  patch.normal = Eigen::Vector3d(0.2, 0.3, 1).normalized();
  targets.patches.push_back(patch);
  ShapeOptions options;
  for (const double drift : {0.1, 3.0}) {  // under and over the biphasic threshold
    Eigen::Matrix3Xd p = random_points(3, 0.3, 7);
    targets.patches[0].start_sum = p.col(0) + 0.5 * p.col(1) + 0.5 * p.col(2);
    p.row(2).array() += drift;
    Eigen::Matrix3Xd grad = Eigen::Matrix3Xd::Zero(3, 3);
    patch_energy(targets, options, 1.0, p, grad);
    expect_gradient(p, grad, [&](const Eigen::Matrix3Xd& x) {
      Eigen::Matrix3Xd g = Eigen::Matrix3Xd::Zero(3, 3);
      return patch_energy(targets, options, 1.0, x, g);
    });
  }
}

TEST(YarnSystem, SegmentsNeighboursAndSampleCounts) {
  const auto yarn = skein::testing::linked_rings(0.5, 24);
  const auto system = make_yarn_system(yarn);
  EXPECT_EQ(system.num_segments(), 48);  // closed rings: as many segments as points
  EXPECT_EQ(system.segment_points[0][0], 23);  // wraps around
  EXPECT_TRUE(system.consecutive(0, 1));
  EXPECT_TRUE(system.consecutive(0, 23));  // across the closing point
  EXPECT_FALSE(system.consecutive(0, 2));
  EXPECT_FALSE(system.consecutive(0, 24));  // other ring
  EXPECT_TRUE(system.adjacent(0, 2));  // 0.78 mm of yarn between them, less than 2r = 1 mm
  EXPECT_FALSE(system.adjacent(0, 3));
  EXPECT_TRUE(system.adjacent(0, 22));  // the other way round
  EXPECT_NEAR(relax::model::arc_distance(relax::segment_view(system), 0, 0.1, system.curve_length[0] - 0.1), 0.2, 1e-12);  // the short way round
  for (int s = 0; s < system.num_segments(); ++s) {
    EXPECT_EQ(system.contact_samples[s] % 2, 1);
    EXPECT_GT(system.contact_samples[s], system.rest_length[s] / (2 * system.radius));  // Leaf §3.1
  }
}

TEST(YarnSystem, RejectsBadYarn) {
  auto yarn = skein::testing::linked_rings();
  yarn.radius = 0;
  EXPECT_NE(skein::testing::error_of([&] { make_yarn_system(yarn); }).find("radius must be positive"), std::string::npos);
  yarn = skein::testing::linked_rings();
  yarn.points[1] = yarn.points[0];
  EXPECT_NE(skein::testing::error_of([&] { make_yarn_system(yarn); }).find("consecutive control points coincide"), std::string::npos);
}

TEST(YarnSystem, TakeUpPerStitchTypeScalesOnlyThatTypesSegments) {
  const auto pattern = mesh::parse_pattern("format knit\nk k s k\n", "slip.knit");
  const auto yarn = mesh::emit_yarn(mesh::pattern_stitch_mesh(pattern, 2, 2), mesh::StitchLibrary::bundled(), {});
  const auto plain = make_yarn_system(yarn), slipped = make_yarn_system(yarn, 1.0, {{"s", 0.8}});
  const int s_type = static_cast<int>(std::find(yarn.type_names.begin(), yarn.type_names.end(), "s") - yarn.type_names.begin());
  int scaled = 0;
  for (int k = 0; k < plain.num_segments(); ++k) {
    const bool in_slip = yarn.point_type[yarn.segment_owner(plain.segment_points[k][1])] == s_type;
    EXPECT_NEAR(slipped.rest_length[k], plain.rest_length[k] * (in_slip ? 0.8 : 1.0), 1e-12);
    scaled += in_slip;
  }
  EXPECT_GT(scaled, 0);
  EXPECT_NE(skein::testing::error_of([&] { make_yarn_system(yarn, 1.0, {{"q", 0.8}}); }).find("the yarn has no stitch of that type"), std::string::npos);
  EXPECT_NE(skein::testing::error_of([&] { make_yarn_system(yarn, 1.0, {{"s", -1}}); }).find("must be positive"), std::string::npos);
}

TEST(YarnSystem, TakeUpOfAStitchsVerticalOrHorizontalMaterialScalesOnlyThatPart) {
  // Leaf 2018 §6.1: a slipped stitch holds the loop below carried up through its row (vertical material: two
  // pieces from the bottom edge to the top, two segments each) and the row's yarn floating behind it
  // (horizontal: one piece from the left wale edge to the right, three segments). Two slipped stitches here.
  const auto pattern = mesh::parse_pattern("format knit\nk k k k\nk s k k\nk k k k\n", "slip.knit");
  const auto yarn = mesh::emit_yarn(mesh::pattern_stitch_mesh(pattern, 2, 1), mesh::StitchLibrary::bundled(), {});
  ASSERT_EQ(yarn.point_vertical.size(), yarn.points.size());
  const auto plain = make_yarn_system(yarn);
  const auto vertical = make_yarn_system(yarn, 1.0, {{"s:vertical", 0.5}});
  const auto horizontal = make_yarn_system(yarn, 1.0, {{"s:horizontal", 0.5}});
  const auto both = make_yarn_system(yarn, 1.0, {{"s", 0.8}, {"s:vertical", 0.5}});
  int vertical_segments = 0, horizontal_segments = 0;
  for (int k = 0; k < plain.num_segments(); ++k) {
    const Eigen::Vector3d d = plain.points.col(plain.segment_points[k][2]) - plain.points.col(plain.segment_points[k][1]);
    const double v = vertical.rest_length[k] / plain.rest_length[k], h = horizontal.rest_length[k] / plain.rest_length[k];
    if (v != 1.0) {
      EXPECT_NEAR(v, 0.5, 1e-12);
      EXPECT_GT(std::abs(d.y()), 2 * std::abs(d.x())) << "segment " << k << " runs along the wale";
      EXPECT_NEAR(both.rest_length[k], 0.4 * plain.rest_length[k], 1e-12);
      ++vertical_segments;
    }
    if (h != 1.0) {
      EXPECT_NEAR(h, 0.5, 1e-12);
      EXPECT_NEAR(v, 1.0, 0) << "segment " << k << " is vertical and horizontal";
      EXPECT_GT(std::abs(d.x()), std::abs(d.y())) << "segment " << k << " runs along the course";
      EXPECT_NEAR(both.rest_length[k], 0.8 * plain.rest_length[k], 1e-12);
      ++horizontal_segments;
    }
  }
  EXPECT_EQ(vertical_segments, 2 * 2 * 2);
  EXPECT_EQ(horizontal_segments, 2 * 3);
  EXPECT_NE(skein::testing::error_of([&] { make_yarn_system(yarn, 1.0, {{"s:up", 0.5}}); }).find("must be vertical or horizontal"), std::string::npos);
  EXPECT_NE(skein::testing::error_of([&] { make_yarn_system(yarn, 1.0, {{"s:", 0.5}}); }).find("must be vertical or horizontal"), std::string::npos);
  EXPECT_NE(skein::testing::error_of([&] { make_yarn_system(yarn, 1.0, {{":vertical", 0.5}}); }).find("expected a stitch type"), std::string::npos);
  EXPECT_NE(skein::testing::error_of([&] { make_yarn_system(yarn, 1.0, {{"k:vertical", 0.5}}); }).find("stitch k has no vertical yarn"), std::string::npos);
  auto read_back = yarn;  // yarn from a .bcc knows its stitch types at most, not its pieces
  read_back.point_vertical.clear();
  EXPECT_NE(skein::testing::error_of([&] { make_yarn_system(read_back, 1.0, {{"s:vertical", 0.5}}); }).find("does not say which of its material is vertical"),
            std::string::npos);
}

TEST(YarnSystem, RestLengthsOfAnotherShapeKeepTheirLengthsAndTakeTheNewPoints) {
  const auto flat = skein::testing::linked_rings(0.5, 24);
  auto bent = flat;
  for (auto& p : bent.points) p = Eigen::Vector3d(p.x() * 1.5, p.y(), p.z() + 0.1 * p.x() * p.x());  // longer rings
  const auto rest = make_yarn_system(flat, 0.9);
  const auto system = with_rest_lengths_of(rest, bent, "flat.bcc");
  EXPECT_EQ(system.rest_length, rest.rest_length);
  EXPECT_EQ(system.contact_samples, rest.contact_samples);
  for (int p = 0; p < system.num_points(); ++p) EXPECT_EQ(system.points.col(p), bent.points[p]);
  EXPECT_GT(make_yarn_system(bent, 0.9).curve_length[0], rest.curve_length[0] * 1.1);  // its own lengths would be longer
  auto fewer = bent;
  fewer.points.pop_back();
  fewer.curve_start.back() -= 1;
  fewer.point_type.resize(fewer.points.size());
  EXPECT_EQ(skein::testing::error_of([&] { with_rest_lengths_of(rest, fewer, "flat.bcc"); }),
            "flat.bcc: yarn 1: has 23 points, closed, where the yarn relaxed has 24 points, closed");
}
