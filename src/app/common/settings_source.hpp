#pragma once
// The settings every command reads, found the same way as the kiosk finds them: --config
// (default: the operator's mallet.toml, data_paths.hpp) merged with the drop-ins of
// --config-dir (default: the file's own drop-in folder, mallet.toml.d beside it), and said
// on stderr: which file, which drop-ins, and each drop-in refused.
#include <filesystem>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "core/config/settings_files.hpp"

namespace mallet::app {

//! Adds --config and --config-dir to `cmd`; `file` should hold its default (default_settings()).
void add_settings_options(CLI::App& cmd, std::optional<std::filesystem::path>& file,
                          std::optional<std::filesystem::path>& drop_in_dir);

//! The drop-in folder used: `drop_in_dir` if given, else FILE.d, else <config>/mallet.toml.d.
std::filesystem::path drop_in_dir_for(const std::optional<std::filesystem::path>& file,
                                      const std::optional<std::filesystem::path>& drop_in_dir);

//! Loads the settings (a bad settings file throws ConfigError, as before; a bad drop-in is
//! refused alone and listed in `refused`): the file, then the drop-ins of its folder and those
//! the kiosk measured (the state folder's measured.d: data_paths.hpp), in the order of their
//! names.
config::LoadedSettings operator_settings(const std::optional<std::filesystem::path>& file,
                                         const std::optional<std::filesystem::path>& drop_in_dir);

//! Says on stderr where the settings came from (after `info_prefix`) and each drop-in refused
//! (after `warning_prefix`): the kiosk's journald priorities, or a command's name.
void say_settings(const config::LoadedSettings& s, const std::string& info_prefix, const std::string& warning_prefix);

//! A command's settings (`mallet COMMAND`), said on stderr as "mallet COMMAND: settings: ..."
//! once the command has succeeded (commands.hpp: say_when_done).
AppConfig command_settings(const std::optional<std::filesystem::path>& file,
                           const std::optional<std::filesystem::path>& drop_in_dir, const std::string& command);

}  // namespace mallet::app
