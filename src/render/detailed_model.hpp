#pragma once
// A detailed instrument for `mallet bench render`: the unit bar (x ∈ [-0.5, 0.5], y ∈ [-1, 0],
// z ∈ [-0.5, 0.5]) with every face cut into a fine grid, as a museum's commissioned model
// might be, written as a .glb through tinygltf. Only its triangle count differs from the
// shipped bar: the same box, the same material factors.
#include <array>
#include <cstddef>
#include <filesystem>

namespace mallet::render {

//! Writes it to `file` with `cells` × `cells` quads per face (12·cells² triangles); returns
//! its triangle count. Throws std::runtime_error naming the file when it cannot.
std::size_t write_detailed_bar(const std::filesystem::path& file, int cells, std::array<double, 4> base_color,
                               double metallic, double roughness);

}  // namespace mallet::render
