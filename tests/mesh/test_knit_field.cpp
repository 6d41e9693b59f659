// Stitch meshes traced from the knitting field (issue 25, part 1) on surfaces nobody labeled: triangulated
// tubes and sheets, a sphere, a pole of valence 8, and the refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <set>

#include "common/error.hpp"
#include "stitchmesh/knit_field.hpp"
#include "stitchmesh/stitch_mesh.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "testing.hpp"

using namespace skein;
using skein::testing::error_of;

namespace {

/// A grid of (nx x ny) quads over (u, v) in [0, 1]^2 mapped by `at`, each quad cut into two triangles along a
/// diagonal that alternates; `wrap` joins the u = 1 column to u = 0 (a tube). `keep(i, j)` leaves quads out.
template <class At, class Keep>
mesh::InputMesh triangle_grid(int nx, int ny, bool wrap, At at, Keep keep, const std::string& name) {
  std::vector<Eigen::Vector3d> points;
  const int columns = wrap ? nx : nx + 1;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i < columns; ++i) points.push_back(at(static_cast<double>(i) / nx, static_cast<double>(j) / ny));
  const auto id = [&](int i, int j) { return j * columns + (wrap ? i % nx : i); };
  std::vector<std::vector<int>> faces;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (!keep(i, j)) continue;
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2) {
        faces.push_back({a, b, c});
        faces.push_back({a, c, d});
      } else {
        faces.push_back({a, b, d});
        faces.push_back({b, c, d});
      }
    }
  return mesh::with_used_points(points, std::move(faces), name);  // without the left-out quads' points
}

mesh::InputMesh tube(double radius, double height) {
  return triangle_grid(
      20, 6, true, [&](double u, double v) { return Eigen::Vector3d(radius * std::cos(2 * M_PI * u), height * v, radius * std::sin(2 * M_PI * u)); },
      [](int, int) { return true; }, "tube.obj");
}

mesh::InputMesh sheet(double width, double height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  return triangle_grid(
      12, 10, false,
      [&](double u, double v) {  // inner points jittered by up to 0.3 of a grid step
        const bool inner = u > 0 && u < 1 && v > 0 && v < 1;
        return Eigen::Vector3d(width * (u + (inner ? jitter(rng) / 12 : 0)), height * (v + (inner ? jitter(rng) / 10 : 0)), 0);
      },
      [](int, int) { return true; }, "sheet.obj");
}

/// An icosahedron split four ways `levels` times onto a sphere: a closed triangle mesh.
mesh::InputMesh sphere(double radius, int levels) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> p{{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                 {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::vector<int>> f{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                  {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                  {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& x : p) x = radius * x.normalized();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> middle;
    const auto mid = [&](int a, int b) {
      auto [it, added] = middle.try_emplace(std::minmax(a, b), static_cast<int>(p.size()));
      if (added) p.push_back(radius * (p[a] + p[b]).normalized());
      return it->second;
    };
    std::vector<std::vector<int>> next;
    for (const auto& t : f) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      next.insert(next.end(), {{t[0], ab, ca}, {t[1], bc, ab}, {t[2], ca, bc}, {ab, bc, ca}});
    }
    f = std::move(next);
  }
  return mesh::InputMesh(std::move(p), std::move(f), "sphere.obj");
}

/// A shallow dome of quads round a pole of valence 8: 8 quads meet at the pole, then 3 rings of 16 quads, a
/// border at the rim.
mesh::InputMesh pole_dome() {
  const int around = 16, rings = 4;
  std::vector<Eigen::Vector3d> p{{0, 40, 0}};
  for (int r = 1; r <= rings; ++r)
    for (int s = 0; s < around; ++s) {
      const double a = 2 * M_PI * s / around, rho = 90.0 * r / rings;
      p.emplace_back(rho * std::cos(a), 40 - rho * rho / 200, rho * std::sin(a));
    }
  const auto at = [&](int r, int s) { return 1 + (r - 1) * around + (s % around); };
  std::vector<std::vector<int>> f;
  for (int s = 0; s < around; s += 2) f.push_back({0, at(1, s), at(1, s + 1), at(1, s + 2)});
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < around; ++s) f.push_back({at(r, s + 1), at(r, s), at(r + 1, s), at(r + 1, s + 1)});
  return mesh::InputMesh(std::move(p), std::move(f), "pole.obj");
}

mesh::StitchMesh stitches_of(const mesh::TracedRows& traced) { return mesh::tessellate(traced.mesh, traced.labels, traced.values); }

/// Every traced row is a stitch row; the stitch mesh obeys Yuksel's rules and emits one continuous yarn per
/// piece of knitting.
void expect_valid(const mesh::TracedRows& traced, const std::string& what) {
  const auto stitch = stitches_of(traced);
  const auto report = mesh::validate(stitch);
  ASSERT_TRUE(report.valid()) << what << "\n" << report.summary();
  EXPECT_EQ(static_cast<int>(stitch.faces.size()), traced.mesh.num_faces()) << what;  // one stitch a traced face
  const auto yarn = mesh::emit_yarn(stitch, mesh::StitchLibrary::bundled(), {});
  EXPECT_GE(yarn.curves(), 1) << what;
}

/// Mean lengths of the traced mesh's wale and course edges.
std::pair<double, double> edge_means(const mesh::TracedRows& t) {
  double wale = 0, course = 0;
  int nw = 0, nc = 0;
  for (int e = 0; e < t.mesh.num_edges(); ++e) {
    if (t.labels.edges[e] == mesh::EdgeLabel::Wale) wale += t.mesh.edge_length(e), ++nw;
    if (t.labels.edges[e] == mesh::EdgeLabel::Course) course += t.mesh.edge_length(e), ++nc;
  }
  return {wale / nw, course / nc};
}

}  // namespace

TEST(KnitField, ATriangulatedTubeKnitsInTheRoundAtTheStitchSize) {
  const mesh::StitchSize size{6, 5};
  const auto surface = tube(40, 120);
  const auto traced = mesh::trace_stitch_mesh(surface, {mesh::default_start_edge(surface), {}}, size);
  expect_valid(traced, "tube");
  // 2 pi 40 / 6 = 41.9 stitches a round; rows from 0.25 mm up to 119.75 mm, 5 mm apart: 23 rows of stitches.
  EXPECT_EQ(traced.labels.rows, 23);
  EXPECT_EQ(traced.mesh.num_faces(), 23 * 42);
  EXPECT_EQ(traced.row_starts, 1);
  EXPECT_EQ(traced.row_ends, 1);
  EXPECT_NEAR(traced.field_max, 120, 0.6);
  const auto [wale, course] = edge_means(traced);
  EXPECT_NEAR(wale, 5, 0.1);
  EXPECT_NEAR(course, 2 * M_PI * 40 / 42, 0.2);  // chords of the traced ring, a little inside the tube's facets
  const auto s = mesh::stitch_stats(stitches_of(traced));
  EXPECT_EQ(s.increases + s.decreases, 0);
}

TEST(KnitField, AJitteredTriangleSheetGetsStraightRowsOneStitchHeightApart) {
  const mesh::StitchSize size{6, 5};
  const auto surface = sheet(120, 100, 3);
  const auto traced = mesh::trace_stitch_mesh(surface, {mesh::default_start_edge(surface), {}}, size);
  expect_valid(traced, "sheet");
  EXPECT_EQ(traced.labels.rows, 19);
  EXPECT_EQ(traced.mesh.num_faces(), 19 * 20);
  // The field is the distance from y = 0: row k lies at 0.25 mm + k 5 mm. Each row's mean height is within
  // 2 % of a row of it (the rows' spacing), and every point within 12 % (the heat method's local error on
  // this jittered mesh: 0.6 mm at the first rows, where the field is least accurate).
  std::map<long, std::pair<double, int>> rows;  // row -> sum of offsets, count
  for (const auto& p : traced.mesh.points()) {
    const double k = (p.y() - 0.25) / 5;
    const long row = std::lround(k);
    EXPECT_NEAR(k, static_cast<double>(row), 0.12) << "a point at y = " << p.y();
    rows[row].first += k - static_cast<double>(row);
    ++rows[row].second;
  }
  EXPECT_EQ(rows.size(), 20u);
  for (const auto& [row, sum] : rows) EXPECT_NEAR(sum.first / sum.second, 0, 0.02) << "row " << row;
}

TEST(KnitField, ASphereKnitsFromAPointWithIncreasesThenDecreases) {
  const mesh::StitchSize size{6, 5};
  const auto traced = mesh::trace_stitch_mesh(sphere(50, 4), {-1, Eigen::Vector3d(0, 60, 0)}, size);
  expect_valid(traced, "sphere");
  EXPECT_NEAR(traced.field_max, M_PI * 50, 1.5);
  const auto s = mesh::stitch_stats(stitches_of(traced));
  EXPECT_GT(s.increases, 20);  // the rows grow to the equator ...
  EXPECT_GT(s.decreases, 20);  // ... and shrink past it
  EXPECT_EQ(traced.row_starts, 1);
  EXPECT_EQ(traced.row_ends, 1);
  // The cast-on ring: one stitch width round the pole, 2 pi 6 / 6 = 6 stitches.
  int first_row = 0;
  for (int f = 0; f < traced.mesh.num_faces(); ++f) first_row += traced.labels.faces[f].row == 0;
  EXPECT_GE(first_row, 6);
  EXPECT_LE(first_row, 12);
  // No row more than doubles or halves (Yuksel Table 1 has 1->2 and 2->1 faces).
  for (int f = 0; f < traced.mesh.num_faces(); ++f) EXPECT_LE(traced.mesh.face(f).size(), 5u);
}

TEST(KnitField, APoleOfValenceEightIsKnitFromTheRimAndFromThePole) {
  const mesh::StitchSize size{6, 5};
  const auto dome = pole_dome();
  const auto from_rim = mesh::trace_stitch_mesh(dome, {mesh::default_start_edge(dome), {}}, size);
  expect_valid(from_rim, "dome from its rim");
  EXPECT_GT(mesh::stitch_stats(stitches_of(from_rim)).decreases, 10);
  const auto from_pole = mesh::trace_stitch_mesh(dome, {-1, Eigen::Vector3d(0, 40, 0)}, size);
  expect_valid(from_pole, "dome from its pole");
  EXPECT_GT(mesh::stitch_stats(stitches_of(from_pole)).increases, 10);
}

TEST(KnitField, RowsSplitRoundASlotAndRingsSplitAndMergeRoundATorusHole) {
  const mesh::StitchSize size{6, 5};
  // A U: from the bottom, the rows split round the slot cut down from the top at 60 mm into two prongs of
  // 40 mm (about 7 stitches each), knit on as separate rows.
  const auto u_shape = triangle_grid(
      12, 12, false, [](double u, double v) { return Eigen::Vector3d(120 * u, 120 * v, 0); }, [](int i, int j) { return !(j >= 6 && i >= 4 && i < 8); },
      "u.obj");
  const auto u = mesh::trace_stitch_mesh(u_shape, {mesh::default_start_edge(u_shape), {}}, size);
  expect_valid(u, "U");
  // No face bridges the slot (its middle stitches are closed off below it), and each prong is knit up by rows
  // of its own.
  std::map<int, std::pair<int, int>> sides;  // row -> faces on the left prong, on the right
  for (int f = 0; f < u.mesh.num_faces(); ++f) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int v : u.mesh.face(f)) centre += u.mesh.point(v) / static_cast<double>(u.mesh.face(f).size());
    EXPECT_FALSE(centre.y() > 60 && centre.x() > 40 && centre.x() < 80) << "a face over the slot at " << centre.transpose();
    if (centre.y() > 60) ++(centre.x() < 60 ? sides[u.labels.faces[f].row].first : sides[u.labels.faces[f].row].second);
  }
  int prong_rows = 0;
  for (const auto& [row, count] : sides) {
    EXPECT_TRUE(count.first == 0 || count.second == 0) << "row " << row << " runs over both prongs";
    ++prong_rows;
  }
  EXPECT_GE(prong_rows, 2 * 11);  // 11 rows up each prong, from 60 mm to 118.5 mm
  EXPECT_EQ(u.row_starts, 1);
  EXPECT_EQ(u.row_ends, 2);

  // A torus from a point: the rings split round the hole and merge on the far side.
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> faces;
  const int na = 32, nb = 16;
  for (int j = 0; j < nb; ++j)
    for (int i = 0; i < na; ++i) {
      const double a = 2 * M_PI * i / na, b = 2 * M_PI * j / nb, r = 60 + 20 * std::cos(b);
      points.emplace_back(r * std::cos(a), 20 * std::sin(b), r * std::sin(a));
    }
  const auto at = [&](int i, int j) { return (j % nb) * na + (i % na); };
  for (int j = 0; j < nb; ++j)
    for (int i = 0; i < na; ++i) {
      faces.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      faces.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  const mesh::InputMesh closed(points, faces, "torus.obj");
  const auto t = mesh::trace_stitch_mesh(closed, {-1, Eigen::Vector3d(80, 0, 0)}, size);
  expect_valid(t, "torus");
  EXPECT_EQ(t.row_starts, 1);
  // Area 4 pi^2 R r = 47,374 mm^2 over 30 mm^2 a stitch: about 1,580 stitches (less the ends' small holes).
  EXPECT_GT(t.mesh.num_faces(), 1300);
  EXPECT_LT(t.mesh.num_faces(), 1700);
}

TEST(KnitField, TheStartRunStopsAtCornersAndGoesRoundATubeEnd) {
  const auto flat = sheet(120, 100, 5);
  const auto run = mesh::field_start_run(flat, mesh::default_start_edge(flat));
  EXPECT_EQ(run.size(), 12u);  // the bottom side's 12 edges, not round the corners
  for (int e : run) {
    const auto [a, b] = flat.edge_vertices(e);
    EXPECT_EQ(flat.point(a).y(), 0);
    EXPECT_EQ(flat.point(b).y(), 0);
  }
  const auto round = tube(40, 120);
  EXPECT_EQ(mesh::field_start_run(round, mesh::default_start_edge(round)).size(), 20u);
}

/// The rows of the faces along a traced mesh's border at y > 50 (a tube's far end, its start at y = 0).
std::set<int> rows_at_far_border(const mesh::TracedRows& traced) {
  std::set<int> rows;
  for (int e = 0; e < traced.mesh.num_edges(); ++e) {
    if (!traced.mesh.is_border(e)) continue;
    const auto [a, b] = traced.mesh.edge_vertices(e);
    if (traced.mesh.point(a).y() > 50 && traced.mesh.point(b).y() > 50) rows.insert(traced.labels.faces[traced.mesh.edge_uses(e)[0].face].row);
  }
  return rows;
}

TEST(KnitField, RowsTurnToLieAlongAGivenEnd) {
  const mesh::StitchSize size{6, 5};
  const auto slanted = triangle_grid(
      48, 30, true, [](double u, double v) {
        const double x = 40 * std::cos(2 * M_PI * u);
        return Eigen::Vector3d(x, (100 + 0.5 * x) * v, 40 * std::sin(2 * M_PI * u));
      },
      [](int, int) { return true; }, "slanted.obj");
  int end_edge = -1;
  for (int e = 0; e < slanted.num_edges() && end_edge < 0; ++e) {
    const auto [a, b] = slanted.edge_vertices(e);
    if (slanted.is_border(e) && slanted.point(a).y() > 50 && slanted.point(b).y() > 50) end_edge = e;
  }
  ASSERT_GE(end_edge, 0);
  const mesh::KnitStart start{mesh::default_start_edge(slanted), {}};
  const auto straight = mesh::trace_stitch_mesh(slanted, start, size);
  const auto turned = mesh::trace_stitch_mesh(slanted, start, size, mesh::KnitStart{end_edge, {}});
  expect_valid(straight, "slanted tube, no end");
  expect_valid(turned, "slanted tube to its end");
  // Without an end the rows stay square to the tube and run into the slant one after another (40 mm of slant:
  // about 8 rows end there). With it the last row follows the slant: one row makes the end.
  EXPECT_GE(rows_at_far_border(straight).size(), 6u);
  EXPECT_EQ(rows_at_far_border(turned).size(), 1u);
  EXPECT_EQ(turned.row_starts, 1);
  EXPECT_EQ(turned.row_ends, 1);
  // The rows keep their count between the start and the end: 18 to 20 rows over the tube's mean length 100 mm.
  EXPECT_GE(turned.labels.rows, 18);
  EXPECT_LE(turned.labels.rows, 20);

  // A sphere from one pole to the other: the field is the same latitude rings (field_max pi r), closed at the end.
  const auto ball = sphere(50, 4);
  const auto poles = mesh::trace_stitch_mesh(ball, {-1, Eigen::Vector3d(0, 60, 0)}, size, mesh::KnitStart{-1, Eigen::Vector3d(0, -60, 0)});
  expect_valid(poles, "sphere pole to pole");
  EXPECT_NEAR(poles.field_max, M_PI * 50, 1.5);
  EXPECT_EQ(poles.row_ends, 1);

  // Refusals: an end that is no border edge, and an end on the start.
  int inner = -1;
  for (int e = 0; e < slanted.num_edges() && inner < 0; ++e)
    if (!slanted.is_border(e)) inner = e;
  EXPECT_EQ(error_of([&] { mesh::trace_stitch_mesh(slanted, start, size, mesh::KnitStart{inner, {}}); }),
            "slanted.obj: edge " + std::to_string(inner) + ": is not a border edge; knitting ends on a border or at a point (--end-point)");
  EXPECT_EQ(error_of([&] { mesh::trace_stitch_mesh(slanted, start, size, start); }), "slanted.obj: the knitting end touches the start: give an end away from it");
}

TEST(KnitField, RefusesWhatItCannotKnitSayingWhereAndWhy) {
  const mesh::StitchSize size{6, 5};
  const auto flat = sheet(120, 100, 7);
  int inner = -1;
  for (int e = 0; e < flat.num_edges() && inner < 0; ++e)
    if (!flat.is_border(e)) inner = e;
  EXPECT_EQ(error_of([&] { mesh::trace_stitch_mesh(flat, {inner, {}}, size); }),
            "sheet.obj: edge " + std::to_string(inner) + ": is not a border edge; knitting starts on a border or at a point (--start-point)");

  // Two pieces: the start reaches one.
  const auto one = tube(40, 120);
  auto points = one.points();
  auto faces = one.faces();
  const int offset = static_cast<int>(points.size());
  for (const auto& p : one.points()) points.push_back(p + Eigen::Vector3d(200, 0, 0));
  for (auto f : one.faces()) {
    for (int& v : f) v += offset;
    faces.push_back(f);
  }
  const mesh::InputMesh two(points, faces, "two.obj");
  const std::string pieces = error_of([&] { mesh::trace_stitch_mesh(two, {mesh::default_start_edge(two), {}}, size); });
  EXPECT_NE(pieces.find("lies on a piece of the surface the knitting start does not reach (2 pieces)"), std::string::npos) << pieces;

  // Too small for a row.
  const auto small = sheet(12, 4, 1);
  const std::string tiny = error_of([&] { mesh::trace_stitch_mesh(small, {mesh::default_start_edge(small), {}}, size); });
  EXPECT_NE(tiny.find("no row fits"), std::string::npos) << tiny;
}

TEST(KnitField, NoisyMeshesWithHolesAreTracedOrRefusedNeverBroken) {
  // Tubes and spheres with their points moved at random by up to a third of an edge and up to 6 faces cut out
  // (holes, so more borders, and rows that split round them), from random border edges and random points: every
  // trace either gives a valid stitch mesh that emits yarn, or is refused with a skein::Error naming the mesh.
  std::mt19937 rng(2026);
  int traced = 0, refused = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const bool closed = trial % 3 == 2;
    const auto base = closed ? sphere(50, 3) : tube(40, 120);
    std::uniform_real_distribution<double> noise(-3, 3);
    std::vector<Eigen::Vector3d> points = base.points();
    for (auto& p : points) p += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    auto faces = base.faces();
    std::uniform_int_distribution<int> pick(0, static_cast<int>(faces.size()) - 1), holes(0, 6);
    for (int h = holes(rng); h > 0 && faces.size() > 10; --h) faces.erase(faces.begin() + pick(rng) % static_cast<int>(faces.size()));
    std::optional<mesh::InputMesh> m;
    try {
      m.emplace(mesh::with_used_points(points, faces, "noisy.obj"));
    } catch (const Error&) {
      continue;  // a hole that left a bow tie: the reader's rules, tested elsewhere
    }
    mesh::KnitStart start;
    std::vector<int> borders;
    for (int e = 0; e < m->num_edges(); ++e)
      if (m->is_border(e)) borders.push_back(e);
    if (borders.empty() || trial % 2) {
      start.point = m->point(std::uniform_int_distribution<int>(0, m->num_vertices() - 1)(rng));
    } else {
      start.border_edge = borders[std::uniform_int_distribution<std::size_t>(0, borders.size() - 1)(rng)];
    }
    try {
      const auto t = mesh::trace_stitch_mesh(*m, start, {6, 5});
      expect_valid(t, "trial " + std::to_string(trial));
      ++traced;
    } catch (const Error& e) {
      EXPECT_EQ(e.file(), "noisy.obj") << e.what();
      ++refused;
    }
  }
  EXPECT_GE(traced, 20) << refused << " refused";  // most of them knit (of 120 such trials: 80 traced, 4 refused)
}
