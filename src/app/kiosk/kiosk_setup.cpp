#include "app/kiosk/kiosk_setup.hpp"

#include <unistd.h>

#include "app/kiosk/systemd_notify.hpp"

#include <system_error>

#include "core/data_paths.hpp"
#include "app/common/settings_source.hpp"
#include "core/visitor_catalogues.hpp"
#include "core/config/scene_config.hpp"
#include "core/config/settings_files.hpp"
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

namespace {

//! What `o` names, with `settings` (already loaded) as the settings; scenes named in them
//! are found beside `scenes_beside` (the settings file they are read as).
KioskSetup setup_from(const KioskOptions& o, config::LoadedSettings settings,
                      const std::optional<std::filesystem::path>& scenes_beside) {
  KioskSetup s;
  s.config = std::move(settings.config);
  s.settings_line = "settings: " + settings.describe();
  s.problems = std::move(settings.refused);
  const ScenesConfig& sc = s.config.scenes;
  for (const std::string& name : sc.choices) {
    try {
      const std::filesystem::path file = named_scene(scenes_beside, name, sc.choices_at, "scenes.choices");
      config::load_scene(file);  // parses, with its materials and instruments
      s.scene_choices.push_back(file);
    } catch (const std::exception& e) {
      s.problems.push_back(std::string("scene choice skipped: ") + e.what());
    }
  }
  const std::filesystem::path scene =
      o.scene.empty() ? named_scene(scenes_beside, sc.start, sc.start_at, "scenes.start") : o.scene;
  s.scene = config::load_scene(scene);
  start_visitor_language(s.config.language, s.problems);
  return s;
}

}  // namespace

KioskSetup load_kiosk_setup(const KioskOptions& o) {
  config::LoadedSettings settings = operator_settings(o.config, o.config_dir);
  std::string kept = config::show_settings(settings);
  KioskSetup s = setup_from(o, std::move(settings), o.config);
  s.kept_settings = std::move(kept);
  return s;
}

std::string last_good_text(const KioskSetup& setup) {
  if (setup.kept_settings.empty()) return {};
  return "# The kiosk's last good settings: those of its last start or reload whose settings loaded, kept by\n"
         "# `mallet run`. The kiosk starts on them when its settings are refused (a broken file). Not for\n"
         "# editing: edit the files named below, then `systemctl reload mallet`.\n" +
         setup.kept_settings;
}

Result<KioskSetup, std::string> load_setup(const KioskOptions& o) {
  try {
    return load_kiosk_setup(o);
  } catch (const std::exception& e) {  // FileError, and whatever a library throws (bad_alloc...)
    return refused(e.what());
  }
}

Result<KioskSetup, std::string> start_setup(const KioskOptions& o, const std::filesystem::path& last_good) {
  Result<KioskSetup, std::string> own = load_setup(o);
  if (own) return own;
  std::vector<std::string> not_used;  // fallbacks that did not load, each with its reason
  // Each fallback as the reload's route loads: whatever it throws is its reason.
  const auto fall_back = [&](const std::filesystem::path& file, const std::optional<std::filesystem::path>& as_if,
                             const KioskOptions& options, bool kept, const std::string& what) -> bool {
    try {
      config::LoadedSettings settings = kept ? config::load_kept_settings(file, as_if)
                                             : config::load_settings(file, {});
      KioskSetup s = setup_from(options, std::move(settings), as_if);
      // A problem with a kept setting (a scene choice gone since) is named in the operator's
      // own file, where it is fixed, not in the generated one.
      if (kept)
        for (std::string& p : s.problems) p = config::at_kept_origin(file, p);
      s.fallback = what + " (" + file.string() + ")";
      s.refused = "settings refused: " + own.error() + "; the kiosk runs on " + s.fallback +
                  " until they load (fix them, then reload: " +
                  reload_command(NotifyEnvironment::from_process(), static_cast<long>(getpid())) + ")";
      s.settings_line = "settings: " + s.fallback + ", the operator's are refused";
      s.problems.insert(s.problems.begin(), not_used.begin(), not_used.end());
      s.problems.insert(s.problems.begin(), s.refused);
      own = std::move(s);
      return true;
    } catch (const std::exception& e) {
      not_used.push_back(what + " not used: " + (kept ? config::at_kept_origin(file, e.what()) : std::string(e.what())));
      return false;
    }
  };
  std::error_code ec;
  if (std::filesystem::exists(last_good, ec) && fall_back(last_good, o.config, o, true, "its last good settings"))
    return own;
  // The shipped defaults whole: their own start scene, found beside them.
  KioskOptions shipped = o;
  shipped.scene.clear();
  const std::filesystem::path defaults = data_dir() / "config" / "mallet.toml";
  if (fall_back(defaults, defaults, shipped, false, "the shipped defaults")) return own;
  std::string why = own.error();
  for (const std::string& n : not_used) why += "; " + n;
  return refused(why);
}

}  // namespace mallet::app
