#include <gtest/gtest.h>

#include <algorithm>

#include <cstring>
#include <fstream>
#include <sstream>

#include <tiny_gltf.h>

#include "common/error.hpp"
#include "garments.hpp"
#include "stitchmesh/labeling.hpp"
#include "stitchmesh/pattern.hpp"
#include "stitchmesh/tessellation.hpp"
#include "stitchmesh/yarn_emission.hpp"
#include "workflow/yarn_io.hpp"
#include "testing.hpp"

using namespace skein;
using skein::testing::error_of;
using skein::testing::ScratchDir;

namespace {
relax::YarnCurves tube_yarn() {
  const auto m = models::tube();
  const auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  return mesh::emit_yarn(mesh::tessellate(m, l, mesh::initial_values(m, l, {12, 10})), mesh::StitchLibrary::bundled(), {});
}
std::string bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

TEST(YarnIo, BccRoundTripIsBitExact) {
  ScratchDir dir;
  const auto y = tube_yarn();
  workflow::write_bcc(y, dir / "a.bcc");
  const auto back = workflow::read_bcc(dir / "a.bcc");
  workflow::write_bcc(back, dir / "b.bcc");
  EXPECT_EQ(bytes(dir / "a.bcc"), bytes(dir / "b.bcc"));
  ASSERT_EQ(back.points.size(), y.points.size());
  EXPECT_EQ(back.curve_start, y.curve_start);
  EXPECT_EQ(back.closed, y.closed);
  EXPECT_DOUBLE_EQ(back.radius, y.radius);
  for (size_t i = 0; i < y.points.size(); ++i)
    EXPECT_EQ(back.points[i].cast<float>(), y.points[i].cast<float>());
  // The layout: 64-byte header, then int32 counts (negative = closed) and float xyz.
  const std::string b = bytes(dir / "a.bcc");
  EXPECT_EQ(b.substr(0, 3), "BCC");
  EXPECT_EQ(static_cast<unsigned char>(b[3]), 0x44);
  EXPECT_EQ(b.substr(4, 2), "C0");
  std::int32_t first = 0;
  std::memcpy(&first, b.data() + 64, 4);
  EXPECT_EQ(first, -y.curve_size(0));
  EXPECT_EQ(b.size(), 64 + 4 * y.curves() + 12 * y.points.size());
}

TEST(YarnIo, MalformedBccFilesAreRejected) {
  ScratchDir dir;
  const auto y = tube_yarn();
  workflow::write_bcc(y, dir / "good.bcc");
  const std::string good = bytes(dir / "good.bcc");
  const auto bad = [&](const std::string& name, std::string content, const std::string& rule) {
    const auto p = dir.write(name, content);
    const std::string msg = error_of([&] { workflow::read_bcc(p); });
    EXPECT_NE(msg.find(name), std::string::npos) << msg;
    EXPECT_NE(msg.find(rule), std::string::npos) << name << ": " << msg;
  };
  bad("short.bcc", good.substr(0, 40), "shorter than the 64-byte");
  std::string s = good;
  s[0] = 'X';
  bad("magic.bcc", s, "does not start with 'BCC'");
  s = good, s[3] = 0x48;
  bad("width.bcc", s, "expected 0x44");
  s = good, s[4] = 'P', s[5] = 'L';
  bad("type.bcc", s, "is not C0");
  s = good, s[6] = 2;
  bad("dims.bcc", s, "dimensions 2");
  s = good;
  const std::uint64_t huge = 1ull << 40;
  std::memcpy(s.data() + 8, &huge, 8);
  bad("count.bcc", s, "larger than the file can hold");
  bad("truncated.bcc", good.substr(0, good.size() - 7), "file ends inside curve");
  bad("trailing.bcc", good + "xyz", "bytes follow the last curve");
  s = good;
  const float nan = std::nanf("");
  std::memcpy(s.data() + 68, &nan, 4);
  bad("nan.bcc", s, "not a finite number");
  EXPECT_NE(error_of([&] { workflow::read_bcc(dir / "none.bcc"); }).find("no such file"), std::string::npos);
  EXPECT_NE(error_of([&] { workflow::read_bcc(dir / (std::string(300, 'x') + ".bcc")); }).find("File name too long"), std::string::npos);
}

TEST(YarnIo, ObjPolylinesAndTubes) {
  ScratchDir dir;
  const auto y = tube_yarn();
  workflow::write_obj_polylines(y, dir / "y.obj");
  const std::string obj = bytes(dir / "y.obj");
  // Every segment its own two-point `l` record (Blender 3.4 keeps only the first segment of a longer one),
  // joining consecutive points of one curve, and closing the closed ones.
  size_t segments = 0;
  for (int c = 0; c < y.curves(); ++c) segments += y.curve_size(c) - 1 + (y.closed[c] ? 1 : 0);
  size_t vertices = 0, objects = 0;
  std::vector<std::pair<int, int>> lines;
  std::istringstream in(obj);
  for (std::string line; std::getline(in, line);) {
    vertices += line.rfind("v ", 0) == 0;
    objects += line.rfind("o yarn", 0) == 0;
    int a = 0, b = 0;
    char tail = 0;
    if (line.rfind("l ", 0) == 0) {
      ASSERT_EQ(std::sscanf(line.c_str(), "l %d %d %c", &a, &b, &tail), 2) << line;
      lines.emplace_back(a - 1, b - 1);
    }
  }
  EXPECT_EQ(vertices, y.points.size());
  EXPECT_EQ(objects, static_cast<size_t>(y.curves()));
  ASSERT_EQ(lines.size(), segments);
  for (const auto& [a, b] : lines) {
    const int c = static_cast<int>(std::upper_bound(y.curve_start.begin(), y.curve_start.end(), a) - y.curve_start.begin()) - 1;
    const bool closing = y.closed[c] && a == y.curve_start[c + 1] - 1 && b == y.curve_start[c];
    EXPECT_TRUE((b == a + 1 && b < y.curve_start[c + 1]) || closing) << a << " " << b;
  }
  workflow::write_tube_obj(y, dir / "t.obj", {6, 2});
  const auto tubes = mesh::load_mesh(dir / "t.obj");  // a mesh any tool reads
  EXPECT_GT(tubes.num_faces(), static_cast<int>(6 * y.points.size()));
  // Smooth shading: as many normals as vertices, each a unit vector, every face corner naming one.
  const std::string t = bytes(dir / "t.obj");
  std::istringstream tin(t);
  size_t tv = 0, tn = 0;
  for (std::string line; std::getline(tin, line);) {
    tv += line.rfind("v ", 0) == 0;
    if (line.rfind("vn ", 0) == 0) {
      ++tn;
      double x = 0, yy = 0, z = 0;
      std::sscanf(line.c_str(), "vn %lf %lf %lf", &x, &yy, &z);
      EXPECT_NEAR(x * x + yy * yy + z * z, 1, 1e-4) << line;
    }
    if (line.rfind("f ", 0) == 0) {
      EXPECT_EQ(std::count(line.begin(), line.end(), '/'), 8) << line;
    }
  }
  EXPECT_EQ(tv, tn);
}

TEST(YarnIo, StatsCountAndMeasure) {
  relax::YarnCurves y;
  y.radius = 0.5;
  // Two straight yarns 3 mm apart, and a closed square.
  y.points = {{0, 0, 0}, {10, 0, 0}, {0, 3, 0}, {10, 3, 0}, {0, 10, 0}, {1, 10, 0}, {1, 11, 0}, {0, 11, 0}};
  y.curve_start = {0, 2, 4, 8};
  y.closed = {0, 0, 1};
  const auto s = workflow::yarn_stats(y);
  EXPECT_EQ(s.curves, 3);
  EXPECT_EQ(s.closed_curves, 1);
  EXPECT_EQ(s.control_points, 8);
  EXPECT_DOUBLE_EQ(s.total_length, 10 + 10 + 4);
  EXPECT_NEAR(s.min_segment_distance, 1.0, 1e-12);  // the square's opposite sides
}

TEST(YarnIo, StitchIdsReadBackAndBrokenOnesAreRefusedNamingTheLine) {
  ScratchDir dir;
  const auto m = models::tube();
  const auto l = mesh::auto_label(m, mesh::default_start_edge(m));
  const auto stitch = mesh::tessellate(m, l, mesh::initial_values(m, l, {12, 10}));
  const auto yarn = mesh::emit_yarn(stitch, mesh::StitchLibrary::bundled(), {});
  const auto file = dir / "ids.csv";
  workflow::write_point_ids(yarn, stitch, file);
  const auto ids = workflow::read_point_ids(file, yarn);
  ASSERT_EQ(ids.size(), yarn.points.size());
  for (size_t p = 0; p < ids.size(); p += 97) {
    EXPECT_EQ(ids[p].curve, yarn.yarn_of(static_cast<int>(p)));
    EXPECT_EQ(ids[p].face, yarn.point_face[p]);
    if (ids[p].face >= 0) {
      EXPECT_EQ(ids[p].row, stitch.faces[ids[p].face].row);
      EXPECT_EQ(ids[p].type, stitch.faces[ids[p].face].type);
    }
  }
  // Broken files: each names the file, the line and the rule.
  const std::string good = bytes(file);
  const std::string first = good.substr(0, good.find('\n', good.find('\n') + 1) + 1);  // the header and point 0
  const std::string rest = good.substr(first.size());
  const std::string curve0 = std::to_string(yarn.yarn_of(0)), curve1 = std::to_string(yarn.yarn_of(1));
  for (const auto& [text, message] : std::vector<std::pair<std::string, std::string>>{
           {"point,face\n" + rest, "line 1: expected the header"},
           {first + "1," + curve1 + ",3,0\n" + rest.substr(rest.find('\n') + 1), "line 3: expected 5 fields"},
           {first + "1," + curve1 + ",x,0,k\n" + rest.substr(rest.find('\n') + 1), "line 3: field 3 is not a whole number"},
           {first + "7," + curve1 + ",3,0,k\n" + rest.substr(rest.find('\n') + 1), "line 3: names point 7 where point 1 comes"},
           {first + "1," + std::to_string(yarn.curves()) + ",3,0,k\n" + rest.substr(rest.find('\n') + 1), "line 3: puts point 1 on curve"},
           {first + "1," + curve1 + ",3,-1,k\n" + rest.substr(rest.find('\n') + 1), "line 3: a face needs its row"},
           {first, "names 1 control points; the yarn has"},
           {good + std::to_string(yarn.points.size()) + "," + curve0 + ",-1,-1,\n", "names more control points than the yarn's"},
       }) {
    const auto broken = dir.write("broken.csv", text);
    const std::string e = error_of([&] { workflow::read_point_ids(broken, yarn); });
    EXPECT_NE(e.find(message), std::string::npos) << e;
    EXPECT_NE(e.find("broken.csv"), std::string::npos) << e;
  }
  EXPECT_NE(error_of([&] { workflow::read_point_ids(dir / "missing.csv", yarn); }).find("missing.csv: does not exist"), std::string::npos);
  // Not a file to read whole: a device that never ends, a folder (patterns too).
  EXPECT_NE(error_of([&] { workflow::read_point_ids("/dev/zero", yarn); }).find("/dev/zero: is not a regular file"), std::string::npos);
  EXPECT_NE(error_of([&] { mesh::read_pattern(dir.path()); }).find("is not a regular file"), std::string::npos);
}

TEST(YarnIo, GltfTubesReadBackAsTheObjTubesInMetres) {
  ScratchDir dir;
  const auto y = tube_yarn();
  workflow::write_tube_obj(y, dir / "t.obj", {6, 2});
  const auto obj = mesh::load_mesh(dir / "t.obj");
  for (const char* name : {"t.glb", "t.gltf"}) {
    SCOPED_TRACE(name);
    workflow::write_tube_gltf(y, dir / name, {6, 2});
    // tinygltf reads it back: one mesh, a primitive of triangles with positions, normals and indices.
    tinygltf::Model model;
    std::string error, warning;
    tinygltf::TinyGLTF loader;
    const bool ok = std::string(name).ends_with(".glb") ? loader.LoadBinaryFromFile(&model, &error, &warning, (dir / name).string())
                                                        : loader.LoadASCIIFromFile(&model, &error, &warning, (dir / name).string());
    ASSERT_TRUE(ok) << error;
    ASSERT_EQ(model.meshes.size(), 1u);
    const auto& primitive = model.meshes[0].primitives.at(0);
    EXPECT_EQ(primitive.mode, TINYGLTF_MODE_TRIANGLES);
    const auto& positions = model.accessors[primitive.attributes.at("POSITION")];
    const auto& normals = model.accessors[primitive.attributes.at("NORMAL")];
    const auto& indices = model.accessors[primitive.indices];
    // The OBJ's vertices, and two triangles for each of its quads (assimp welds nothing here: one ring a sample).
    EXPECT_EQ(positions.count, normals.count);
    EXPECT_EQ(static_cast<int>(indices.count), 6 * obj.num_faces());
    // In metres: the bounding box is the yarn's in mm over 1000, widened by the tube's radius.
    double lo = 1e9, hi = -1e9;
    for (const auto& p : y.points) lo = std::min(lo, p.x()), hi = std::max(hi, p.x());
    EXPECT_NEAR(positions.minValues[0], 1e-3 * (lo - y.radius), 2e-3 * y.radius);
    EXPECT_NEAR(positions.maxValues[0], 1e-3 * (hi + y.radius), 2e-3 * y.radius);
    // Unit normals, as written.
    const auto& view = model.bufferViews[normals.bufferView];
    const float* n = reinterpret_cast<const float*>(model.buffers[view.buffer].data.data() + view.byteOffset + normals.byteOffset);
    for (size_t i = 0; i < normals.count; i += 101) EXPECT_NEAR(n[3 * i] * n[3 * i] + n[3 * i + 1] * n[3 * i + 1] + n[3 * i + 2] * n[3 * i + 2], 1, 1e-5);
    // And assimp, as any tool's importer, reads the same triangles.
    EXPECT_EQ(mesh::load_mesh(dir / name).num_faces(), 2 * obj.num_faces());
  }
}

TEST(YarnIo, YarnInColoursGetsAMaterialPerColourInObjAndGltf) {
  // The peerie chart tiled 2 x 1: its navy diamonds on natural, each colour a material with its linear colour.
  ScratchDir dir;
  const auto pattern = mesh::read_pattern(std::string(SKEIN_PATTERNS_DIR) + "/charts/peerie.txt");
  ASSERT_EQ(pattern.palette.size(), 2u);
  const auto y = mesh::emit_yarn(mesh::pattern_stitch_mesh(pattern, 2, 1), mesh::StitchLibrary::bundled(), {});  // coloured by its faces
  ASSERT_EQ(y.point_colour.size(), y.points.size());
  workflow::write_tube_obj(y, dir / "t.obj", {6, 2});
  const std::string mtl = bytes(dir / "t.mtl"), obj = bytes(dir / "t.obj");
  EXPECT_NE(obj.find("mtllib t.mtl\n"), std::string::npos);
  EXPECT_NE(mtl.find("newmtl yarn-MC\nKd 0.8148 0.7157 0.5457\n"), std::string::npos) << mtl;  // #e9dcc3, linear
  EXPECT_NE(mtl.find("newmtl yarn-CC\n"), std::string::npos) << mtl;
  EXPECT_NE(obj.find("usemtl yarn-MC\n"), std::string::npos);
  EXPECT_NE(obj.find("usemtl yarn-CC\n"), std::string::npos);
  // The OBJ's faces are the one-colour tubes' faces, shared out between the two materials.
  relax::YarnCurves plain = y;
  plain.point_colour.clear();
  plain.colours.clear();
  workflow::write_tube_obj(plain, dir / "p.obj", {6, 2});
  EXPECT_FALSE(std::filesystem::exists(dir / "p.mtl"));
  EXPECT_EQ(mesh::load_mesh(dir / "t.obj").num_faces(), mesh::load_mesh(dir / "p.obj").num_faces());
  workflow::write_tube_gltf(y, dir / "t.glb", {6, 2});
  tinygltf::Model model;
  std::string error, warning;
  ASSERT_TRUE(tinygltf::TinyGLTF().LoadBinaryFromFile(&model, &error, &warning, (dir / "t.glb").string())) << error;
  ASSERT_EQ(model.materials.size(), 2u);
  ASSERT_EQ(model.meshes.at(0).primitives.size(), 2u);
  size_t triangles = 0;
  for (const auto& primitive : model.meshes[0].primitives) {
    EXPECT_GE(primitive.material, 0);
    triangles += model.accessors[primitive.indices].count / 3;
  }
  EXPECT_EQ(model.materials[1].name, "yarn-CC");
  EXPECT_NEAR(model.materials[1].pbrMetallicRoughness.baseColorFactor[2], 0.0578, 1e-3);  // navy #1f2a44's blue, linear
  EXPECT_EQ(static_cast<int>(triangles), 2 * mesh::load_mesh(dir / "p.obj").num_faces());
}
