#include "app/kiosk/kiosk_setup.hpp"

#include <system_error>

#include "core/data_paths.hpp"
#include "app/common/settings_source.hpp"
#include "core/visitor_catalogues.hpp"
#include "core/config/scene_config.hpp"
#include "core/file_error.hpp"

namespace mallet::app {

std::filesystem::path named_scene(const std::optional<std::filesystem::path>& settings, const std::string& name,
                                  const FilePlace& named_at, const char* key) {
  const std::filesystem::path file = scene_file(settings, name);
  std::error_code ec;
  if (!named_at.file.empty() && !std::filesystem::is_regular_file(file, ec))
    throw FileError(named_at, std::string(key) + ": \"" + name + "\": no such scene file (looked for " +
                                  file.string() + ")");
  return file;
}

KioskSetup load_kiosk_setup(const KioskOptions& o) {
  KioskSetup s;
  config::LoadedSettings settings = operator_settings(o.config, o.config_dir);
  s.config = std::move(settings.config);
  s.settings_line = "settings: " + settings.describe();
  s.problems = std::move(settings.refused);
  const ScenesConfig& sc = s.config.scenes;
  for (const std::string& name : sc.choices) {
    try {
      const std::filesystem::path file = named_scene(o.config, name, sc.choices_at, "scenes.choices");
      config::load_scene(file);  // parses, with its materials and instruments
      s.scene_choices.push_back(file);
    } catch (const std::exception& e) {
      s.problems.push_back(std::string("scene choice skipped: ") + e.what());
    }
  }
  const std::filesystem::path scene =
      o.scene.empty() ? named_scene(o.config, sc.start, sc.start_at, "scenes.start") : o.scene;
  s.scene = config::load_scene(scene);
  start_visitor_language(s.config.language, s.problems);
  return s;
}

Result<KioskSetup, std::string> load_setup(const KioskOptions& o) {
  try {
    return load_kiosk_setup(o);
  } catch (const std::exception& e) {  // FileError, and whatever a library throws (bad_alloc...)
    return refused(e.what());
  }
}

}  // namespace mallet::app
