#pragma once
// What the kiosk runs on, loaded the same way at start-up and on every reload (SIGHUP, the
// operator page's S): the settings with their drop-ins, the scene, and the [scenes] choices
// checked one by one, so that one bad entry is skipped (and shown on the operator page)
// instead of blocking the others.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/kiosk/kiosk.hpp"
#include "core/app_config.hpp"
#include "core/config/settings_files.hpp"
#include "core/result.hpp"
#include "core/scene.hpp"

namespace mallet::app {

struct KioskSetup {
  AppConfig config;
  Scene scene;
  std::string settings_line;                          //!< where the settings came from
  std::vector<std::filesystem::path> scene_choices;  //!< [scenes] choices that load, resolved
  //! Problems the kiosk runs despite, for the log and the operator page: drop-ins and scene
  //! choices refused, each one line naming the file, the place and the problem.
  std::vector<std::string> problems;
  //! The operator's settings as they merged (config::show_settings' text), to keep as the
  //! last good settings; empty when the kiosk runs on a fallback.
  std::string kept_settings;
  //! At a start whose settings were refused: the one line that says so (the file, the line,
  //! the problem, and what the kiosk runs on instead); empty otherwise.
  std::string refused;
  //! What it runs on then: "its last good settings (PATH)" or "the shipped defaults (PATH)".
  std::string fallback;
};

//! The file in the state folder where the kiosk keeps its last good settings.
inline constexpr const char* kLastGoodSettings = "last-good-settings.toml";

//! The text kept as the last good settings: `setup.kept_settings` under a header saying what
//! the file is; empty when there is nothing to keep (a fallback).
std::string last_good_text(const KioskSetup& setup);

//! The scene file named by `[scenes] start` (or a choice): a missing one is a FileError
//! against the settings line that named it.
std::filesystem::path named_scene(const std::optional<std::filesystem::path>& settings, const std::string& name,
                                  const FilePlace& named_at, const char* key);

//! Loads everything `options` names (options.scene, or [scenes] start). Throws FileError
//! for a bad settings file or scene.
KioskSetup load_kiosk_setup(const KioskOptions& options);

//! As load_kiosk_setup, for a reload: the setup, or the one-line reason, whatever was thrown
//! — a reload never ends the kiosk.
Result<KioskSetup, std::string> load_setup(const KioskOptions& options);

//! The kiosk's start with a display (and what the doctor says it would run on): the
//! operator's settings as a reload loads them (load_setup); when they are refused, the same
//! route with the last good settings kept at `last_good` (read as if they were the
//! operator's file, so that relative paths and scenes resolve as before, no drop-ins), else
//! with the shipped defaults (data_dir()/config/mallet.toml, no drop-ins, their own start
//! scene). The setup then says so in `refused` (also the first of its `problems`) and
//! `fallback`; a last good file that did not load either is one more problem. Refused only
//! when the shipped defaults do not load either: every reason, joined.
Result<KioskSetup, std::string> start_setup(const KioskOptions& options, const std::filesystem::path& last_good);

}  // namespace mallet::app
