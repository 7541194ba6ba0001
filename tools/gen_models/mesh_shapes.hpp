#pragma once
// The unit shapes the shipped models are made of, as indexed triangle lists wound
// counter-clockwise seen from outside (glTF's front faces). The renderer scales each unit
// shape to the scene's sizes, so one model serves every bar of an instrument.
#include <array>
#include <cstdint>
#include <vector>

namespace mallet::gen {

using Vec3 = std::array<double, 3>;

struct MeshData {
  std::vector<std::array<float, 3>> positions;
  std::vector<std::array<float, 3>> normals;
  std::vector<std::array<float, 2>> uvs;
  std::vector<std::uint16_t> indices;  //!< a triangle list
};

//! Which horizontal axis a box's texture u runs along (the grain of a bar or a rail).
enum class LengthAxis { kX, kZ };

//! An axis-aligned box with one flat-shaded quad per face (24 vertices, 12 triangles).
//! u runs along `length` on the top, bottom and long sides; v runs across the top and
//! down the sides (v = 0 at the top edge).
MeshData box(const Vec3& min, const Vec3& max, LengthAxis length);

//! A sphere of radius 1 centred on the origin, smooth normals, `slices` around y and
//! `stacks` from the north pole (+y) to the south pole; u around, v = 0 at the north pole.
MeshData uv_sphere(int slices, int stacks);

//! A flat disc of radius 1 in the plane z = 0 facing +z (towards the viewer), a fan of
//! `segments` triangles; u, v map x, y from [-1, 1] to [0, 1] (v down).
MeshData disc(int segments);

//! A cylinder of radius 1 around y from y = 0 to y = 1: a smooth side and two flat caps.
MeshData capped_cylinder(int segments);

}  // namespace mallet::gen
