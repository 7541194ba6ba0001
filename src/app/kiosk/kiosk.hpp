#pragma once
// `mallet run`: the kiosk. With a display: a window (fullscreen and borderless unless
// windowed) showing the scene, the mouse as the mallet, sound and actuator signal on the
// PortAudio device, and the attract mode's ghost player whenever nobody has played for a
// while. Without a display (or --headless): the same loop offscreen on a simulated clock,
// the attract loop playing into a WAV file; writes screenshot.png, audio.wav, log.txt.
#include <filesystem>
#include <optional>
#include <string>

#include "app/kiosk/visitor_sessions.hpp"

namespace mallet::app {

struct KioskOptions {
  std::filesystem::path scene;                  //!< empty = [scenes] start of the settings
  std::optional<std::filesystem::path> config;      //!< the settings file (none: built-in defaults)
  std::optional<std::filesystem::path> config_dir;  //!< its drop-ins (none: FILE.d)
  bool headless = false;
  bool windowed = false;
  double seconds = 10.0;                        //!< headless: how long the loop runs
  std::filesystem::path out_dir;                //!< headless: empty = a new folder, named on stdout
  std::string size = "1280x720";                //!< headless image / windowed window size
  std::optional<double> idle_after_s;           //!< overrides [attract].idle_after_s
  double quit_after_s = 0;                      //!< window: quit after this long (0 = never)
  std::string device;                           //!< Vulkan device (substring of its name)
  bool no_frame_cap = false;                    //!< window: frames as fast as they come (for measuring)
  VisitorSessions visitor_sessions;             //!< window: the study's ([study] visitor_protocol); empty: none
  //! `mallet calibrate latency --photodiode CH`: [timing] photodiode_channel and
  //! photodiode_input overridden, the operator page open and its latency test (T) run at
  //! once, and the kiosk ends once the operator answered (0), or when nothing usable was
  //! measured (2).
  struct DisplayLatencyRun {
    int photodiode_channel = 1;  //!< from 1
    std::string input;           //!< "" = the default input
  };
  std::optional<DisplayLatencyRun> measure_display_latency;
};

//! Returns the process exit status.
int run_kiosk(const KioskOptions& options);

}  // namespace mallet::app
