#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <vector>

#include "common/contained.hpp"
#include "common/error.hpp"
#include "stitchmesh/input_mesh.hpp"
#include "testing.hpp"

using namespace skein;
using skein::testing::error_of;
using skein::testing::ScratchDir;

namespace {
// Two quads sharing an edge, written the way exporters do: one vertex per corner, with normals and UVs.
const char* kTwoQuadsObj = R"(# two quads
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 1 0 0
v 2 0 0
v 2 1 0
v 1 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
f 1/1/1 2/2/1 3/3/1 4/4/1
f 5/1/1 6/2/1 7/3/1 8/4/1
)";
}  // namespace

TEST(InputMesh, ObjKeepsQuadsAndWeldsCorners) {
  ScratchDir dir;
  const auto m = mesh::load_mesh(dir.write("quads.obj", kTwoQuadsObj));
  EXPECT_EQ(m.num_faces(), 2);
  EXPECT_EQ(m.num_vertices(), 6);  // the two shared corners joined
  EXPECT_EQ(m.face(0).size(), 4u);
  EXPECT_EQ(m.face(1).size(), 4u);
  EXPECT_EQ(m.num_edges(), 7);
  int border = 0;
  for (int e = 0; e < m.num_edges(); ++e) border += m.is_border(e);
  EXPECT_EQ(border, 6);
}

TEST(InputMesh, ReadsPlyAndOffPolygons) {
  ScratchDir dir;
  const auto ply = mesh::load_mesh(dir.write("quad.ply", R"(ply
format ascii 1.0
element vertex 5
property float x
property float y
property float z
element face 2
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
1 1 0
0 1 0
0.5 2 0
4 0 1 2 3
3 3 2 4
)"));
  EXPECT_EQ(ply.num_faces(), 2);
  EXPECT_EQ(ply.face(0).size(), 4u);
  EXPECT_EQ(ply.face(1).size(), 3u);
  const auto off = mesh::load_mesh(dir.write("penta.off", "OFF\n5 1 0\n0 0 0\n2 0 0\n3 1 0\n1 2 0\n-1 1 0\n5 0 1 2 3 4\n"));
  EXPECT_EQ(off.num_faces(), 1);
  EXPECT_EQ(off.face(0).size(), 5u);
}

TEST(InputMesh, MissingFileIsNamed) {
  const std::string msg = error_of([] { mesh::load_mesh("/nonexistent/garment.obj"); });
  EXPECT_NE(msg.find("/nonexistent/garment.obj"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no such file"), std::string::npos) << msg;
}

TEST(InputMesh, FolderIsNotAMesh) {
  ScratchDir dir;
  const std::string msg = error_of([&] { mesh::load_mesh(dir.path()); });
  EXPECT_NE(msg.find("not a regular file"), std::string::npos) << msg;
}

TEST(InputMesh, UnknownFormatIsRejected) {
  ScratchDir dir;
  const auto p = dir.write("mesh.qqq", "this is not a mesh\n");
  const std::string msg = error_of([&] { mesh::load_mesh(p); });
  EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
  EXPECT_NE(msg.find("cannot read it as a mesh"), std::string::npos) << msg;
}

TEST(InputMesh, GarbageWithAMeshExtensionDoesNotCrash) {
  ScratchDir dir;
  std::string junk;
  for (int i = 0; i < 4096; ++i) junk += static_cast<char>((i * 7919) % 256);
  for (const char* ext : {"obj", "ply", "gltf", "glb", "fbx", "off", "stl"}) {
    const auto p = dir.write(std::string("junk.") + ext, junk);
    EXPECT_THROW(mesh::load_mesh(p), Error) << ext;
  }
}

TEST(InputMesh, NoFacesIsRejected) {
  ScratchDir dir;
  const std::string msg = error_of([&] { mesh::load_mesh(dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n")); });
  EXPECT_NE(msg.find("points.obj"), std::string::npos) << msg;
  EXPECT_NE(msg.find("face"), std::string::npos) << msg;
}

TEST(InputMesh, NonManifoldEdgeNamesTheEdge) {
  ScratchDir dir;
  // Three triangles on edge 1-2.
  const std::string msg = error_of([&] {
    mesh::load_mesh(dir.write("fin.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 2 0 0\nv 1 0 1\nf 1 2 3\nf 2 4 3\nf 2 3 5\n"));
  });
  EXPECT_NE(msg.find("edge 1-2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("more than two faces"), std::string::npos) << msg;
}

TEST(InputMesh, InconsistentOrientationIsRejected) {
  const std::string msg = error_of([] {
    mesh::InputMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}, {0, 3, 2}}, "flip.obj");
  });
  EXPECT_FALSE(msg.empty());
  const std::string msg2 = error_of([] {
    mesh::InputMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 3, 2}}, "flip.obj");
  });
  EXPECT_NE(msg2.find("oriented consistently"), std::string::npos) << msg2;
}

TEST(InputMesh, NonManifoldVertexIsRejected) {
  // Two triangles touching at vertex 0 only (a bow tie).
  const std::string msg = error_of([] {
    mesh::InputMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}}, {{0, 1, 2}, {0, 3, 4}}, "bowtie.obj");
  });
  EXPECT_NE(msg.find("non-manifold"), std::string::npos) << msg;
}

TEST(InputMesh, EveryProblemIsListedAtOnce) {
  // Three bow ties (pairs of triangles touching at one vertex), one flipped quad and an edge of three faces.
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> faces;
  for (int k = 0; k < 3; ++k) {
    const double x = 10.0 * k;
    const int b = static_cast<int>(points.size());
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(x, 0, 0), {x + 1, 0, 0}, {x + 1, 1, 0}, {x - 1, 0, 0}, {x - 1, -1, 0}}) points.push_back(p);
    faces.push_back({b, b + 1, b + 2});
    faces.push_back({b, b + 3, b + 4});
  }
  std::string msg = error_of([&] { mesh::InputMesh(points, faces, "ties.obj"); });
  EXPECT_EQ(msg, "ties.obj: vertex 0: is non-manifold: faces 0 and 1 meet only at this vertex (two fans); 2 more: vertex 5 is non-manifold: faces 2 "
                 "and 3 meet only at this vertex (two fans); vertex 10 is non-manifold: faces 4 and 5 meet only at this vertex (two fans)");
  // Edge problems and vertex problems of one stage come together.
  points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}, {1, 0, 1}};
  faces = {{0, 1, 2, 3}, {1, 4, 5, 2}, {1, 2, 6}, {2, 1, 4}};
  msg = error_of([&] { mesh::InputMesh(points, faces, "mixed.obj"); });
  EXPECT_NE(msg.find("more:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("shared by more than two faces"), std::string::npos) << msg;
  EXPECT_NE(msg.find("in the same direction"), std::string::npos) << msg;
}

TEST(InputMesh, NonFiniteCoordinatesNameTheVertex) {
  const std::string msg = error_of([] {
    mesh::InputMesh({{0, 0, 0}, {1, 0, 0}, {std::nan(""), 1, 0}}, {{0, 1, 2}}, "nan.obj");
  });
  EXPECT_NE(msg.find("vertex 2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not finite"), std::string::npos) << msg;
  ScratchDir dir;
  const std::string from_file = error_of([&] { mesh::load_mesh(dir.write("inf.obj", "v 0 0 0\nv 1 0 0\nv 1 inf 0\nf 1 2 3\n")); });
  EXPECT_NE(from_file.find("inf.obj"), std::string::npos) << from_file;
}

TEST(InputMesh, ZeroAreaFaceIsNamed) {
  ScratchDir dir;
  const std::string msg = error_of([&] {
    mesh::load_mesh(dir.write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n"));
  });
  EXPECT_NE(msg.find("face 0"), std::string::npos) << msg;
  EXPECT_NE(msg.find("zero area"), std::string::npos) << msg;
}

TEST(InputMesh, RepeatedVertexInAFaceIsNamed) {
  const std::string msg = error_of([] { mesh::InputMesh({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {{0, 1, 2, 1}}, "rep.obj"); });
  EXPECT_NE(msg.find("twice"), std::string::npos) << msg;
}

TEST(InputMesh, WriteObjReadsBack) {
  ScratchDir dir;
  const auto m = mesh::load_mesh(dir.write("quads.obj", kTwoQuadsObj));
  mesh::write_obj(m, dir / "out.obj");
  const auto back = mesh::load_mesh(dir / "out.obj");
  EXPECT_EQ(back.faces(), m.faces());
}

namespace {
std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const unsigned n = (static_cast<unsigned char>(bytes[i]) << 16) | (i + 1 < bytes.size() ? static_cast<unsigned char>(bytes[i + 1]) << 8 : 0) |
                       (i + 2 < bytes.size() ? static_cast<unsigned char>(bytes[i + 2]) : 0);
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[n & 63] : '=';
  }
  return out;
}
}  // namespace

TEST(InputMesh, ReadsGltfAndWeldsAcrossMeshes) {
  // Two glTF meshes (a triangle each) that share an edge: welding joins them into one surface.
  std::string buffer;
  const auto put_float = [&](float x) { buffer.append(reinterpret_cast<const char*>(&x), 4); };
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put_float(v);  // triangle A
  for (float v : {1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f}) put_float(v);  // triangle B
  const std::string gltf = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1]}],
"nodes":[{"mesh":0},{"mesh":1}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]},{"primitives":[{"attributes":{"POSITION":1}}]}],
"buffers":[{"byteLength":72,"uri":"data:application/octet-stream;base64,)" + base64(buffer) + R"("}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":36}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
{"bufferView":1,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}]})";
  ScratchDir dir;
  const auto m = mesh::load_mesh(dir.write("two.gltf", gltf));
  EXPECT_EQ(m.num_faces(), 2);
  EXPECT_EQ(m.num_vertices(), 4);
  EXPECT_EQ(m.num_edges(), 5);
}

TEST(ContainedReader, FilesThatAskForBillionsOfElementsAreRefusedAtOnce) {
  ScratchDir dir;
  const auto ply = dir.write("big.ply", "ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\n"
                                        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n");
  const auto off = dir.write("big.off", "OFF\n3 1000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  for (const auto& p : {ply, off}) {
    const std::string msg = error_of([&] { mesh::load_mesh(p); });
    EXPECT_EQ(msg.rfind(p.string() + ": ", 0), 0u) << msg;
  }
}

TEST(ContainedReader, AFileThatHangsTheReaderIsStoppedAtItsDeadline) {
  // 101 bytes that send the system's assimp into an endless loop (found by fuzz_mesh): without a time limit of
  // its own, 10 s for a file this small.
  ScratchDir dir;
  const auto ply = dir.write("hang.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                                         "element face 1\np 2 3\n");
  const auto started = std::chrono::steady_clock::now();
  const std::string msg = error_of([&] { mesh::load_mesh(ply, {1, 1}); });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  // Some assimp versions refuse it at once instead; either way an error naming the file comes back, promptly.
  EXPECT_EQ(msg.rfind(ply.string() + ": ", 0), 0u) << msg;
  EXPECT_LT(seconds, 5);
}
