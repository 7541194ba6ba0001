// `mallet camera ...`: the operator's window into a V4L2 camera as the IR tracker.
#include <atomic>
#include <cstdio>
#include <memory>
#include <string>

#include "app/cli/commands.hpp"
#include "app/common/settings_source.hpp"
#include "app/kiosk/camera_monitor.hpp"
#include "core/data_paths.hpp"
#include "input/camera/camera_device.hpp"
#include "input/camera/v4l2_grabber.hpp"
#include "input/camera/v4l2_node.hpp"
#include "input/clock.hpp"

namespace mallet::app {

namespace cam = mallet::input::camera;

namespace {

void add_list(CLI::App& camera) {
  auto dir = std::make_shared<std::string>(cam::kDefaultVideoDir);
  CLI::App* cmd = camera.add_subcommand("list", "List the cameras (V4L2 capture devices) and what each offers");
  cmd->footer(R"(Lists every video capture node under /dev (video0, video1, ...) that streams: its path,
name, driver and bus, then each pixel format with its sizes and frame rates, and the
exposure and gain controls with their ranges and values now, e.g.
  /dev/video0  "USB Camera"  uvcvideo  usb-0000:00:14.0-2
    GREY 8-bit Greyscale
         640x480: 240, 120, 60 Hz
    control exposure 1..5000 (100 µs), now 5
Mallet reads GREY, YUYV and MJPG; other formats are marked. A UVC camera's second
node (its metadata) does not capture and is not listed. When none is found it says so
and still exits 0: "none found" is an answer, not a failure.)");
  cmd->add_option("--dir", *dir, "Where to look for video* nodes")->capture_default_str();
  cmd->callback([dir] {
    const std::string out = format_camera_list(cam::scan_cameras(*dir), *dir);
    std::fwrite(out.data(), 1, out.size(), stdout);
  });
}

struct CameraMonitorCli {
  CameraMonitorOptions options;
  std::optional<std::filesystem::path> config = default_settings();
  std::optional<std::filesystem::path> config_dir;
  std::string device;
  std::string dir = cam::kDefaultVideoDir;
};

void camera_monitor_command(const CameraMonitorCli& cli) {
  if (!(cli.options.seconds >= 0 && cli.options.seconds <= 1e7))
    throw CLI::ValidationError("--seconds", "must be >= 0 (0 = until Ctrl+C)");
  const AppConfig config = command_settings(cli.config, cli.config_dir, "camera monitor");
  CameraConfig camera = config.camera;
  if (!cli.device.empty()) camera.device = cli.device;
  input::SteadyClock clock;
  cam::CameraDevice device(std::make_unique<cam::V4l2Grabber>(camera, cli.dir), clock, cam::camera_device_config(config));
  finish_with(run_until_interrupted([&](const std::atomic<bool>& interrupted) {
    return run_camera_monitor(device, clock, cli.options, interrupted, stdout);
  }));
}

void add_monitor(CLI::App& camera) {
  auto cli = std::make_shared<CameraMonitorCli>();
  CLI::App* cmd = camera.add_subcommand(
      "monitor", "Watch the camera as the kiosk reads it: its mode, the rate achieved, the LED's position and noise");
  cmd->footer(R"X(Opens the camera as the kiosk does ([camera] of the settings: device, size, rate_hz,
exposure_us, gain, format; --device overrides the device) and prints one line about
every 0.1 s, times since the start:
     1.200 s  streaming   240.0 Hz  frames 288  dropped 0  led 312.45,240.10 (9 px)
  Hz        frames stamped in the last second: the rate achieved
  dropped   frames the driver's sequence numbers skipped
  led       the LED's centroid in camera pixels (subpixel) and its area; "no led"
Tracking changes are printed as they happen. A camera that cannot be opened or is
unplugged is looked for again every second ("searching (why)").
Runs until --seconds have passed or Ctrl+C, then prints a summary: the mode the
camera agreed to, the rate achieved, dropped and unreadable frames, the exposure and
gain in force, how frames are stamped (the kernel's stamp moved to mid-exposure), and
the LED's spread in px RMS, which is the centroid's noise when the LED is held still.
Exit 0 if the camera was open at some point, 1 if never (the reason is printed).)X");
  cmd->add_option("--seconds", cli->options.seconds, "Stop after this many seconds (0 = until Ctrl+C)");
  cmd->add_option("--device", cli->device,
                  "A /dev/video* node or a part of the camera's name (default: [camera].device)")
      ->type_name("D");
  cmd->add_option("--dir", cli->dir, "Where \"auto\" and a name look for video* nodes")->capture_default_str();
  add_settings_options(*cmd, cli->config, cli->config_dir);  // [camera], [tracking]
  cmd->callback([cli] { camera_monitor_command(*cli); });
}

}  // namespace

void register_camera(CLI::App& app) {
  CLI::App* camera =
      app.add_subcommand("camera", "A V4L2 camera as the IR tracker: list cameras, monitor one");
  camera->require_subcommand(1);
  add_list(*camera);
  add_monitor(*camera);
}

}  // namespace mallet::app
