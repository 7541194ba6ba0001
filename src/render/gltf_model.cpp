#include "render/gltf_model.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <stb_image.h>
#include <tiny_gltf.h>

#include <fmt/format.h>

#include "core/enum_names.hpp"
#include "core/file_error.hpp"
#include "render/gltf_source.hpp"

// What this loader does with the parts of glTF 2.0 a static kiosk scene can meet:
// * the default scene (else scene 0, else every root node), node transforms (matrix or
//   TRS) baked into positions and normals (inverse-transpose), winding flipped under a
//   mirroring transform so front faces stay counter-clockwise;
// * TRIANGLES, and TRIANGLE_STRIP / TRIANGLE_FAN converted to lists; POINTS and LINES are
//   refused (the renderer draws shaded triangles only);
// * a missing NORMAL gets flat normals, as the glTF spec requires of clients;
// * pbrMetallicRoughness factors, base-colour and metallic-roughness textures decoded to
//   RGBA8. Normal, occlusion and emissive maps and samplers are ignored: the renderer's
//   shading does not use them.
// Refused, because the renderer could not draw them faithfully: sparse accessors, morph
// targets, skins, any extension in extensionsRequired, textures on TEXCOORD_1+.
namespace mallet::render {

namespace {

static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian");

// The largest texture side accepted: far above what the kiosk ships (512x128), and a
// bound on what a hostile image header can make the loader allocate.
constexpr int kMaxTextureSide = 8192;

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string str(const glm::dvec3& v) {
  return fmt::format("({:g}, {:g}, {:g})", v.x, v.y, v.z);
}

// NaN for a zero vector, so the caller's finiteness check catches it (glm::normalize would
// give a finite direction for a vector of length 1e-13).
glm::dvec3 normalized(const glm::dvec3& v) {
  const double length = glm::length(v);
  if (!(length > 1e-12)) return {std::nan(""), 0, 0};
  return v / length;
}

std::array<float, 3> to_float(const glm::dvec3& v) {
  return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
}

// "mesh 'bar'" when the element has a name, else "mesh 3".
std::string named(const std::string& kind, std::size_t index, const std::string& name) {
  return name.empty() ? kind + " " + std::to_string(index) : kind + " '" + name + "'";
}

//! A glTF constant's name ("VEC3"), or its number for one the specification does not define.
template <std::size_t N>
std::string code_name(const EnumNames<int, N>& names, int code) {
  const char* name = name_in(names, code, nullptr);
  return name ? name : std::to_string(code);
}

constexpr EnumNames<int, 7> kTypeNames{{
    {TINYGLTF_TYPE_SCALAR, "SCALAR"}, {TINYGLTF_TYPE_VEC2, "VEC2"}, {TINYGLTF_TYPE_VEC3, "VEC3"},
    {TINYGLTF_TYPE_VEC4, "VEC4"}, {TINYGLTF_TYPE_MAT2, "MAT2"}, {TINYGLTF_TYPE_MAT3, "MAT3"},
    {TINYGLTF_TYPE_MAT4, "MAT4"}}};

std::string type_name(int type) { return code_name(kTypeNames, type); }

constexpr EnumNames<int, 6> kComponentTypeNames{{
    {TINYGLTF_COMPONENT_TYPE_BYTE, "BYTE"}, {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, "UNSIGNED_BYTE"},
    {TINYGLTF_COMPONENT_TYPE_SHORT, "SHORT"}, {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, "UNSIGNED_SHORT"},
    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, "UNSIGNED_INT"}, {TINYGLTF_COMPONENT_TYPE_FLOAT, "FLOAT"}}};

std::string component_type_name(int component_type) { return code_name(kComponentTypeNames, component_type); }

constexpr EnumNames<int, 7> kModeNames{{
    {TINYGLTF_MODE_POINTS, "POINTS"}, {TINYGLTF_MODE_LINE, "LINES"}, {TINYGLTF_MODE_LINE_LOOP, "LINE_LOOP"},
    {TINYGLTF_MODE_LINE_STRIP, "LINE_STRIP"}, {TINYGLTF_MODE_TRIANGLES, "TRIANGLES"},
    {TINYGLTF_MODE_TRIANGLE_STRIP, "TRIANGLE_STRIP"}, {TINYGLTF_MODE_TRIANGLE_FAN, "TRIANGLE_FAN"}}};

std::string mode_name(int mode) { return code_name(kModeNames, mode); }

// tinygltf's messages end lines with '\n', may hold several and may quote raw bytes of
// the file: one printable line for FileError.
std::string one_line(std::string text) {
  for (char& c : text) {
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text.empty() ? "unknown error" : text;
}

// Image loader for tinygltf: keeps the encoded bytes of uri images (data: or external
// files) and leaves bufferView images alone, so decoding happens below, after their
// bufferView has been bounds-checked, always to RGBA8.
bool keep_encoded_image(tinygltf::Image* image, int, std::string*, std::string*, int, int, const unsigned char* bytes,
                        int size, void*) {
  if (image->bufferView < 0 && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

//! An accessor whose every element lies inside its buffer.
struct AccessorView {
  const unsigned char* data = nullptr;  //!< nullptr: no bufferView, every element is zero
  std::size_t stride = 0;
  std::size_t count = 0;
  int components = 0;
  int component_type = 0;
  bool normalized = false;

  //! Component `c` of element `i`, normalised integers mapped to [0, 1] or [-1, 1].
  double get(std::size_t i, int c) const {
    if (data == nullptr) return 0.0;
    const unsigned char* p = data + i * stride + static_cast<std::size_t>(c * component_size());
    switch (component_type) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return read<float>(p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return scaled(read<std::uint8_t>(p), 255.0);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return scaled(read<std::uint16_t>(p), 65535.0);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return read<std::uint32_t>(p);
      case TINYGLTF_COMPONENT_TYPE_BYTE:
        return std::max(scaled(read<std::int8_t>(p), 127.0), -1.0);
      case TINYGLTF_COMPONENT_TYPE_SHORT:
        return std::max(scaled(read<std::int16_t>(p), 32767.0), -1.0);
      default:
        return 0.0;
    }
  }
  glm::dvec3 vec3(std::size_t i) const { return {get(i, 0), get(i, 1), get(i, 2)}; }

  int component_size() const { return tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(component_type)); }

 private:
  template <typename T>
  static T read(const unsigned char* p) {
    T value;
    std::memcpy(&value, p, sizeof value);
    return value;
  }
  double scaled(double value, double max) const { return normalized ? value / max : value; }
};

class Loader {
 public:
  Loader(std::string file, const tinygltf::Model& gltf, std::string warnings)
      : file_(std::move(file)), gltf_(gltf), warnings_(std::move(warnings)) {}

  Model load() {
    for (const auto& extension : gltf_.extensionsRequired) {
      if (const std::optional<std::string> compression = mesh_compression(extension))
        fail("its meshes are compressed with " + *compression +
             ", which Mallet cannot decode: export the model without mesh compression");
      fail("requires extension '" + extension + "', which the renderer does not support");
    }
    model_.file = file_;
    for (std::size_t i = 0; i < gltf_.materials.size(); ++i) model_.materials.push_back(material(i));
    std::vector<bool> visited(gltf_.nodes.size(), false);
    for (const int root : root_nodes()) add_node_tree(root, visited);
    if (model_.primitives.empty()) fail("no triangles to draw (the scene holds no mesh)");
    compute_bounds();
    return std::move(model_);
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const { throw FileError(file_, 0, 0, problem); }

  // ---- scene graph ----

  std::vector<int> root_nodes() const {
    if (gltf_.defaultScene >= 0) {
      if (static_cast<std::size_t>(gltf_.defaultScene) >= gltf_.scenes.size()) {
        fail("default scene " + std::to_string(gltf_.defaultScene) + " does not exist (the file has " +
             std::to_string(gltf_.scenes.size()) + ")");
      }
      return gltf_.scenes[static_cast<std::size_t>(gltf_.defaultScene)].nodes;
    }
    if (!gltf_.scenes.empty()) return gltf_.scenes.front().nodes;
    // No scene at all: every node that is nobody's child.
    std::vector<bool> is_child(gltf_.nodes.size(), false);
    for (const auto& node : gltf_.nodes) {
      for (const int child : node.children) {
        if (child >= 0 && static_cast<std::size_t>(child) < is_child.size())
          is_child[static_cast<std::size_t>(child)] = true;
      }
    }
    std::vector<int> roots;
    for (std::size_t i = 0; i < is_child.size(); ++i) {
      if (!is_child[i]) roots.push_back(static_cast<int>(i));
    }
    return roots;
  }

  // Depth first with an explicit stack: a deep hierarchy in a hostile file cannot
  // overflow the call stack.
  void add_node_tree(int root, std::vector<bool>& visited) {
    std::vector<std::pair<int, glm::dmat4>> pending{{root, glm::dmat4(1.0)}};
    while (!pending.empty()) {
      const auto [index, parent] = pending.back();
      pending.pop_back();
      if (index < 0 || static_cast<std::size_t>(index) >= gltf_.nodes.size()) {
        fail("node " + std::to_string(index) + " does not exist (the file has " + std::to_string(gltf_.nodes.size()) +
             ")");
      }
      const auto i = static_cast<std::size_t>(index);
      const tinygltf::Node& node = gltf_.nodes[i];
      const std::string place = named("node", i, node.name);
      if (visited[i]) fail(place + ": reached twice (the node hierarchy has a cycle or a node with two parents)");
      visited[i] = true;
      const glm::dmat4 world = parent * local_transform(node, place);
      if (node.mesh >= 0) {
        if (node.skin >= 0) fail(place + ": skinned meshes are not supported");
        add_mesh(node.mesh, world, place);
      }
      for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) {
        pending.emplace_back(*child, world);
      }
    }
  }

  glm::dmat4 local_transform(const tinygltf::Node& node, const std::string& place) const {
    const auto check = [&](const std::vector<double>& values, std::size_t size, const char* what) {
      if (!values.empty() && values.size() != size) {
        fail(place + ": " + what + " has " + std::to_string(values.size()) + " numbers, expected " +
             std::to_string(size));
      }
      for (const double v : values) {
        if (!std::isfinite(v)) fail(place + ": " + what + " is not finite");
      }
    };
    check(node.matrix, 16, "matrix");
    check(node.translation, 3, "translation");
    check(node.rotation, 4, "rotation");
    check(node.scale, 3, "scale");
    if (!node.matrix.empty()) {
      const glm::dmat4 m = glm::make_mat4(node.matrix.data());  // column-major, like glTF's
      if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0) {
        fail(place + ": matrix is not affine (its last row must be 0 0 0 1)");
      }
      return m;
    }
    // T · R · S, the rotation a unit quaternion (x, y, z, w).
    double x = 0, y = 0, z = 0, w = 1;
    if (!node.rotation.empty()) {
      const double length = std::hypot(node.rotation[0], node.rotation[1], node.rotation[2]);
      const double norm = std::sqrt(length * length + node.rotation[3] * node.rotation[3]);
      if (norm < 1e-6) fail(place + ": rotation is not a unit quaternion");
      x = node.rotation[0] / norm;
      y = node.rotation[1] / norm;
      z = node.rotation[2] / norm;
      w = node.rotation[3] / norm;
    }
    const glm::dvec3 s = node.scale.empty() ? glm::dvec3(1.0) : glm::make_vec3(node.scale.data());
    const glm::dvec3 t = node.translation.empty() ? glm::dvec3(0.0) : glm::make_vec3(node.translation.data());
    const glm::dmat3 r = glm::mat3_cast(glm::dquat(w, x, y, z));
    return {glm::dvec4(r[0] * s.x, 0.0), glm::dvec4(r[1] * s.y, 0.0), glm::dvec4(r[2] * s.z, 0.0), glm::dvec4(t, 1.0)};
  }

  // ---- meshes ----

  void add_mesh(int mesh_index, const glm::dmat4& world, const std::string& node_place) {
    if (static_cast<std::size_t>(mesh_index) >= gltf_.meshes.size()) {
      fail(node_place + ": mesh " + std::to_string(mesh_index) + " does not exist (the file has " +
           std::to_string(gltf_.meshes.size()) + ")");
    }
    const auto m = static_cast<std::size_t>(mesh_index);
    const tinygltf::Mesh& mesh = gltf_.meshes[m];
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      add_primitive(mesh.primitives[p], named("mesh", m, mesh.name) + " primitive " + std::to_string(p), world,
                    node_place);
    }
  }

  void add_primitive(const tinygltf::Primitive& gltf_primitive, const std::string& place, const glm::dmat4& world,
                     const std::string& node_place) {
    if (!gltf_primitive.targets.empty()) fail(place + ": morph targets are not supported");
    const auto position = gltf_primitive.attributes.find("POSITION");
    if (position == gltf_primitive.attributes.end()) fail(place + ": no POSITION attribute");
    const AccessorView positions =
        accessor(position->second, place + " POSITION", TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT});
    const std::size_t vertex_count = positions.count;

    const auto optional_attribute = [&](const char* name, int type, std::initializer_list<int> component_types) {
      const auto found = gltf_primitive.attributes.find(name);
      if (found == gltf_primitive.attributes.end()) return AccessorView{};
      AccessorView view = accessor(found->second, place + " " + name, type, component_types);
      if (view.count != vertex_count) {
        fail(place + ": " + name + " has " + std::to_string(view.count) + " elements but POSITION has " +
             std::to_string(vertex_count));
      }
      return view;
    };
    const AccessorView normals = optional_attribute("NORMAL", TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT});
    const AccessorView uvs = optional_attribute(
        "TEXCOORD_0", TINYGLTF_TYPE_VEC2,
        {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
    if (uvs.count > 0 && uvs.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT && !uvs.normalized) {
      fail(place + " TEXCOORD_0: integer texture coordinates must be normalized");
    }
    if (gltf_primitive.material >= 0 && static_cast<std::size_t>(gltf_primitive.material) >= gltf_.materials.size()) {
      fail(place + ": material " + std::to_string(gltf_primitive.material) + " does not exist (the file has " +
           std::to_string(gltf_.materials.size()) + ")");
    }

    std::vector<std::uint32_t> triangles = triangle_list(gltf_primitive, place, vertex_count);

    // The node's transform: positions by the affine matrix, normals by the inverse
    // transpose of its linear part; a mirroring transform (det < 0) turns the winding.
    const glm::dmat3 linear(world);
    const double det = glm::determinant(linear);
    if (!std::isfinite(det) || std::abs(det) < 1e-30) {
      fail(node_place + ": its transform is singular (a zero scale): " + place + " would collapse");
    }
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));
    if (det < 0) {
      for (std::size_t t = 0; t < triangles.size(); t += 3) std::swap(triangles[t + 1], triangles[t + 2]);
    }

    Primitive out;
    out.material = gltf_primitive.material;
    out.vertices.resize(vertex_count);
    for (std::size_t i = 0; i < vertex_count; ++i) {
      const glm::dvec3 p = positions.vec3(i);
      if (!finite(p)) fail(place + ": POSITION " + std::to_string(i) + " is not finite " + str(p));
      const glm::dvec3 moved = linear * p + glm::dvec3(world[3]);
      if (!finite(moved))
        fail(node_place + ": its transform takes " + place + " POSITION " + std::to_string(i) + " to infinity");
      Vertex& v = out.vertices[i];
      v.position = to_float(moved);
      if (normals.count > 0) {
        const glm::dvec3 n = normals.vec3(i);
        const glm::dvec3 turned = normalized(normal_matrix * n);
        if (!finite(n) || !finite(turned))
          fail(place + ": NORMAL " + std::to_string(i) + " is not a direction " + str(n));
        v.normal = to_float(turned);
      }
      if (uvs.count > 0) {
        const double u = uvs.get(i, 0);
        const double w = uvs.get(i, 1);
        if (!std::isfinite(u) || !std::isfinite(w))
          fail(place + ": TEXCOORD_0 " + std::to_string(i) + " is not finite");
        v.uv = {static_cast<float>(u), static_cast<float>(w)};
      }
    }
    out.indices = std::move(triangles);
    if (normals.count == 0) give_flat_normals(out);
    model_.primitives.push_back(std::move(out));
  }

  // The primitive's triangles as a list of vertex indices, every one checked.
  std::vector<std::uint32_t> triangle_list(const tinygltf::Primitive& p, const std::string& place,
                                           std::size_t vertex_count) const {
    std::vector<std::uint32_t> indices;
    if (p.indices >= 0) {
      const AccessorView view = accessor(p.indices, place + " indices", TINYGLTF_TYPE_SCALAR,
                                         {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                          TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
      if (view.normalized) fail(place + " indices: must not be normalized");
      if (view.data == nullptr) fail(place + " indices: accessor has no bufferView");
      indices.resize(view.count);
      for (std::size_t i = 0; i < view.count; ++i) {
        const double index = view.get(i, 0);
        if (index >= static_cast<double>(vertex_count)) {
          fail(place + ": index " + std::to_string(static_cast<std::uint64_t>(index)) +
               " >= " + std::to_string(vertex_count) + " vertices");
        }
        indices[i] = static_cast<std::uint32_t>(index);
      }
    } else {
      if (vertex_count > std::numeric_limits<std::uint32_t>::max()) fail(place + ": too many vertices");
      indices.resize(vertex_count);
      for (std::size_t i = 0; i < vertex_count; ++i) indices[i] = static_cast<std::uint32_t>(i);
    }

    const std::size_t n = indices.size();
    switch (p.mode) {
      case TINYGLTF_MODE_TRIANGLES:
        if (n % 3 != 0) fail(place + ": " + std::to_string(n) + " indices are not a whole number of triangles");
        if (n == 0) break;
        return indices;
      case TINYGLTF_MODE_TRIANGLE_STRIP:
      case TINYGLTF_MODE_TRIANGLE_FAN: {
        if (n < 3) break;
        std::vector<std::uint32_t> list;
        list.reserve((n - 2) * 3);
        for (std::size_t i = 0; i + 2 < n; ++i) {
          if (p.mode == TINYGLTF_MODE_TRIANGLE_FAN) {
            list.insert(list.end(), {indices[i + 1], indices[i + 2], indices[0]});
          } else if (i % 2 == 0) {  // strips alternate their winding (glTF 2.0, "Topology Types")
            list.insert(list.end(), {indices[i], indices[i + 1], indices[i + 2]});
          } else {
            list.insert(list.end(), {indices[i], indices[i + 2], indices[i + 1]});
          }
        }
        return list;
      }
      default:
        fail(place + ": mode " + mode_name(p.mode) +
             " cannot be drawn (only TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN)");
    }
    fail(place + ": no triangle (" + std::to_string(n) + " indices)");
  }

  // glTF: "When normals are not specified, client implementations MUST calculate flat
  // normals": every triangle gets its own three vertices. A degenerate triangle covers no
  // pixel, so the normal it gets does not matter.
  static void give_flat_normals(Primitive& primitive) {
    std::vector<Vertex> flat;
    flat.reserve(primitive.indices.size());
    for (std::size_t t = 0; t < primitive.indices.size(); t += 3) {
      std::array<Vertex, 3> corner{};
      std::array<glm::dvec3, 3> p{};
      for (std::size_t k = 0; k < 3; ++k) {
        corner[k] = primitive.vertices[primitive.indices[t + k]];
        p[k] = glm::dvec3(glm::make_vec3(corner[k].position.data()));
      }
      glm::dvec3 n = normalized(glm::cross(p[1] - p[0], p[2] - p[0]));
      if (!finite(n)) n = {0, 1, 0};
      for (auto& v : corner) {
        v.normal = to_float(n);
        flat.push_back(v);
      }
    }
    primitive.vertices = std::move(flat);
    for (std::size_t i = 0; i < primitive.indices.size(); ++i) primitive.indices[i] = static_cast<std::uint32_t>(i);
  }

  // ---- accessors ----

  AccessorView accessor(int index, const std::string& place, int type,
                        std::initializer_list<int> component_types) const {
    if (index < 0 || static_cast<std::size_t>(index) >= gltf_.accessors.size()) {
      fail(place + ": accessor " + std::to_string(index) + " does not exist (the file has " +
           std::to_string(gltf_.accessors.size()) + ")");
    }
    const tinygltf::Accessor& a = gltf_.accessors[static_cast<std::size_t>(index)];
    const std::string where = place + " (accessor " + std::to_string(index) + ")";
    if (a.sparse.isSparse) fail(where + ": sparse accessors are not supported");
    if (a.type != type) fail(where + ": type " + type_name(a.type) + ", expected " + type_name(type));
    if (std::find(component_types.begin(), component_types.end(), a.componentType) == component_types.end()) {
      std::string allowed;
      for (const int t : component_types) allowed += (allowed.empty() ? "" : " or ") + component_type_name(t);
      fail(where + ": component type " + component_type_name(a.componentType) + ", expected " + allowed);
    }
    if (a.count == 0) fail(where + ": count is 0");
    AccessorView view;
    view.count = a.count;
    view.components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    view.component_type = a.componentType;
    view.normalized = a.normalized;
    const auto element = static_cast<std::size_t>(view.components * view.component_size());
    if (a.bufferView < 0) return view;  // the spec's all-zero accessor

    const std::span<const unsigned char> bytes = buffer_view(a.bufferView, where);
    const tinygltf::BufferView& bv = gltf_.bufferViews[static_cast<std::size_t>(a.bufferView)];
    view.stride = bv.byteStride == 0 ? element : bv.byteStride;
    if (bv.byteStride != 0 && (bv.byteStride < element || bv.byteStride > 252 || bv.byteStride % 4 != 0)) {
      fail(where + ": byteStride " + std::to_string(bv.byteStride) + " of bufferView " + std::to_string(a.bufferView) +
           " must be a multiple of 4 in [" + std::to_string(element) + ", 252]");
    }
    // The last element ends at byteOffset + stride·(count − 1) + element; count is checked
    // against the view's size first so the product cannot overflow.
    const bool fits = a.byteOffset <= bytes.size() && a.count <= bytes.size() &&
                      view.stride * (a.count - 1) + element <= bytes.size() - a.byteOffset;
    if (!fits) {
      fail(where + ": " + std::to_string(a.count) + " elements of " + std::to_string(element) + " bytes from offset " +
           std::to_string(a.byteOffset) + " run past the end of bufferView " + std::to_string(a.bufferView) + " (" +
           std::to_string(bytes.size()) + " bytes)");
    }
    view.data = bytes.data() + a.byteOffset;
    return view;
  }

  std::span<const unsigned char> buffer_view(int index, const std::string& place) const {
    if (index < 0 || static_cast<std::size_t>(index) >= gltf_.bufferViews.size()) {
      fail(place + ": bufferView " + std::to_string(index) + " does not exist (the file has " +
           std::to_string(gltf_.bufferViews.size()) + ")");
    }
    const tinygltf::BufferView& view = gltf_.bufferViews[static_cast<std::size_t>(index)];
    const std::string where = place + ": bufferView " + std::to_string(index);
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= gltf_.buffers.size()) {
      fail(where + ": buffer " + std::to_string(view.buffer) + " does not exist (the file has " +
           std::to_string(gltf_.buffers.size()) + ")");
    }
    const std::vector<unsigned char>& data = gltf_.buffers[static_cast<std::size_t>(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
      fail(where + ": bytes " + std::to_string(view.byteOffset) + " + " + std::to_string(view.byteLength) +
           " run past the end of buffer " + std::to_string(view.buffer) + " (" + std::to_string(data.size()) +
           " bytes)");
    }
    return {data.data() + view.byteOffset, view.byteLength};
  }

  // ---- materials and textures ----

  PbrMaterial material(std::size_t index) {
    const tinygltf::Material& m = gltf_.materials[index];
    const std::string place = named("material", index, m.name);
    const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
    const auto unit = [](double v) { return std::isfinite(v) && v >= 0.0 && v <= 1.0; };
    PbrMaterial out;
    out.name = m.name;
    if (pbr.baseColorFactor.size() != 4 || !std::all_of(pbr.baseColorFactor.begin(), pbr.baseColorFactor.end(), unit)) {
      fail(place + ": baseColorFactor must be 4 numbers in [0, 1]");
    }
    for (std::size_t i = 0; i < 4; ++i) out.base_color[i] = static_cast<float>(pbr.baseColorFactor[i]);
    if (!unit(pbr.metallicFactor)) fail(place + ": metallicFactor must lie in [0, 1]");
    if (!unit(pbr.roughnessFactor)) fail(place + ": roughnessFactor must lie in [0, 1]");
    out.metallic = static_cast<float>(pbr.metallicFactor);
    out.roughness = static_cast<float>(pbr.roughnessFactor);
    out.base_color_texture = texture(pbr.baseColorTexture, place + " baseColorTexture");
    out.metallic_roughness_texture = texture(pbr.metallicRoughnessTexture, place + " metallicRoughnessTexture");
    return out;
  }

  // The Model::textures slot of a glTF texture, decoding its image the first time.
  int texture(const tinygltf::TextureInfo& info, const std::string& place) {
    if (info.index < 0) return -1;
    if (static_cast<std::size_t>(info.index) >= gltf_.textures.size()) {
      fail(place + ": texture " + std::to_string(info.index) + " does not exist (the file has " +
           std::to_string(gltf_.textures.size()) + ")");
    }
    if (info.texCoord != 0) {
      fail(place + ": uses TEXCOORD_" + std::to_string(info.texCoord) + "; only TEXCOORD_0 is supported");
    }
    if (const auto known = texture_slots_.find(info.index); known != texture_slots_.end()) return known->second;
    const auto t = static_cast<std::size_t>(info.index);
    const tinygltf::Texture& gltf_texture = gltf_.textures[t];
    if (gltf_texture.source < 0 || static_cast<std::size_t>(gltf_texture.source) >= gltf_.images.size()) {
      fail(named("texture", t, gltf_texture.name) + ": no image source the renderer can decode (PNG or JPEG)");
    }
    model_.textures.push_back(decode_image(static_cast<std::size_t>(gltf_texture.source)));
    const int slot = static_cast<int>(model_.textures.size() - 1);
    texture_slots_[info.index] = slot;
    return slot;
  }

  //! ": why" for an external file tinygltf could not read ("File read error : PATH : why"
  //! or "File not found : URI" among its warnings), else nothing.
  std::string read_failure(const std::string& uri) const {
    std::size_t start = 0;
    while (start < warnings_.size()) {
      std::size_t end = warnings_.find('\n', start);
      if (end == std::string::npos) end = warnings_.size();
      const std::string_view line(warnings_.data() + start, end - start);
      start = end + 1;
      if (uri.empty() || line.find(uri) == std::string_view::npos) continue;
      if (line.starts_with("File not found")) return ": no such file";
      if (line.starts_with("File read error")) {
        const std::size_t why = line.rfind(" : ");
        if (why != std::string_view::npos) return ": " + std::string(line.substr(why + 3));
      }
    }
    return {};
  }

  TextureImage decode_image(std::size_t index) const {
    const tinygltf::Image& image = gltf_.images[index];
    const std::string place = named("image", index, image.name);
    std::span<const unsigned char> encoded = image.image;
    if (image.bufferView >= 0) {
      encoded = buffer_view(image.bufferView, place);
    } else if (encoded.empty()) {
      fail(place + ": cannot read '" + image.uri + "'" + read_failure(image.uri));
    }
    if (encoded.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) fail(place + ": too large");
    int width = 0;
    int height = 0;
    int channels = 0;
    const auto size = static_cast<int>(encoded.size());
    // The header first: a few hostile bytes must not make the kiosk allocate gigabytes.
    if (stbi_info_from_memory(encoded.data(), size, &width, &height, &channels) != 0 &&
        (width > kMaxTextureSide || height > kMaxTextureSide)) {
      fail(place + ": " + std::to_string(width) + "x" + std::to_string(height) + " is larger than the " +
           std::to_string(kMaxTextureSide) + "x" + std::to_string(kMaxTextureSide) + " a texture may be");
    }
    const std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
        stbi_load_from_memory(encoded.data(), size, &width, &height, &channels, 4), stbi_image_free);
    if (!pixels) fail(place + ": cannot decode (" + std::string(stbi_failure_reason()) + ")");
    TextureImage out;
    out.name = image.name;
    out.width = width;
    out.height = height;
    out.rgba.assign(pixels.get(),
                    pixels.get() + static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
    return out;
  }

  void compute_bounds() {
    std::array<float, 3> lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
                            std::numeric_limits<float>::max()};
    std::array<float, 3> hi{-lo[0], -lo[1], -lo[2]};
    for (const auto& primitive : model_.primitives) {
      for (const auto& v : primitive.vertices) {
        for (std::size_t i = 0; i < 3; ++i) {
          lo[i] = std::min(lo[i], v.position[i]);
          hi[i] = std::max(hi[i], v.position[i]);
        }
      }
    }
    model_.bounds_min = lo;
    model_.bounds_max = hi;
  }

  std::string file_;
  const tinygltf::Model& gltf_;
  std::string warnings_;  //!< tinygltf's: why an external image could not be read
  Model model_;
  std::map<int, int> texture_slots_;  // glTF texture index → Model::textures index
};

//! tinygltf's model and its warnings (external images it could not read, and why).
struct Parsed {
  tinygltf::Model gltf;
  std::string warnings;
};

Parsed parse(const std::filesystem::path& file, const std::vector<unsigned char>& bytes) {
  const std::string name = file.string();
  // A .glb is recognised by its magic, whatever the file is called.
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  const std::string_view json = gltf_json_text(bytes, binary);
  check_json_nesting(json, name, binary);
  tinygltf::TinyGLTF reader;
  use_guarded_files(reader);
  reader.SetImageLoader(&keep_encoded_image, nullptr);
  Parsed parsed;
  std::string error;
  const auto size = static_cast<unsigned int>(bytes.size());  // read_gltf_file bounds it far below 4 GiB
  const std::string base_dir = file.parent_path().string();
  const bool ok = binary ? reader.LoadBinaryFromMemory(&parsed.gltf, &error, &parsed.warnings, bytes.data(), size,
                                                       base_dir)
                         : reader.LoadASCIIFromString(&parsed.gltf, &error, &parsed.warnings,
                                                      reinterpret_cast<const char*>(bytes.data()), size, base_dir);
  if (!ok) {
    // A compressed mesh's accessors have no bufferView of their own: tinygltf fails on them
    // without naming the compression, which is the reason a modeller can act on.
    if (const std::optional<std::string> compression = mesh_compression(json))
      throw FileError(name, 0, 0, "its meshes are compressed with " + *compression +
                                      ", which Mallet cannot decode: export the model without mesh compression");
    throw FileError(name, 0, 0,
                    std::string(binary ? "not a valid glTF binary: " : "not valid glTF: ") + one_line(error));
  }
  return parsed;
}

}  // namespace

Model load_gltf(const std::filesystem::path& file) {
  const std::vector<unsigned char> bytes = read_gltf_file(file);
  const Parsed parsed = parse(file, bytes);
  return Loader(file.string(), parsed.gltf, parsed.warnings).load();
}

}  // namespace mallet::render
