#pragma once
// `mallet doctor`: everything a kiosk needs, checked in one go, one line a check (ok, warn,
// fail; what was found; how to fix it). The command opens each device itself; the operator
// page's D (a kiosk that already holds the display, the sound card and the remote) passes
// what it knows of them instead and runs the rest of the checks the same way.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/app_config.hpp"
#include "core/doctor_check.hpp"

namespace mallet::audio {
class PortAudioOutput;
}

namespace mallet::app {

struct DoctorOptions {
  std::optional<std::filesystem::path> config;      //!< the settings file (default: the operator's)
  std::optional<std::filesystem::path> config_dir;  //!< its drop-ins
  std::string device;                               //!< Vulkan device (substring of its name)
  double remote_wait_s = 4.0;                       //!< how long a found remote may take to start its camera
  double camera_wait_s = 2.0;                       //!< how long a V4L2 camera is watched (rate, LED)
  //! The checks to run and print, by name (doctor_check_names()); empty: every one. A device
  //! not named is not opened (`--only wiimote,hidraw` draws no frame and opens no sound card).
  std::vector<std::string> only;
};

//! Every check's name, in the order the doctor prints them.
const std::vector<std::string>& doctor_check_names();

//! What the running kiosk already knows of its devices (the operator page).
struct KioskDeviceFacts {
  DoctorCheck vulkan;
  DoctorCheck audio;
  DoctorCheck wiimote;
  DoctorCheck camera;
  std::optional<std::string> connected_remote;  //!< its identity, for the calibration check
  //! Why the kiosk's last write into its state folder failed (state_folder.hpp); empty: it
  //! did not, or the doctor runs alone (it then tries a write of its own).
  std::string state_problem;
  //! The language on the kiosk's screen now (the operator page's L may have changed it from
  //! the settings'); empty: the doctor runs alone, and the settings' is what shows.
  std::string shown_language;
};

//! The render nodes in /dev/dri (renderD*), each with its kernel driver
//! (/sys/class/drm/renderD*/device/driver), in order of their names.
std::vector<RenderNode> render_nodes();

//! Whether Vulkan finds a GPU (a device that is not the CPU, e.g. not lavapipe); none when
//! no instance can be made or no device is found.
std::optional<bool> vulkan_finds_gpu();

//! The renderer the kiosk's compositor uses (core/doctor_check.hpp: compositor_renderer)
//! on this machine: its render nodes, whether Vulkan finds a GPU, and $WLR_RENDERER. With `ask_unit` and systemd running,
//! a WLR_RENDERER set in mallet-session.service's environment (an operator's drop-in) when
//! this process has none. `mallet doctor --print-renderer` prints its renderer (mallet-session
//! exports it as WLR_RENDERER).
CompositorRenderer kiosk_compositor_renderer(bool ask_unit);

//! The wiimote check where no Wii Remote is held, in the one wording `mallet doctor` and the
//! operator page's D share: "not used" (ok) for a mouse, replay or camera source; "no Wii
//! Remote connected", a warning for "auto" (the kiosk plays with the mouse) and a failure for
//! "wiimote".
DoctorCheck wiimote_without_remote(const std::string& source);

//! The audio check of an output as the kiosk opened it (its device, rate, latency and the
//! settings' routing), in the one wording `mallet doctor` and the operator page's D print.
DoctorCheck judge_audio_output(const AppConfig& config, const audio::PortAudioOutput& output);
//! The audio check where no output opened, `why` as the open said it.
DoctorCheck audio_missing(const std::string& why);

//! Every check (or those `options.only` names), each device opened and released again. Never
//! throws: a probe that fails is a `fail` line.
std::vector<DoctorCheck> run_doctor(const DoctorOptions& options);

//! The checks that open no device (the compositor's renderer, settings, scenes, models,
//! soundfont, hidraw access, calibration, disk, service, watchdog), with the kiosk's own
//! device facts.
std::vector<DoctorCheck> run_doctor_with(const DoctorOptions& options, const KioskDeviceFacts& facts);

//! The same checks as JSON: {"checks": [{"name", "status", "found", "fix"}...], "ok": N, "warn": N, "fail": N}.
std::string doctor_json(const std::vector<DoctorCheck>& checks);

}  // namespace mallet::app
