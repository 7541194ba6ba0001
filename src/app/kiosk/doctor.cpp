#include "app/kiosk/doctor.hpp"

#include <grp.h>
#include <pwd.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <memory>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <system_error>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include "audio/audio_setup.hpp"
#include "core/data_paths.hpp"
#include "app/kiosk/kiosk_setup.hpp"
#include "app/kiosk/state_folder.hpp"
#include "app/strike/remote_pointer.hpp"
#include "app/common/settings_source.hpp"
#include "core/visitor_catalogues.hpp"
#include "app/kiosk/language_check.hpp"
#include "render/render_setup.hpp"
#include "audio/portaudio_output.hpp"
#include "core/calibration_file.hpp"
#include "core/config/scene_config.hpp"
#include "core/visitor_language.hpp"
#include "app/kiosk/input_choice.hpp"
#include "input/camera/camera_device.hpp"
#include "input/camera/v4l2_grabber.hpp"
#include "input/camera/v4l2_node.hpp"
#include "input/clock.hpp"
#include "input/wiimote/hid_transport.hpp"
#include "input/wiimote/wiimote_device.hpp"
#include "render/font_atlas.hpp"
#include "render/gltf_model.hpp"
#include "render/window_target.hpp"

namespace mallet::app {
namespace fs = std::filesystem;
namespace wm = input::wiimote;

namespace {

constexpr const char* kUnit = "mallet.service";

DoctorCheck fail(std::string name, std::string found, std::string fix) {
  return {std::move(name), CheckLevel::fail, std::move(found), std::move(fix)};
}

//! A command's first line of output and its exit status (-1: it could not be run). The
//! commands are fixed strings: nothing from a file or a person reaches the shell.
struct Ran {
  int status = -1;
  std::string out;
};
Ran run(const std::string& command) {
  Ran r;
  FILE* p = ::popen((command + " 2>/dev/null").c_str(), "r");
  if (!p) return r;
  std::array<char, 512> buf{};
  while (std::fgets(buf.data(), buf.size(), p)) r.out += buf.data();
  const int st = ::pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  while (!r.out.empty() && (r.out.back() == '\n' || r.out.back() == ' ')) r.out.pop_back();
  return r;
}

std::size_t count_lines(const std::string& s) {
  return s.empty() ? 0 : static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n')) + 1;
}

std::string ms_text(double s) {
  return fmt::format("{:.1f} ms", s * 1e3);
}

// ---- the devices (the command only) ----

VkExtent2D display_size(std::string& said) {
  if (render::WindowSystem::display_available()) {
    render::WindowSystem ws;
    if (GLFWmonitor* m = glfwGetPrimaryMonitor())
      if (const GLFWvidmode* mode = glfwGetVideoMode(m)) {
        said = "the display";
        return {static_cast<std::uint32_t>(mode->width), static_cast<std::uint32_t>(mode->height)};
      }
  }
  said = "no display here: a 1080p screen assumed";
  return {1920, 1080};
}

DoctorCheck check_vulkan(const DoctorOptions& o, const AppConfig& config, const Scene& scene) {
  try {
    std::string said;
    const render::HeadlessOptions ho = render::kiosk_headless_options(config.render, display_size(said), o.device);
    render::HeadlessRenderer renderer(scene, ho);
    VkPhysicalDeviceProperties props{};
    vkGetPhysicalDeviceProperties(renderer.context().physical_device(), &props);
    // The kiosk's own frame: the mallet over the cached background, with its shadow; the
    // first frames build the background and warm the pipelines, so they are not counted.
    render::FrameState state;
    state.mallet_centre = {0.0, 0.05};
    for (int i = 0; i < 3; ++i) renderer.draw(state);
    constexpr int kFrames = 20;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < kFrames; ++i) {
      state.mallet_centre = {0.002 * i, 0.05};
      renderer.draw(state);
    }
    renderer.read_back();  // waits for the last frame
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / kFrames;
    DoctorCheck c = judge_renderer(renderer.context().device_name(), props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU,
                                   ho.size.width, ho.size.height, ms);
    c.found += " (" + said + ")";
    return c;
  } catch (const std::exception& e) {
    return fail("vulkan", std::string("no usable Vulkan 1.3 device: ") + e.what(),
                "install the GPU's Vulkan driver (mesa-vulkan-drivers; lavapipe draws on the CPU) and check "
                "`vulkaninfo --summary`");
  }
}

DoctorCheck check_audio(const AppConfig& config, const Scene& scene) {
  try {
    // The output exactly as the kiosk opens it: the configured device, rate and routing.
    audio::AudioRig rig = audio::make_audio_rig(scene, config, config.audio.sample_rate_hz, /*acoustic_enabled=*/false);
    const audio::PortAudioOutput output(*rig.engine, config.audio, {});
    return judge_audio_output(config, output);
  } catch (const std::exception& e) {
    return audio_missing(e.what());
  }
}

}  // namespace

DoctorCheck audio_missing(const std::string& why) {
  // The check's name says it is audio: the reason without the output's own "audio: " head,
  // as the page's status line has it after "running silent".
  return fail("audio", why.rfind("audio: ", 0) == 0 ? why.substr(7) : why,
              "connect the sound card and check that ALSA sees it (`aplay -l`), then choose it with [audio] device "
              "(`mallet audio devices` lists them)");
}

DoctorCheck judge_audio_output(const AppConfig& config, const audio::PortAudioOutput& output) {
  {
    const audio::DeviceInfo d = output.device();
    const AudioRouting& r = config.audio.routing;
    const std::string buf = fmt::format(
        "\"{}\" ({}), {:.0f} Hz, output latency {}, {} channels: note on {}, actuator on {} (device has {})", d.name,
        d.host_api, output.sample_rate_hz(), ms_text(output.output_latency_s()), r.channels, r.acoustic, r.actuator,
        d.max_output_channels);
    DoctorCheck c{"audio", CheckLevel::ok, buf, ""};
    if (r.channels > d.max_output_channels) {
      c.level = CheckLevel::fail;
      c.fix = "[audio.routing] channels is more than the device has: lower it, or choose another [audio] device "
              "(`mallet audio devices`)";
    } else if (r.acoustic == r.actuator) {
      c.level = CheckLevel::warn;
      c.fix = "the note and the actuator share a channel: set [audio.routing] acoustic and actuator apart, then "
              "check the wiring with `mallet audio test --channel actuator`";
    } else if (static_cast<int>(output.sample_rate_hz()) != config.audio.sample_rate_hz) {
      c.level = CheckLevel::warn;
      c.fix = "the device runs at another rate than [audio] sample_rate_hz: set it to the device's";
    } else if (output.output_latency_s() > 0.030) {
      c.level = CheckLevel::warn;
      c.fix = "over 30 ms: the actuator is felt late; lower [audio] suggested_latency_ms or frames_per_buffer";
    }
    return c;
  }
}

DoctorCheck wiimote_without_remote(const std::string& source) {
  if (source == "mouse" || source == "replay" || source == "camera")
    return {"wiimote", CheckLevel::ok, "not used: [input] source = \"" + source + "\"", ""};
  return {"wiimote", source == "wiimote" ? CheckLevel::fail : CheckLevel::warn,
          "no Wii Remote connected" + std::string(source == "auto" ? " (the kiosk plays with the mouse instead)" : ""),
          "pair and connect it (bluetoothctl: scan on, the red sync button under the battery cover, then "
          "pair, trust and connect its address); if it is connected, see the hidraw check"};
}

namespace {

DoctorCheck check_wiimote(const DoctorOptions& o, const AppConfig& config, std::optional<std::string>& identity) {
  const std::string& source = config.input.source;
  if (source == "mouse" || source == "replay" || source == "camera") return wiimote_without_remote(source);
  wm::HidDeviceFinder finder;
  std::optional<wm::HidDeviceInfo> found;
  try {
    found = wm::first_matching(finder.enumerate(), config.wiimote.device);
  } catch (const std::exception& e) {
    return fail("wiimote", std::string("cannot list HID devices: ") + e.what(), "see the hidraw check");
  }
  if (!found) return wiimote_without_remote(source);
  identity = remote_identity(*found);
  input::SteadyClock clock;
  wm::WiimoteDeviceConfig dc = wm::device_config(config);
  dc.device = found->path;
  wm::WiimoteDevice device(finder, clock, dc);
  device.start();
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(o.remote_wait_s);
  wm::WiimoteState s = device.state();
  while (std::chrono::steady_clock::now() < until) {
    s = device.state();
    if (s.link == wm::LinkState::running && s.remote.battery) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  device.stop();
  std::string found_text = "Wii Remote " + *identity + " (" + found->path + "), " + to_string(s.link);
  if (s.link != wm::LinkState::running)
    return fail("wiimote", found_text + (s.problem.empty() ? "" : ": " + s.problem),
                "the IR camera's start-up was not answered: press 1+2 to reconnect it, change its batteries");
  const double battery = s.remote.battery ? *s.remote.battery / 200.0 : -1.0;
  const std::string battery_text =
      battery >= 0 ? std::to_string(static_cast<int>(std::min(1.0, battery) * 100)) + " %" : "unknown";
  DoctorCheck c{"wiimote", CheckLevel::ok,
                found_text + fmt::format(", IR camera answered, {:.0f} reports/s, battery {}", s.remote.ir_rate_hz,
                                         battery_text),
                ""};
  if (s.remote.battery_low) {
    c.level = CheckLevel::warn;
    c.fix = "the batteries are low: change them";
  }
  return c;
}

//! The V4L2 camera as the kiosk opens it, watched for camera_wait_s: its mode, the rate
//! achieved, the exposure and whether it sees the LED.
DoctorCheck check_camera(const DoctorOptions& o, const AppConfig& config, std::optional<std::string>& identity) {
  namespace cam = input::camera;
  if (config.input.source != "camera") {
    const cam::CameraScan scan = cam::scan_cameras(cam::kDefaultVideoDir, false);
    std::string found = "not used: [input] source = \"" + config.input.source + "\"";
    if (!scan.cameras.empty())
      found += fmt::format("; {} camera(s) found, the first {} ({})", scan.cameras.size(), scan.cameras.front().path,
                           scan.cameras.front().name);
    return {"camera", CheckLevel::ok, found, ""};
  }
  input::SteadyClock clock;
  cam::CameraDevice device(std::make_unique<cam::V4l2Grabber>(config.camera), clock, cam::camera_device_config(config));
  device.start();
  std::this_thread::sleep_for(std::chrono::duration<double>(o.camera_wait_s));
  cam::CameraStatus s = device.status();
  const std::string described = device.describe();
  device.stop();
  // describe() names the camera once it was opened, else says why it was not.
  const std::string problem = s.mode.device.empty() || s.connected ? "" : ": " + s.problem;
  if (s.counters.frames == 0 && s.problem.find(cam::kCameraInUse) != std::string::npos)
    return {"camera", CheckLevel::warn, described + problem,
            "the running kiosk streams from it: its operator page's D checks it from inside (Ctrl+Alt+O, then D)"};
  if (s.counters.frames == 0)
    return fail("camera", described + (s.connected ? ": no frame came" : problem),
                "plug the camera in and check `mallet camera list`; the kiosk's user must be in the 'video' group; "
                "[camera] device names it");
  identity = camera_identity(s.mode);
  DoctorCheck c{"camera", CheckLevel::ok,
                described + fmt::format(", {:.0f} frames/s achieved, exposure {} µs ({}), LED {}", s.rate_hz,
                                        s.mode.exposure_us, s.mode.exposure_manual ? "manual" : "automatic",
                                        s.led_seen && s.led ? fmt::format("seen at {:.1f},{:.1f}", s.led->x, s.led->y)
                                                            : std::string("not seen")),
                ""};
  if (s.rate_hz < 0.9 * config.camera.rate_hz) {
    c.level = CheckLevel::warn;
    c.fix = fmt::format("the camera gives {:.0f} of the {:g} frames a second asked: see `mallet camera list` for the "
                        "rates it offers at this size and format; a long exposure can slow it",
                        s.rate_hz, config.camera.rate_hz);
  } else if (!s.led_seen) {
    c.level = CheckLevel::warn;
    c.fix = "hold the stick's LED in the camera's view; if it is lit and not seen, check the 850 nm filter and "
            "`mallet camera monitor`";
  }
  return c;
}

// ---- what opens no device ----

DoctorCheck check_models(const std::vector<fs::path>& scenes) {
  std::size_t models = 0;
  for (const fs::path& file : scenes) {
    try {
      const Scene scene = config::load_scene(file);
      std::vector<std::string> seen;
      for (const Scene::ModelRef& ref : scene.model_refs) {
        if (std::find(seen.begin(), seen.end(), ref.model) != seen.end()) continue;
        seen.push_back(ref.model);
        try {
          render::load_gltf(render::models_dir() / ref.model);
          ++models;
        } catch (const std::exception& e) {
          return fail("models", (ref.at.file.empty() ? "" : FileError(ref.at, ref.key + ": ").what()) + std::string(e.what()),
                      "replace the model, or name a shipped one (" + render::models_dir().string() + ")");
        }
      }
    } catch (const std::exception& e) {
      return fail("models", e.what(), "fix the scene file");
    }
  }
  return {"models", CheckLevel::ok, std::to_string(models) + " glTF models of " + std::to_string(scenes.size()) +
                                        " scenes load (" + render::models_dir().string() + ")", ""};
}

DoctorCheck check_soundfont(const AppConfig& config) {
  if (config.audio.acoustic != AcousticRoute::midi)
    return {"soundfont", CheckLevel::ok, "not needed ([audio] acoustic = \"modal\")", ""};
  std::error_code ec;
  const fs::path sf = config.audio.soundfont;
  if (!fs::is_regular_file(sf, ec) || ::access(sf.c_str(), R_OK) != 0)
    return fail("soundfont", "[audio] soundfont " + sf.string() + " cannot be read",
                "install Debian's timgm6mb-soundfont (or another GM soundfont) and name its .sf2 in [audio] soundfont");
  return {"soundfont", CheckLevel::ok, sf.string() + " (" + std::to_string(fs::file_size(sf, ec) >> 20) + " MiB)", ""};
}

//! The visitor languages: every shipped catalogue readable (the page's L reaches them all),
//! every dropped-in one too, and the ones the settings show (the language check looks into those).
DoctorCheck check_languages(const AppConfig& config, const std::string& on_screen) {
  std::vector<std::string> problems;
  catalogue_texts(locale_dir(), problems);
  std::string shown = config.language;
  if (!on_screen.empty() && on_screen != config.language) shown = on_screen + " (the page's L; the settings: " + shown + ")";
  if (!config.attract.languages.empty()) {
    shown += " (attract:";
    for (const std::string& l : config.attract.languages) shown += " " + l;
    shown += ")";
  }
  std::string dropped;
  for (const std::string& l : visitor_languages())
    if (!dropin_catalogue(l).empty()) dropped += (dropped.empty() ? "" : " ") + l;
  std::string found = visitor_languages_text() + ": catalogues in " + locale_dir().string() +
                      (problems.empty() ? "" : " (" + std::to_string(problems.size()) + " unreadable)") +
                      (dropped.empty() ? "" : ", " + dropped + " from " + dropin_locale_dir().string()) +
                      "; shown: " + shown;
  if (!problems.empty())
    return {"languages", CheckLevel::warn, found + "; " + problems.front(),
            "reinstall the package (its catalogues are /usr/share/locale/*/LC_MESSAGES/mallet.mo); meanwhile those "
            "languages show in English"};
  for (const std::string& p : dropin_problems())
    return {"languages", CheckLevel::warn, found + "; " + p,
            "fix what is named (`msgfmt --check` checks a .po), or remove the file: a file that does not read is not "
            "offered, a translation whose printf directives differ from its text's shows in English"};
  return {"languages", CheckLevel::ok, found, ""};
}

//! The user the service runs as (mallet), else whoever runs the doctor.
struct KioskUser {
  std::string name;
  bool service = false;  //!< the package's own user
};
KioskUser kiosk_user() {
  if (::getpwnam("mallet") != nullptr) return {"mallet", true};
  const passwd* me = ::getpwuid(::getuid());
  return {me ? me->pw_name : "?", false};
}

DoctorCheck check_hidraw() {
  std::error_code ec;
  std::string rule;
  const fs::path shipped(wm::kUdevRulePath);
  for (const fs::path& p : {fs::path(wm::kLocalUdevRulePath), shipped, "/lib/udev/rules.d" / shipped.filename()})
    if (fs::exists(p, ec)) {
      rule = p.string();
      break;
    }
  const KioskUser kiosk = kiosk_user();
  const std::string& user = kiosk.name;
  const bool service_user = kiosk.service;
  std::vector<std::string> missing;
  if (const passwd* pw = service_user ? ::getpwnam(user.c_str()) : nullptr) {
    std::vector<gid_t> groups(64);
    int n = static_cast<int>(groups.size());
    if (::getgrouplist(pw->pw_name, pw->pw_gid, groups.data(), &n) < 0) {
      groups.resize(static_cast<std::size_t>(n));
      ::getgrouplist(pw->pw_name, pw->pw_gid, groups.data(), &n);
    }
    groups.resize(static_cast<std::size_t>(std::max(n, 0)));
    for (const char* want : {"input", "audio", "video", "render"}) {
      const group* g = ::getgrnam(want);
      if (g && std::find(groups.begin(), groups.end(), g->gr_gid) == groups.end()) missing.emplace_back(want);
    }
  }
  // Remotes present whose node this process cannot open (hidapi lists them from sysfs
  // without opening them; a keyboard's or a mouse's hidraw node is none of ours).
  std::vector<std::string> closed;
  for (const wm::HidDeviceInfo& d : wm::HidTransport::enumerate())
    if (::access(d.path.c_str(), R_OK | W_OK) != 0) closed.push_back(d.path);
  std::string found = (rule.empty() ? "udev rule " + shipped.filename().string() + " not installed" : "udev rule " + rule) +
                      "; user " + user + (service_user ? " (the service's)" : " (no mallet user: not installed)");
  if (!missing.empty()) {
    found += " is not in";
    for (const std::string& g : missing) found += " " + g;
  }
  if (!closed.empty()) found += "; " + std::to_string(closed.size()) + " Wii Remote hidraw node(s) this user cannot open";
  DoctorCheck c{"hidraw", CheckLevel::ok, found, ""};
  if (rule.empty()) {
    c.level = CheckLevel::fail;
    c.fix = "install the mallet package (it ships the rule), or create " + std::string(wm::kLocalUdevRulePath) +
            " containing " + std::string(wm::kUdevRule) + " and run `udevadm control --reload && udevadm trigger`";
  } else if (!missing.empty() && service_user) {
    c.level = CheckLevel::warn;
    c.fix = "`adduser mallet GROUP` for each group named (the package's postinst does this)";
  } else if (!closed.empty()) {
    c.level = CheckLevel::warn;
    c.fix = "the seat session gives the kiosk its remote (TAG uaccess); from a shell, run as the mallet user, or "
            "reconnect the remote after installing the rule";
  }
  return c;
}

//! A file of the state folder as a check reads it: none when absent; when it is there but does
//! not read, none and `problem` says why.
template <typename Load>
auto read_state_file(const fs::path& path, Load load, std::string& problem) -> std::optional<decltype(load(path))> {
  std::error_code ec;
  if (!fs::exists(path, ec)) return std::nullopt;
  try {
    return load(path);
  } catch (const std::exception& e) {
    problem = e.what();
    return std::nullopt;
  }
}

//! A state file's loader that says "none" for an absent file, as one that throws instead:
//! read_state_file has looked for the file already, so absent now means removed meanwhile.
template <typename T>
auto present(std::optional<T> (*load)(const fs::path&)) {
  return [load](const fs::path& p) -> T {
    if (std::optional<T> r = load(p)) return *r;
    throw std::runtime_error(p.string() + ": removed while it was read");
  };
}

DoctorCheck check_calibration(const std::optional<std::string>& remote) {
  const fs::path path = calibration_path();
  std::string problem;
  const std::optional<Calibration> cal = read_state_file(path, load_calibration, problem);
  return judge_calibration(path.string(), cal, problem, static_cast<std::int64_t>(std::time(nullptr)), remote);
}

DoctorCheck check_actuator(const AppConfig& config) {
  const fs::path path = actuator_eq_path();
  std::string problem;
  const std::optional<ActuatorEq> eq = read_state_file(path, load_actuator_eq, problem);
  return judge_actuator_eq(path.string(), eq, problem, static_cast<std::int64_t>(std::time(nullptr)),
                           config.actuator.equalize, config.audio.sample_rate_hz);
}

DoctorCheck check_latency(const AppConfig& config) {
  const fs::path path = latency_record_path();
  std::string problem;
  const std::optional<LatencyMeasurement> m = read_state_file(path, present(load_latency_record), problem);
  return judge_latency(path.string(), m, problem, static_cast<std::int64_t>(std::time(nullptr)),
                       config.audio.output_latency_ms);
}

DoctorCheck check_display_latency(const AppConfig& config) {
  const fs::path path = display_latency_path();
  std::string problem;
  const std::optional<DisplayLatencyMeasurement> m = read_state_file(path, present(load_display_latency), problem);
  return judge_display_latency(path.string(), m, problem, static_cast<std::int64_t>(std::time(nullptr)),
                               config.timing.display_latency_ms);
}

//! Why the kiosk could not write into its state folder `dir`, tried as far as this process
//! stands for the kiosk's user: a read-only file system always; a file created, written and
//! removed again when it runs as root or as the folder's owner. Empty: nothing found.
std::string state_write_problem(const fs::path& dir) {
  std::error_code ec;
  fs::path where = dir;
  while (!where.empty() && !fs::exists(where, ec) && where != where.parent_path()) where = where.parent_path();
  struct statvfs st {};
  if (!where.empty() && ::statvfs(where.c_str(), &st) == 0 && (st.f_flag & ST_RDONLY)) return std::strerror(EROFS);
  if (!fs::exists(dir, ec)) return fs::is_directory(where, ec) ? "" : where.string() + " is not a folder";
  if (!fs::is_directory(dir, ec)) return dir.string() + " is not a folder";
  struct stat info {};
  if (::stat(dir.c_str(), &info) != 0 || (::geteuid() != 0 && info.st_uid != ::geteuid())) return "";
  const fs::path probe = dir / (".doctor-probe-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) return probe.string() + ": " + std::strerror(errno);
  const char byte = 0;
  std::string problem;
  if (::write(fd, &byte, 1) != 1 || ::fsync(fd) != 0) problem = probe.string() + ": " + std::strerror(errno);
  ::close(fd);
  fs::remove(probe, ec);
  return problem;
}

DoctorCheck check_disk(const std::string& kiosk_problem) {
  // Where the kiosk writes: its state (calibration, last good settings, counters) and, by
  // default, the study results. What the running kiosk found wins over a probe's guess.
  const fs::path dir = state_dir();
  const std::optional<std::uint64_t> space = free_bytes(dir);
  if (!space) return fail("disk", "cannot read the free space of " + dir.string(), "check that the disk is mounted");
  return judge_state_folder(dir.string(), *space, kiosk_problem.empty() ? state_write_problem(dir) : kiosk_problem);
}

DoctorCheck check_compositor() {
  const std::vector<RenderNode> nodes = render_nodes();
  return judge_compositor(kiosk_compositor_renderer(true), nodes);
}

bool systemd_running() {
  std::error_code ec;
  return fs::is_directory("/run/systemd/system", ec);
}

//! WLR_RENDERER in mallet-session.service's environment (`systemctl show`), if set there.
std::optional<std::string> session_unit_renderer() {
  if (!systemd_running()) return std::nullopt;
  const Ran env = run("systemctl show --property=Environment --value mallet-session.service");
  if (env.status != 0) return std::nullopt;
  std::istringstream words(env.out);
  std::string word;
  while (words >> word)
    if (word.rfind("WLR_RENDERER=", 0) == 0 && word.size() > 13) return word.substr(13);
  return std::nullopt;
}

DoctorCheck check_service() {
  if (!systemd_running())
    return {"service", CheckLevel::warn, "systemd is not running on this machine (a container, or CI)",
            "on the kiosk itself: `systemctl enable --now mallet`"};
  const Ran enabled = run(std::string("systemctl is-enabled ") + kUnit);
  const Ran active = run(std::string("systemctl is-active ") + kUnit);
  const Ran restarts = run(std::string("journalctl --no-pager -q -o cat --since=-24h -u ") + kUnit +
                           " -g 'Scheduled restart job'");
  const std::size_t n = restarts.status == 0 ? count_lines(restarts.out) : 0;
  std::string found = kUnit + std::string(" ") + (enabled.out.empty() ? "not installed" : enabled.out) + ", " +
                      (active.out.empty() ? "unknown" : active.out) + ", " + std::to_string(n) +
                      " restart(s) in the last 24 h";
  DoctorCheck c{"service", CheckLevel::ok, found, ""};
  if (enabled.out != "enabled") {
    c.level = CheckLevel::warn;
    c.fix = "`systemctl enable mallet` so that the kiosk starts at boot";
  } else if (active.out != "active") {
    c.level = CheckLevel::warn;
    c.fix = "`systemctl start mallet`; `journalctl -u mallet -b` says why it stopped";
  } else if (n > 0) {
    c.level = CheckLevel::warn;
    c.fix = "`journalctl -u mallet --since=-24h` shows each crash's last lines";
  }
  return c;
}

DoctorCheck check_watchdog() {
  if (!systemd_running()) return {"watchdog", CheckLevel::ok, "no journal to read here (systemd is not running)", ""};
  const Ran last = run(std::string("journalctl --no-pager -q -o short-iso -n 1 -u ") + kUnit + " -g 'Watchdog timeout'");
  if (last.status != 0 || last.out.empty())
    return {"watchdog", CheckLevel::ok, "the watchdog has not stopped the kiosk (journal)", ""};
  // The kiosk says which of input, audio or render stalled when it stops feeding the watchdog.
  const Ran why = run(std::string("journalctl --no-pager -q -o cat -n 1 -u ") + kUnit + " -g 'watchdog not fed'");
  return {"watchdog", CheckLevel::warn, "last stop: " + last.out + (why.out.empty() ? "" : "; the kiosk said: " + why.out),
          "the kiosk stopped feeding the watchdog (input, audio or render stalled): `journalctl -u mallet` around "
          "that time"};
}

}  // namespace

std::vector<RenderNode> render_nodes() {
  std::vector<RenderNode> nodes;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator("/dev/dri", ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("renderD", 0) != 0) continue;
    std::error_code link;
    const fs::path driver = fs::read_symlink(fs::path("/sys/class/drm") / name / "device" / "driver", link);
    nodes.push_back({name, link ? std::string() : driver.filename().string()});
  }
  std::sort(nodes.begin(), nodes.end(), [](const RenderNode& a, const RenderNode& b) { return a.name < b.name; });
  return nodes;
}

std::optional<bool> vulkan_finds_gpu() {
  // A bare instance, no layers: only which kinds of device the installed drivers offer.
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.apiVersion = VK_API_VERSION_1_0;
  VkInstanceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  info.pApplicationInfo = &app;
  VkInstance instance = VK_NULL_HANDLE;
  if (vkCreateInstance(&info, nullptr, &instance) != VK_SUCCESS) return std::nullopt;
  std::uint32_t count = 0;
  std::vector<VkPhysicalDevice> devices;
  if (vkEnumeratePhysicalDevices(instance, &count, nullptr) == VK_SUCCESS) {
    devices.resize(count);
    if (vkEnumeratePhysicalDevices(instance, &count, devices.data()) != VK_SUCCESS) devices.clear();
    devices.resize(count);
  }
  std::optional<bool> gpu;
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceProperties props{};
    vkGetPhysicalDeviceProperties(d, &props);
    gpu = gpu.value_or(false) || props.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU;
  }
  vkDestroyInstance(instance, nullptr);
  return gpu;
}

CompositorRenderer kiosk_compositor_renderer(bool ask_unit) {
  std::optional<std::string> process_env;
  if (const char* v = std::getenv("WLR_RENDERER"); v && *v) process_env = v;
  const std::optional<std::string> env = process_env || !ask_unit ? process_env : session_unit_renderer();
  const std::vector<RenderNode> nodes = render_nodes();
  // Vulkan is asked only when its answer decides (no WLR_RENDERER, a render node there).
  const std::optional<bool> gpu = env || nodes.empty() ? std::nullopt : vulkan_finds_gpu();
  CompositorRenderer r = compositor_renderer(nodes, env, gpu);
  if (r.from_environment && !process_env) r.reason = "WLR_RENDERER set in mallet-session.service's environment";
  return r;
}

std::vector<DoctorCheck> run_doctor_with(const DoctorOptions& o, const KioskDeviceFacts& facts) {
  std::vector<DoctorCheck> checks{facts.vulkan, check_compositor(), facts.audio, facts.wiimote, facts.camera};
  KioskOptions ko;
  ko.config = o.config;
  ko.config_dir = o.config_dir;
  try {
    const KioskSetup setup = load_kiosk_setup(ko);
    DoctorCheck c{"settings", CheckLevel::ok,
                  operator_settings(o.config, o.config_dir).describe() + "; scene " + setup.scene.file + "; " +
                      std::to_string(setup.scene_choices.size()) + " scene choices",
                  ""};
    if (!setup.problems.empty()) {
      c.level = CheckLevel::warn;
      // Every problem of the start (refused drop-ins among them, which describe() counts),
      // counted once, and the first whole.
      const std::size_t n = setup.problems.size();
      c.found += "; " + std::to_string(n) + (n == 1 ? " problem: " : " problems, the first: ") + setup.problems.front();
      c.fix = "fix or remove the file named (`mallet config show` shows what is in force)";
    }
    checks.push_back(c);
    std::vector<fs::path> scenes = setup.scene_choices;
    if (std::find(scenes.begin(), scenes.end(), fs::path(setup.scene.file)) == scenes.end())
      scenes.insert(scenes.begin(), setup.scene.file);
    checks.push_back(check_models(scenes));
    checks.push_back(check_soundfont(setup.config));
    checks.push_back(check_languages(setup.config, facts.shown_language));
    checks.push_back(check_language(setup.config));
    checks.push_back(check_actuator(setup.config));
    checks.push_back(check_latency(setup.config));
    checks.push_back(check_display_latency(setup.config));
  } catch (const std::exception& e) {
    // What the kiosk starts on meanwhile: the same route as its start (kiosk_setup.hpp).
    const Result<KioskSetup, std::string> fallback = start_setup(ko, state_dir() / kLastGoodSettings);
    checks.push_back(fail("settings", e.what(),
                          "fix the line named, then `systemctl reload mallet`; `mallet config show` shows what is in "
                          "force; meanwhile " +
                              (fallback && !fallback->fallback.empty() ? "the kiosk runs on " + fallback->fallback
                                        : std::string("the kiosk cannot start: nothing to fall back on"))));
  }
  checks.push_back(check_hidraw());
  checks.push_back(check_calibration(facts.connected_remote));
  checks.push_back(check_disk(facts.state_problem));
  checks.push_back(check_service());
  checks.push_back(check_watchdog());
  return checks;
}

const std::vector<std::string>& doctor_check_names() {
  static const std::vector<std::string> names{"vulkan",   "compositor", "audio",       "wiimote", "camera",
                                              "settings", "models",     "soundfont",   "languages", "language",
                                              "actuator", "latency",    "display",     "hidraw",  "calibration",
                                              "disk",     "service",    "watchdog"};
  return names;
}

std::vector<DoctorCheck> run_doctor(const DoctorOptions& o) {
  const auto wanted = [&o](const char* name) {
    return o.only.empty() || std::find(o.only.begin(), o.only.end(), name) != o.only.end();
  };
  const auto only_wanted = [&](std::vector<DoctorCheck> checks) {
    std::erase_if(checks, [&](const DoctorCheck& c) { return !wanted(c.name.c_str()); });
    return checks;
  };
  KioskDeviceFacts facts;
  AppConfig config;
  Scene scene;
  try {
    KioskOptions ko;
    ko.config = o.config;
    ko.config_dir = o.config_dir;
    // The devices as the kiosk opens them: with its settings, or what it falls back on
    // while they are refused (the settings check says which).
    Result<KioskSetup, std::string> setup = start_setup(ko, state_dir() / kLastGoodSettings);
    if (!setup) throw std::runtime_error(setup.error());
    config = std::move(setup->config);
    scene = std::move(setup->scene);
  } catch (const std::exception& e) {  // the settings check says why; the devices need them
    const DoctorCheck skipped = fail("", "not checked: the settings or the scene cannot be read", "see `settings`");
    facts.vulkan = skipped, facts.audio = skipped, facts.wiimote = skipped, facts.camera = skipped;
    facts.vulkan.name = "vulkan", facts.audio.name = "audio", facts.wiimote.name = "wiimote";
    facts.camera.name = "camera";
    return only_wanted(run_doctor_with(o, facts));
  }
  // A device no check asks about is left alone: its line is not printed.
  if (wanted("vulkan")) facts.vulkan = check_vulkan(o, config, scene);
  if (wanted("audio")) facts.audio = check_audio(config, scene);
  // The calibration and camera checks name the remote connected now.
  if (wanted("wiimote") || wanted("calibration") || wanted("camera"))
    facts.wiimote = check_wiimote(o, config, facts.connected_remote);
  if (wanted("camera")) facts.camera = check_camera(o, config, facts.connected_remote);
  return only_wanted(run_doctor_with(o, facts));
}

std::string doctor_json(const std::vector<DoctorCheck>& checks) {
  nlohmann::ordered_json j;
  int counts[3] = {0, 0, 0};
  j["checks"] = nlohmann::ordered_json::array();
  for (const DoctorCheck& c : checks) {
    ++counts[static_cast<int>(c.level)];
    j["checks"].push_back({{"name", c.name}, {"status", to_string(c.level)}, {"found", c.found}, {"fix", c.fix}});
  }
  j["ok"] = counts[0];
  j["warn"] = counts[1];
  j["fail"] = counts[2];
  // What a check found can quote a device's bytes: any that are not UTF-8 become U+FFFD.
  return j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

}  // namespace mallet::app
