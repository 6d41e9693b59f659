#include <gtest/gtest.h>

#include <random>

#include "common/error.hpp"
#include "garments.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/tessellation.hpp"
#include "surface/subdiv_surface.hpp"

using namespace skein;

namespace {
surface::SubdivSurface surface_of(const mesh::InputMesh& m) { return surface::SubdivSurface(m.points(), m.faces()); }
}  // namespace

TEST(SubdivSurface, FlatSwatchStaysFlatAndKeepsItsCorners) {
  const auto m = models::swatch();
  const auto s = surface_of(m);
  EXPECT_EQ(s.num_ptex_faces(), 16);
  for (int p = 0; p < s.num_ptex_faces(); ++p)
    for (double u : {0.0, 0.3, 1.0})
      for (double v : {0.0, 0.7, 1.0}) EXPECT_NEAR(s.evaluate({p, u, v}).position.z(), 0.0, 1e-12);
  // Border corners are interpolated (boundary edges and corners sharp, as the garment's hem and seams).
  for (const auto& corner : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(120, 0, 0), Eigen::Vector3d(120, 100, 0), Eigen::Vector3d(0, 100, 0)}) {
    double best = 1e9;
    for (int p = 0; p < s.num_ptex_faces(); ++p)
      for (double u : {0.0, 1.0})
        for (double v : {0.0, 1.0}) best = std::min(best, (s.evaluate({p, u, v}).position - corner).norm());
    EXPECT_LT(best, 1e-9);
  }
  EXPECT_THROW(s.evaluate({99, 0, 0}), Error);
}

TEST(SubdivSurface, DerivativesMatchFiniteDifferences) {
  for (const auto& g : models::garments()) {
    const auto m = g.make();
    const auto s = surface_of(m);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uv(0.05, 0.95);
    for (int trial = 0; trial < 40; ++trial) {
      const int p = static_cast<int>(rng() % s.num_ptex_faces());
      const double u = uv(rng), v = uv(rng), h = 1e-6;
      const auto at = s.evaluate({p, u, v});
      const Eigen::Vector3d du = (s.evaluate({p, u + h, v}).position - s.evaluate({p, u - h, v}).position) / (2 * h);
      const Eigen::Vector3d dv = (s.evaluate({p, u, v + h}).position - s.evaluate({p, u, v - h}).position) / (2 * h);
      const double scale = std::max(1.0, at.du.norm() + at.dv.norm());
      EXPECT_LT((du - at.du).norm() / scale, 1e-5) << g.name << " ptex " << p;
      EXPECT_LT((dv - at.dv).norm() / scale, 1e-5) << g.name << " ptex " << p;
    }
  }
}

TEST(SubdivSurface, TubeLimitLiesJustInsideItsControlCylinder) {
  const auto s = surface_of(models::tube());  // 12-gon of radius 40
  for (int p = 0; p < s.num_ptex_faces(); ++p) {
    const Eigen::Vector3d x = s.evaluate({p, 0.5, 0.5}).position;
    const double r = std::hypot(x.x(), x.z());
    EXPECT_GT(r, 37.0);
    EXPECT_LT(r, 40.0);
  }
}

TEST(SubdivSurface, NonQuadFacesHaveOnePtexFacePerCorner) {
  // A pentagon fan around a square: 1 quad + 4 pentagons.
  const std::vector<Eigen::Vector3d> pts{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, -1, 0}, {0.5, -1.5, 0}, {2, -1, 0}, {2.5, 0.5, 0},
                                         {2, 2, 0}, {0.5, 2.5, 0}, {-1, 2, 0}, {-1.5, 0.5, 0}};
  const std::vector<std::vector<int>> faces{{0, 1, 2, 3}, {0, 4, 5, 6, 1}, {1, 6, 7, 8, 2}, {2, 8, 9, 10, 3}, {3, 10, 11, 4, 0}};
  const surface::SubdivSurface s(pts, faces);
  EXPECT_EQ(s.num_ptex_faces(), 1 + 4 * 5);
  EXPECT_EQ(s.ptex_count(1), 5);
  EXPECT_EQ(s.face_of_ptex(s.ptex_of(2) + 3), 2);
  for (int p = 0; p < s.num_ptex_faces(); ++p) EXPECT_NEAR(s.evaluate({p, 0.4, 0.6}).position.z(), 0.0, 1e-12);
}

TEST(SurfaceTriangles, BorderIsTheOpenEdgesOnly) {
  const int n = 4;
  const auto swatch = surface_of(models::swatch());
  const auto st = surface::triangulate(swatch, n);
  EXPECT_EQ(st.border.size(), 16u * n);  // 4 sides of 4 faces, n samples each
  EXPECT_EQ(st.triangles.size(), 16u * n * n * 2);
  // A closed cube has no border.
  const std::vector<Eigen::Vector3d> pts{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const std::vector<std::vector<int>> cube{{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  const surface::SubdivSurface cs(pts, cube);
  EXPECT_TRUE(surface::triangulate(cs, n).border.empty());
}

TEST(SurfaceProjector, AttachesToTheClosestPointAndStaysOnTheLimit) {
  const auto m = models::beanie();
  const auto s = surface_of(m);
  const surface::SurfaceProjector projector(s, surface::triangulate(s, 6));
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-3, 3);
  const auto& tris = projector.triangles();
  for (int trial = 0; trial < 60; ++trial) {
    const Eigen::Vector3d q = tris.positions[rng() % tris.positions.size()] + Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
    const auto a = projector.attach(q);
    // On the limit surface at its coordinates, and no farther than the closest triangle (brute force) plus the
    // gap between triangles and limit.
    EXPECT_LT((s.evaluate(a.coord).position - a.position).norm(), 1e-12);
    double brute = 1e9;
    for (const auto& t : tris.triangles)
      for (int k = 0; k < 3; ++k) brute = std::min(brute, (tris.positions[t[k]] - q).norm());
    EXPECT_LE(a.distance, brute + 1.0) << trial;
  }
}

TEST(SurfaceProjector, BorderPointsAttachToTheBorder) {
  const auto s = surface_of(models::swatch());
  const surface::SurfaceProjector projector(s, surface::triangulate(s, 6));
  for (const auto& q : {Eigen::Vector3d(-2, 40, 1), Eigen::Vector3d(60, 101, 0), Eigen::Vector3d(125, 10, -1)}) {
    const auto a = projector.attach(q, true);
    const bool on_border_line = std::abs(a.position.x()) < 1e-6 || std::abs(a.position.x() - 120) < 1e-6 || std::abs(a.position.y()) < 1e-6 ||
                                std::abs(a.position.y() - 100) < 1e-6;
    EXPECT_TRUE(on_border_line) << a.position.transpose();
  }
}

TEST(SurfaceProjector, PointsOffTheSurfaceComeBackAlongTheNormal) {
  const auto s = surface_of(models::tube());
  const surface::SurfaceProjector projector(s, surface::triangulate(s, 8));
  for (int p = 0; p < s.num_ptex_faces(); p += 5) {
    const auto at = s.evaluate({p, 0.4, 0.45});
    const auto a = projector.attach(at.position + 2.0 * at.normal());
    EXPECT_NEAR(a.distance, 2.0, 0.02) << p;
    EXPECT_LT((a.position - at.position).norm(), 0.05) << p;
  }
}

TEST(StitchAttachment, EveryVertexOnTheLimitBorderVerticesOnTheBorder) {
  const auto m = models::beanie();
  const auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  const auto stitch = mesh::tessellate(m, l, mesh::initial_values(m, l, {}));
  const auto s = surface_of(m);
  const surface::SurfaceProjector projector(s, surface::triangulate(s, 8));
  const auto attached = surface::attach_stitch_mesh(stitch, projector);
  ASSERT_EQ(attached.coords.size(), stitch.vertices.size());
  int border = 0;
  for (size_t v = 0; v < stitch.vertices.size(); ++v) {
    EXPECT_LT((s.evaluate(attached.coords[v]).position - attached.positions[v]).norm(), 1e-12);
    if (!attached.on_border[v]) continue;
    ++border;
    const auto& c = attached.coords[v];
    EXPECT_TRUE(c.u < 1e-9 || c.u > 1 - 1e-9 || c.v < 1e-9 || c.v > 1 - 1e-9) << "border vertex " << v << " at (" << c.u << ", " << c.v << ")";
  }
  EXPECT_GT(border, 0);
  // The stitch mesh sits on the control polygons; the limit surface lies within a few mm of them.
  EXPECT_LT(attached.max_distance, 10.0);
}
