// A glTF model through the project's loader on arbitrary bytes, written to a file as the
// kiosk reads one (fuzz.glb when the bytes start with the binary magic "glTF", fuzz.gltf
// otherwise): a model the renderer can draw, or one FileError line naming the file.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "fuzz_support.hpp"
#include "render/gltf_model.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes = mallet::fuzz::text_of(data, size);
  const bool binary = bytes.substr(0, 4) == "glTF";
  const std::string name = binary ? "fuzz.glb" : "fuzz.gltf";
  mallet::fuzz::scratch().remove(binary ? "fuzz.gltf" : "fuzz.glb");  // only this input's file
  const std::filesystem::path path = mallet::fuzz::scratch().write(name, bytes);
  mallet::render::Model model;
  try {
    model = mallet::render::load_gltf(path);
  } catch (const mallet::FileError& e) {
    mallet::fuzz::check_refusal(e, path.string());
    return 0;
  }
  // What the renderer relies on (mesh_data.hpp).
  if (model.primitives.empty()) std::abort();
  for (const mallet::render::Primitive& p : model.primitives) {
    if (p.indices.empty() || p.indices.size() % 3 != 0) std::abort();
    for (std::uint32_t i : p.indices)
      if (i >= p.vertices.size()) std::abort();
    if (p.material < -1 || (p.material >= 0 && static_cast<std::size_t>(p.material) >= model.materials.size()))
      std::abort();
    for (const mallet::render::Vertex& v : p.vertices)
      for (float c : v.position)
        if (!std::isfinite(c)) std::abort();
  }
  for (const mallet::render::PbrMaterial& m : model.materials)
    for (int t : {m.base_color_texture, m.metallic_roughness_texture})
      if (t < -1 || (t >= 0 && static_cast<std::size_t>(t) >= model.textures.size())) std::abort();
  for (const mallet::render::TextureImage& t : model.textures)
    if (t.width <= 0 || t.height <= 0 ||
        t.rgba.size() != static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height) * 4)
      std::abort();
  return 0;
}
