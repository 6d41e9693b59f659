#include "stitchmesh/input_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <unordered_map>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <Eigen/Geometry>

#include "common/atomic_file.hpp"
#include "common/error.hpp"

namespace skein::mesh {
namespace {

std::uint64_t edge_key(int u, int v) {
  if (u > v) std::swap(u, v);
  return (static_cast<std::uint64_t>(u) << 32) | static_cast<std::uint32_t>(v);
}

std::string vertex_list(const std::vector<int>& f) {
  std::string s;
  for (int v : f) s += (s.empty() ? "" : " ") + std::to_string(v);
  return s;
}

/// Newell's vector: twice the area vector of a (possibly non-planar) polygon.
Eigen::Vector3d area_vector(const std::vector<Eigen::Vector3d>& p, const std::vector<int>& f) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < f.size(); ++i) n += p[f[i]].cross(p[f[(i + 1) % f.size()]]);
  return n;
}

}  // namespace

InputMesh::InputMesh(std::vector<Eigen::Vector3d> points, std::vector<std::vector<int>> faces, std::string source)
    : m_source(std::move(source)), m_points(std::move(points)), m_faces(std::move(faces)) {
  const auto fail = [&](const std::string& place, const std::string& rule) { throw Error(m_source, place, rule); };
  if (m_faces.empty()) fail("", "the mesh has no faces (points or lines only?)");
  // Every problem of a stage is listed, as mesh tools list them (issue 25); the next stage runs only on a mesh
  // that passed the one before, since it relies on it.
  std::vector<std::pair<std::string, std::string>> problems;
  const auto note = [&](const std::string& place, const std::string& rule) { problems.emplace_back(place, rule); };
  const auto stop_if_any = [&] {
    if (problems.empty()) return;
    std::string rule = problems[0].second;
    constexpr size_t kListed = 10;
    if (problems.size() > 1) {
      rule += "; " + std::to_string(problems.size() - 1) + " more:";
      for (size_t i = 1; i < problems.size() && i <= kListed; ++i) rule += (i > 1 ? "; " : " ") + problems[i].first + " " + problems[i].second;
      if (problems.size() > kListed + 1) rule += "; ...";
    }
    fail(problems[0].first, rule);
  };
  const int nv = num_vertices();
  for (int v = 0; v < nv; ++v)
    if (!m_points[v].allFinite()) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "coordinates (%g, %g, %g) are not finite numbers", m_points[v].x(), m_points[v].y(), m_points[v].z());
      note("vertex " + std::to_string(v), buf);
    }
  stop_if_any();

  Eigen::AlignedBox3d box;
  for (const auto& p : m_points) box.extend(p);
  const double diag = box.diagonal().norm();

  for (int f = 0; f < num_faces(); ++f) {
    const auto& face = m_faces[f];
    const std::string place = "face " + std::to_string(f);
    if (face.size() < 3) {
      note(place, "has " + std::to_string(face.size()) + " vertices; a face needs at least 3");
      continue;
    }
    bool indices = true;
    for (size_t i = 0; i < face.size() && indices; ++i) {
      if (face[i] < 0 || face[i] >= nv) {
        note(place, "refers to vertex " + std::to_string(face[i]) + ", but there are " + std::to_string(nv));
        indices = false;
        break;
      }
      for (size_t j = 0; j < i && indices; ++j)
        if (face[i] == face[j]) {
          note(place, "uses vertex " + std::to_string(face[i]) + " twice (vertices " + vertex_list(face) + ")");
          indices = false;
        }
    }
    if (indices && area_vector(m_points, face).norm() * 0.5 <= 1e-12 * diag * diag) note(place, "has zero area (vertices " + vertex_list(face) + ")");
  }
  stop_if_any();

  // Edges: each used at most twice, in opposite directions.
  auto& edge_of = m_edge_of;
  edge_of.reserve(m_faces.size() * 4);
  m_face_edges.resize(m_faces.size());
  for (int f = 0; f < num_faces(); ++f) {
    const auto& face = m_faces[f];
    for (size_t k = 0; k < face.size(); ++k) {
      const int u = face[k], v = face[(k + 1) % face.size()];
      auto [it, inserted] = edge_of.try_emplace(edge_key(u, v), num_edges());
      if (inserted) {
        m_edge_vertices.emplace_back(std::min(u, v), std::max(u, v));
        m_edge_uses.emplace_back();
      }
      auto& uses = m_edge_uses[it->second];
      const std::string place = "edge " + std::to_string(u) + "-" + std::to_string(v);
      if (uses.size() == 2)
        note(place, "is shared by more than two faces (faces " + std::to_string(uses[0].face) + ", " + std::to_string(uses[1].face) + ", " +
                        std::to_string(f) + "); the mesh must be manifold");
      if (uses.size() == 1) {
        const auto& other = m_faces[uses[0].face];
        if (other[uses[0].local] == u)
          note(place, "faces " + std::to_string(uses[0].face) + " and " + std::to_string(f) +
                          " run along it in the same direction; the faces must be oriented consistently");
      }
      uses.push_back({f, static_cast<int>(k)});
      m_face_edges[f].push_back(it->second);
    }
  }

  // Each vertex's faces must form one fan (joined through edges at the vertex); two fans meeting at a
  // single vertex (a bow tie) are non-manifold. OpenMesh would accept some of these.
  {
    std::vector<int> parent;
    const auto find = [&](int x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    std::vector<std::vector<int>> faces_at(nv);
    for (int f = 0; f < num_faces(); ++f)
      for (int v : m_faces[f]) faces_at[v].push_back(f);
    for (int v = 0; v < nv; ++v) {
      const auto& fs = faces_at[v];
      if (fs.size() < 2) continue;
      parent.resize(fs.size());
      for (size_t i = 0; i < fs.size(); ++i) parent[i] = static_cast<int>(i);
      for (size_t i = 0; i < fs.size(); ++i)
        for (size_t j = i + 1; j < fs.size(); ++j) {
          // Faces i and j are joined at v when they share an edge that has v as an end.
          const auto& a = m_faces[fs[i]];
          const auto& b = m_faces[fs[j]];
          bool joined = false;
          for (size_t k = 0; k < a.size() && !joined; ++k) {
            if (a[k] != v) continue;
            const int prev = a[(k + a.size() - 1) % a.size()], next = a[(k + 1) % a.size()];
            joined = std::find(b.begin(), b.end(), prev) != b.end() || std::find(b.begin(), b.end(), next) != b.end();
          }
          if (joined) parent[find(static_cast<int>(i))] = find(static_cast<int>(j));
        }
      for (size_t i = 1; i < fs.size(); ++i)
        if (find(static_cast<int>(i)) != find(0)) {
          note("vertex " + std::to_string(v), "is non-manifold: faces " + std::to_string(fs[0]) + " and " + std::to_string(fs[i]) +
                                                   " meet only at this vertex (two fans)");
          break;
        }
    }
  }
  stop_if_any();
  std::vector<PolyMesh::VertexHandle> vh(nv);
  for (int v = 0; v < nv; ++v) vh[v] = m_mesh.add_vertex(PolyMesh::Point(m_points[v].x(), m_points[v].y(), m_points[v].z()));
  std::vector<PolyMesh::VertexHandle> loop;
  for (int f = 0; f < num_faces(); ++f) {
    loop.clear();
    for (int v : m_faces[f]) loop.push_back(vh[v]);
    if (!m_mesh.add_face(loop).is_valid())
      fail("face " + std::to_string(f), "makes a vertex non-manifold (vertices " + vertex_list(m_faces[f]) + ")");
  }
}

int InputMesh::find_edge(int u, int v) const {
  const auto it = m_edge_of.find(edge_key(u, v));
  return it == m_edge_of.end() ? -1 : it->second;
}

double InputMesh::edge_length(int e) const {
  const auto [a, b] = m_edge_vertices[e];
  return (m_points[a] - m_points[b]).norm();
}

double InputMesh::bounding_diagonal() const {
  Eigen::AlignedBox3d box;
  for (const auto& p : m_points) box.extend(p);
  return box.diagonal().norm();
}

namespace {



MeshSoup read_with_assimp(const std::filesystem::path& path) {
  const std::string name = path.string();
  Assimp::Importer importer;
  // Drop everything but positions so that welding joins corners that differ only in normals or UVs.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS | aiComponent_COLORS |
                                                          aiComponent_TEXCOORDS | aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
                                                          aiComponent_TEXTURES | aiComponent_LIGHTS | aiComponent_CAMERAS | aiComponent_MATERIALS);
  // Never aiProcess_Triangulate: quads and other polygons must survive.
  const aiScene* scene = importer.ReadFile(path.string(), aiProcess_RemoveComponent | aiProcess_JoinIdenticalVertices |
                                                              aiProcess_PreTransformVertices | aiProcess_ValidateDataStructure);
  if (!scene) throw Error(name, "", std::string("cannot read it as a mesh: ") + importer.GetErrorString());

  MeshSoup data;
  auto& [points, faces] = data;
  // Weld identical positions across all meshes of the scene (assimp joins only within one mesh).
  std::map<std::array<double, 3>, int> index_of;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    std::vector<int> remap(mesh->mNumVertices);
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      const std::array<double, 3> key{p.x, p.y, p.z};
      const bool finite = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
      if (!finite) {  // never weld NaNs: keep the vertex so that the error names it
        remap[v] = static_cast<int>(points.size());
        points.emplace_back(p.x, p.y, p.z);
        continue;
      }
      auto [it, inserted] = index_of.try_emplace(key, static_cast<int>(points.size()));
      if (inserted) points.emplace_back(p.x, p.y, p.z);
      remap[v] = it->second;
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices < 3) continue;  // points and lines are not surface
      std::vector<int> loop;
      loop.reserve(face.mNumIndices);
      for (unsigned i = 0; i < face.mNumIndices; ++i) {
        if (face.mIndices[i] >= mesh->mNumVertices) throw Error(name, "face " + std::to_string(faces.size()), "refers to a vertex that does not exist");
        loop.push_back(remap[face.mIndices[i]]);
      }
      faces.push_back(std::move(loop));
    }
  }
  return data;
}

// MeshSoup through the contained reader's pipe: counts, then doubles and ints as this machine stores them.
template <class T> void put(std::string& out, T v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); }
template <class T> T take(const std::string& in, size_t& at) {
  if (at + sizeof(T) > in.size()) throw Error("the mesh reader's answer is cut short");
  T v;
  std::memcpy(&v, in.data() + at, sizeof v);
  at += sizeof v;
  return v;
}

std::string pack(const MeshSoup& data) {
  std::string out;
  put<std::uint64_t>(out, data.points.size());
  for (const auto& p : data.points) put(out, p.x()), put(out, p.y()), put(out, p.z());
  put<std::uint64_t>(out, data.faces.size());
  for (const auto& f : data.faces) {
    put<std::uint32_t>(out, static_cast<std::uint32_t>(f.size()));
    for (int v : f) put<std::int32_t>(out, v);
  }
  return out;
}

MeshSoup unpack(const std::string& in) {
  MeshSoup data;
  size_t at = 0;
  const auto points = take<std::uint64_t>(in, at);
  if (points > in.size() / 24) throw Error("the mesh reader's answer is cut short");
  data.points.resize(points);
  for (auto& p : data.points) {
    const double x = take<double>(in, at), y = take<double>(in, at), z = take<double>(in, at);
    p = {x, y, z};
  }
  const auto faces = take<std::uint64_t>(in, at);
  if (faces > in.size() / 4) throw Error("the mesh reader's answer is cut short");
  data.faces.resize(faces);
  for (auto& f : data.faces) {
    f.resize(take<std::uint32_t>(in, at));
    for (int& v : f) v = take<std::int32_t>(in, at);
  }
  return data;
}

}  // namespace

InputMesh with_used_points(const std::vector<Eigen::Vector3d>& points, std::vector<std::vector<int>> faces, std::string source) {
  std::vector<int> remap(points.size(), -1);
  std::vector<Eigen::Vector3d> used;
  for (auto& f : faces)
    for (int& v : f) {
      if (remap[static_cast<std::size_t>(v)] < 0) remap[static_cast<std::size_t>(v)] = static_cast<int>(used.size()), used.push_back(points[static_cast<std::size_t>(v)]);
      v = remap[static_cast<std::size_t>(v)];
    }
  return InputMesh(std::move(used), std::move(faces), std::move(source));
}

MeshSoup read_mesh_soup(const std::filesystem::path& path, const ContainedLimits& limits) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error(name, "", "no such file");
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(name, "", "not a regular file");
  {
    std::FILE* probe = std::fopen(path.c_str(), "rb");
    if (!probe) throw Error(name, "", "cannot be opened for reading");
    std::fclose(probe);
  }
  // assimp parses the file in a child process: a crash or a blow-up there is an error here (issue 25).
  // Without a time limit given, 10 s and 2 s more per MB of file: a few bytes that hang assimp (fuzzing found
  // a truncated PLY face list) wait 10 s, not forever.
  ContainedLimits bounded = limits;
  if (!(bounded.seconds > 0)) bounded.seconds = 10 + 2 * static_cast<double>(std::filesystem::file_size(path, ec)) / 1e6;
  auto [points, faces] = unpack(run_contained(name, "the mesh reader", bounded, [&] { return pack(read_with_assimp(path)); }));

  // Drop vertices no face uses (OBJ files often carry them); keep the order of the rest.
  std::vector<int> used(points.size(), -1);
  for (const auto& f : faces)
    for (int v : f) used[v] = 0;
  std::vector<Eigen::Vector3d> kept;
  for (size_t v = 0; v < points.size(); ++v)
    if (used[v] == 0) {
      used[v] = static_cast<int>(kept.size());
      kept.push_back(points[v]);
    }
  for (auto& f : faces)
    for (int& v : f) v = used[v];
  return {std::move(kept), std::move(faces)};
}

InputMesh load_mesh(const std::filesystem::path& path, const ContainedLimits& limits) {
  auto soup = read_mesh_soup(path, limits);
  return InputMesh(std::move(soup.points), std::move(soup.faces), path.string());
}

void write_obj(const InputMesh& mesh, const std::filesystem::path& path) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "# skein input mesh: " << mesh.num_vertices() << " vertices, " << mesh.num_faces() << " faces\n";
    char buf[128];
    for (const auto& p : mesh.points()) {
      std::snprintf(buf, sizeof buf, "v %.9g %.9g %.9g\n", p.x(), p.y(), p.z());
      out << buf;
    }
    for (const auto& f : mesh.faces()) {
      out << 'f';
      for (int v : f) out << ' ' << v + 1;
      out << '\n';
    }
  });
}

}  // namespace skein::mesh
