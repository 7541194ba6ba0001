#pragma once
// The kiosk on a display: a GLFW window (fullscreen and borderless unless windowed), the
// scene, the mallet driven by the Wii Remote or the mouse ([input] source: "auto" takes a
// remote found at start-up, else the mouse, and says so on screen; "replay" plays a
// recording through the same device path as a remote), sound and actuator
// signal on the PortAudio device, and the kiosk's states (src/core/kiosk_states.hpp):
// Attract (the ghost player and the invitation), Play, Calibration and the operator page
// behind the chord Ctrl+Alt+O.
//
// Threads: the mouse and the ghost are read and struck on this (main, render) thread; the
// Wii Remote's samples are struck on the remote's own reading thread (RemotePointer, the
// device's sample sink), which posts to the audio engine's second ring, so an impact never
// waits for a frame. The main thread takes the remote's samples once a frame for the states
// (movement, tracking lost) and the calibration screen.
//
// Calibration (calibration_screen.hpp): entered by R on the operator page, or at
// start-up once the remote's link runs, when no valid calibration file is in state_dir()
// or it names another remote. Accepted → saved atomically and used at once; abandoned or
// failed → the previous one stays. With the mouse as input the screen runs with the mouse
// as the dot and saves nothing.
//
// The operator page (operator_page.hpp: its keys, its panel, the doctor's view;
// latency_test.hpp): input, audio device and latency, frame time, uptime, the volume and
// the actuator gain (the paper's amplifier knob, in software), recalibrate, quit. Keys on
// the page: Up/Down volume, Left/Right actuator gain, R recalibrate, Q quit, Esc close.
// Visitors cannot leave the app: the window's close request is refused outside the page.
//
// This file is the frame loop: input → states → strikes → picture, once a frame. What it
// plays with is a KioskStage (kiosk_stage.hpp), its input chosen by input_choice.hpp; its
// liveness and metrics are KioskHealth's (kiosk_health.hpp).
//
// SIGHUP reloads the settings (with their drop-ins) and the scene; an invalid new file is
// refused with its reason on stderr and on the operator page, and the running configuration
// stays. At start, settings that are refused do not keep the kiosk dark: run_kiosk starts it
// on its last good settings or the shipped defaults (kiosk_setup.hpp: start_setup), with the
// refusal first on the operator page; each start or reload that loads keeps its settings as
// the last good ones in the state folder (state_folder.hpp: written atomically, a failure
// said once, the kiosk plays on). SIGTERM (systemd's
// stop) ends the loop as the operator's Q does: a closing log line and exit status 0.
//
// Faults: a Wii Remote that is gone → Attract with the remote-missing hint, reconnected by
// WiimoteDevice (it never gives up); a lost audio device is survived (silent, retried by PortAudioOutput); an
// out-of-date swapchain is recreated (WindowTarget). A lost GPU device
// (VK_ERROR_DEVICE_LOST) is recovered in-process: the scene renderer and the window's
// Vulkan context, pipeline cache and swapchain are made anew on the same window, the sound
// and the strikes of the reading threads go on meanwhile, and the loss is logged and
// counted (mallet_render_device_lost_total). Only when no new device can be made (five
// tries, a second apart) does the RenderError end the run with exit status 1, and systemd
// (Restart=always, RestartSec=2) starts a fresh kiosk.
#include <filesystem>
#include <optional>

#include "app/kiosk/kiosk.hpp"
#include "app/kiosk/kiosk_setup.hpp"
#include "core/app_config.hpp"
#include "core/scene.hpp"

namespace mallet::app {

//! Returns the process's exit status: 0 for an operator's quit, or for a stop systemd asks
//! for (SIGTERM).
int run_window_kiosk(const KioskOptions& options, KioskSetup setup);

//! Installs the SIGHUP handler; reload_requested() reports (and clears) a pending request.
void watch_for_reload();
bool reload_requested();

}  // namespace mallet::app
