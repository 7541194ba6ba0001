#include "app/kiosk/input_choice.hpp"

#include <cstdio>

#include <fmt/format.h>

#include "core/camera_prediction.hpp"
#include "core/data_paths.hpp"
#include "core/journal.hpp"
#include "core/saved_calibration.hpp"
#include "core/strike_line.hpp"
#include "input/camera/v4l2_grabber.hpp"

namespace mallet::app {

namespace {

//! evdev when it can be opened, else the window system's events.
void choose_mouse(KioskStage& stage, const InputDevices& devices) {
  const InputConfig& in = stage.config.input;
  if (in.mouse == "window") {
    stage.mouse_line = "mouse: the window system's events, once a frame (the settings say window)";
    return;
  }
  input::evdev::EvdevMouseConfig mc;
  mc.screen_width_px = static_cast<int>(devices.window.window->extent().width);
  mc.screen_height_px = static_cast<int>(devices.window.window->extent().height);
  input::evdev::EvdevOpenResult opened =
      input::evdev::EvdevMouse::open(in.mouse_device.empty() ? input::evdev::kAutoDevice : in.mouse_device, mc);
  if (!opened) {
    stage.mouse_line = "mouse: the window system's events, once a frame (evdev: " + opened.error() + ")";
    // Asked for by name: said as a warning; the window system's events keep the kiosk playable.
    if (in.mouse == "evdev")
      journal::warning("[input] mouse = \"evdev\" could not be opened: {}", opened.error().c_str());
    return;
  }
  stage.evdev = std::move(*opened);
  stage.mouse = std::make_unique<MousePointer>(stage.scene, stage.config, *stage.rig.engine,
                                               &devices.window.window->present_clock(), &devices.window.aspect);
  stage.mouse->on_strike = [t = stage.tally.get()](const Strike& s) { t->record(s.impact); };
  if (devices.last_cursor) stage.evdev->warp(devices.last_cursor->x, devices.last_cursor->y);
  stage.mouse_line = stage.evdev->describe() + ", each report stamped by the kernel";
}

//! The saved calibration (camera → screen), its status line, and a warning when it was refused.
void load_calibration(KioskStage& stage) {
  SavedCalibration saved = load_saved_calibration(calibration_path());
  stage.calibration = std::move(saved.calibration);
  stage.calibration_status = std::move(saved.status);
  if (!saved.warning.empty()) journal::warning("{}", saved.warning.c_str());
}

//! The IR tracker's pointer (the remote's or the camera's): the route on `route_config`,
//! which must live as long as the stage, with the calibration in use.
void make_remote_pointer(KioskStage& stage, const InputDevices& devices, const AppConfig& route_config) {
  stage.remote = std::make_unique<RemotePointer>(stage.scene, route_config, *stage.rig.engine,
                                                 &devices.window.window->present_clock(), &devices.window.aspect);
  stage.remote->set_calibration(stage.calibration);
}

//! A V4L2 camera as the IR tracker: the remote's pointer and calibration, its own reading
//! thread, and the route's prediction tuned for it.
void choose_camera(KioskStage& stage, const InputDevices& devices) {
  stage.source = InputSource::camera;
  stage.input_why = "the settings say camera";
  load_calibration(stage);
  // Contact prediction tuned for the camera: its noise, its rate and its read-out, at the
  // rate asked for (the doctor and the log say when the camera gives less).
  const CameraRouteTiming timing = camera_route_timing(stage.config, stage.scene);
  AppConfig& tuned = stage.camera_route_config.emplace(stage.config);
  tuned.timing.predict = timing.predict;
  if (timing.predict.horizon_ms > 0)
    journal::info("camera: contact prediction tuned for {:g} Hz: fit window {:.2f} ms, noise {:.3f} mm, read-out "
                  "{:.2f} ms{}", stage.config.camera.rate_hz, timing.predict.fit_window_ms, timing.noise_m * 1e3,
                  timing.read_delay_ms, timing.predict.sample_delay_ms > 0 ? " (predicted up to it)" : "");
  make_remote_pointer(stage, devices, tuned);
  stage.camera = std::make_unique<input::camera::CameraDevice>(
      std::make_unique<input::camera::V4l2Grabber>(stage.config.camera), devices.clock,
      input::camera::camera_device_config(stage.config));
  KioskStage* s = &stage;
  stage.remote->on_strike = [s](const Impact& i) { s->tally->record(i); };
  stage.camera->set_sample_sink(
      [s](std::span<const input::wiimote::LedSample> samples, Nanos now) { s->remote->on_samples(samples, now); });
}

}  // namespace

void choose_input(KioskStage& stage, const InputDevices& devices) {
  const std::string& want = stage.config.input.source;
  stage.source = InputSource::mouse;
  if (want == "mouse") {
    stage.input_why = "the settings say mouse";
    choose_mouse(stage, devices);
    return;
  }
  if (want == "camera") {
    choose_camera(stage, devices);
    return;
  }
  if (want == "replay") {
    stage.replay = std::make_unique<input::wiimote::ReplayFinder>(
        input::wiimote::ReplayFinder::open_file(stage.config.input.replay_file, devices.clock));
    stage.source = InputSource::replay;
    stage.input_why = "replay of " + stage.config.input.replay_file;
  } else if (want == "auto") {
    const std::optional<input::wiimote::HidDeviceInfo> found =
        input::wiimote::first_matching(devices.finder.enumerate(), stage.config.wiimote.device);
    if (!found) {
      stage.input_why = "no Wii Remote found at start-up";
      choose_mouse(stage, devices);
      return;
    }
    stage.input_why = "found " + remote_identity(*found);
  } else {
    stage.input_why = "the settings say wiimote";
  }
  if (want != "replay") stage.source = InputSource::wiimote;
  load_calibration(stage);
  if (stage.source == InputSource::replay && !stage.calibration) {
    // A recording without a calibration: the camera's view mirrored onto the whole screen
    // (the camera faces the visitor), so a demo plays at once.
    Calibration c;
    c.camera_to_screen.h = {-1.0 / 1023.0, 0, 1, 0, 1.0 / 767.0, 0, 0, 0, 1};
    stage.calibration = c;
    stage.calibration_status = "calibration: none; the camera's view mirrored onto the screen";
  }
  make_remote_pointer(stage, devices, stage.config);
  input::wiimote::WiimoteDeviceConfig dc = kiosk_device_config(stage.config, stage.calibration);
  if (stage.calibration && !stage.calibration->ir_sensitivity.empty())
    stage.calibration_status_sensitivity = "IR sensitivity " + stage.calibration->ir_sensitivity + " (saved with it)";
  dc.every_frame = true;  // the calibration screen's sensitivity tuner counts every frame's dots
  if (stage.replay) dc.device.clear();  // the recording is the only device
  stage.device = std::make_unique<input::wiimote::WiimoteDevice>(
      stage.replay ? static_cast<input::wiimote::DeviceFinder&>(*stage.replay) : devices.finder, devices.clock, dc);
  KioskStage* s = &stage;
  // The reading thread: strikes go from there through the strike route (RemotePointer);
  // this only pulses the rumble when configured.
  stage.remote->on_strike = [s](const Impact& i) {
    s->tally->record(i);
    s->device->on_impact();
  };
  stage.device->set_sample_sink(
      [s](std::span<const input::wiimote::LedSample> samples, Nanos now) { s->remote->on_samples(samples, now); });
}

std::string camera_identity(const input::camera::CameraMode& mode) { return "camera " + mode.name; }

IrLink ir_link(const KioskStage& s) {
  IrLink link;
  if (s.camera) {
    const input::camera::CameraStatus c = s.camera->status();
    link.present = true;
    link.up = c.connected;
    if (!c.mode.device.empty()) link.identity = camera_identity(c.mode);
    link.problem = c.problem;
    link.drops = c.losses;
    link.last_drop = c.last_loss;
  } else if (s.device) {
    const input::wiimote::WiimoteState w = s.device->state();
    link.present = true;
    link.up = w.link == input::wiimote::LinkState::running;
    link.identity = remote_identity(w.device);
    link.problem = w.problem;
    link.drops = w.disconnects;
    link.last_drop = w.last_drop;
  }
  return link;
}

void start_ir_tracker(KioskStage& stage) {
  if (stage.device) stage.device->start();
  if (stage.camera) stage.camera->start();
}

void stop_ir_tracker(KioskStage& stage) {
  if (stage.device) stage.device->stop();
  if (stage.camera) stage.camera->stop();
}

std::string input_line(const KioskStage& s) {
  if (s.camera) {
    const input::camera::CameraStatus c = s.camera->status();
    std::string line = "input: " + (c.mode.device.empty() ? std::string("camera") : s.camera->describe()) + " (" +
                       s.input_why + ")";
    if (c.connected)
      line += fmt::format(", {:.0f} frames/s{}", c.rate_hz, c.led_seen ? ", LED seen" : ", no LED");
    else
      line += ", not streaming (" + c.problem + ")";
    return line;
  }
  if (s.source == InputSource::mouse) {
    std::string line = "input: mouse (" + s.input_why + "); " + s.mouse_line;
    if (s.evdev) {
      const input::evdev::EvdevMouseStatus m = s.evdev->status();
      line += m.connected ? fmt::format(", {:.0f} reports/s", m.rate_hz) : ", lost: " + m.problem;
    }
    return line;
  }
  const input::wiimote::WiimoteState w = s.device->state();
  // Before the link runs the remote has no identity yet: why it was chosen says which.
  const std::string id = remote_identity(w.device);
  std::string line = s.replay ? "input: " + s.input_why + ", " + to_string(w.link)
                              : "input: Wii Remote " + (id.empty() ? "(" + s.input_why + ")" : id) + ", " +
                                    to_string(w.link);
  if (w.link == input::wiimote::LinkState::running) {
    const std::string buf = fmt::format(", {:.0f} reports/s{}", w.remote.ir_rate_hz,
                                        w.tracking ? ", LED seen" : ", no LED");
    line += buf;
  } else if (!w.problem.empty()) {
    line += " (" + w.problem + ")";
  }
  return line;
}

}  // namespace mallet::app
