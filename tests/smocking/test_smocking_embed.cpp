// The 2-D embedding of Zhou 2024 §4.1 (Algorithm 1) and the lift of §4.2 (eqs. 6-8).
#include <cmath>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "smocking/smocking_embed.hpp"
#include "testing.hpp"

using namespace skein;
using namespace skein::smocking;

namespace {
SmockingPattern pattern_of(const std::string& text) { return parse_smocking_pattern("format smocking\n" + text, "test.smock"); }
std::vector<std::filesystem::path> bundled() {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(SKEIN_PATTERNS_DIR) / "smocking"))
    if (e.path().extension() == ".smock") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}
}  // namespace

TEST(SmockingEmbed, OneStepOfAlgorithm1ByHand) {
  // Two points 10 mm apart joined by a front stitch and a fabric spring; τ = 1 % of 10 mm = 0.1 mm.
  const auto p = pattern_of("grid 2 1\npath 0,0 1,0\n");
  EmbedOptions o;
  o.max_iterations = 1;
  o.settle = false;
  const auto e = embed(p, o);
  EXPECT_DOUBLE_EQ(e.thickness, 0.1);
  // The stitch's target is max(τ, its extent across the pull) = τ; the fabric spring, at its flat length, pulls nothing.
  // a_0 = 5 (10 - 0.1) towards the other point, v = 0.9 · 0.1 · a, x += 0.1 v.
  const double move = 0.1 * 0.9 * 0.1 * 5 * (10 - 0.1);
  EXPECT_EQ(e.iterations, 1);
  EXPECT_NEAR(e.positions(0, 0), move, 1e-12);
  EXPECT_NEAR(e.positions(0, 1), 10 - move, 1e-12);
  EXPECT_NEAR(e.threads, 10 - 2 * move, 1e-12);
  EXPECT_EQ(e.stopped, EmbedStop::IterationCap);
  ASSERT_EQ(e.history.size(), 2u);  // at 0, and where it ended
  EXPECT_EQ(e.history.back().x(), 1);
  EXPECT_NEAR(e.history.back().y(), (10 - 2 * move) / 10, 1e-12);
}

TEST(SmockingEmbed, GammaOneLeavesTheFabricFlat) {
  const auto p = read_smocking_pattern(bundled().front());
  EmbedOptions o;
  o.gamma = 1;
  const auto e = embed(p, o);
  EXPECT_EQ(e.iterations, 0);
  EXPECT_EQ(e.stopped, EmbedStop::Reached);
  EXPECT_EQ(e.positions, e.rest);
}

TEST(SmockingEmbed, EveryBundledPatternGathersToItsGammaWithinTheConstraints) {
  for (const auto& file : bundled()) {
    const auto p = read_smocking_pattern(file);
    EmbedOptions o;
    o.gamma = p.gamma;
    o.pull_along_stitches = file.stem() == "spiral";
    const auto e = embed(p, o);
    SCOPED_TRACE(file.filename().string());
    EXPECT_EQ(e.stopped, EmbedStop::Reached);
    EXPECT_LE(e.shrinkage_before_settling, p.gamma);  // eq. 1c's upper bound, where Algorithm 1 stops
    EXPECT_LE(e.shrinkage(), p.gamma * (1 + o.settle_tolerance));  // settling eq. 1b gives back no more than that
    // Eq. 1b: no fabric spring longer than in the flat fabric or shorter than τ (to the settling tolerance).
    EXPECT_LE(e.largest_stretch, o.settle_tolerance * 1.0001);
    EXPECT_GE(e.shortest_fabric, 1 - o.settle_tolerance * 1.0001);
    // Eq. 1c's lower bound: taut threads are τ a stitch (Canadian knots aim at 0).
    if (p.style != Style::Canadian) {
      EXPECT_GE(e.threads, e.thickness * e.stitches.size() * (1 - 1e-9));
    }
  }
}

TEST(SmockingEmbed, Eq1bIsBrokenWithoutTheProjectionAsThePaperPrintsIt) {
  const auto p = read_smocking_pattern(std::filesystem::path(SKEIN_PATTERNS_DIR) / "smocking" / "canadian-lattice.smock");
  EmbedOptions o;
  o.gamma = p.gamma;
  o.settle = false;
  const auto e = embed(p, o);
  EXPECT_EQ(e.stopped, EmbedStop::Reached);
  EXPECT_LE(e.iterations, 10);  // knots with target 0 close within a few steps of Δt = 0.1 at k = 5
  EXPECT_GT(e.largest_stretch, 0.2);
}

TEST(SmockingEmbed, StitchesAcrossThePullDoNotShortenUnlessPulledAlong) {
  // Eq. 5: a vertical thread's target is its own vertical extent when the pull is horizontal.
  const auto p = pattern_of("grid 5 5\npath 2,0 2,1 2,2 2,3 2,4\n");
  EmbedOptions o;
  o.gamma = 0.5;
  const auto across = embed(p, o);
  EXPECT_EQ(across.stopped, EmbedStop::Stalled);
  EXPECT_NEAR(across.shrinkage(), 1.0, 1e-9);
  o.pull = {0, 1};
  EXPECT_EQ(embed(p, o).stopped, EmbedStop::Reached);
  o.pull = {1, 0};
  o.pull_along_stitches = true;
  EXPECT_EQ(embed(p, o).stopped, EmbedStop::Reached);
}

TEST(SmockingEmbed, RunsAreDeterministicAndSnapshotsComeInOrder) {
  const auto p = read_smocking_pattern(std::filesystem::path(SKEIN_PATTERNS_DIR) / "smocking" / "zigzag.smock");
  EmbedOptions o;
  o.snapshots = {0.5, 0.8, 0.6};
  const auto a = embed(p, o), b = embed(p, o);
  EXPECT_EQ(a.positions, b.positions);
  ASSERT_EQ(a.snapshots.size(), 3u);
  EXPECT_DOUBLE_EQ(a.snapshots[0].first, 0.8);
  EXPECT_DOUBLE_EQ(a.snapshots[2].first, 0.5);
  Embedding at = a;
  at.positions = a.snapshots[1].second;
  double d = 0;
  for (const auto& s : at.stitches) d += (at.positions.col(s.a) - at.positions.col(s.b)).norm();
  EXPECT_LE(d / a.threads_rest, 0.6);
  EXPECT_GT(d / a.threads_rest, 0.5);
}

TEST(SmockingEmbed, LiftPutsStitchingPointsAtZeroAndMidpointsByEq8) {
  const auto p = pattern_of("grid 5 1\npath 0,0 2,0 4,0\n");  // a front stitch, then a back one, each 20 mm
  auto e = make_mass_spring_system(p, 0.5);
  e.positions.col(2).x() = 12;  // the middle point slides: the first stitch is now 12 mm long, the second 28... kept at 20 by moving the end
  e.positions.col(4).x() = 32;
  const auto l = lift(e);
  ASSERT_EQ(l.points, (std::vector<int>{0, 2, 4}));
  EXPECT_EQ(l.point_positions.row(2), Eigen::RowVector3d::Zero());  // eq. 6
  ASSERT_EQ(l.midpoints.cols(), 2);
  EXPECT_NEAR(l.midpoints(0, 0), 6, 1e-12);                              // between its ends
  EXPECT_NEAR(l.midpoints(2, 0), -std::sqrt(10.0 * 10.0 - 6.0 * 6.0), 1e-12);  // front: -h, h² + (12/2)² = (20/2)²
  EXPECT_NEAR(l.midpoints(2, 1), 0, 1e-12);                              // the back stitch kept its length: no fold
  EXPECT_NEAR(l.midpoints(0, 1), 22, 1e-12);
}

TEST(SmockingEmbed, OptionsAreChecked) {
  const auto p = pattern_of("grid 2 1\npath 0,0 1,0\n");
  EmbedOptions o;
  o.gamma = 0;
  EXPECT_NE(skein::testing::error_of([&] { embed(p, o); }).find("gamma in (0, 1]"), std::string::npos);
  o = {};
  o.pull = {0, 0};
  EXPECT_NE(skein::testing::error_of([&] { embed(p, o); }).find("a pulling direction of non-zero length"), std::string::npos);
  o = {};
  o.damping = 1;
  EXPECT_THROW(embed(p, o), Error);
}

TEST(SmockingEmbed, ABeadKeepsItsStitchOpen) {
  // Zhou §5.2: a bead on a stitch is a lower bound on its length.
  const auto p = read_smocking_pattern(std::filesystem::path(SKEIN_PATTERNS_DIR) / "smocking" / "zigzag-beads.smock");
  ASSERT_EQ(p.beads.size(), 25u);  // five on each of the five threads
  EmbedOptions o;
  o.gamma = p.gamma;
  const auto e = embed(p, o);
  EXPECT_EQ(e.stopped, EmbedStop::Reached);
  int beaded = 0;
  for (const auto& s : e.stitches) {
    const double length = (e.positions.col(s.a) - e.positions.col(s.b)).norm();
    if (s.bead > 0) {
      ++beaded;
      EXPECT_GE(length, 0.95 * s.bead);
    }
  }
  EXPECT_EQ(beaded, 25);
  EXPECT_NE(skein::testing::error_of([] { parse_smocking_pattern("format smocking\ngrid 4 2\npath 0,0 1,1 2,0\nbead 0,0 2,0 5\n", "b.smock"); })
                .find("b.smock: line 4: no stitch goes between (0,0) and (2,0) to thread the bead on"),
            std::string::npos);
}
