// A scene file (config/scenes/*.toml) on arbitrary text, with the shipped materials: a
// scene whose every target is a usable bar or wall, or one FileError line naming the file.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "core/config/materials_config.hpp"
#include "core/config/scene_config.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const mallet::MaterialLibrary materials =
      mallet::config::load_materials(mallet::fuzz::source_file("config/materials.toml"));
  const std::string name = "fuzz.toml";
  mallet::Scene scene;
  try {
    scene = mallet::config::parse_scene(mallet::fuzz::text_of(data, size), name, materials);
  } catch (const mallet::FileError& e) {
    mallet::fuzz::check_refusal(e, name);
    return 0;
  }
  for (const mallet::Target& t : scene.targets) {
    if (t.material < 0 || static_cast<std::size_t>(t.material) >= scene.materials.size()) std::abort();
    if (!std::isfinite(t.x_min) || !std::isfinite(t.x_max) || !std::isfinite(t.top_y)) std::abort();
    if (!(t.x_max > t.x_min) || !(t.length_m > 0) || !std::isfinite(t.length_m)) std::abort();
    if (!(t.thickness_m > 0) || !std::isfinite(t.thickness_m)) std::abort();
    if (!(t.frequency_hz > 0) || !std::isfinite(t.frequency_hz)) std::abort();
    (void)scene.material_of(t);
  }
  for (const mallet::Instrument& inst : scene.instruments)
    for (int id : inst.targets)
      if (id < 0 || static_cast<std::size_t>(id) >= scene.targets.size()) std::abort();
  for (int m : scene.wall_materials)
    if (m < 0 || static_cast<std::size_t>(m) >= scene.materials.size()) std::abort();
  return 0;
}
