// Adaptive sampling (issue 10): contact samples per segment from the yarn radius and the segment's shape.
// Straight segments get the fewest samples that cover them, unevenly parametrised ones more; at the largest spacing allowed,
// two yarns that cross anywhere still have samples closer than 2r (contact is felt); a relaxation with
// adaptive samples ends near one with Leaf's counts. The auditor's polylines: as many edges per segment as
// its curvature needs to stay within the deviation, checked against the curve point by point.
#include <gtest/gtest.h>

#include <cmath>

#include "relax/yarn_checkpoint.hpp"
#include "relax/yarn_relax.hpp"
#include "relax/yarn_segment.hpp"
#include "relax/yarn_system.hpp"
#include "testing.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;

namespace {
/// A straight open yarn along `direction` through `start`, `n` points `step` apart.
void add_line(relax::YarnCurves& yarn, const Eigen::Vector3d& start, const Eigen::Vector3d& direction, double step, int n) {
  for (int k = 0; k < n; ++k) {
    yarn.points.push_back(start + k * step * direction);
    yarn.point_face.push_back(-1);
    yarn.point_type.push_back(-1);
  }
  yarn.curve_start.push_back(static_cast<int>(yarn.points.size()));
  yarn.closed.push_back(0);
}

relax::YarnCurves line(double radius, double step, int n) {
  relax::YarnCurves yarn;
  yarn.radius = radius;
  add_line(yarn, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), step, n);
  return yarn;
}

/// Every contact sample's position, as the relaxers place them.
std::vector<model::Vec3<double>> sample_positions(const YarnSystem& system) {
  const int total = system.sample_start.back() + system.contact_samples.back();
  std::vector<model::Vec3<double>> pos(total), vel(total);
  std::vector<double> weight(total), arc(total);
  const model::SampleView<double> out{pos.data(), vel.data(), weight.data(), arc.data()};
  const auto point = [&](int i) { return model::Vec3<double>{system.points(0, i), system.points(1, i), system.points(2, i)}; };
  const auto still = [](int) { return model::Vec3<double>{0, 0, 0}; };
  for (int s = 0; s < system.num_segments(); ++s) model::segment_samples(segment_view(system), s, point, still, out);
  return pos;
}
}  // namespace

TEST(ContactSampling, WeightsSumToOneForEveryCount) {
  for (int n : {2, 3, 5, 7, 63}) {
    double sum = 0;
    for (int k = 0; k < n; ++k) sum += model::contact_weight<double>(k, n);
    EXPECT_NEAR(sum, 1.0, 1e-14) << n;
  }
}

TEST(ContactSampling, StraightSegmentsGetTheFewestSamplesThatCoverThem) {
  const double r = 0.5;
  // Inner segments of an evenly spaced straight yarn have uniform speed: gaps of step / (n - 1).
  for (const auto& [step, expected] : std::vector<std::pair<double, int>>{{2.0, 2}, {2.4, 2}, {3.0, 3}, {4.8, 3}, {6.0, 5}, {12.0, 7}}) {
    const auto system = make_yarn_system(line(r, step * r, 6), 1.0, {}, ContactSampling{2.5});
    for (int s = 1; s + 1 < system.num_segments(); ++s) EXPECT_EQ(system.contact_samples[s], expected) << "step " << step << " r";
    // Leaf's rule: an odd count over L / 2r.
    const auto leaf = make_yarn_system(line(r, step * r, 6));
    for (int s = 1; s + 1 < system.num_segments(); ++s) EXPECT_EQ(leaf.contact_samples[s], std::max(3, (static_cast<int>(step / 2) + 1) | 1));
  }
}

TEST(ContactSampling, UnevenParameterSpeedGetsMoreSamplesThanAnEvenSegmentOfItsLength) {
  // The segment from x = 0.5 r to 5 r between neighbours at 0 and 14 r runs slowly at first and fast at the
  // end: at uniform parameter steps its second half holds more arc than the even segment's 2.25 r.
  const double r = 0.5;
  relax::YarnCurves uneven;
  uneven.radius = r;
  for (double x : {0.0, 0.5, 5.0, 14.0}) {
    uneven.points.push_back({x * r, 0, 0});
    uneven.point_face.push_back(-1);
    uneven.point_type.push_back(-1);
  }
  uneven.curve_start.push_back(4);
  uneven.closed.push_back(0);
  const auto system = make_yarn_system(uneven, 1.0, {}, ContactSampling{2.5});
  const auto even = make_yarn_system(line(r, 4.5 * r, 6), 1.0, {}, ContactSampling{2.5});
  EXPECT_NEAR(system.rest_length[1], even.rest_length[2], 0.05 * r);
  EXPECT_EQ(even.contact_samples[2], 3);
  EXPECT_EQ(system.contact_samples[1], 5);
}

TEST(ContactSampling, AtTheLargestSpacingCrossingYarnsAlwaysHaveSamplesCloserThan2r) {
  // Two straight yarns whose centrelines cross, at every offset against the other's samples: with gaps just
  // under 2√2 r, some pair of samples is closer than 2r, so contact pushes them apart before they can pass.
  const double r = 0.5, step = 2.8 * r;
  for (double dx : {0.0, 0.25, 0.5, 0.75})
    for (double dy : {0.0, 0.25, 0.5, 0.75}) {
      relax::YarnCurves yarn;
      yarn.radius = r;
      add_line(yarn, {-5 * step, 0, 0}, Eigen::Vector3d::UnitX(), step, 11);
      add_line(yarn, {dx * step, -5 * step + dy * step, 0}, Eigen::Vector3d::UnitY(), step, 11);
      const auto system = make_yarn_system(yarn, 1.0, {}, ContactSampling{ContactSampling::kMaxCoveringSpacing});
      EXPECT_EQ(system.contact_samples[4], 2);
      const auto pos = sample_positions(system);
      const int first_b = system.sample_start[10];  // yarn A's 11 points make 10 segments
      double closest = 1e9;
      for (int a = 0; a < first_b; ++a)
        for (int b = first_b; b < static_cast<int>(pos.size()); ++b) closest = std::min(closest, model::norm(pos[a] - pos[b]));
      EXPECT_LT(closest, 2 * r) << "offset " << dx << ", " << dy;
    }
}

TEST(ContactSampling, SpacingIsValidatedAndCheckpointsTellSamplingsApart) {
  EXPECT_NE(skein::testing::error_of([] { ContactSampling{3.0}.validate(); }).find("at most 2√2"), std::string::npos);
  EXPECT_NE(skein::testing::error_of([] { ContactSampling{-1}.validate(); }).find("contact spacing"), std::string::npos);
  YarnRelaxOptions options;
  options.sampling.spacing = 2.9;
  EXPECT_NE(skein::testing::error_of([&] { options.validate(); }).find("2.828 yarn radii"), std::string::npos);
  const auto yarn = skein::testing::linked_rings(0.5, 24);
  EXPECT_NE(checkpoint_fingerprint(make_yarn_system(yarn), YarnMethod::Fire),
            checkpoint_fingerprint(make_yarn_system(yarn, 1.0, {}, ContactSampling{2.5}), YarnMethod::Fire));
}

TEST(YarnRelax, AdaptiveContactSamplesEndNearLeafsCountsWithFewerSamples) {
  const auto k = skein::testing::knitted(models::swatch(), "rib");
  const auto adaptive = make_yarn_system(k.yarn, 1.0, {}, ContactSampling{2.5});
  const auto total = [](const YarnSystem& s) { return s.sample_start.back() + s.contact_samples.back(); };
  EXPECT_LT(total(adaptive), total(k.system));
  YarnRelaxOptions options;
  YarnState leaf_state = initial_state(k.system, options);
  const auto leaf = make_cpu_yarn_relaxer(k.system, k.targets, options)->run(leaf_state);
  YarnState state = initial_state(adaptive, options);
  const auto report = make_cpu_yarn_relaxer(adaptive, k.targets, options)->run(state);
  ASSERT_TRUE(leaf.converged);
  ASSERT_TRUE(report.converged) << report.stopped_by;
  EXPECT_EQ(report.pull_through_events, 0);
  const double rms = std::sqrt((state.points - leaf_state.points).colwise().squaredNorm().mean()) / k.system.radius;
  std::printf("contact samples %d (Leaf's rule %d); steps %ld vs %ld; RMS %.4f r; energy %.6g vs %.6g\n", total(adaptive), total(k.system),
              report.steps, leaf.steps, rms, report.energy, leaf.energy);
  EXPECT_LT(rms, 0.25);
}
