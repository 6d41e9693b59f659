#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include <Eigen/Geometry>

#include "common/error.hpp"
#include "garments.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/tessellation.hpp"
#include "surface/mesh_relax.hpp"

using namespace skein;

namespace {
/// A tube whose stitches are twice as narrow on one side: course edges with x > 0 carry twice the stitches.
mesh::StitchMesh uneven_tube(const mesh::InputMesh& m, const mesh::StitchSize& size = {}) {
  const auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  auto values = mesh::initial_values(m, l, size);
  for (int e = 0; e < m.num_edges(); ++e) {
    const auto [a, b] = m.edge_vertices(e);
    if (l.edges[e] == mesh::EdgeLabel::Course && m.point(a).x() + m.point(b).x() > 0) values.edge[e] *= 2;
  }
  return mesh::tessellate(m, l, values);
}

double area_variation(const std::vector<Eigen::Vector3d>& x, const mesh::StitchMesh& s) {
  std::vector<double> areas;
  for (const auto& f : s.faces) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    for (int k = 0; k < f.size(); ++k) n += x[f.vertex(k)].cross(x[f.vertex(k + 1)]);
    areas.push_back(0.5 * n.norm());
  }
  double mean = 0, var = 0;
  for (double a : areas) mean += a / areas.size();
  for (double a : areas) var += (a - mean) * (a - mean) / areas.size();
  return std::sqrt(var) / mean;
}
}  // namespace

TEST(MeshRelax, UnevenTubeBecomesUniformOnTheSurface) {
  const auto m = models::tube();
  const auto s = uneven_tube(m);
  surface::MeshRelaxer relaxer(m.points(), m.faces(), s);
  const double before = area_variation(relaxer.positions(), s);
  const double size = m.bounding_diagonal();
  const auto& tris = surface::triangulate(relaxer.surface(), 8);
  double energy = relaxer.energy();
  surface::MeshRelaxReport report;
  for (int step = 0; step < 200; ++step) {
    const auto st = relaxer.step();
    report.steps.push_back(st);
    // Energy never rises; every vertex stays on the limit surface; border vertices stay on the border.
    EXPECT_LE(st.energy, energy * (1 + 1e-12)) << "step " << st.step;
    energy = st.energy;
    for (size_t v = 0; v < relaxer.positions().size(); ++v) {
      ASSERT_LT((relaxer.surface().evaluate(relaxer.coords()[v]).position - relaxer.positions()[v]).norm(), 1e-6 * size);
      if (!relaxer.on_border()[v]) continue;
      double to_border = 1e9;
      for (const auto& [a, b] : tris.border) {
        const Eigen::Vector3d pa = tris.positions[a], pb = tris.positions[b], x = relaxer.positions()[v];
        const double t = std::clamp((x - pa).dot(pb - pa) / (pb - pa).squaredNorm(), 0.0, 1.0);
        to_border = std::min(to_border, (pa + t * (pb - pa) - x).norm());
      }
      ASSERT_LT(to_border, 1e-3 * size) << "border vertex " << v << " left the border";
    }
    if (st.max_displacement < 0.01 * relaxer.r_course()) break;
  }
  const double after = area_variation(relaxer.positions(), s);
  std::printf("  face-area variation %.3f -> %.3f in %zu steps\n", before, after, report.steps.size());
  EXPECT_LE(after, 0.5 * before);
}

// Yuksel's constants hold for any unit: a garment modelled in mm and the same garment ten times larger relax
// to the same shape, ten times larger. (Before the shear was taken in units of the rest size, the cubic shear
// swamped the stretch at 10 mm stitches and relaxed a beanie into alternating wide and narrow columns.)
TEST(MeshRelax, TheShapeDoesNotDependOnTheModelsUnit) {
  const auto small = models::tube();
  std::vector<Eigen::Vector3d> points = small.points();
  for (auto& p : points) p *= 10;
  const mesh::InputMesh large(points, small.faces(), "tube × 10");
  std::vector<std::vector<Eigen::Vector3d>> shapes;
  for (const auto* m : {&small, &large}) {
    const double scale = m == &large ? 10 : 1;
    const auto s = uneven_tube(*m, {10 * scale, 8 * scale});
    surface::MeshRelaxOptions options;
    options.max_steps = 10;
    surface::MeshRelaxer relaxer(m->points(), m->faces(), s, options);
    relaxer.run();
    shapes.push_back(relaxer.positions());
    for (auto& p : shapes.back()) p /= scale;
  }
  ASSERT_EQ(shapes[0].size(), shapes[1].size());
  double largest = 0;
  for (size_t v = 0; v < shapes[0].size(); ++v) largest = std::max(largest, (shapes[0][v] - shapes[1][v]).norm());
  EXPECT_LT(largest, 1e-6 * small.bounding_diagonal());
}

TEST(MeshRelax, RunsAreDeterministic) {
  const auto m = models::tube();
  const auto s = uneven_tube(m);
  surface::MeshRelaxOptions o;
  o.max_steps = 5;
  surface::MeshRelaxer a(m.points(), m.faces(), s, o), b(m.points(), m.faces(), s, o);
  a.run();
  b.run();
  EXPECT_EQ(a.positions(), b.positions());
}

TEST(MeshRelax, AnInterruptStopsTheRunAfterItsStep) {
  const auto m = models::tube();
  const auto s = uneven_tube(m);
  std::atomic<bool> interrupt{false};
  surface::MeshRelaxOptions o;
  o.interrupt = &interrupt;
  surface::MeshRelaxer relaxer(m.points(), m.faces(), s, o);
  const auto report = relaxer.run([&](const surface::MeshRelaxStep& step) {
    if (step.step == 3) interrupt = true;
  });
  EXPECT_EQ(report.steps.size(), 3u);
  EXPECT_FALSE(report.converged);
}

TEST(MeshRelax, RestLengthsFollowTheSurfaceArea) {
  // N r_wale r_course = α A (Yuksel §6.1) on a flat swatch, whose area is known: 120 × 100 mm.
  const auto m = models::swatch();
  const auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  const auto s = mesh::tessellate(m, l, mesh::initial_values(m, l, {}));
  surface::MeshRelaxOptions o;
  o.alpha = 0.8;
  o.aspect = 0.75;
  surface::MeshRelaxer r(m.points(), m.faces(), s, o);
  EXPECT_NEAR(s.faces.size() * r.r_course() * r.r_wale(), 0.8 * 120 * 100, 1e-6);
  EXPECT_NEAR(r.r_wale() / r.r_course(), 0.75, 1e-12);
  const auto stretch = surface::face_stretch(s, r.r_course(), r.r_wale());
  EXPECT_EQ(stretch.area_strain.size(), s.faces.size());
}

TEST(MeshRelax, OptionsAndInputsAreChecked) {
  const auto m = models::swatch();
  const auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  auto s = mesh::tessellate(m, l, mesh::initial_values(m, l, {}));
  surface::MeshRelaxOptions bad;
  bad.alpha = 1.5;
  EXPECT_THROW(surface::MeshRelaxer(m.points(), m.faces(), s, bad), Error);
  s.faces[0].type = "kp";
  EXPECT_THROW(surface::MeshRelaxer(m.points(), m.faces(), s), Error);
}

TEST(MeshRelax, TurnedOverStitchesAreTurnedBack) {
  const auto m = models::tube();
  const auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  auto s = mesh::tessellate(m, l, mesh::initial_values(m, l, {}));
  // Throw stitches' top-right corners across their diagonals (bottom-right to top-left): they turn over.
  const auto rows = mesh::faces_by_row(s);
  for (int r = 4; r < 24; r += 4)
    for (int c = 2; c < 60; c += 30) {
      const auto& f = s.faces[rows[r][c]];
      const int br = f.vertex(f.bottom), tr = f.vertex(f.bottom + 1), tl = f.vertex(f.size() - 1);
      s.vertices[tr] = 2.0 * (s.vertices[br] + s.vertices[tl]) - 3.0 * s.vertices[tr];
    }
  surface::MeshRelaxer relaxer(m.points(), m.faces(), s);
  const int before = relaxer.turned_over();
  EXPECT_GT(before, 0);
  const auto report = relaxer.run();
  EXPECT_TRUE(report.converged);
  EXPECT_EQ(relaxer.turned_over(), 0) << "turned over before relaxation: " << before;
  std::printf("  turned over: %d after attachment, %d after relaxation\n", before, relaxer.turned_over());
}
