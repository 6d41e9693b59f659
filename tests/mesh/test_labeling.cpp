#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <set>

#include "common/error.hpp"
#include "garments.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/tessellation.hpp"
#include "testing.hpp"

using namespace skein;
using skein::testing::error_of;

namespace {
int wale_count(const mesh::InputMesh& m, const mesh::Labeling& l, int f) {
  int n = 0;
  for (int e : m.face_edges(f)) n += l.edges[e] == mesh::EdgeLabel::Wale;
  return n;
}
/// The bottom border edge of the swatch at x in [0, 30].
int swatch_bottom_edge(const mesh::InputMesh& m) {
  for (int e = 0; e < m.num_edges(); ++e) {
    const auto [a, b] = m.edge_vertices(e);
    if (m.is_border(e) && m.point(a).y() == 0 && m.point(b).y() == 0 && std::max(m.point(a).x(), m.point(b).x()) == 30) return e;
  }
  return -1;
}
}  // namespace

TEST(Labeling, SwatchAutoLabelGivesFourStraightRows) {
  const auto m = models::swatch();
  const auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  EXPECT_EQ(l.rows, 4);
  const auto report = mesh::validate_labels(m, l);
  EXPECT_TRUE(report.valid());
  EXPECT_TRUE(report.mismatches.empty());
  for (int f = 0; f < m.num_faces(); ++f) {
    EXPECT_EQ(wale_count(m, l, f), 2);
    // Rows are horizontal: every face of a row has the same height.
    double y = 0;
    for (int v : m.face(f)) y += m.point(v).y() / 4;
    EXPECT_NEAR(y, 12.5 + 25.0 * l.faces[f].row, 1e-9);
  }
  // The swatch's side borders are wale edges, its top and bottom course edges.
  for (int e = 0; e < m.num_edges(); ++e) {
    const auto [a, b] = m.edge_vertices(e);
    const bool vertical = m.point(a).x() == m.point(b).x();
    EXPECT_EQ(l.edges[e], vertical ? mesh::EdgeLabel::Wale : mesh::EdgeLabel::Course) << e;
  }
}

TEST(Labeling, TubeRowsAreRings) {
  const auto m = models::tube();
  const auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  EXPECT_EQ(l.rows, 5);
  std::vector<int> per_row(l.rows, 0);
  for (const auto& f : l.faces) ++per_row[f.row];
  for (int n : per_row) EXPECT_EQ(n, 12);
  EXPECT_EQ(mesh::border_run(m, mesh::default_start_edge(m)).size(), 12u);  // the whole end loop
}

TEST(Labeling, FirstRowThenNextRowByHand) {
  const auto m = models::swatch();
  mesh::Labeling l(m);
  const int start = swatch_bottom_edge(m);
  ASSERT_GE(start, 0);
  EXPECT_EQ(mesh::border_run(m, start).size(), 4u);  // stops at the corners
  const auto rows = mesh::label_first_row(m, l, start);
  ASSERT_EQ(rows.size(), 1u);
  int labeled = 0;
  for (const auto& f : l.faces) labeled += f.labeled();
  EXPECT_EQ(labeled, 4);
  // A top edge of the first row starts the second.
  int top = -1;
  for (int f = 0; f < m.num_faces() && top < 0; ++f)
    if (l.faces[f].row == 0) top = m.face_edge(f, mesh::top_edges(m, l.faces[f], f)[0]);
  EXPECT_EQ(mesh::label_next_row(m, l, top), 1);
  labeled = 0;
  for (const auto& f : l.faces) labeled += f.labeled();
  EXPECT_EQ(labeled, 8);
  EXPECT_TRUE(mesh::validate_labels(m, l).mismatches.empty());
  // The same edge cannot start another row, and a border edge is no next row.
  EXPECT_THROW(mesh::label_next_row(m, l, top), Error);
  EXPECT_THROW(mesh::label_next_row(m, l, start), Error);
}

TEST(Labeling, FirstRowNeedsABorderEdge) {
  const auto m = models::swatch();
  mesh::Labeling l(m);
  int inner = 0;
  while (m.is_border(inner)) ++inner;
  const std::string msg = error_of([&] { mesh::label_first_row(m, l, inner); });
  EXPECT_NE(msg.find("not a border edge"), std::string::npos) << msg;
}

TEST(Labeling, FlipRowShowsMismatchesAndFlipsBack) {
  const auto m = models::swatch();
  auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  mesh::flip_row(l, 1);
  const auto report = mesh::validate_labels(m, l);
  EXPECT_TRUE(report.valid());  // opposite wale directions are allowed (Yuksel §4.4) ...
  EXPECT_EQ(report.mismatches.size(), 8u);  // ... and named: 4 course edges below row 1 and 4 above
  for (const auto& [e, why] : report.mismatches) EXPECT_NE(why.find("opposite wale directions"), std::string::npos);
  mesh::flip_row(l, 1);
  EXPECT_TRUE(mesh::validate_labels(m, l).mismatches.empty());
}

TEST(Labeling, ValidationNamesFacesWithoutTwoWaleEdges) {
  const auto m = models::swatch();
  auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  // Turn one course edge between two rows into a wale edge: both faces now have three.
  int e = 0;
  while (m.is_border(e) || l.edges[e] != mesh::EdgeLabel::Course) ++e;
  l.edges[e] = mesh::EdgeLabel::Wale;
  const auto report = mesh::validate_labels(m, l);
  ASSERT_EQ(report.face_problems.size(), 2u);
  std::set<int> named;
  for (const auto& [f, why] : report.face_problems) {
    named.insert(f);
    EXPECT_NE(why.find("3 wale edges"), std::string::npos) << why;
  }
  EXPECT_EQ(named, (std::set<int>{m.edge_uses(e)[0].face, m.edge_uses(e)[1].face}));
}

TEST(Labeling, TrianglesThatCannotCarryARowAreReported) {
  // A fan of triangles around a centre: no face can have two wale edges and course edges on both sides.
  std::vector<Eigen::Vector3d> p{{0, 0, 0}};
  std::vector<std::vector<int>> f;
  for (int i = 0; i < 6; ++i) p.emplace_back(std::cos(i * M_PI / 3), std::sin(i * M_PI / 3), 0);
  for (int i = 0; i < 6; ++i) f.push_back({0, 1 + i, 1 + (i + 1) % 6});
  const mesh::InputMesh m(p, f, "fan");
  const auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  const auto report = mesh::validate_labels(m, l);
  EXPECT_FALSE(report.valid());
  EXPECT_EQ(report.face_problems.size(), 6u);
}

TEST(Labeling, EveryBundledGarmentLabelsCompletely) {
  for (const auto& g : models::garments()) {
    const auto m = g.make();
    const auto l = mesh::auto_label(m, mesh::default_start_edge(m));
    const auto report = mesh::validate_labels(m, l);
    EXPECT_TRUE(report.valid()) << g.name << ": " << (report.face_problems.empty() ? "" : report.face_problems[0].second);
    for (int f = 0; f < m.num_faces(); ++f) EXPECT_EQ(wale_count(m, l, f), 2) << g.name << " face " << f;
    // Only where two pieces are grafted (underarms, the thumb gusset) do wale directions oppose.
    const size_t expected = g.name == "sweater" ? 8 : g.name == "mitten" ? 2 : 0;
    EXPECT_EQ(report.mismatches.size(), expected) << g.name;
  }
}

TEST(Labeling, AutoLabelIsDeterministic) {
  const auto m = models::sweater();
  const auto a = mesh::auto_label(m, mesh::default_start_edge(m));
  const auto b = mesh::auto_label(m, mesh::default_start_edge(m));
  EXPECT_EQ(a.edges, b.edges);
  for (int f = 0; f < m.num_faces(); ++f) {
    EXPECT_EQ(a.faces[f].row, b.faces[f].row);
    EXPECT_EQ(a.faces[f].left, b.faces[f].left);
  }
}

TEST(Labeling, IrregularMeshesNeverHangOrCrash) {
  // Grids with random diagonal splits, merged quads (hexagons) and holes: labeling must finish, and either
  // tessellation succeeds or it refuses naming a face.
  std::mt19937 rng(5);
  int tessellated = 0, refused = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int w = 3 + static_cast<int>(rng() % 5), h = 2 + static_cast<int>(rng() % 5);
    std::vector<Eigen::Vector3d> p;
    for (int y = 0; y <= h; ++y)
      for (int x = 0; x <= w; ++x) p.emplace_back(10.0 * x, 10.0 * y, 0.3 * ((x * 7 + y * 3) % 5));
    const auto id = [&](int x, int y) { return y * (w + 1) + x; };
    std::vector<std::vector<int>> faces;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const int kind = static_cast<int>(rng() % 8);
        if (kind == 0) continue;  // a hole
        if (kind == 1) {           // two triangles
          faces.push_back({id(x, y), id(x + 1, y), id(x + 1, y + 1)});
          faces.push_back({id(x, y), id(x + 1, y + 1), id(x, y + 1)});
        } else if (kind == 2 && x + 1 < w) {  // a hexagon over two cells
          faces.push_back({id(x, y), id(x + 1, y), id(x + 2, y), id(x + 2, y + 1), id(x + 1, y + 1), id(x, y + 1)});
          ++x;
        } else {
          faces.push_back({id(x, y), id(x + 1, y), id(x + 1, y + 1), id(x, y + 1)});
        }
      }
    if (faces.empty()) continue;
    std::unique_ptr<mesh::InputMesh> m;
    try {
      m = std::make_unique<mesh::InputMesh>(p, faces, "random");
    } catch (const Error&) {
      continue;  // holes can leave bow-tie vertices, which are refused
    }
    const auto l = mesh::auto_label(*m, mesh::default_start_edge(*m));
    const auto report = mesh::validate_labels(*m, l);
    try {
      const auto s = mesh::tessellate(*m, l, mesh::initial_values(*m, l, {}));
      EXPECT_TRUE(report.valid());
      EXPECT_TRUE(mesh::validate(s).valid()) << mesh::validate(s).summary();
      ++tessellated;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("face"), std::string::npos) << e.what();
      ++refused;
    }
  }
  EXPECT_GT(tessellated, 10);
  EXPECT_GT(refused, 10);
}
