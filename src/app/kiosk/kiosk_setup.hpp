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
};

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

}  // namespace mallet::app
