// Periodic stand-ins: relaxed repeats mapped over a garment's stitch faces.
#include <gtest/gtest.h>

#include <map>
#include <tuple>

#include "relax/yarn_active.hpp"
#include "relax/yarn_relax.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "workflow/yarn_periodic.hpp"
#include "workflow/yarn_standin.hpp"
#include "yarn_fixtures.hpp"

using namespace skein;
using namespace skein::relax;
using namespace skein::workflow;

namespace {
/// The reference for a stand-in on a flat sheet of a pattern: the pattern's periodic patch relaxed as the
/// stand-in relaxes it, tiled over the sheet's emitted `yarn`.
TiledPreview tiled_relaxed_patch(const mesh::Pattern& pattern, const mesh::StitchSize& size, double take_up, const std::map<std::string, double>& take_up_by_type,
                                 const YarnRelaxOptions& options, const relax::YarnCurves& yarn) {
  auto patch = periodic_patch(pattern, mesh::StitchLibrary::bundled(), size, 0.6);
  const auto system = make_yarn_system(patch.yarn, take_up, take_up_by_type);
  auto shape = options.shape;
  shape.boundary = false;
  // The patch's own repeat (an odd number of rows twice over) tiled as it was emitted, for its faces.
  const auto patch_repeat = patch.repeat[1] == pattern.height() ? pattern : mesh::stacked(pattern, 2);
  ShapeTargets targets = shape_targets(mesh::pattern_stitch_mesh(patch_repeat, patch.tiles, patch.tiles, size), patch.yarn, shape);
  targets.periodic = patch.map;
  YarnState state = initial_state(system, options);
  make_cpu_yarn_relaxer(system, targets, options)->run(state);
  return tile_relaxed_patch(patch, state.points, yarn);
}

/// The largest distance between the preview and the reference over `inside`, their mean difference (the
/// patch's drift, which the stand-in removes) taken off.
double largest_apart(const Eigen::Matrix3Xd& preview, const Eigen::Matrix3Xd& reference, const std::vector<int>& inside) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int p : inside) mean += reference.col(p) - preview.col(p);
  mean /= static_cast<double>(inside.size());
  double largest = 0;
  for (int p : inside) largest = std::max(largest, (reference.col(p) - preview.col(p) - mean).norm());
  return largest;
}
}  // namespace

TEST(YarnStandIn, OnAFlatSheetTheStandInMovesInteriorPointsAsTheTiledRelaxedPatchDoes) {
  // Flat sheets of stockinette, 2 x 2 rib (with 90 % of its yarn, and its purls with 95 % of that) and seed
  // stitch: their inner faces are exactly their repeat's periodic patch, so the stand-in must move each of
  // their points as the relaxed patch moved its copy (tile_relaxed_patch), up to the patch's drift, which the
  // stand-in removes.
  const auto& library = mesh::StitchLibrary::bundled();
  for (const auto& [rows, take_up, purl_take_up] : {std::tuple{std::string("k\n"), 1.0, 1.0}, {"k k p p\n", 0.9, 0.95}, {"p k\nk p\n", 1.0, 1.0}}) {
    SCOPED_TRACE(rows);
    const auto pattern = mesh::parse_pattern("format knit\n" + rows, "test.knit");
    const mesh::StitchSize size;
    const int side = 16;
    const auto sheet = mesh::pattern_stitch_mesh(pattern, side / pattern.width(), side / pattern.height(), size);
    const auto yarn = mesh::emit_yarn(sheet, library, {.yarn_radius = 0.6});
    YarnRelaxOptions options;
    options.audit = false;
    StandInOptions stand_in;
    stand_in.min_faces = 1;
    stand_in.take_up = take_up;
    stand_in.take_up_by_type = {{"p", purl_take_up}, {"s", 0.5}};  // a type the sheet has not: no error
    if (purl_take_up == 1.0) stand_in.take_up_by_type.clear();
    StandInReport report;
    const auto preview = stand_in_preview(sheet, yarn, library, options, stand_in, report);
    ASSERT_EQ(report.repeats.size(), 1u);
    EXPECT_EQ(report.repeats[0].faces, side * side);  // the faces inside the sheet, and its border reached beyond them
    EXPECT_EQ(report.repeats[0].across * report.repeats[0].up, pattern.width() * pattern.height());
    EXPECT_GT(report.placed, 0);
    EXPECT_EQ(report.placed + report.following, static_cast<int>(yarn.points.size()));

    const auto tiled = tiled_relaxed_patch(pattern, size, take_up, purl_take_up == 1.0 ? std::map<std::string, double>{} : std::map<std::string, double>{{"p", purl_take_up}},
                                           options, yarn);

    std::vector<int> inside;
    for (int p = 0; p < static_cast<int>(yarn.points.size()); ++p) {
      const int f = yarn.point_face[p], row = f / side, col = f % side;
      if (f < 0 || row < 2 || row > side - 3 || col < 2 || col > side - 3) continue;  // the faces the stand-in maps, less a ring
      inside.push_back(p);
    }
    ASSERT_FALSE(inside.empty());
    // A repeat of an odd number of rows is relaxed twice over up (its rows go left and right by turns): the
    // stand-in maps each row onto the lower copy, the reference onto the copy of the row's own direction, and the
    // two copies relax up to 0.004 r apart (2 x 2 rib).
    EXPECT_LT(largest_apart(preview, tiled.points, inside), (pattern.height() % 2 ? 5e-3 : 1e-6) * 0.6) << "over " << inside.size() << " points";
  }
}

TEST(YarnStandIn, OnAFlatSheetOfACableOrALaceTheStandInMovesInteriorPointsAsTheTiledRelaxedPatchDoes) {
  // The same for patterns that re-mesh, named to the stand-in: a 2-over-2 cable and an eyelet lace (increase
  // into three, three-way decrease). The yarn of the cable faces made at emission follows its placed neighbours.
  const auto& library = mesh::StitchLibrary::bundled();
  for (const auto& [rows, across, up] : {std::tuple{std::string("p p k k k k p p\np p k k k k p p\np p k k k k p p\np p cable2x2+ p p\n"), 3, 4},
                                         {"k k k k k\nkyk d123k k\nk k k k k\n", 4, 5}}) {
    SCOPED_TRACE(rows);
    const auto pattern = mesh::parse_pattern("# name: test\nformat knit\n" + rows, "test.knit");
    const mesh::StitchSize size;
    const auto sheet = mesh::pattern_stitch_mesh(pattern, across, up, size);
    const auto yarn = mesh::emit_yarn(sheet, library, {.yarn_radius = 0.6});
    YarnRelaxOptions options;
    options.audit = false;
    StandInOptions stand_in;
    stand_in.min_faces = 1;
    stand_in.patterns = {pattern};
    StandInReport report;
    const auto preview = stand_in_preview(sheet, yarn, library, options, stand_in, report);
    ASSERT_EQ(report.repeats.size(), 1u);
    EXPECT_EQ(report.repeats[0].pattern, "test");
    EXPECT_EQ(report.repeats[0].faces, across * up * pattern.stitches());  // every repeat of the sheet
    EXPECT_GT(report.placed, 0);
    EXPECT_EQ(report.taken_back, 0);

    const auto tiled = tiled_relaxed_patch(pattern, size, 1.0, {}, options, yarn);
    // The faces at least one repeat from the sheet's border.
    const double w = pattern.width() * size.width, h = pattern.height() * size.height;
    std::vector<int> inside;
    for (int p = 0; p < static_cast<int>(yarn.points.size()); ++p) {
      const int f = yarn.point_face[p];
      if (f < 0) continue;
      const Eigen::Vector3d& corner = sheet.vertices[sheet.faces[f].vertex(0)];
      if (corner.x() >= w - 1e-9 && corner.x() < (across - 1) * w - 1e-9 && corner.y() >= h - 1e-9 && corner.y() < (up - 1) * h - 1e-9) inside.push_back(p);
    }
    ASSERT_FALSE(inside.empty());
    // To 10⁻³ r for the cable: where its yarn crosses the repeat's bottom and top course lines the periodic patch
    // holds the crossing twice, as two real points (one on each line), which relax about 10⁻⁴ r apart; the
    // reference takes one of them and the stand-in, matching in the stitch's frame, may take the other. The lace's
    // three rows are relaxed twice over up, and its rows map onto the lower copy (the test above): 5 x 10⁻³ r.
    EXPECT_LT(largest_apart(preview, tiled.points, inside), (pattern.height() % 2 ? 5e-3 : 1e-3) * 0.6) << "over " << inside.size() << " points";
  }
}
