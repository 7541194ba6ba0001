#include "render/detailed_model.hpp"

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

#include <tiny_gltf.h>

namespace mallet::render {

namespace {

template <typename T>
void append(std::vector<unsigned char>& bytes, const std::vector<T>& values) {
  const std::size_t at = bytes.size();
  bytes.resize(at + values.size() * sizeof(T));
  std::memcpy(bytes.data() + at, values.data(), values.size() * sizeof(T));
}

int add_view_and_accessor(tinygltf::Model& m, std::size_t offset, std::size_t bytes, int component, int type,
                          std::size_t count, int target) {
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = bytes;
  view.target = target;
  m.bufferViews.push_back(view);
  tinygltf::Accessor a;
  a.bufferView = static_cast<int>(m.bufferViews.size() - 1);
  a.componentType = component;
  a.type = type;
  a.count = count;
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size() - 1);
}

}  // namespace

std::size_t write_detailed_bar(const std::filesystem::path& file, int cells, std::array<double, 4> base_color,
                               double metallic, double roughness) {
  std::vector<float> positions, normals, uvs;
  std::vector<std::uint32_t> indices;
  const float lo[3] = {-0.5f, -1.0f, -0.5f}, hi[3] = {0.5f, 0.0f, 0.5f};
  for (int axis = 0; axis < 3; ++axis)
    for (const bool positive : {false, true}) {
      // (u, v, axis) right-handed on the + face, swapped on the − face: u × v points out.
      const int u = positive ? (axis + 1) % 3 : (axis + 2) % 3;
      const int v = positive ? (axis + 2) % 3 : (axis + 1) % 3;
      const auto first = static_cast<std::uint32_t>(positions.size() / 3);
      for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) {
          float p[3];
          p[axis] = positive ? hi[axis] : lo[axis];
          p[u] = lo[u] + (hi[u] - lo[u]) * static_cast<float>(i) / static_cast<float>(cells);
          p[v] = lo[v] + (hi[v] - lo[v]) * static_cast<float>(j) / static_cast<float>(cells);
          positions.insert(positions.end(), {p[0], p[1], p[2]});
          float n[3] = {0, 0, 0};
          n[axis] = positive ? 1.0f : -1.0f;
          normals.insert(normals.end(), {n[0], n[1], n[2]});
          uvs.insert(uvs.end(), {static_cast<float>(i) / static_cast<float>(cells),
                                 static_cast<float>(j) / static_cast<float>(cells)});
        }
      const auto row = static_cast<std::uint32_t>(cells + 1);
      for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
          const std::uint32_t a = first + static_cast<std::uint32_t>(j) * row + static_cast<std::uint32_t>(i);
          indices.insert(indices.end(), {a, a + 1, a + row + 1, a, a + row + 1, a + row});
        }
    }

  tinygltf::Model m;
  tinygltf::Buffer buffer;
  append(buffer.data, positions);
  append(buffer.data, normals);
  append(buffer.data, uvs);
  append(buffer.data, indices);
  m.buffers.push_back(buffer);
  const std::size_t vertices = positions.size() / 3;
  std::size_t offset = 0;
  const int position = add_view_and_accessor(m, offset, positions.size() * 4, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                             TINYGLTF_TYPE_VEC3, vertices, TINYGLTF_TARGET_ARRAY_BUFFER);
  m.accessors[static_cast<std::size_t>(position)].minValues = {lo[0], lo[1], lo[2]};
  m.accessors[static_cast<std::size_t>(position)].maxValues = {hi[0], hi[1], hi[2]};
  offset += positions.size() * 4;
  const int normal = add_view_and_accessor(m, offset, normals.size() * 4, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                           TINYGLTF_TYPE_VEC3, vertices, TINYGLTF_TARGET_ARRAY_BUFFER);
  offset += normals.size() * 4;
  const int uv = add_view_and_accessor(m, offset, uvs.size() * 4, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2,
                                       vertices, TINYGLTF_TARGET_ARRAY_BUFFER);
  offset += uvs.size() * 4;
  const int index = add_view_and_accessor(m, offset, indices.size() * 4, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                          TINYGLTF_TYPE_SCALAR, indices.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);

  tinygltf::Material material;
  material.name = "detailed_bar";
  material.pbrMetallicRoughness.baseColorFactor = {base_color[0], base_color[1], base_color[2], base_color[3]};
  material.pbrMetallicRoughness.metallicFactor = metallic;
  material.pbrMetallicRoughness.roughnessFactor = roughness;
  m.materials.push_back(material);
  tinygltf::Primitive primitive;
  primitive.attributes = {{"POSITION", position}, {"NORMAL", normal}, {"TEXCOORD_0", uv}};
  primitive.indices = index;
  primitive.material = 0;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh mesh;
  mesh.primitives.push_back(primitive);
  m.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  m.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  m.scenes.push_back(scene);
  m.defaultScene = 0;
  m.asset.version = "2.0";
  m.asset.generator = "mallet bench render";
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToFile(&m, file.string(), true, true, false, true))
    throw std::runtime_error("bench render: cannot write the detailed model " + file.string());
  return indices.size() / 3;
}

}  // namespace mallet::render
