#include <gtest/gtest.h>

#include <map>
#include <random>

#include "common/error.hpp"
#include "garments.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/mean_value.hpp"
#include "stitchmesh/stitch_types.hpp"
#include "stitchmesh/tessellation.hpp"
#include "testing.hpp"

using namespace skein;
using skein::testing::error_of;

TEST(MeanValue, LinearPrecisionOnPolygonWithCollinearCorners) {
  // The canonical stitch polygon: a unit square with extra corners on its bottom and top sides.
  const std::vector<Eigen::Vector2d> poly{{0, 0}, {0.25, 0}, {0.7, 0}, {1, 0}, {1, 1}, {0.4, 1}, {0, 1}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.01, 0.99);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector2d p(u(rng), u(rng));
    const Eigen::VectorXd w = mesh::mean_value_coordinates(poly, p);
    Eigen::Vector2d back = Eigen::Vector2d::Zero();
    for (size_t k = 0; k < poly.size(); ++k) {
      EXPECT_GE(w[k], -1e-12);  // convex polygon: all weights non-negative
      back += w[k] * poly[k];
    }
    EXPECT_NEAR(w.sum(), 1.0, 1e-12);
    EXPECT_NEAR((back - p).norm(), 0.0, 1e-12);
  }
}

namespace {
struct Tessellated {
  mesh::InputMesh input;
  mesh::Labeling labels;
  mesh::TessellationValues values;
  mesh::StitchMesh stitch;
};
Tessellated tessellate_model(mesh::InputMesh m, mesh::StitchSize size = {}) {
  auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  auto v = mesh::initial_values(m, l, size);
  auto s = mesh::tessellate(m, l, v);
  return {std::move(m), std::move(l), std::move(v), std::move(s)};
}
int side_total(const Tessellated& t, int f, const std::vector<int>& locals) {
  int n = 0;
  for (int k : locals) n += t.values.edge[t.input.face_edge(f, k)];
  return n;
}
}  // namespace

TEST(Tessellation, InvariantsOnEveryBundledGarment) {
  for (const auto& g : models::garments()) {
    const auto t = tessellate_model(g.make());
    const auto report = mesh::validate(t.stitch);
    ASSERT_TRUE(report.valid()) << g.name << "\n" << report.summary();
    // Per input face: stitch rows, stitch counts along each line, increases only where course values differ.
    std::map<int, std::map<int, std::pair<int, int>>> lines;  // input face → stitch row → (bottom, top) totals
    std::map<int, int> extra_top, extra_bottom;
    for (const auto& f : t.stitch.faces) {
      auto& line = lines[f.input_face][f.row];
      line.first += f.bottom;
      line.second += f.top();
      extra_top[f.input_face] += std::max(0, f.top() - f.bottom);
      extra_bottom[f.input_face] += std::max(0, f.bottom - f.top());
      EXPECT_EQ(f.type, f.bottom == 1 && f.top() == 1 ? "k" : mesh::default_stitch_type(f.bottom, f.top()));
    }
    for (int f = 0; f < t.input.num_faces(); ++f) {
      const auto& fl = t.labels.faces[f];
      const int B = side_total(t, f, mesh::bottom_edges(t.input, fl, f)), T = side_total(t, f, mesh::top_edges(t.input, fl, f));
      const auto& rows = lines[f];
      ASSERT_EQ(static_cast<int>(rows.size()), t.values.edge[t.input.face_edge(f, fl.left)]) << g.name << " face " << f;
      EXPECT_EQ(rows.begin()->second.first, B) << g.name << " face " << f;
      EXPECT_EQ(rows.rbegin()->second.second, T) << g.name << " face " << f;
      for (auto it = rows.begin(); std::next(it) != rows.end(); ++it) EXPECT_EQ(it->second.second, std::next(it)->second.first);
      EXPECT_EQ(extra_top[f], std::max(0, T - B)) << g.name << " face " << f;
      EXPECT_EQ(extra_bottom[f], std::max(0, B - T)) << g.name << " face " << f;
    }
  }
}

TEST(Tessellation, StitchMeshIsConformingAlongInputEdges) {
  const auto t = tessellate_model(models::beanie());
  // Border edges of the stitch mesh = the tessellation values of the input border edges.
  int input_border = 0, stitch_border = 0;
  for (int e = 0; e < t.input.num_edges(); ++e)
    if (t.input.is_border(e)) input_border += t.values.edge[e];
  for (const auto& [key, uses] : mesh::edge_table(t.stitch)) stitch_border += uses.count == 1;
  EXPECT_EQ(stitch_border, input_border);
}

TEST(Tessellation, StitchSizeSetsTheDensity) {
  const auto coarse = tessellate_model(models::swatch(), {15, 12.5});
  const auto fine = tessellate_model(models::swatch(), {6, 5});
  EXPECT_EQ(coarse.stitch.faces.size(), 64u);  // 120 x 100 mm
  EXPECT_EQ(fine.stitch.faces.size(), 400u);
  EXPECT_THROW(tessellate_model(models::swatch(), {0, 5}), Error);
}

TEST(Tessellation, SweaterAtDefaultSizeHasAtLeastTwentyThousandStitches) {
  const auto t = tessellate_model(models::sweater());
  EXPECT_GE(t.stitch.faces.size(), 20000u);
  EXPECT_TRUE(mesh::validate(t.stitch).valid());
}

TEST(Tessellation, MarkedWaleEdgeGathersTheIncreases) {
  auto t = tessellate_model(models::swatch());
  // Make row 0's first face grow from 5 to 8 stitches; mark its left wale edge.
  const int f = 0;
  const auto& fl = t.labels.faces[f];
  const int top = t.input.face_edge(f, mesh::top_edges(t.input, fl, f)[0]);
  mesh::set_course_value(t.input, t.labels, t.values, top, 8);
  const int marked = t.input.face_edge(f, fl.left);
  mesh::mark_wale_edge(t.input, t.labels, t.values, marked, true);
  const double marked_x = t.input.point(t.input.edge_vertices(marked).first).x();
  const auto s = mesh::tessellate(t.input, t.labels, t.values);
  ASSERT_TRUE(mesh::validate(s).valid()) << mesh::validate(s).summary();
  // Every increase face of input face 0 starts on the marked (left) wale edge.
  int increases = 0;
  for (const auto& sf : s.faces) {
    if (sf.input_face != f || sf.top() == sf.bottom) continue;
    ++increases;
    EXPECT_NEAR(s.vertices[sf.vertex(0)].x(), marked_x, 1e-9);
  }
  EXPECT_EQ(increases, 3);
}

TEST(Tessellation, TooSteepAChangeIsRefusedNamingTheFace) {
  auto t = tessellate_model(models::swatch());
  const auto& fl = t.labels.faces[0];
  mesh::set_row_value(t.input, t.labels, t.values, fl.row, 1);
  mesh::set_course_value(t.input, t.labels, t.values, t.input.face_edge(0, mesh::top_edges(t.input, fl, 0)[0]), 40);
  const std::string msg = error_of([&] { mesh::tessellate(t.input, t.labels, t.values); });
  EXPECT_NE(msg.find("face 0"), std::string::npos) << msg;
  EXPECT_NE(msg.find("at most 3x"), std::string::npos) << msg;
  EXPECT_THROW(mesh::set_course_value(t.input, t.labels, t.values, t.input.face_edge(0, fl.left), 3), Error);  // a wale edge
  EXPECT_THROW(mesh::set_row_value(t.input, t.labels, t.values, 0, 0), Error);
}

TEST(Tessellation, IncompleteLabelingIsRefused) {
  const auto m = models::swatch();
  mesh::Labeling l(m);
  const auto v = mesh::initial_values(m, l, {});
  const std::string msg = error_of([&] { mesh::tessellate(m, l, v); });
  EXPECT_NE(msg.find("not labeled"), std::string::npos) << msg;
}

TEST(Tessellation, OppositeWaleDirectionsStillGiveAValidStitchMesh) {
  const auto m = models::tube();
  auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  mesh::flip_row(l, 2);
  const auto s = mesh::tessellate(m, l, mesh::initial_values(m, l, {}));
  EXPECT_TRUE(mesh::validate(s).valid()) << mesh::validate(s).summary();
}

TEST(Tessellation, IsDeterministic) {
  const auto a = tessellate_model(models::mitten());
  const auto b = tessellate_model(models::mitten());
  EXPECT_TRUE(a.stitch == b.stitch);
}
