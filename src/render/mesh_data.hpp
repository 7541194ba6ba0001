#pragma once
// A model as the renderer consumes it, independent of any file format or GPU API:
// triangle lists with positions, normals and UVs in the model's own space (node
// transforms already applied), glTF PBR metal-roughness materials and decoded RGBA8
// textures.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace mallet::render {

struct Vertex {
  std::array<float, 3> position{};
  std::array<float, 3> normal{};
  std::array<float, 2> uv{};
};

struct TextureImage {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  //!< width·height·4 bytes, rows top to bottom
};

//! glTF 2.0 pbrMetallicRoughness.
struct PbrMaterial {
  std::string name;
  std::array<float, 4> base_color{1, 1, 1, 1};  //!< linear RGBA factor
  float metallic = 1.0f;
  float roughness = 1.0f;
  int base_color_texture = -1;          //!< index in Model::textures, or -1
  int metallic_roughness_texture = -1;  //!< index in Model::textures (B = metal, G = rough), or -1
};

struct Primitive {
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;  //!< a triangle list; every index < vertices.size()
  int material = -1;                   //!< index in Model::materials, or -1 (glTF default)
};

struct Model {
  std::string file;  //!< where it was loaded from (for messages)
  std::vector<Primitive> primitives;
  std::vector<PbrMaterial> materials;
  std::vector<TextureImage> textures;
  std::array<float, 3> bounds_min{};
  std::array<float, 3> bounds_max{};
};

}  // namespace mallet::render
