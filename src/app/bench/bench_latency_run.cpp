#include "app/bench/bench_latency_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "app/bench/bench_kiosk_child.hpp"
#include "app/bench/bench_latency_child.hpp"
#include "app/bench/bench_latency_onset.hpp"
#include "app/bench/bench_latency_strokes.hpp"

namespace mallet::app::latency {

namespace {

//! The kiosk's stderr as it arrives: whether it runs, its strike lines, its status lines.
struct KioskLog {
  std::mutex mutex;
  bool started = false;
  std::optional<Nanos> replay_origin;  //!< the recording's time 0 on the kiosk's clock
  std::vector<Nanos> strikes;
  std::vector<std::string> status;

  void line(std::string_view text) {
    std::lock_guard lock(mutex);
    if (const std::size_t at = text.find("strike t="); at != std::string_view::npos) {
      if (const std::optional<Nanos> t = parse_log_seconds(text.substr(at + 9))) strikes.push_back(*t);
      return;
    }
    if (const std::size_t at = text.find("recording's time 0 is t="); at != std::string_view::npos) {
      if (!replay_origin) replay_origin = parse_log_seconds(text.substr(at + 24));
      return;
    }
    if (text.find("mallet run:") != std::string_view::npos && !started) {
      started = true;
      status.emplace_back(text.substr(text.find("mallet run:")));
    }
    for (const char* key : {"input:", "timing:"})
      if (text.find(key) != std::string_view::npos && status.size() < 4)
        status.emplace_back(text.substr(text.find(key)));
  }
};

std::string settings_text(const Config& c) {
  std::string t = "# written by `mallet bench latency` for one run of the kiosk under test\n";
  t += "quality = \"" + c.preset + "\"\n";
  t += "[audio]\n";
  t += "device = \"system\"   # the JACK host API's device, on the bench's own JACK server\n";
  t += "sample_rate_hz = " + std::to_string(kRate) + "\n";
  t += "[audio.routing]\nchannels = 2\nacoustic = 0\nactuator = 1\n";
  if (c.source == "remote") t += "[input]\nsource = \"replay\"\nreplay_file = \"" + c.replay_file.string() + "\"\n";
  else t += "[input]\nsource = \"mouse\"\nmouse = \"window\"\n";
  t += "[timing]\nalign = \"" + c.align + "\"\n";
  t += "[attract]\nidle_after_s = 86400.0   # the ghost never takes over\n";
  t += "[render]\npresent_mode = \"fifo\"\n";
  return t;
}

[[noreturn]] void kiosk_failed(Child& kiosk, const std::string& what) {
  latency::kiosk_failed(kiosk, "bench latency", what);
}

//! A run's recorded cues matched to its true contacts; stops the kiosk.
ConfigResult finish_run(Rig& rig, Child& kiosk, KioskLog& log, Recording& rec, AudioTrack& track, Nanos begin,
                        Nanos end, std::uint64_t xruns_before, ConfigResult& result) {
  rig.recorder->stop_recording();
  // Each contact's first new sample on each channel, from 50 ms before it to 300 ms after
  // (or to the next contact's window), not counting the seams of late cycles.
  const std::vector<Gap> gaps = track.irregular(rig.recorder->period());
  for (std::size_t k = 0; k < rec.contacts.size(); ++k) {
    const Nanos c = rec.contacts[k].t;
    const Nanos to =
        k + 1 < rec.contacts.size() ? std::min(c + kCueAfter, rec.contacts[k + 1].t - kCueBefore) : c + kCueAfter;
    const std::size_t i0 = track.index_at(c - kCueBefore), i1 = track.index_at(to);
    for (int channel : {0, 1})
      if (const std::optional<std::size_t> i =
              find_onset(track.channels[static_cast<std::size_t>(channel)], i0, i1, {}, gaps))
        (channel == 1 ? rec.actuator : rec.note).push_back(track.time_of(*i));
  }
  for (const PictureEvent& p : rig.watch->take()) rec.picture[static_cast<std::size_t>(p.strip)].push_back(p.t);
  {
    std::lock_guard lock(log.mutex);
    for (Nanos t : log.strikes)
      if (t >= begin - kStrikeWindow && t <= end) rec.strikes.push_back(t);
  }
  result.xruns = rig.recorder->xruns() - xruns_before;
  kiosk.stop(std::chrono::milliseconds(3000));
  result.matched = match_recording(rec);
  // Where each false strike lay, for a closer look: its time from the run's first true contact.
  for (Nanos t : rec.strikes) {
    Nanos nearest = -1;
    for (const Recording::Contact& c : rec.contacts)
      if (nearest < 0 || std::llabs(c.t - t) < std::llabs(nearest - t)) nearest = c.t;
    if (nearest < 0 || std::llabs(nearest - t) > kStrikeWindow)
      std::printf("    false strike at %+.1f ms from the first contact (nearest contact %+.1f ms away)\n",
                  rec.contacts.empty() ? 0.0 : ms_of(t - rec.contacts.front().t), nearest < 0 ? 0.0 : ms_of(t - nearest));
  }
  const double px_m = std::fabs(rig.map.y_of_row(0) - rig.map.y_of_row(1));
  result.resolution_ms = px_m / 1.0 * 1e3;  // the slowest stroke, 1.0 m/s
  return result;
}

//! The remote's run: the kiosk plays the script from its start; this listens and looks.
ConfigResult run_remote(Rig& rig, Child& kiosk, KioskLog& log, const RemoteScript& script, ConfigResult& result,
                        const Deadline& deadline) {
  const Nanos waited_from = monotonic_now();
  std::optional<Nanos> origin;
  while (!origin) {
    deadline.check();
    if (!kiosk.running()) kiosk_failed(kiosk, "exited before its replay started");
    if (monotonic_now() > waited_from + 20 * kNanosPerSecond) kiosk_failed(kiosk, "never said when its replay started");
    {
      std::lock_guard lock(log.mutex);
      origin = log.replay_origin;
    }
    sleep_ms(20);
  }
  for (int i = 0; i < 2; ++i) {
    result.rest_row[i] = rig.rest_row[i];
    rig.watch->set_rest_row(i, rig.rest_row[i]);
  }
  const Nanos first = *origin + script.first_stroke;
  if (monotonic_now() > first - 300 * kMs)
    kiosk_failed(kiosk, "was not up 300 ms before the recording's first stroke (" +
                            std::to_string(to_seconds(monotonic_now() - *origin)) + " s after the replay started)");
  Recording rec;
  rec.picture.resize(rig.bars.size());
  for (const Recording::Contact& c : script.contacts) rec.contacts.push_back({*origin + c.t, c.bar, c.speed});
  sleep_until(first - 200 * kMs);
  AudioTrack track;
  rig.recorder->start_recording(track);
  rig.watch->take();
  const Nanos begin = monotonic_now();
  const std::uint64_t xruns_before = rig.recorder->xruns();
  while (monotonic_now() < *origin + script.end) {
    deadline.check();
    if (!kiosk.running()) kiosk_failed(kiosk, "exited during the strokes");
    rig.recorder->drain(track);
    sleep_ms(50);
  }
  const Nanos end = monotonic_now();
  rig.recorder->drain(track);
  return finish_run(rig, kiosk, log, rec, track, begin, end, xruns_before, result);
}

//! The mouse's run, once the kiosk is up: the hand takes over from the attract mode's ghost,
//! strikes each bar once to find where the head rests on it, then makes the measured strokes.
ConfigResult run_mouse(Rig& rig, Child& kiosk, KioskLog& log, ConfigResult& result, int strokes,
                       const Deadline& deadline) {
  // Take over from the attract mode's ghost: a first sample anchors, a second moves.
  rig.hand->move_to(kWidth / 2, kHeight / 6);
  sleep_ms(40);
  rig.hand->move_to(kWidth / 2, kHeight / 6 + 30);
  sleep_ms(400);
  // Warm-up: one stroke per bar, and while the hand is held below it, where the head rests
  // at the bar in the picture (the contact solver holds it at the surface).
  for (std::size_t i = 0; i < rig.bars.size(); ++i) {
    deadline.check();
    std::optional<int> rest;
    mouse_stroke(rig, rig.bars[i], 1.0, [&] {
      Grab g;
      if (rig.eye->grab(rig.bars[i].strip, g)) rest = lowest_white_row(g, rig.bars[i].strip);
    });
    // The head's lowest white pixels lie between its centre (the lit top half of a round
    // head is the white one) and its bottom, a radius below: not higher.
    const double centre = rig.map.row_of_y(rig.bars[i].contact_y_m);
    const double radius_rows = rig.map.row_of_y(rig.bars[i].contact_y_m - rig.map.scene->mallet_radius_m) - centre;
    if (!rest || *rest < centre - radius_rows / 2 || *rest > rig.bars[i].strip.y + rig.bars[i].strip.height - 2)
      kiosk_failed(kiosk, "does not show the mallet resting on " + rig.bars[i].name +
                              " where expected (lowest white row " +
                              (rest ? std::to_string(*rest) : std::string("none")) + ", head centre row " +
                              std::to_string(static_cast<int>(centre)) + ")");
    result.rest_row[i] = *rest;
    rig.rest_row[i] = *rest;
    rig.watch->set_rest_row(static_cast<int>(i), *rest);
    sleep_ms(350);
  }

  // The measured strokes.
  Recording rec;
  rec.picture.resize(rig.bars.size());
  sleep_ms(200);
  AudioTrack track;
  rig.recorder->start_recording(track);
  rig.watch->take();
  const Nanos begin = monotonic_now();
  const std::uint64_t xruns_before = rig.recorder->xruns();
  for (int s = 0; s < strokes; ++s) {
    deadline.check();
    if (!kiosk.running()) kiosk_failed(kiosk, "exited during the strokes");
    const Nanos started = monotonic_now();
    const int bar = s % 2;
    const double v = stroke_speed(s);
    const Nanos contact = mouse_stroke(rig, rig.bars[static_cast<std::size_t>(bar)], v, {});
    if (contact >= 0) rec.contacts.push_back({contact, bar, v});
    rig.recorder->drain(track);
    sleep_until(started + 600 * kMs);
  }
  sleep_ms(400);
  const Nanos end = monotonic_now();
  rig.recorder->drain(track);
  return finish_run(rig, kiosk, log, rec, track, begin, end, xruns_before, result);
}

}  // namespace

ConfigResult run_config(Rig& rig, const Config& config_in, int strokes, const std::string& device,
                        const Deadline& deadline) {
  Config config = config_in;
  const Nanos lead = 12 * kNanosPerSecond;  // the kiosk is up within it (asserted below), a loaded CI too
  RemoteScript script;
  if (config.source == "remote") {
    if (rig.rest_row[0] < 0) throw std::logic_error("bench latency: a remote run needs a mouse run's warm-up first");
    config.replay_file = rig.folders.temp.path() / ("remote-" + config.preset + "-" + config.align + ".replay");
    script = write_remote_script(rig, config.replay_file, strokes, lead);
  }
  ConfigResult result;
  result.config = config;
  const std::filesystem::path settings = rig.folders.temp.path() / ("settings-" + config.preset + "-" + config.align + ".toml");
  write_text(settings, settings_text(config));

  const std::filesystem::path exe = kiosk_executable("bench latency");
  auto log = std::make_shared<KioskLog>();
  ChildOptions o;
  o.argv = {exe.string(),
            "run",
            "--windowed",
            "--size",
            std::to_string(kWidth) + "x" + std::to_string(kHeight),
            "--config",
            settings.string(),
            "--scene",
            rig.scene_file.string()};
  if (!device.empty()) o.argv.insert(o.argv.end(), {"--device", device});
  o.env = rig.folders.kiosk_env(rig.x->name(), rig.jack->name());
  o.on_line = [log](Nanos, std::string_view line) { log->line(line); };
  Child kiosk(std::move(o));

  // Up: it says it runs, its window is on the screen, its audio ports are connected, and
  // a frame has been drawn (the bars are in the strips).
  auto wait_for = [&](const char* what, const std::function<bool()>& done) {
    wait_for_kiosk(kiosk, "bench latency", what, 60 * kNanosPerSecond, done, [&] { deadline.check(); });
  };
  wait_for("its start line", [&] {
    std::lock_guard lock(log->mutex);
    return log->started;
  });
  std::optional<PixelBox> window;
  wait_for("a window on the screen", [&] { return (window = rig.hand->find_window(kWidth, kHeight)).has_value(); });
  if (window->x != 0 || window->y != 0)
    kiosk_failed(kiosk, "window could not be placed at the screen's origin (it is at " + std::to_string(window->x) +
                            "," + std::to_string(window->y) + ")");
  std::vector<std::string> ports;
  wait_for("audio ports on the JACK server", [&] {
    ports = rig.recorder->connect_source(std::chrono::milliseconds(0));
    return !ports.empty();
  });
  wait_for("a first frame", [&] {
    Grab g;
    if (!rig.eye->grab(rig.bars[1].strip, g)) return false;
    const auto [lo, hi] = std::minmax_element(g.rgb.begin(), g.rgb.end());
    return ((*hi >> 8) & 0xff) > ((*lo >> 8) & 0xff) + 30;  // not one flat colour any more
  });
  {
    std::lock_guard lock(log->mutex);
    result.kiosk_status = log->status;
  }
  if (config.source == "remote") return run_remote(rig, kiosk, *log, script, result, deadline);
  return run_mouse(rig, kiosk, *log, result, strokes, deadline);
}

}  // namespace mallet::app::latency
