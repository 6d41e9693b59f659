// skein yarn, stats and render: the emitted yarn written for other tools, with its stitch ids
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <utility>

#include <Eigen/Core>

#include "cli_support.hpp"

using namespace skein::testing::cli;
using skein::testing::ScratchDir;

TEST(Cli, YarnObjInMetresForBlenderAndTheStitchIdsBesideIt) {
  ScratchDir dir;
  const auto project = (dir / "s.skein").string();
  ASSERT_EQ(run_skein("stitch " + kModels + "/swatch.obj --labels " + kModels + "/swatch.skein -o " + project).status, 0);
  const auto first_vertex = [](const std::string& text) {
    double x = 0, y = 0, z = 0;
    const auto at = text.find("\nv ");
    std::sscanf(text.c_str() + at, "\nv %lf %lf %lf", &x, &y, &z);
    return Eigen::Vector3d(x, y, z);
  };
  ASSERT_EQ(run_skein("yarn " + project + " -o " + (dir / "mm.obj").string() + " --tubes " + (dir / "mm-tubes.obj").string()).status, 0);
  auto r = run_skein("yarn " + project + " -o " + (dir / "m.obj").string() + " --tubes " + (dir / "m-tubes.obj").string() + " --units m");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const auto& [mm, m] : {std::pair{"mm.obj", "m.obj"}, std::pair{"mm-tubes.obj", "m-tubes.obj"}}) {
    const auto a = first_vertex(slurp(dir / mm)), b = first_vertex(slurp(dir / m));
    EXPECT_GT(a.norm(), 0.1) << mm;
    EXPECT_NEAR((b - 1e-3 * a).norm(), 0, 1e-6 * a.norm()) << m;
  }
  EXPECT_NE(slurp(dir / "m.obj").find("radius 0.0006 m\n"), std::string::npos);
  // The stitch ids side file: a row per control point, numbered as the OBJ's vertices, every face a real one.
  r = run_skein("yarn " + project + " -o " + (dir / "y.obj").string() + " --ids " + (dir / "ids.csv").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto stats = run_skein("stats " + project + " --json").output;
  const auto at = stats.find("\"faces\": ");
  ASSERT_NE(at, std::string::npos) << stats;
  const int faces = std::atoi(stats.c_str() + at + 9);
  long points = 0, with_face = 0;
  std::set<int> rows;
  for (const auto& id : read_ids(dir / "ids.csv")) {
    EXPECT_EQ(id.point, points++);
    EXPECT_LT(id.face, faces) << id.point;
    if (id.face >= 0) ++with_face, rows.insert(id.row);
  }
  const std::string obj = slurp(dir / "y.obj");
  long vertices = 0;
  for (size_t at = obj.find("\nv "); at != std::string::npos; at = obj.find("\nv ", at + 1)) ++vertices;
  EXPECT_EQ(points, vertices);
  EXPECT_GT(with_face, points / 2);
  EXPECT_GT(rows.size(), 1u);
  r = run_skein("yarn " + project + " -o " + (dir / "y.bcc").string() + " --units cm");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("--units cm: applies to OBJ outputs; a .bcc is in millimetres"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "y.bcc"));
}

TEST(Cli, YarnExportStatsAndRender) {
  ScratchDir dir;
  const auto project = (dir / "tube.skein").string();
  ASSERT_EQ(run_skein("stitch " + kModels + "/tube.obj --auto-label --stitch-size 12 -o " + project).status, 0);
  const auto r = run_skein("yarn " + project + " -o " + (dir / "y.bcc").string() + " --tubes " + (dir / "t.obj").string() + " --png " +
                           (dir / "y.png").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("closed"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "t.obj"));
  EXPECT_TRUE(std::filesystem::exists(dir / "y.png"));
  const auto stats = run_skein("stats " + (dir / "y.bcc").string() + " --json");
  ASSERT_EQ(stats.status, 0) << stats.output;
  for (const char* key : {"\"curves\"", "\"closed_curves\"", "\"control_points\"", "\"total_length\"", "\"min_segment_distance\""})
    EXPECT_NE(stats.output.find(key), std::string::npos) << key << "\n" << stats.output;
  ASSERT_EQ(run_skein("yarn " + project + " -o " + (dir / "y.obj").string()).status, 0);
  EXPECT_NE(slurp(dir / "y.obj").find("\nl "), std::string::npos);
  ASSERT_EQ(run_skein("render " + (dir / "y.bcc").string() + " --color yarn -o " + (dir / "r.png").string()).status, 0);
  // Bad inputs: a yarn format skein does not write, a broken .bcc, a project without a stitch mesh.
  const auto ply = run_skein("yarn " + project + " -o " + (dir / "y.ply").string());
  EXPECT_EQ(ply.status, 2);
  EXPECT_NE(ply.output.find(".bcc or .obj"), std::string::npos) << ply.output;
  const auto broken = dir.write("broken.bcc", "BCC\x44" "C0");
  const auto bad = run_skein("stats " + broken.string());
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.output.find("64-byte"), std::string::npos) << bad.output;
  const auto labels_only = run_skein("yarn " + kModels + "/tube.skein -o " + (dir / "z.bcc").string());
  EXPECT_EQ(labels_only.status, 2);
  EXPECT_NE(labels_only.output.find("no stitch mesh"), std::string::npos) << labels_only.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "z.bcc"));
}
