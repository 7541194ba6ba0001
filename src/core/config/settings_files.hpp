#pragma once
// The kiosk's settings as an operator's IT manages them: one file (mallet.toml) and a
// drop-in folder beside it (mallet.toml.d/*.toml), merged over the file in lexical order of
// their names, key by key, as systemd and many Debian tools do. A later file's value
// replaces an earlier one's; a table merges key by key; an array is replaced whole.
//
// A drop-in that cannot be read, or whose values the merged settings refuse, is refused
// alone with its file and line: the file and the other drop-ins stay in force. A bad
// mallet.toml itself is still a ConfigError, as before.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/app_config.hpp"

namespace mallet::config {

struct LoadedSettings {
  AppConfig config;
  std::optional<std::filesystem::path> file;     //!< the settings file; none: built-in defaults
  std::vector<std::filesystem::path> drop_ins;   //!< applied, in the order they were merged
  std::vector<std::string> refused;              //!< one line per drop-in refused: FILE:LINE: problem

  //! Where the settings came from, e.g.
  //! "/etc/mallet/mallet.toml + 2 drop-ins (10-volume.toml, 20-audio.toml)".
  std::string describe() const;
};

//! The drop-in folder of a settings file: FILE.d (mallet.toml → mallet.toml.d).
std::filesystem::path drop_in_dir_of(const std::filesystem::path& settings_file);

//! The `*.toml` files in `dir` (regular files only), in lexical order of their names; none
//! when the folder does not exist.
std::vector<std::filesystem::path> drop_in_files(const std::filesystem::path& dir);

//! Reads `file` (none: the built-in defaults), then merges each drop-in of `drop_ins` over
//! it in order. Throws ConfigError only for a bad `file`.
LoadedSettings load_settings(const std::optional<std::filesystem::path>& file,
                             const std::vector<std::filesystem::path>& drop_ins);

//! Settings kept as one merged file (the kiosk's last good settings, show_settings' text),
//! read as if they were `as_if`: their relative paths (a replay file, [metrics] textfile,
//! [study] files) resolve against as_if's folder, as they did in the files they came from
//! (none: against the kept file's own folder). Throws ConfigError for a bad file.
LoadedSettings load_kept_settings(const std::filesystem::path& kept, const std::optional<std::filesystem::path>& as_if);

//! `message` with each place in the kept settings `kept` ("KEPT:LINE:", as an error names
//! it) named as the operator's own file and line that setting was kept from (its line's
//! `# from FILE:LINE`, show_settings), the kept place after it in brackets: a problem is
//! fixed in the operator's file, not in the generated one. Unchanged where the kept line
//! names no origin or cannot be read.
std::string at_kept_origin(const std::filesystem::path& kept, const std::string& message);

//! The merged TOML of what `settings` applied (its file, then its accepted drop-ins), each
//! key followed by `# from FILE`; keys no file sets keep their built-in defaults and are
//! not listed.
std::string show_settings(const LoadedSettings& settings);

}  // namespace mallet::config
