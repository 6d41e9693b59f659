#include "common/gltf_mesh.hpp"

#include <cmath>
#include <cstring>

#include <tiny_gltf.h>

#include "common/atomic_file.hpp"
#include "common/error.hpp"

namespace skein {

void write_gltf_mesh(const GltfMesh& mesh, const std::filesystem::path& path) {
  std::size_t triangles = 0;
  for (const auto& p : mesh.primitives) triangles += p.indices.size() / 3;
  if (triangles == 0 || mesh.positions.empty()) throw Error(path.string(), "", "there is no triangle to write");
  if (mesh.positions.size() > 0xffffffffull) throw Error(path.string(), "", "more vertices than 32-bit indices reach");
  std::vector<float> positions, normals;
  float low[3] = {INFINITY, INFINITY, INFINITY}, high[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const float x = static_cast<float>(1e-3 * mesh.positions[i][k]);
      positions.push_back(x), normals.push_back(static_cast<float>(mesh.normals[i][k]));
      low[k] = std::min(low[k], x), high[k] = std::max(high[k], x);
    }
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "skein";
  tinygltf::Buffer buffer;
  const auto view = [&](const void* data, std::size_t bytes, int target) {
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = buffer.data.size();
    v.byteLength = bytes;
    v.target = target;
    buffer.data.resize(buffer.data.size() + bytes);
    std::memcpy(buffer.data.data() + v.byteOffset, data, bytes);
    model.bufferViews.push_back(v);
    return static_cast<int>(model.bufferViews.size()) - 1;
  };
  const auto accessor = [&](int buffer_view, int component, std::size_t count, int type) {
    tinygltf::Accessor a;
    a.bufferView = buffer_view;
    a.componentType = component;
    a.count = count;
    a.type = type;
    model.accessors.push_back(a);
    return static_cast<int>(model.accessors.size()) - 1;
  };
  const int pos = accessor(view(positions.data(), positions.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER), TINYGLTF_COMPONENT_TYPE_FLOAT,
                           positions.size() / 3, TINYGLTF_TYPE_VEC3);
  model.accessors[pos].minValues = {low[0], low[1], low[2]};
  model.accessors[pos].maxValues = {high[0], high[1], high[2]};
  const int nrm = accessor(view(normals.data(), normals.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER), TINYGLTF_COMPONENT_TYPE_FLOAT,
                           normals.size() / 3, TINYGLTF_TYPE_VEC3);
  tinygltf::Mesh out;
  out.name = mesh.mesh_name;
  for (const auto& p : mesh.primitives) {
    if (p.indices.empty()) continue;
    tinygltf::Primitive primitive;
    primitive.attributes["POSITION"] = pos;
    primitive.attributes["NORMAL"] = nrm;
    primitive.indices = accessor(view(p.indices.data(), p.indices.size() * sizeof(std::uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                                 TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, p.indices.size(), TINYGLTF_TYPE_SCALAR);
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    if (!p.material.empty()) {
      tinygltf::Material material;
      material.name = p.material;
      material.pbrMetallicRoughness.baseColorFactor = {p.linear_rgb[0], p.linear_rgb[1], p.linear_rgb[2], 1.0};
      material.pbrMetallicRoughness.metallicFactor = 0.0;
      material.pbrMetallicRoughness.roughnessFactor = 0.9;
      material.doubleSided = p.double_sided;
      model.materials.push_back(material);
      primitive.material = static_cast<int>(model.materials.size()) - 1;
    }
    out.primitives.push_back(primitive);
  }
  model.buffers.push_back(std::move(buffer));
  model.meshes.push_back(out);
  tinygltf::Node node;
  node.mesh = 0;
  node.name = mesh.node_name;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  const bool binary = path.extension() == ".glb";
  write_file_atomically(path, [&](std::ostream& stream) {
    if (!tinygltf::TinyGLTF().WriteGltfSceneToStream(&model, stream, !binary, binary)) throw Error(path.string(), "", "tinygltf could not write it");
  });
}

}  // namespace skein
