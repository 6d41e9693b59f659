// The yarn system: segments, neighbours and sample counts from yarn curves; bad yarn refused; rest lengths and
// take-up, per stitch type and per part of a stitch.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "relax/yarn_system.hpp"
#include "stitchmesh/pattern.hpp"
#include "testing.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;

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
