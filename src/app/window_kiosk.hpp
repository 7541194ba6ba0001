#pragma once
// The kiosk on a display: a GLFW window (fullscreen and borderless unless windowed), the
// scene, the mouse as the mallet, sound and actuator signal on the PortAudio device, and
// the kiosk's states (src/core/kiosk_states.hpp): Attract (the ghost player and the
// invitation), Play, and the operator page behind the chord Ctrl+Alt+O.
//
// The operator page: input, audio device and latency, frame time, uptime, the volume and
// the actuator gain (the paper's amplifier knob, in software), recalibrate, quit. Keys on
// the page: Up/Down volume, Left/Right actuator gain, R recalibrate, Q quit, Esc close.
// Visitors cannot leave the app: the window's close request is refused outside the page.
//
// SIGHUP reloads the settings and the scene; an invalid new file is refused with its
// reason on stderr and the running configuration stays.
//
// Faults: a lost audio device is survived (silent, retried by PortAudioOutput); an
// out-of-date swapchain is recreated (WindowTarget). A lost GPU device
// (VK_ERROR_DEVICE_LOST) is not recovered in-process: the RenderError ends the run with
// exit status 1, and systemd (Restart=always, RestartSec=2) starts a fresh kiosk.
#include <filesystem>
#include <optional>

#include "app/kiosk.hpp"
#include "core/app_config.hpp"
#include "core/scene.hpp"

namespace mallet::app {

//! Returns the process's exit status: 0 for an operator's quit.
int run_window_kiosk(const KioskOptions& options, Scene scene, AppConfig config);

//! Installs the SIGHUP handler; reload_requested() reports (and clears) a pending request.
void watch_for_reload();
bool reload_requested();

struct KioskSetup {
  AppConfig config;
  Scene scene;
};

//! Loads the settings and scene as `mallet run` does. On a bad file: nothing, and `why`
//! holds its one-line error.
std::optional<KioskSetup> load_setup(const KioskOptions& options, std::string& why);

}  // namespace mallet::app
