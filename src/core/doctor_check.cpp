#include "core/doctor_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>

#include <fmt/format.h>

namespace mallet {

namespace {
constexpr std::uint64_t kMiB = 1024ull * 1024ull;
constexpr double kRefreshMs = 1000.0 / 60.0;
constexpr std::int64_t kOldCalibrationDays = 90;  //!< a remote or a screen is often moved by then
constexpr double kCalibrationErrorPx = 20.0;       //!< about a bar's half-width at 1080p
}  // namespace

const char* to_string(CheckLevel level) { return name_in(kCheckLevelNames, level); }

std::string format_check(const DoctorCheck& c) {
  std::string line = fmt::format("{:<5} {:<12} {}", to_string(c.level), c.name, c.found);
  if (!c.fix.empty()) line += " -> fix: " + c.fix;
  std::replace(line.begin(), line.end(), '\n', ' ');  // one line a check, whatever a probe said
  return line;
}

int doctor_exit_status(const std::vector<DoctorCheck>& checks) {
  for (const DoctorCheck& c : checks)
    if (c.level == CheckLevel::fail) return 1;
  return 0;
}

DoctorCheck judge_free_space(const std::string& where, std::uint64_t available) {
  DoctorCheck c{"disk", CheckLevel::ok,
                fmt::format("{:.1f} GiB free in {}", static_cast<double>(available) / (1024.0 * kMiB), where), ""};
  if (available < 100 * kMiB) {
    c.level = CheckLevel::fail;
    c.fix = "free space on that file system: study rows and calibrations can no longer be saved";
  } else if (available < 1024 * kMiB) {
    c.level = CheckLevel::warn;
    c.fix = "free space on that file system (study results and the journal grow)";
  }
  return c;
}

DoctorCheck judge_state_folder(const std::string& where, std::uint64_t available, const std::string& write_problem) {
  DoctorCheck c = judge_free_space(where, available);
  c.found = "state folder: " + c.found;  // "state folder: 71.2 GiB free in /var/lib/mallet"
  if (write_problem.empty()) {
    c.found += ", writable";
    return c;
  }
  c.level = CheckLevel::fail;
  c.found += ", cannot be written: " + write_problem;
  c.fix = "free space on that file system or make " + where +
          " writable by the kiosk's user (the package's StateDirectory=mallet); meanwhile the kiosk plays on but keeps "
          "no calibration, counters, last good settings or visitor results";
  return c;
}

namespace {
std::string node_names(const std::vector<RenderNode>& nodes) {
  std::string out;
  for (const RenderNode& n : nodes)
    out += (out.empty() ? "" : ", ") + n.name + (n.driver.empty() ? std::string() : ", driver " + n.driver);
  return out;
}
}  // namespace

CompositorRenderer compositor_renderer(const std::vector<RenderNode>& nodes, const std::optional<std::string>& env,
                                       std::optional<bool> vulkan_gpu) {
  if (env && !env->empty()) return {*env, "WLR_RENDERER set by the unit's environment", true};
  if (nodes.empty())
    return {"pixman", "no GPU render node in /dev/dri: software", false};
  if (vulkan_gpu && !*vulkan_gpu)
    return {"pixman", "Vulkan finds no GPU, only a software driver, although /dev/dri has " + node_names(nodes) +
                          ": software",
            false};
  return {"gles2", "the GPU's: " + node_names(nodes), false};
}

DoctorCheck judge_compositor(const CompositorRenderer& r, const std::vector<RenderNode>& nodes) {
  DoctorCheck c{"compositor", CheckLevel::ok, r.renderer + " (" + r.reason + ")", ""};
  if (r.from_environment && nodes.empty() && r.renderer != "pixman") {
    c.level = CheckLevel::warn;
    c.found += "; /dev/dri has no render node";
    c.fix = "without a GPU render node wlroots falls back to Mesa's kms_swrast, which crashes on some virtual GPUs: "
            "remove WLR_RENDERER from the drop-in (the session then uses pixman)";
  } else if (r.from_environment && !nodes.empty()) {
    c.found += "; render node " + node_names(nodes);
  }
  return c;
}

DoctorCheck judge_renderer(const std::string& device, bool cpu, std::uint32_t width, std::uint32_t height,
                           double frame_ms) {
  DoctorCheck c{"vulkan", CheckLevel::ok,
                fmt::format("{}{}, a {}x{} frame takes {:.1f} ms", device, cpu ? " (software: the CPU draws)" : "",
                            width, height, frame_ms),
                ""};
  const bool large = static_cast<std::uint64_t>(width) * height >= 1920ull * 1080ull;
  if (frame_ms > kRefreshMs) {
    c.level = CheckLevel::fail;
    c.fix = "the kiosk cannot keep up with a 60 Hz display: install the GPU's Vulkan driver (mesa-vulkan-drivers "
            "for Intel/AMD), or set quality = \"fast\" in mallet.toml";
  } else if (cpu && large) {
    c.level = CheckLevel::warn;
    c.fix = "a software renderer on a large display costs a core: install the GPU's Vulkan driver "
            "(mesa-vulkan-drivers for Intel/AMD) and check `vulkaninfo --summary`";
  }
  return c;
}

std::optional<std::int64_t> parse_utc(const std::string& iso) {
  std::tm t{};
  int y = 0, mo = 0, d = 0, h = 0, mi = 0, s = 0;
  char z = 0;
  if (std::sscanf(iso.c_str(), "%4d-%2d-%2dT%2d:%2d:%2d%c", &y, &mo, &d, &h, &mi, &s, &z) != 7 || z != 'Z')
    return std::nullopt;
  if (mo < 1 || mo > 12 || d < 1 || d > 31 || h > 23 || mi > 59 || s > 60) return std::nullopt;
  t.tm_year = y - 1900;
  t.tm_mon = mo - 1;
  t.tm_mday = d;
  t.tm_hour = h;
  t.tm_min = mi;
  t.tm_sec = s;
  return static_cast<std::int64_t>(timegm(&t));
}

DoctorCheck judge_actuator_eq(const std::string& path, const std::optional<ActuatorEq>& eq, const std::string& problem,
                              std::int64_t now, bool equalize, int sample_rate_hz) {
  DoctorCheck c{"actuator", CheckLevel::ok, "", ""};
  const std::string measure = "with the sensor on the stick: `mallet calibrate actuator` (docs/operators.md)";
  if (!problem.empty()) {
    c.level = CheckLevel::warn;
    c.found = problem + "; the actuator plays uncorrected";
    c.fix = "measure again " + measure;
    return c;
  }
  if (!eq) {
    c.found = "not measured (" + path + "): the actuator plays Eq. 1 as computed, through the voice coil's own response";
    c.fix = "optional: " + measure;
    return c;
  }
  const std::optional<std::int64_t> made = parse_utc(eq->created_utc);
  const std::int64_t days = made ? (now - *made) / 86400 : -1;
  c.found = fmt::format("{}, made {} ({}), sensor \"{}\", resonance {:.0f} Hz, band {:.0f}-{:.0f} Hz, calibration {}", path,
                        eq->created_utc.empty() ? "at an unknown time" : eq->created_utc,
                        days >= 0 ? std::to_string(days) + " days ago" : "age unknown", eq->sensor, eq->resonance_hz,
                        eq->band_low_hz, eq->band_high_hz, eq->hash());
  if (eq->sample_rate_hz != sample_rate_hz) {
    c.level = CheckLevel::warn;
    c.found += fmt::format("; measured at {} Hz, the audio runs at {} Hz: not applied", eq->sample_rate_hz, sample_rate_hz);
    c.fix = "measure again at this rate " + measure;
  } else if (!equalize) {
    c.found += "; not applied ([actuator] equalize = false)";
  } else {
    c.found += "; applied to the actuator channel";
  }
  return c;
}

DoctorCheck judge_latency(const std::string& path, const std::optional<LatencyMeasurement>& m, const std::string& problem,
                          std::int64_t now, double setting_ms) {
  DoctorCheck c{"latency", CheckLevel::ok, "", ""};
  const std::string setting =
      setting_ms < 0 ? std::string("PortAudio's own figure") : fmt::format("{:.3f} ms", setting_ms);
  if (!problem.empty()) {
    c.level = CheckLevel::warn;
    c.found = problem;
    c.fix = "measure again: `mallet calibrate latency --loopback CH` (docs/operators.md)";
    return c;
  }
  if (!m) {
    c.found = "never measured (" + path + "); [timing] audio_output_latency_ms: " + setting;
    c.fix = "optional: a loopback cable and `mallet calibrate latency --loopback CH` (docs/operators.md)";
    return c;
  }
  const std::optional<std::int64_t> made = parse_utc(m->measured_utc);
  const std::int64_t days = made ? (now - *made) / 86400 : -1;
  c.found = fmt::format("measured {} ({}): round trip {:.3f} ms, output {:.3f} ms (PortAudio said {:.3f} ms); "
                        "[timing] audio_output_latency_ms: {}",
                        m->measured_utc, days >= 0 ? std::to_string(days) + " days ago" : "age unknown", m->round_trip_ms(),
                        m->output_latency_ms(), m->portaudio_output_latency_ms, setting);
  const double in_force = setting_ms < 0 ? m->portaudio_output_latency_ms : setting_ms;
  if (std::abs(in_force - m->output_latency_ms()) > 1.0) {
    c.level = CheckLevel::warn;
    c.fix = "the setting is not what was measured: `mallet calibrate latency --loopback CH --save`, then "
            "`systemctl reload mallet`";
  }
  return c;
}

DoctorCheck judge_display_latency(const std::string& path, const std::optional<DisplayLatencyMeasurement>& m,
                                  const std::string& problem, std::int64_t now, double setting_ms) {
  DoctorCheck c{"display", CheckLevel::ok, "", ""};
  if (!problem.empty()) {
    c.level = CheckLevel::warn;
    c.found = problem;
    c.fix = "measure again: `mallet calibrate latency --photodiode CH` (docs/operators.md)";
    return c;
  }
  if (!m) {
    c.found = fmt::format("never measured ({}); [timing] display_latency_ms: {:.1f} ms", path, setting_ms);
    c.fix = "optional: a photodiode on the screen's corner and `mallet calibrate latency --photodiode CH` "
            "(docs/operators.md)";
    return c;
  }
  const std::optional<std::int64_t> made = parse_utc(m->measured_utc);
  const std::int64_t days = made ? (now - *made) / 86400 : -1;
  c.found = fmt::format("measured {} ({}): {:.1f} ms ({:.1f} to {:.1f} over {} of {} squares){}; [timing] "
                        "display_latency_ms: {:.1f} ms",
                        m->measured_utc, days >= 0 ? std::to_string(days) + " days ago" : "age unknown",
                        m->display_latency_ms, m->min_ms, m->max_ms, m->squares_seen, m->squares,
                        m->saved ? "" : ", not confirmed", setting_ms);
  if (std::abs(setting_ms - m->display_latency_ms) > 2.0) {
    c.level = CheckLevel::warn;
    c.fix = "the setting is not what was measured: `mallet calibrate latency --photodiode CH` and confirm with "
            "Enter on its page, then `systemctl reload mallet`";
  }
  return c;
}

DoctorCheck judge_calibration(const std::string& path, const std::optional<Calibration>& cal,
                              const std::string& problem, std::int64_t now, const std::optional<std::string>& remote) {
  DoctorCheck c{"calibration", CheckLevel::ok, "", ""};
  if (!problem.empty()) {
    c.level = CheckLevel::warn;
    c.found = problem;
    c.fix = "the kiosk calibrates again when the remote connects; or Ctrl+Alt+O then R";
    return c;
  }
  if (!cal) {
    c.level = CheckLevel::warn;
    c.found = "none yet (" + path + ")";
    c.fix = "the kiosk asks for one when the Wii Remote connects; or Ctrl+Alt+O then R";
    return c;
  }
  const std::optional<std::int64_t> made = parse_utc(cal->created_utc);
  const std::int64_t days = made ? (now - *made) / 86400 : -1;
  c.found = fmt::format("{}, made {} ({}), max error {:.1f} px, remote {}", path,
                        cal->created_utc.empty() ? "at an unknown time" : cal->created_utc,
                        days >= 0 ? std::to_string(days) + " days ago" : "age unknown", cal->max_error_screen_px,
                        cal->remote.empty() ? "unknown" : cal->remote);
  if (remote && !cal->remote.empty() && *remote != cal->remote) {
    c.level = CheckLevel::warn;
    c.found += "; the remote connected now is " + *remote;
    c.fix = "the kiosk calibrates again at start-up with this remote; or Ctrl+Alt+O then R";
  } else if (cal->max_error_screen_px > kCalibrationErrorPx) {
    c.level = CheckLevel::warn;
    c.fix = "recalibrate (Ctrl+Alt+O then R), holding the stick still on each target";
  } else if (days > kOldCalibrationDays) {
    c.level = CheckLevel::warn;
    c.fix = "older than 90 days: recalibrate if the remote or the screen has moved (Ctrl+Alt+O then R)";
  }
  return c;
}

}  // namespace mallet
