#pragma once
// Loading any glTF 2.0 file (.glb or .gltf with its buffers) into a Model: every mesh
// primitive of the default scene with its node transforms applied, indices, normals,
// UVs, PBR metal-roughness factors and textures.
#include <filesystem>

#include "render/mesh_data.hpp"

namespace mallet::render {

//! Throws FileError ("FILE: problem") for a missing, unreadable or malformed file, or one
//! the renderer cannot draw faithfully (no triangles, missing normals, bad indices …):
//! the kiosk refuses to start rather than draw garbage.
Model load_gltf(const std::filesystem::path& file);

}  // namespace mallet::render
