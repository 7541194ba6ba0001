#pragma once
// Where the shipped data and the operator's settings are found.
//
// data_dir() (models/, shaders/, config/ as shipped): $MALLET_DATA_DIR; else
// <dir of /proc/self/exe>/../share/mallet when it holds config/materials.toml (the
// installed package, or one unpacked with `dpkg -x` into any root); else the source tree
// this binary was built from; else /usr/share/mallet.
//
// config_dir() (the operator's editable settings: mallet.toml, materials.toml,
// instruments.toml, scenes/, trajectories/): for an installed binary, <exe>/../../etc/mallet
// (/etc/mallet for /usr/bin/mallet, ROOT/etc/mallet in an unpacked root) when that folder
// exists; in every other case <data>/config — so the source tree and $MALLET_DATA_DIR
// (the tests) behave as before.
//
// state_dir() (what the kiosk writes and keeps: calibration.toml): $MALLET_STATE_DIR (tests);
// else $STATE_DIRECTORY, which systemd sets from the unit's StateDirectory=mallet
// (/var/lib/mallet); else /var/lib/mallet for an installed binary when that folder exists;
// else $XDG_STATE_HOME/mallet, else ~/.local/state/mallet. It may not exist yet: writers
// create it.
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>

#ifndef MALLET_SOURCE_DATA_DIR
#define MALLET_SOURCE_DATA_DIR ""
#endif

namespace mallet {

struct DataPaths {
  std::filesystem::path data;    //!< models/, shaders/, config/ (the shipped defaults)
  std::filesystem::path config;  //!< the operator's settings
};

//! <prefix> of the running <prefix>/bin/mallet (its real path: links resolved); empty if unknown.
inline std::filesystem::path executable_prefix() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec || !exe.is_absolute()) return {};
  return exe.parent_path().parent_path();
}

inline DataPaths data_paths() {
  namespace fs = std::filesystem;
  std::error_code ec;
  auto holds_data = [&ec](const fs::path& dir) { return fs::exists(dir / "config" / "materials.toml", ec); };
  // Installed: the settings in <root>/etc/mallet if the package put them there.
  auto installed = [&ec](const fs::path& data, const fs::path& etc) -> DataPaths {
    return {data, fs::is_directory(etc, ec) ? etc : data / "config"};
  };

  if (const char* env = std::getenv("MALLET_DATA_DIR"); env && *env) return {env, fs::path(env) / "config"};
  if (const fs::path prefix = executable_prefix(); !prefix.empty() && holds_data(prefix / "share" / "mallet"))
    return installed(prefix / "share" / "mallet", prefix.parent_path() / "etc" / "mallet");
  if (const fs::path source = MALLET_SOURCE_DATA_DIR; !source.empty() && holds_data(source))
    return {source, source / "config"};
  return installed("/usr/share/mallet", "/etc/mallet");
}

inline std::filesystem::path data_dir() { return data_paths().data; }
inline std::filesystem::path config_dir() { return data_paths().config; }

inline std::filesystem::path default_scene() { return config_dir() / "scenes" / "percussion.toml"; }

//! A scene named in the settings ([scenes] start / choices): relative names are files in the
//! scenes/ folder next to the settings file if it has one, else the shipped scenes/.
inline std::filesystem::path scene_file(const std::optional<std::filesystem::path>& settings,
                                        const std::string& name) {
  const std::filesystem::path p(name);
  if (p.is_absolute()) return p;
  std::error_code ec;
  if (settings && std::filesystem::exists(settings->parent_path() / "scenes" / p, ec))
    return settings->parent_path() / "scenes" / p;
  return config_dir() / "scenes" / p;
}

//! The kiosk's settings file when there is one (<config>/mallet.toml); else the built-in
//! defaults apply (they equal the shipped file).
inline std::optional<std::filesystem::path> default_settings() {
  std::error_code ec;
  const std::filesystem::path file = config_dir() / "mallet.toml";
  if (std::filesystem::exists(file, ec)) return file;
  return std::nullopt;
}

//! Where the kiosk keeps its own state (see the top of this file).
inline std::filesystem::path state_dir() {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (const char* env = std::getenv("MALLET_STATE_DIR"); env && *env) return env;
  // systemd may list several folders, separated by ':'; ours is the only one.
  if (const char* env = std::getenv("STATE_DIRECTORY"); env && *env) {
    const std::string dirs = env;
    return dirs.substr(0, dirs.find(':'));
  }
  if (const fs::path prefix = executable_prefix();
      !prefix.empty() && fs::exists(prefix / "share" / "mallet" / "config" / "materials.toml", ec) &&
      fs::is_directory("/var/lib/mallet", ec))
    return "/var/lib/mallet";
  if (const char* env = std::getenv("XDG_STATE_HOME"); env && *env) return fs::path(env) / "mallet";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".local" / "state" / "mallet";
  return fs::temp_directory_path(ec) / "mallet-state";
}

//! The kiosk's camera → screen calibration (written by its calibration screen).
inline std::filesystem::path calibration_path() { return state_dir() / "calibration.toml"; }
//! The actuator's measured chain and its inverse (core/actuator_eq_file.hpp).
inline std::filesystem::path actuator_eq_path() { return state_dir() / "actuator_eq.toml"; }
//! The sound card's latency as last measured (core/latency_record.hpp).
inline std::filesystem::path latency_record_path() { return state_dir() / "latency.toml"; }
//! The display's latency as last measured (core/display_latency_record.hpp).
inline std::filesystem::path display_latency_path() { return state_dir() / "display_latency.toml"; }
//! Settings the kiosk measured and the operator confirmed (the display's latency): drop-ins
//! in its own, writable, state folder, merged with the settings' drop-ins in the order of
//! their names (app/common/settings_source.hpp).
inline std::filesystem::path measured_settings_dir() { return state_dir() / "measured.d"; }

}  // namespace mallet
