#include "app/common/settings_source.hpp"

#include <algorithm>
#include <cstdio>

#include "app/common/command_support.hpp"
#include "core/data_paths.hpp"

namespace mallet::app {

void add_settings_options(CLI::App& cmd, std::optional<std::filesystem::path>& file,
                          std::optional<std::filesystem::path>& drop_in_dir) {
  cmd.add_option("--config", file,
                 "Settings file (default: " + (file ? file->string() : std::string("built-in, same as config/mallet.toml")) +
                     ")");
  cmd.add_option("--config-dir", drop_in_dir,
                 "Drop-in folder: its *.toml files are merged over the settings in lexical order, key by key "
                 "(default: the settings file's name + .d, e.g. /etc/mallet/mallet.toml.d)")
      ->check(CLI::ExistingDirectory);
}

std::filesystem::path drop_in_dir_for(const std::optional<std::filesystem::path>& file,
                                      const std::optional<std::filesystem::path>& drop_in_dir) {
  if (drop_in_dir) return *drop_in_dir;
  if (file) return config::drop_in_dir_of(*file);
  return config_dir() / "mallet.toml.d";
}

config::LoadedSettings operator_settings(const std::optional<std::filesystem::path>& file,
                                         const std::optional<std::filesystem::path>& drop_in_dir) {
  // The operator's drop-ins and those the kiosk measured (the state folder's: the kiosk may
  // not write /etc), in the order of their names, as systemd orders a unit's.
  std::vector<std::filesystem::path> drop_ins = config::drop_in_files(drop_in_dir_for(file, drop_in_dir));
  for (const std::filesystem::path& m : config::drop_in_files(measured_settings_dir())) drop_ins.push_back(m);
  std::stable_sort(drop_ins.begin(), drop_ins.end(), [](const std::filesystem::path& a, const std::filesystem::path& b) {
    return a.filename().string() < b.filename().string();
  });
  return config::load_settings(file, drop_ins);
}

void say_settings(const config::LoadedSettings& s, const std::string& info_prefix, const std::string& warning_prefix) {
  std::fprintf(stderr, "%ssettings: %s\n", info_prefix.c_str(), s.describe().c_str());
  for (const std::string& r : s.refused) std::fprintf(stderr, "%s%s\n", warning_prefix.c_str(), r.c_str());
}

AppConfig command_settings(const std::optional<std::filesystem::path>& file,
                           const std::optional<std::filesystem::path>& drop_in_dir, const std::string& command) {
  config::LoadedSettings s = operator_settings(file, drop_in_dir);
  say_when_done("mallet " + command + ": settings: " + s.describe());
  for (const std::string& r : s.refused) say_when_done("mallet " + command + ": warning: " + r);
  return std::move(s.config);
}

}  // namespace mallet::app
