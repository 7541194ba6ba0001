#include "mesh_shapes.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace mallet::gen {

namespace {

using Vec2 = std::array<double, 2>;

// Everything is computed in double and rounded to float once, and values within rounding
// noise of zero are snapped to it, so the output does not depend on the last bit of a
// libm's sin/cos: the models must come out byte-identical on every run.
float to_float(double v) { return static_cast<float>(std::abs(v) < 1e-12 ? 0.0 : v); }

std::uint16_t push_vertex(MeshData& mesh, const Vec3& p, const Vec3& n, const Vec2& uv) {
  if (mesh.positions.size() >= 0xffff) throw std::length_error("mesh too large for 16-bit indices");
  mesh.positions.push_back({to_float(p[0]), to_float(p[1]), to_float(p[2])});
  mesh.normals.push_back({to_float(n[0]), to_float(n[1]), to_float(n[2])});
  mesh.uvs.push_back({to_float(uv[0]), to_float(uv[1])});
  return static_cast<std::uint16_t>(mesh.positions.size() - 1);
}

void push_triangle(MeshData& mesh, std::uint16_t a, std::uint16_t b, std::uint16_t c) {
  mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

// The direction at angle `phi` around y, turning from +x towards -z: with this sense,
// (a, b, c) below winds counter-clockwise seen from outside.
Vec3 around_y(double phi) { return {std::cos(phi), 0.0, -std::sin(phi)}; }

double angle(int step, int steps) {
  return 2.0 * std::numbers::pi * static_cast<double>(step % steps) / static_cast<double>(steps);
}

double ratio(int a, int b) { return static_cast<double>(a) / static_cast<double>(b); }

}  // namespace

MeshData box(const Vec3& min, const Vec3& max, LengthAxis length) {
  const std::size_t along = length == LengthAxis::kX ? 0 : 2;
  const std::size_t across = 2 - along;
  MeshData mesh;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    for (const bool positive : {false, true}) {
      // (u, v, axis) is right-handed on the + face and swapped on the − face, so u × v is
      // the outward normal and the corners (−,−) (+,−) (+,+) (−,+) turn counter-clockwise.
      const std::size_t u = positive ? (axis + 1) % 3 : (axis + 2) % 3;
      const std::size_t v = positive ? (axis + 2) % 3 : (axis + 1) % 3;
      Vec3 normal{};
      normal[axis] = positive ? 1.0 : -1.0;
      constexpr std::array<std::array<bool, 2>, 4> kHigh{{{false, false}, {true, false}, {true, true}, {false, true}}};
      std::array<std::uint16_t, 4> corner{};
      for (std::size_t k = 0; k < 4; ++k) {
        Vec3 p{};
        p[axis] = positive ? max[axis] : min[axis];
        p[u] = kHigh[k][0] ? max[u] : min[u];
        p[v] = kHigh[k][1] ? max[v] : min[v];
        Vec3 s{};  // p in the box's own 0..1 coordinates
        for (std::size_t i = 0; i < 3; ++i) s[i] = (p[i] - min[i]) / (max[i] - min[i]);
        const Vec2 uv = axis == 1       ? Vec2{s[along], s[across]}
                        : axis == along ? Vec2{s[across], 1.0 - s[1]}
                                        : Vec2{s[along], 1.0 - s[1]};
        corner[k] = push_vertex(mesh, p, normal, uv);
      }
      push_triangle(mesh, corner[0], corner[1], corner[2]);
      push_triangle(mesh, corner[0], corner[2], corner[3]);
    }
  }
  return mesh;
}

MeshData uv_sphere(int slices, int stacks) {
  MeshData mesh;
  for (int i = 0; i <= stacks; ++i) {
    const double theta = std::numbers::pi * ratio(i, stacks);
    // The poles exactly on the axis: sin(π) is not 0 in floating point.
    const double ring = (i == 0 || i == stacks) ? 0.0 : std::sin(theta);
    const double y = i == 0 ? 1.0 : i == stacks ? -1.0 : std::cos(theta);
    for (int j = 0; j <= slices; ++j) {
      const Vec3 d = around_y(angle(j, slices));
      const Vec3 p{ring * d[0], y, ring * d[2]};
      push_vertex(mesh, p, p, {ratio(j, slices), ratio(i, stacks)});
    }
  }
  const auto at = [slices](int i, int j) { return static_cast<std::uint16_t>(i * (slices + 1) + j); };
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      // Row i is nearer the north pole; at the poles one triangle of the quad is empty.
      if (i != stacks - 1) push_triangle(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1));
      if (i != 0) push_triangle(mesh, at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return mesh;
}

MeshData capped_cylinder(int segments) {
  MeshData mesh;
  // Side: a seam column duplicated at u = 1, normals pointing straight out.
  const auto side = static_cast<std::uint16_t>(mesh.positions.size());
  for (int j = 0; j <= segments; ++j) {
    const Vec3 d = around_y(angle(j, segments));
    push_vertex(mesh, {d[0], 0.0, d[2]}, d, {ratio(j, segments), 1.0});
    push_vertex(mesh, {d[0], 1.0, d[2]}, d, {ratio(j, segments), 0.0});
  }
  for (int j = 0; j < segments; ++j) {
    const auto bottom = static_cast<std::uint16_t>(side + 2 * j);
    const auto next_bottom = static_cast<std::uint16_t>(bottom + 2);
    push_triangle(mesh, bottom, next_bottom, static_cast<std::uint16_t>(next_bottom + 1));
    push_triangle(mesh, bottom, static_cast<std::uint16_t>(next_bottom + 1), static_cast<std::uint16_t>(bottom + 1));
  }
  // Caps: a fan around a centre vertex, flat normals, planar UVs.
  for (const double y : {0.0, 1.0}) {
    const Vec3 normal{0.0, y > 0 ? 1.0 : -1.0, 0.0};
    const std::uint16_t centre = push_vertex(mesh, {0.0, y, 0.0}, normal, {0.5, 0.5});
    for (int j = 0; j < segments; ++j) {
      const Vec3 d = around_y(angle(j, segments));
      push_vertex(mesh, {d[0], y, d[2]}, normal, {0.5 + 0.5 * d[0], 0.5 + 0.5 * d[2]});
    }
    for (int j = 0; j < segments; ++j) {
      const auto a = static_cast<std::uint16_t>(centre + 1 + j);
      const auto b = static_cast<std::uint16_t>(centre + 1 + (j + 1) % segments);
      if (y > 0) {
        push_triangle(mesh, centre, a, b);
      } else {
        push_triangle(mesh, centre, b, a);
      }
    }
  }
  return mesh;
}

MeshData disc(int segments) {
  MeshData mesh;
  const Vec3 n{0.0, 0.0, 1.0};
  const std::uint16_t centre = push_vertex(mesh, {0.0, 0.0, 0.0}, n, {0.5, 0.5});
  std::vector<std::uint16_t> rim;
  for (int i = 0; i < segments; ++i) {
    // Counter-clockwise seen from +z: x = cos, y = sin.
    const double phi = angle(i, segments);
    const double x = std::cos(phi), y = std::sin(phi);
    rim.push_back(push_vertex(mesh, {x, y, 0.0}, n, {0.5 + x / 2, 0.5 - y / 2}));
  }
  for (int i = 0; i < segments; ++i)
    push_triangle(mesh, centre, rim[static_cast<std::size_t>(i)], rim[static_cast<std::size_t>((i + 1) % segments)]);
  return mesh;
}

}  // namespace mallet::gen
