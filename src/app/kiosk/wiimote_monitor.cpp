#include "app/kiosk/wiimote_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

#include "input/wiimote/replay_source.hpp"
#include "input/wiimote/reports.hpp"

namespace mallet::app {

namespace wm = mallet::input::wiimote;

namespace {

std::string time_column(Nanos t_rel_ns) { return fmt::format("{:8.3f} s", to_seconds(t_rel_ns)); }

Nanos seconds_to_ns(double s) { return static_cast<Nanos>(std::llround(s * 1e9)); }

std::string summary(const wm::RemoteStats& r) {
  return fmt::format("{} reports ({} IR, {} status, {} malformed)", r.reports, r.ir_reports, r.status_reports,
                     r.malformed);
}

}  // namespace

std::string format_device_list(const std::vector<wm::HidDeviceInfo>& devices) {
  if (devices.empty()) {
    return "No Wii Remote found (vendor 057e, product 0306 or 0330).\n"
           "Pair and connect it first, e.g. `bluetoothctl`: scan on, press the red sync button\n"
           "under the battery cover, then pair, trust and connect its address. To be opened,\n" +
           wm::udev_hint() + ".\n";
  }
  std::string out = fmt::format("{:<16} {:<22} {:<19} {}\n", "path", "product", "serial", "name");
  for (const wm::HidDeviceInfo& d : devices) {
    const std::string product = wm::product_name(d.product_id) + fmt::format(" ({:04x})", d.product_id);
    out += fmt::format("{:<16} {:<22} {:<19} {}\n", d.path, product, d.serial.empty() ? "-" : d.serial,
                       d.product.empty() ? "-" : d.product);
  }
  out += fmt::format("{} Wii Remote(s). Choose one with [wiimote].device or --device: a part of its path or serial.\n",
                     devices.size());
  return out;
}

std::string format_monitor_line(const MonitorLine& l) {
  std::string out = time_column(l.t_rel_ns) + "  " + fmt::format("{:<9}", l.link);
  if (l.link == "searching" || l.link == "starting") {
    if (!l.note.empty()) out += "  " + l.note;
    return out;
  }
  out += fmt::format("  {:5.1f} Hz", l.remote.ir_rate_hz);
  if (l.remote.battery)
    out += fmt::format("  battery 0x{:02x}{}", *l.remote.battery, l.remote.battery_low ? " LOW" : "");
  else
    out += "  battery ?";
  if (l.tracking && l.point)
    out += fmt::format("  tracking  led {:.0f},{:.0f}", l.point->x, l.point->y);
  else if (l.point)
    out += fmt::format("  lost      led {:.0f},{:.0f}", l.point->x, l.point->y);
  else
    out += "  lost      led -";
  out += "  dots " + wm::format_ir_slots(l.remote.last_slots);
  if (!l.note.empty()) out += "  (" + l.note + ")";
  return out;
}

std::string format_event_line(Nanos t_rel_ns, IrTrackerEvent event, const std::optional<IrPoint>& point) {
  std::string out = time_column(t_rel_ns) + "  tracking " + to_string(event);
  if (point && event != IrTrackerEvent::lost) out += fmt::format(" at {:.0f},{:.0f}", point->x, point->y);
  return out;
}

// ---------------------------------------------------------------------------------------

int run_live_monitor(wm::WiimoteDevice& device, input::Clock& clock, const MonitorOptions& o,
                     const std::atomic<bool>& interrupted, std::FILE* out) {
  std::ofstream record_file;
  std::optional<wm::ReplayWriter> writer;
  if (o.record) {
    if (!device.config().keep_raw_reports)
      throw std::logic_error("wiimote monitor: recording needs a device that keeps raw reports");
    record_file.open(*o.record, std::ios::binary | std::ios::trunc);
    if (!record_file) throw std::runtime_error("cannot write " + o.record->string());
    writer.emplace(record_file);
    record_file.flush();
  }
  const Nanos t0 = clock.now();
  const Nanos interval = std::max<Nanos>(seconds_to_ns(o.interval_s), 1'000'000);
  const Nanos limit = o.seconds > 0 ? seconds_to_ns(o.seconds) : 0;
  std::vector<wm::LedSample> samples;
  std::vector<wm::RawReport> raw;
  std::uint64_t recorded = 0;
  std::string last_problem;

  auto drain = [&] {
    device.drain(samples);
    for (const wm::LedSample& s : samples)
      if (s.event != IrTrackerEvent::none)
        std::fprintf(out, "%s\n",
                     format_event_line(s.t_ns - t0, s.event, s.has_point ? std::optional(s.point) : std::nullopt).c_str());
    if (writer) {
      device.drain_raw(raw);
      for (const wm::RawReport& r : raw) writer->write(r.t_ns, r.span());
      recorded += raw.size();
      record_file.flush();
      if (!record_file) throw std::runtime_error("cannot write " + o.record->string() + " (disk full?)");
    }
  };
  auto print_state = [&](Nanos now) {
    const wm::WiimoteState s = device.state();
    MonitorLine line;
    line.t_rel_ns = now - t0;
    line.link = to_string(s.link);
    line.remote = s.remote;
    line.tracking = s.tracking;
    line.point = s.point;
    if (s.link == wm::LinkState::searching) {
      // A new problem in full once (an open failure carries the udev rule), then its
      // first clause on each line.
      if (s.problem != last_problem && s.problem.find_first_of(";\n") != std::string::npos) {
        std::fprintf(out, "%s  %s\n", time_column(now - t0).c_str(), s.problem.c_str());
        last_problem = s.problem;
      }
      line.note = fmt::format("retry in {:.1f} s: ", to_seconds(std::max<Nanos>(0, s.next_attempt_ns - s.now_ns))) +
                  (s.problem.empty() ? "looking for a remote" : s.problem.substr(0, s.problem.find_first_of(";\n")));
    } else if (s.link == wm::LinkState::starting) {
      line.note = "IR start-up: " + std::string(wm::to_string(s.startup)) + " " + s.device.path;
    }
    std::fprintf(out, "%s\n", format_monitor_line(line).c_str());
    std::fflush(out);
  };

  device.start();
  Nanos next_line = t0 + interval;
  while (!interrupted.load()) {
    const Nanos now = clock.now();
    if (limit > 0 && now - t0 >= limit) break;
    if (now < next_line) {
      clock.sleep_for(std::min<Nanos>(next_line - now, 20'000'000));
      continue;
    }
    drain();
    print_state(now);
    next_line += interval;
    if (next_line <= now) next_line = now + interval;
  }
  device.stop();
  drain();

  const wm::WiimoteState s = device.state();
  std::fprintf(out, "%s  %llu connection(s), %llu drop(s), %s, %llu mode reset(s)\n",
               time_column(clock.now() - t0).c_str(), static_cast<unsigned long long>(s.connects),
               static_cast<unsigned long long>(s.disconnects), summary(s.remote).c_str(),
               static_cast<unsigned long long>(s.mode_resets));
  if (writer)
    std::fprintf(out, "recorded %llu report(s) to %s\n", static_cast<unsigned long long>(recorded),
                 o.record->string().c_str());
  std::fflush(out);
  if (s.connects == 0) {
    std::fprintf(stderr, "mallet: no Wii Remote was connected: %s\n",
                 s.problem.empty() ? "none found" : s.problem.c_str());
    return 1;
  }
  return 0;
}

int run_replay_monitor(const std::filesystem::path& recording, const IrTrackerConfig& tracking,
                       const MonitorOptions& o, std::FILE* out) {
  wm::ReplaySource source = wm::ReplaySource::open(recording, tracking);
  if (source.done()) {
    std::fprintf(out, "%s holds no report\n", recording.string().c_str());
    return 0;
  }
  const Nanos t0 = *source.next_time();
  const Nanos interval = std::max<Nanos>(seconds_to_ns(o.interval_s), 1'000'000);
  const Nanos limit = o.seconds > 0 ? seconds_to_ns(o.seconds) : 0;
  auto print_state = [&](Nanos t) {
    MonitorLine line;
    line.t_rel_ns = t - t0;
    line.link = "replay";
    line.remote = source.tracker().stats();
    line.tracking = source.tracker().tracker().tracking();
    line.point = source.tracker().tracker().last_point();
    std::fprintf(out, "%s\n", format_monitor_line(line).c_str());
  };

  Nanos next_line = t0 + interval;
  Nanos last_t = t0;
  while (const std::optional<Nanos> t = source.next_time()) {
    if (limit > 0 && *t - t0 >= limit) break;
    // Each line shows the state after every report before its time.
    int lines = 0;
    while (*t >= next_line) {
      print_state(next_line);
      next_line += interval;
      // A long gap in the recording: ten lines, then straight to its end.
      if (++lines == 10 && *t >= next_line) next_line += (*t - next_line) / interval * interval;
    }
    const std::optional<wm::ReportOutcome> outcome = source.next();
    if (outcome->update.event != IrTrackerEvent::none)
      std::fprintf(out, "%s\n", format_event_line(outcome->t_ns - t0, outcome->update.event, outcome->update.point).c_str());
    last_t = outcome->t_ns;
  }
  print_state(last_t);
  std::fprintf(out, "%s  replayed %zu of %zu report(s): %s\n", time_column(last_t - t0).c_str(), source.position(),
               source.size(), summary(source.tracker().stats()).c_str());
  return 0;
}

}  // namespace mallet::app
