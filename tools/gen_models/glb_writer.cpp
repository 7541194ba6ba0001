#include "glb_writer.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <tiny_gltf.h>

namespace mallet::gen {

namespace {

// Fills the model's single buffer (the .glb's binary chunk) one bufferView at a time.
class BufferBuilder {
 public:
  explicit BufferBuilder(tinygltf::Model& gltf) : gltf_(gltf) { gltf_.buffers.emplace_back(); }

  //! Appends `size` bytes as a new bufferView starting on a 4-byte boundary (as accessors
  //! of floats require); returns the view's index.
  int add_view(const void* data, std::size_t size, int target, const std::string& name) {
    auto& bytes = gltf_.buffers[0].data;
    bytes.resize((bytes.size() + 3) / 4 * 4, 0);
    tinygltf::BufferView view;
    view.name = name;
    view.buffer = 0;
    view.byteOffset = bytes.size();
    view.byteLength = size;
    view.target = target;
    const auto* first = static_cast<const std::uint8_t*>(data);
    bytes.insert(bytes.end(), first, first + size);
    gltf_.bufferViews.push_back(std::move(view));
    return static_cast<int>(gltf_.bufferViews.size() - 1);
  }

  //! A tightly packed accessor over `values` in a view of its own.
  template <typename T>
  int add_accessor(const std::vector<T>& values, int type, int component_type, int target, const std::string& name) {
    tinygltf::Accessor accessor;
    accessor.name = name;
    accessor.bufferView = add_view(values.data(), values.size() * sizeof(T), target, name);
    accessor.componentType = component_type;
    accessor.count = values.size();
    accessor.type = type;
    gltf_.accessors.push_back(std::move(accessor));
    return static_cast<int>(gltf_.accessors.size() - 1);
  }

 private:
  tinygltf::Model& gltf_;
};

// glTF 2.0 requires min and max on every POSITION accessor.
void set_bounds(tinygltf::Accessor& accessor, const std::vector<std::array<float, 3>>& positions) {
  accessor.minValues.assign(3, std::numeric_limits<double>::infinity());
  accessor.maxValues.assign(3, -std::numeric_limits<double>::infinity());
  for (const auto& p : positions) {
    for (std::size_t i = 0; i < 3; ++i) {
      accessor.minValues[i] = std::min(accessor.minValues[i], static_cast<double>(p[i]));
      accessor.maxValues[i] = std::max(accessor.maxValues[i], static_cast<double>(p[i]));
    }
  }
}

tinygltf::Material material_of(const MaterialSpec& spec, tinygltf::Model& gltf, BufferBuilder& buffer) {
  tinygltf::Material material;
  material.name = spec.name;
  material.emissiveFactor = {0.0, 0.0, 0.0};  // tinygltf would otherwise write an invalid []
  auto& pbr = material.pbrMetallicRoughness;
  pbr.baseColorFactor.assign(spec.base_color.begin(), spec.base_color.end());
  pbr.metallicFactor = spec.metallic;
  pbr.roughnessFactor = spec.roughness;
  if (spec.base_color_texture) {
    const std::vector<std::uint8_t> png = encode_png(*spec.base_color_texture);
    tinygltf::Image image;
    image.name = spec.texture_name;
    image.mimeType = "image/png";
    image.bufferView = buffer.add_view(png.data(), png.size(), 0, spec.texture_name);
    gltf.images.push_back(std::move(image));

    tinygltf::Sampler sampler;
    sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    gltf.samplers.push_back(sampler);

    tinygltf::Texture texture;
    texture.name = spec.texture_name;
    texture.source = static_cast<int>(gltf.images.size() - 1);
    texture.sampler = static_cast<int>(gltf.samplers.size() - 1);
    gltf.textures.push_back(std::move(texture));
    pbr.baseColorTexture.index = static_cast<int>(gltf.textures.size() - 1);
  }
  return material;
}

tinygltf::Model gltf_of(const ModelSpec& spec) {
  tinygltf::Model gltf;
  gltf.asset.version = "2.0";
  gltf.asset.generator = "mallet tools/gen_models";  // no version or date: output must not drift
  BufferBuilder buffer(gltf);

  const MeshData& mesh = spec.mesh;
  tinygltf::Primitive primitive;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  primitive.attributes["POSITION"] =
      buffer.add_accessor(mesh.positions, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT,
                          TINYGLTF_TARGET_ARRAY_BUFFER, spec.name + "_positions");
  set_bounds(gltf.accessors.back(), mesh.positions);
  primitive.attributes["NORMAL"] = buffer.add_accessor(mesh.normals, TINYGLTF_TYPE_VEC3, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                       TINYGLTF_TARGET_ARRAY_BUFFER, spec.name + "_normals");
  primitive.attributes["TEXCOORD_0"] = buffer.add_accessor(mesh.uvs, TINYGLTF_TYPE_VEC2, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                           TINYGLTF_TARGET_ARRAY_BUFFER, spec.name + "_uvs");
  primitive.indices = buffer.add_accessor(mesh.indices, TINYGLTF_TYPE_SCALAR, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                          TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER, spec.name + "_indices");

  gltf.materials.push_back(material_of(spec.material, gltf, buffer));
  primitive.material = 0;

  tinygltf::Mesh gltf_mesh;
  gltf_mesh.name = spec.name;
  gltf_mesh.primitives.push_back(std::move(primitive));
  gltf.meshes.push_back(std::move(gltf_mesh));

  tinygltf::Node node;
  node.name = spec.name;
  node.mesh = 0;
  gltf.nodes.push_back(std::move(node));

  tinygltf::Scene scene;
  scene.name = spec.name;
  scene.nodes = {0};
  gltf.scenes.push_back(std::move(scene));
  gltf.defaultScene = 0;
  return gltf;
}

}  // namespace

void write_glb(const ModelSpec& model, const std::filesystem::path& dir) {
  const tinygltf::Model gltf = gltf_of(model);
  // tinygltf's writer into memory rather than WriteGltfSceneToFile, which does not report
  // a failed write: here a full disk or a missing directory is an error, and a reader of
  // models/ never sees a half-written file.
  std::ostringstream glb;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&gltf, glb, /*prettyPrint=*/false, /*writeBinary=*/true)) {
    throw std::runtime_error(model.name + ": tinygltf could not serialise the model");
  }
  const std::filesystem::path file = dir / (model.name + ".glb");
  std::filesystem::path temporary = file;
  temporary += ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    const std::string bytes = glb.str();
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) throw std::runtime_error(temporary.string() + ": cannot write: " + std::strerror(errno));
  }
  std::error_code error;
  std::filesystem::rename(temporary, file, error);
  if (error) throw std::runtime_error(file.string() + ": cannot rename into place: " + error.message());
}

}  // namespace mallet::gen
