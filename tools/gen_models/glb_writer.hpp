#pragma once
// One shipped model → one glTF 2.0 binary (.glb) with everything embedded: a scene with a
// single node, its mesh, its metal-roughness material and, optionally, a PNG base-colour
// texture stored in the binary chunk.
#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "mesh_shapes.hpp"
#include "wood_grain.hpp"

namespace mallet::gen {

struct MaterialSpec {
  std::string name;
  std::array<double, 4> base_color{};  //!< linear RGBA factor
  double metallic = 0.0;
  double roughness = 1.0;
  std::optional<RgbaImage> base_color_texture;  //!< multiplied by base_color
  std::string texture_name;
};

struct ModelSpec {
  std::string name;  //!< file stem, node and mesh name
  MeshData mesh;
  MaterialSpec material;
};

//! Writes `dir/<name>.glb` atomically (a temporary file renamed into place); the bytes
//! depend only on the spec. Throws std::runtime_error naming the file on failure.
void write_glb(const ModelSpec& model, const std::filesystem::path& dir);

}  // namespace mallet::gen
