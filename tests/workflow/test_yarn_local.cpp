// Local re-relaxation after stitch edits: the splice from the previous relaxation, and relaxing only the
// changed stitches and rings around them.
#include <gtest/gtest.h>

#include "relax/yarn_relax.hpp"
#include "stitchmesh/edits.hpp"
#include "workflow/yarn_local.hpp"
#include "testing.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;
using namespace skein::workflow;

namespace {
/// A knit swatch's yarn relaxed to convergence (the previous relaxation), and a stitch in its middle.
struct Previous {
  skein::testing::Knitted k;
  Eigen::Matrix3Xd relaxed;
  int middle = 0;
};
const Previous& previous() {
  static const Previous p = [] {
    Previous out{skein::testing::knitted(models::swatch(), ""), {}, 0};
    YarnRelaxOptions options;
    options.audit = false;
    YarnState state = initial_state(out.k.system, options);
    const auto run = make_cpu_yarn_relaxer(out.k.system, out.k.targets, options)->run(state);
    EXPECT_TRUE(run.converged) << run.stopped_by;
    std::printf("previous relaxation: %ld steps, %.2f s\n", run.steps, run.wall_seconds);
    out.relaxed = state.points;
    const auto rows = mesh::faces_by_row(out.k.piece);
    const auto& row = rows[rows.size() / 2];
    out.middle = row[row.size() / 2];
    return out;
  }();
  return p;
}
}  // namespace

TEST(YarnLocal, ANoOpEditChangesNothing) {
  const auto& p = previous();
  const auto splice = splice_previous(p.k.yarn, p.k.yarn, p.relaxed);
  EXPECT_EQ(splice.changed(), 0);
  LocalRelaxReport report;
  const auto points = relax_locally(p.k.piece, p.k.yarn, splice, {}, {}, 1.0, {}, report);
  EXPECT_EQ(report.steps, 0);
  EXPECT_EQ(report.stopped_by, StopReason::NothingChanged);
  EXPECT_TRUE(points == p.relaxed);  // bit for bit
  // The same splice from the relaxed yarn as curves (a .bcc read back); other curves are refused.
  const auto from_curves = splice_previous(p.k.yarn, p.k.yarn, with_points(p.k.yarn, p.relaxed));
  EXPECT_TRUE(from_curves.points == splice.points);
  auto other = with_points(p.k.yarn, p.relaxed);
  other.curve_start.back() -= 1;
  other.points.pop_back();
  EXPECT_NE(skein::testing::error_of([&] { splice_previous(p.k.yarn, p.k.yarn, other); }).find("holds other curves"), std::string::npos);
}

TEST(YarnLocal, AnEditRelaxesItsRingsAndLeavesTheRestBitIdentical) {
  const auto& p = previous();
  const auto edited = mesh::set_stitch_type(p.k.piece, {p.middle}, "p");
  const auto yarn = skein::testing::yarn_of(edited);
  const auto splice = splice_previous(yarn, p.k.yarn, p.relaxed);
  ASSERT_GT(splice.changed(), 0);
  const auto owner = owner_faces(yarn);
  for (size_t q = 0; q < yarn.points.size(); ++q)
    if (!splice.matched[q]) {
      EXPECT_EQ(owner[q], p.middle) << "only the repainted stitch emits new points";
    }
  YarnRelaxOptions options;  // the audit on: every step is checked
  LocalRelaxOptions local;
  local.rings = 1;
  local.halo = 1;
  LocalRelaxReport report;
  const auto points = relax_locally(edited, yarn, splice, options, local, 1.0, {}, report);
  EXPECT_EQ(report.changed_stitches, 1);
  EXPECT_EQ(report.splice_crossings, 0);
  EXPECT_EQ(report.pull_through_events, 0);
  EXPECT_TRUE(report.converged) << report.stopped_by;
  EXPECT_GT(report.relaxed_points, 0);
  EXPECT_LT(report.relaxed_points, static_cast<int>(yarn.points.size()) / 2);
  // Outside the rings that relaxed, every point is exactly where the previous relaxation left it.
  const auto relaxed_faces = face_rings(edited, {p.middle}, report.rings);
  int far = 0, moved = 0;
  for (size_t q = 0; q < yarn.points.size(); ++q) {
    if (owner[q] >= 0 && !relaxed_faces[owner[q]]) {
      ++far;
      EXPECT_TRUE(points.col(q) == splice.points.col(q)) << "point " << q;
    } else {
      moved += (points.col(q) - splice.points.col(q)).norm() > 1e-6;
    }
  }
  EXPECT_GT(far, 0);
  EXPECT_GT(moved, 0);
}

TEST(YarnLocal, ASpliceThatWouldPassYarnThroughYarnIsRefused) {
  // Previous positions mirrored through the fabric's plane: on the way from the new emission to such a
  // splice, yarns pass through each other, so nothing may relax from it.
  const auto& p = previous();
  Eigen::Matrix3Xd mirrored = p.relaxed;
  mirrored.row(2) *= -1;
  const auto edited = mesh::set_stitch_type(p.k.piece, {p.middle}, "p");
  const auto yarn = skein::testing::yarn_of(edited);
  const auto splice = splice_previous(yarn, p.k.yarn, mirrored);
  LocalRelaxReport report;
  const auto points = relax_locally(edited, yarn, splice, {}, {}, 1.0, {}, report);
  EXPECT_EQ(report.stopped_by, StopReason::UnsafeSplice);
  EXPECT_GT(report.splice_crossings, 0);
  EXPECT_TRUE(points == splice.points);
}

TEST(YarnLocal, FaceRingsGrowAcrossSharedVertices) {
  const auto& p = previous();
  const auto none = face_rings(p.k.piece, {p.middle}, 0), one = face_rings(p.k.piece, {p.middle}, 1);
  EXPECT_EQ(std::count(none.begin(), none.end(), 1), 1);
  EXPECT_EQ(std::count(one.begin(), one.end(), 1), 9);  // a plain stitch in a grid: itself and its 8 neighbours
}
