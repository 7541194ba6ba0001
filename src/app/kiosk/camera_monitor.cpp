#include "app/kiosk/camera_monitor.hpp"

#include <cmath>
#include <mutex>

#include <fmt/format.h>

#include "app/kiosk/wiimote_monitor.hpp"

namespace mallet::app {

namespace cam = input::camera;

void LedSpread::add(double x, double y) {
  ++n;
  const double dx = x - mean_x, dy = y - mean_y;
  mean_x += dx / static_cast<double>(n);
  mean_y += dy / static_cast<double>(n);
  m2_x += dx * (x - mean_x);
  m2_y += dy * (y - mean_y);
}
double LedSpread::rms_x() const { return n > 1 ? std::sqrt(m2_x / static_cast<double>(n - 1)) : 0.0; }
double LedSpread::rms_y() const { return n > 1 ? std::sqrt(m2_y / static_cast<double>(n - 1)) : 0.0; }

std::string format_camera_list(const cam::CameraScan& scan, const std::string& dir) {
  std::string out;
  for (const cam::CameraInfo& c : scan.cameras) {
    out += fmt::format("{}  \"{}\"  {}  {}\n", c.path, c.name, c.driver, c.bus);
    for (const cam::CameraFormat& f : c.formats) {
      const bool readable = cam::pixel_format_of(f.fourcc).has_value();
      out += fmt::format("  {:<4} {}{}\n", cam::fourcc_text(f.fourcc), f.description,
                         readable ? "" : " (Mallet does not read this format)");
      for (const cam::CameraSize& s : f.sizes) {
        std::string rates;
        for (double r : s.rates_hz) rates += (rates.empty() ? "" : ", ") + fmt::format("{:.4g}", r);
        out += fmt::format("       {}{}x{}: {}\n", s.stepwise ? "up to " : "", s.width, s.height,
                           rates.empty() ? std::string("rate not listed") : rates + " Hz");
      }
    }
    for (const std::string& control : c.controls) out += "  control " + control + "\n";
  }
  if (scan.cameras.empty()) {
    out += fmt::format("No camera found among {}/video*.\n", dir);
    out += "  Plug in a UVC (USB video class) camera; `ls /dev/video*` should then list it.\n";
  }
  if (scan.unreadable > 0)
    out += fmt::format("{} video node(s) could not be opened: {}\n", scan.unreadable, scan.first_error);
  return out;
}

namespace {

std::string seconds(Nanos rel) { return fmt::format("{:8.3f} s", static_cast<double>(rel) * 1e-9); }

std::string led_text(const std::optional<IrPoint>& p, int area) {
  return p ? fmt::format("led {:.2f},{:.2f} ({} px)", p->x, p->y, area) : std::string("no led");
}

}  // namespace

int run_camera_monitor(cam::CameraDevice& device, input::Clock& clock, const CameraMonitorOptions& options,
                       const std::atomic<bool>& interrupted, std::FILE* out) {
  std::mutex mutex;
  LedSpread spread;
  std::vector<std::string> events;
  const Nanos start = clock.now();
  device.set_sample_sink([&](std::span<const input::wiimote::LedSample> samples, Nanos) {
    std::lock_guard lock(mutex);
    for (const input::wiimote::LedSample& s : samples) {
      if (s.has_point) spread.add(s.point.x, s.point.y);
      if (s.event != IrTrackerEvent::none)
        events.push_back(format_event_line(s.t_ns - start, s.event, s.has_point ? std::optional(s.point) : std::nullopt));
    }
  });
  device.start();
  const Nanos interval = static_cast<Nanos>(std::llround(options.interval_s * 1e9));
  const Nanos end = options.seconds > 0 ? start + static_cast<Nanos>(std::llround(options.seconds * 1e9)) : 0;
  bool ever_open = false;
  cam::CameraStatus s;
  while (!interrupted.load() && (end == 0 || clock.now() < end)) {
    clock.sleep_for(interval);
    s = device.status();
    ever_open = ever_open || s.connected;
    std::vector<std::string> happened;
    {
      std::lock_guard lock(mutex);
      happened.swap(events);
    }
    for (const std::string& e : happened) std::fprintf(out, "%s\n", e.c_str());
    const std::string line =
        s.connected ? fmt::format("{}  streaming  {:6.1f} Hz  frames {}  dropped {}  {}", seconds(clock.now() - start),
                                  s.rate_hz, s.counters.frames, s.counters.dropped,
                                  s.led_seen ? led_text(s.led, s.led_area_px) : std::string("no led"))
                    : fmt::format("{}  searching  ({})", seconds(clock.now() - start), s.problem);
    std::fprintf(out, "%s\n", line.c_str());
    std::fflush(out);
  }
  device.stop();
  s = device.status();
  ever_open = ever_open || s.counters.frames > 0;
  if (!ever_open) {
    std::fprintf(out, "summary: no camera was opened: %s\n", s.problem.c_str());
    return 1;
  }
  const double run_s = static_cast<double>(clock.now() - start) * 1e-9;
  std::string summary = fmt::format("summary: {} over {:.1f} s\n", device.describe(), run_s);
  summary += fmt::format("  frames {}, dropped by the driver {}, unreadable {}{}\n", s.counters.frames,
                         s.counters.dropped, s.counters.bad_frames,
                         s.last_bad_frame.empty() ? std::string() : " (last: " + s.last_bad_frame + ")");
  summary += fmt::format("  rate achieved {:.1f} Hz (frames over the run: {:.1f} Hz)\n", s.rate_hz,
                         run_s > 0 ? static_cast<double>(s.counters.frames) / run_s : 0.0);
  summary += fmt::format("  exposure {} µs ({}), gain {}\n", s.mode.exposure_us,
                         s.mode.exposure_manual ? "manual" : "automatic",
                         s.mode.gain >= 0 ? std::to_string(s.mode.gain) : std::string("no control"));
  summary += "  stamping: " + (s.mode.stamping.empty() ? std::string("no frame yet") : s.mode.stamping) + "\n";
  {
    std::lock_guard lock(mutex);
    summary += spread.n > 0 ? fmt::format("  LED in {} of {} frames ({} lost, {} regained); its spread x {:.3f} px, "
                                          "y {:.3f} px RMS (the centroid's noise when the LED was held still)\n",
                                          s.counters.led_frames, s.counters.frames, s.counters.lost,
                                          s.counters.regained, spread.rms_x(), spread.rms_y())
                            : std::string("  LED never seen: is it on, in view, and the exposure short enough?\n");
  }
  for (const std::string& note : s.mode.notes) summary += "  note: " + note + "\n";
  std::fputs(summary.c_str(), out);
  return 0;
}

}  // namespace mallet::app
