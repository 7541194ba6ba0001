#include "core/config/instruments_config.hpp"

#include <sstream>
#include <string>

#include "core/config/toml_reader.hpp"

namespace mallet::config {

namespace {

Mode read_mode(TableReader t, bool fundamental) {
  Mode m;
  m.ratio = t.positive("ratio");
  // The note is named after its first mode: the scene's frequency is that mode's.
  if (fundamental && m.ratio != 1.0)
    t.fail("ratio", "the first mode is the fundamental, its ratio must be 1, got " + number_text(m.ratio));
  m.gain = t.non_negative("gain");
  m.decay_per_s = t.non_negative("decay_per_s");
  t.finish();
  return m;
}

ModalPreset read_preset(TableReader t, const std::string& name) {
  ModalPreset p;
  p.name = name;
  p.loudness = t.number("loudness");
  t.require_range("loudness", p.loudness, 0.0, 1.0);
  p.reference_speed_m_per_s = t.positive("reference_speed_m_per_s");
  p.brightness = t.number("brightness");
  // At most 1: then no partial ever gets quieter when the strike gets harder (modal_preset.hpp).
  t.require_range("brightness", p.brightness, 0.0, 1.0);
  std::vector<TableReader> modes = t.tables("modes");
  if (modes.size() > static_cast<std::size_t>(kMaxModalModes))
    t.fail("modes", "at most " + std::to_string(kMaxModalModes) + " modes, got " + std::to_string(modes.size()));
  for (std::size_t i = 0; i < modes.size(); ++i) p.modes.push_back(read_mode(std::move(modes[i]), i == 0));
  t.finish();
  return p;
}

std::vector<ModalPreset> read_presets(const toml::table& root, const std::string& file) {
  TableReader top(root, file);
  TableReader all = top.table("instrument");
  top.finish();
  std::vector<ModalPreset> presets;
  for (const std::string& name : all.keys()) presets.push_back(read_preset(all.table(name), name));
  if (presets.empty()) all.fail("", "defines no instrument");
  all.finish();
  return presets;
}

}  // namespace

std::vector<ModalPreset> load_instruments(const std::filesystem::path& path) {
  return read_presets(parse_file(path), path.string());
}

std::vector<ModalPreset> parse_instruments(std::string_view text, const std::string& name) {
  return read_presets(parse_text(text, name), name);
}

}  // namespace mallet::config
