#include "core/config/materials_config.hpp"

#include <vector>

#include "core/config/toml_reader.hpp"

namespace mallet::config {

namespace {

VibrationParams read_triple(TableReader t, std::string_view amplitude_key) {
  VibrationParams p;
  p.amplitude = t.non_negative(amplitude_key);
  p.decay_per_s = t.non_negative("decay_per_s");
  p.freq_hz = t.positive("freq_hz");
  t.finish();
  return p;
}

MaterialLibrary read_materials(const toml::table& root, const std::string& file) {
  TableReader top(root, file);
  TableReader all = top.table("material");
  top.finish();
  std::vector<Material> materials;
  for (const std::string& name : all.keys()) {
    TableReader t = all.table(name);
    Material m;
    m.name = name;
    m.display_name = t.string_or("display_name", name);
    m.source = t.string_or("source", "");
    m.visual = read_triple(t.table("visual"), "amplitude_s");
    m.actuator = read_triple(t.table("actuator"), "amplitude");
    if (t.has("glow_srgb")) {
      const std::vector<double> c = t.numbers("glow_srgb");
      if (c.size() != 3) t.fail("glow_srgb", "needs three numbers (red, green, blue in 0..1)");
      for (double v : c)
        if (!(v >= 0 && v <= 1)) t.fail("glow_srgb", "components must be in 0..1");
      m.glow_srgb = {c[0], c[1], c[2]};
    }
    t.finish();
    materials.push_back(std::move(m));
  }
  if (materials.empty()) all.fail("", "defines no material");
  return MaterialLibrary(std::move(materials));
}

}  // namespace

MaterialLibrary load_materials(const std::filesystem::path& path) {
  return read_materials(parse_file(path), path.string());
}

MaterialLibrary parse_materials(std::string_view text, const std::string& name) {
  return read_materials(parse_text(text, name), name);
}

}  // namespace mallet::config
