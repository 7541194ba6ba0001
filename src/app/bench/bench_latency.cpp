// `mallet bench latency`: true contact → actuator, note and picture, measured on the real
// windowed kiosk (a child process) with a virtual X server and a JACK server of the
// bench's own. See bench_latency.hpp for what each time means and --help for the output.
#include "app/bench/bench_latency.hpp"

#include <signal.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include <toml++/toml.h>

#include <fmt/format.h>

#include "app/bench/bench_kiosk_child.hpp"
#include "app/bench/bench_latency_child.hpp"
#include "app/bench/bench_latency_jack.hpp"
#include "app/bench/bench_latency_onset.hpp"
#include "app/bench/bench_latency_x11.hpp"
#include "app/bench/bench_report.hpp"
#include "app/bench/bench_commands.hpp"
#include "core/data_paths.hpp"
#include "core/config/scene_config.hpp"
#include "input/wiimote/reports.hpp"

namespace mallet::app::latency {

// --- matching and statistics (pure)

namespace {

constexpr Nanos kMs = 1'000'000;
constexpr Nanos kStrikeWindow = 50 * kMs;  // a logged strike within ±50 ms of a contact is its strike
constexpr Nanos kCueBefore = 50 * kMs;     // a cue may lead its contact (prediction) by this much
constexpr Nanos kCueAfter = 300 * kMs;     // and lag it by this much at most

std::optional<Nanos> first_in(const std::vector<Nanos>& sorted, Nanos from, Nanos to) {
  auto it = std::lower_bound(sorted.begin(), sorted.end(), from);
  if (it == sorted.end() || *it >= to) return std::nullopt;
  return *it;
}

double ms_of(Nanos dt) { return static_cast<double>(dt) / 1e6; }  // the nearest double: 12 ms is 12.0

}  // namespace

Matched match_recording(const Recording& r) {
  auto sorted = [](std::vector<Nanos> v) {
    std::sort(v.begin(), v.end());
    return v;
  };
  const std::vector<Nanos> strikes = sorted(r.strikes), actuator = sorted(r.actuator), note = sorted(r.note);
  std::vector<std::vector<Nanos>> picture;
  for (const auto& p : r.picture) picture.push_back(sorted(p));
  std::vector<Recording::Contact> contacts = r.contacts;
  std::sort(contacts.begin(), contacts.end(), [](const auto& a, const auto& b) { return a.t < b.t; });

  Matched m;
  m.cues = {{"actuator", {}}, {"note", {}}, {"picture", {}}, {"actuator-picture", {}}, {"note-actuator", {}}};
  std::vector<char> used(strikes.size(), 0);
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Recording::Contact& c = contacts[k];
    // The nearest unused logged strike within the window.
    std::optional<std::size_t> best;
    for (std::size_t i = 0; i < strikes.size(); ++i) {
      if (used[i] || std::llabs(strikes[i] - c.t) > kStrikeWindow) continue;
      if (!best || std::llabs(strikes[i] - c.t) < std::llabs(strikes[*best] - c.t)) best = i;
    }
    StrikeRow row{c, {}, {}, {}, {}};
    if (!best) {
      ++m.missed_strikes;
      m.rows.push_back(row);
      continue;
    }
    used[*best] = 1;
    ++m.strikes;
    row.strike_ms = ms_of(strikes[*best] - c.t);
    // A cue belongs to this contact if it comes before the next contact's own window opens.
    const Nanos to =
        std::min(c.t + kCueAfter, k + 1 < contacts.size() ? contacts[k + 1].t - kCueBefore : c.t + kCueAfter);
    const std::optional<Nanos> a = first_in(actuator, c.t - kCueBefore, to);
    const std::optional<Nanos> n = first_in(note, c.t - kCueBefore, to);
    std::optional<Nanos> p;
    if (c.bar >= 0 && static_cast<std::size_t>(c.bar) < picture.size())
      p = first_in(picture[static_cast<std::size_t>(c.bar)], c.t - kCueBefore, to);
    if (a) m.cues[0].ms.push_back(*(row.actuator_ms = ms_of(*a - c.t)));
    if (n) m.cues[1].ms.push_back(*(row.note_ms = ms_of(*n - c.t)));
    if (p) m.cues[2].ms.push_back(*(row.picture_ms = ms_of(*p - c.t)));
    if (a && p) m.cues[3].ms.push_back(ms_of(*a - *p));
    if (n && a) m.cues[4].ms.push_back(ms_of(*n - *a));
    m.rows.push_back(row);
  }
  for (char u : used) m.false_strikes += u ? 0 : 1;
  return m;
}

Summary summarise(std::vector<double> ms) {
  Summary s;
  s.n = ms.size();
  if (ms.empty()) return s;
  std::sort(ms.begin(), ms.end());
  const std::size_t n = ms.size();
  s.median = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
  s.p99 = nearest_rank(ms, 0.99);
  s.max = std::fabs(ms.front()) > std::fabs(ms.back()) ? ms.front() : ms.back();
  return s;
}

// --- the run

namespace {

constexpr int kWidth = 960, kHeight = 540;
constexpr int kRate = 48000, kPeriod = 128;
constexpr int kPictureTolerancePx = 1;

//! The whole run's bound, and every wait's check for a signal.
struct Deadline {
  Nanos end = 0;
  void check() const {
    if (const int s = stop_signal())
      throw std::runtime_error("bench latency: stopped by signal " + std::to_string(s));
    if (monotonic_now() > end) throw std::runtime_error("bench latency: the run took longer than its bound; stopped");
  }
};

//! The shipped percussion scene with no visual vibration: a copy of the scene and of its
//! materials file with every material's visual amplitude_s set to 0 (the actuator and the
//! acoustic parameters as shipped). The bounce lifts the head a few mm right after the
//! contact, which would delay the picture's "mallet at the bar"; without it, the first
//! frame that shows the head at the bar is the frame where the bounce starts.
std::filesystem::path still_scene(const std::filesystem::path& dir) {
  const std::filesystem::path shipped = default_scene();
  toml::table scene = toml::parse_file(shipped.string());
  const auto beside = [&](std::string_view key, const char* shipped_default) {
    return (shipped.parent_path() / scene[key].value_or(std::string(shipped_default))).lexically_normal();
  };
  const std::filesystem::path materials = beside("materials_file", "../materials.toml");
  scene.insert_or_assign("materials_file", (dir / "materials.toml").string());
  scene.insert_or_assign("instruments_file", beside("instruments_file", "../instruments.toml").string());
  toml::table still = toml::parse_file(materials.string());
  if (toml::table* all = still["material"].as_table())
    for (auto& [name, material] : *all)
      if (toml::table* visual = material.as_table() ? (*material.as_table())["visual"].as_table() : nullptr)
        visual->insert_or_assign("amplitude_s", 0.0);
  std::ostringstream materials_text, scene_text;
  materials_text << still;
  scene_text << scene;
  write_text(dir / "materials.toml", materials_text.str());
  std::filesystem::create_directories(dir / "scenes");
  const std::filesystem::path file = dir / "scenes" / "percussion.toml";
  write_text(file, scene_text.str());
  return file;
}

//! A bar the hand strikes, in world metres and window pixels.
struct Bar {
  int target = 0;
  std::string name;        //!< "glockenspiel bar 4 (metal)"
  double x_m = 0;          //!< the bar's middle
  double contact_y_m = 0;  //!< top + mallet radius: the sphere's centre at contact
  int x_px = 0;            //!< the middle, window pixels
  PixelBox strip;          //!< where the picture watch looks, screen pixels
};

//! The kiosk's window pixels ↔ world metres: the window is the whole screen, and the
//! kiosk maps a cursor at (px, py) to screen_to_world(px / width, py / height).
struct Mapping {
  const Scene* scene = nullptr;
  double y_of_row(int row) const { return scene->screen_to_world.map(0.5, static_cast<double>(row) / kHeight).y; }
  double row_of_y(double y) const { return scene->screen_to_world.unmap({0.0, y}).y * kHeight; }
  double col_of_x(double x) const { return scene->screen_to_world.unmap({x, 0.0}).x * kWidth; }
};

std::vector<Bar> choose_bars(const Scene& scene, const Mapping& map) {
  std::vector<Bar> bars;
  for (const char* material : {"metal", "wood"}) {
    for (const Instrument& inst : scene.instruments) {
      if (inst.targets.empty() || scene.materials.at(static_cast<std::size_t>(inst.material)).name != material)
        continue;
      const Target& t = scene.targets.at(static_cast<std::size_t>(inst.targets[inst.targets.size() / 2]));
      Bar b;
      b.target = t.id;
      b.name = inst.name + " bar " + std::to_string(inst.targets.size() / 2 + 1) + " (" + material + ")";
      b.x_m = 0.5 * (t.x_min + t.x_max);
      b.contact_y_m = t.top_y + scene.mallet_radius_m;
      b.x_px = static_cast<int>(std::lround(map.col_of_x(b.x_m)));
      const double centre_row = map.row_of_y(b.contact_y_m);
      const double radius_px = scene.mallet_radius_m / std::fabs(map.y_of_row(0) - map.y_of_row(1));
      // From 70 px above the resting head's centre (the hovering head is in view) to just
      // below its lowest pixel; 5 px wide around the bar's middle.
      const int top = std::max(0, static_cast<int>(centre_row) - 70);
      const int bottom = std::min(kHeight - 1, static_cast<int>(centre_row + radius_px) + 8);
      b.strip = {std::clamp(b.x_px - 2, 0, kWidth - 5), top, 5, bottom - top + 1};
      bars.push_back(b);
      break;
    }
  }
  if (bars.size() != 2) throw std::runtime_error("bench latency: the scene needs a metal and a wood instrument");
  return bars;
}

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

struct Config {
  std::string preset, align;
  std::string source = "mouse";  //!< or "remote": a recording played as a live Wii Remote
  std::filesystem::path replay_file;  //!< for "remote"
};

struct ConfigResult {
  Config config;
  Matched matched;
  std::vector<std::string> kiosk_status;
  int rest_row[2] = {0, 0};
  double resolution_ms = 0;  //!< ±1 px / v at the slowest stroke
  std::uint64_t xruns = 0;   //!< JACK xruns during the strokes
};

//! Everything the runs share: the servers, the recorder, the hand, the eye.
struct Rig {
  KioskFolders folders{"mallet-bench-latency"};  //!< the kiosk's runtime and state folders, and ours
  std::filesystem::path scene_file;
  Scene scene;
  Mapping map;
  std::vector<Bar> bars;
  std::unique_ptr<VirtualDisplay> x;
  std::unique_ptr<JackServer> jack;
  std::unique_ptr<JackRecorder> recorder;
  std::unique_ptr<FakePointer> hand;
  std::unique_ptr<ScreenReader> eye;
  std::unique_ptr<PictureWatch> watch;
  int rest_row[2] = {-1, -1};  //!< where the head rests on each bar (a mouse run's warm-up)
};

//! The hand (the sphere's centre) at world (x, y): the pointer at that window pixel.
struct Hand {
  const Rig& rig;
  Nanos move(double x_m, double y_m, int* row_out = nullptr) const {
    const int col = static_cast<int>(std::lround(rig.map.col_of_x(x_m)));
    const int row = std::clamp(static_cast<int>(std::lround(rig.map.row_of_y(y_m))), 0, kHeight - 1);
    if (row_out) *row_out = row;
    return rig.hand->move_to(col, row);
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

//! The remote's strokes, as a recording (the `mallet wiimote monitor --record` format) the
//! kiosk plays as a live remote (`[input] source = "replay"`): one report every 10 ms (the
//! camera's 100 Hz), the camera's view mirrored onto the screen (the kiosk's mapping when it
//! has no calibration), whole camera pixels. After `lead` of a hovering hand (the kiosk
//! starts and takes it for a visitor), `strokes` downswings alternating between the bars,
//! one every 600 ms plus 3.3 ms more each time, so that contacts fall anywhere between two
//! camera frames. Times relative to the recording's time 0.
struct RemoteScript {
  std::vector<Recording::Contact> contacts;
  Nanos first_stroke = 0, end = 0;
};

RemoteScript write_remote_script(const Rig& rig, const std::filesystem::path& file, int strokes, Nanos lead) {
  const double above_m = 0.04, below_m = 0.03;
  const double speeds[] = {1.0, 1.5, 2.0, 1.25, 1.75};
  struct Stroke {
    Nanos start;
    int bar;
    double v;
  };
  std::vector<Stroke> plan;
  RemoteScript script;
  for (int k = 0; k < strokes; ++k) {
    const Nanos start = lead + k * 600 * kMs + (k * 3'300'000) % (10 * kMs);
    const int bar = k % 2;
    const double v = speeds[static_cast<std::size_t>(k) % 5];
    plan.push_back({start, bar, v});
    script.contacts.push_back({start + static_cast<Nanos>(std::llround(above_m / v * 1e9)), bar, v});
  }
  script.first_stroke = plan.empty() ? lead : plan.front().start;
  script.end = lead + strokes * 600 * kMs + 300 * kMs;
  // The hand at t: hovering above the bar of the stroke to come (moving over in 100 ms,
  // 250 ms before it), or in a stroke: down at v to below_m under the contact plane, held
  // 80 ms, back up in 70 ms.
  auto hand_at = [&](Nanos t) -> Vec2 {
    std::size_t next = 0;
    while (next < plan.size() && plan[next].start <= t) ++next;
    if (next > 0) {  // in or after stroke next − 1
      const Stroke& s = plan[next - 1];
      const Bar& b = rig.bars[static_cast<std::size_t>(s.bar)];
      const double top = b.contact_y_m + above_m, bottom = b.contact_y_m - below_m;
      const Nanos down = static_cast<Nanos>(std::llround((top - bottom) / s.v * 1e9));
      const Nanos since = t - s.start;
      if (since < down) return {b.x_m, top - s.v * to_seconds(since)};
      if (since < down + 80 * kMs) return {b.x_m, bottom};
      if (since < down + 150 * kMs) return {b.x_m, bottom + (top - bottom) * to_seconds(since - down - 80 * kMs) / 0.07};
    }
    const Bar& to = rig.bars[static_cast<std::size_t>(next < plan.size() ? plan[next].bar : 0)];
    const Bar& from = rig.bars[static_cast<std::size_t>(next > 0 ? plan[next - 1].bar : 0)];
    const Nanos move_at = (next < plan.size() ? plan[next].start : script.end) - 250 * kMs;
    const double f = std::clamp(to_seconds(t - move_at) / 0.1, 0.0, 1.0);
    // A visitor arrives: a 1 cm sway (past the kiosk's dead band, so it leaves the attract
    // mode and its ghost stops playing), whole periods ending 2 s before the first stroke.
    const double sway =
        t < lead - 2 * kNanosPerSecond ? 0.01 * std::sin(2 * M_PI * to_seconds(t) / 2.0) : 0.0;
    return {from.x_m + (to.x_m - from.x_m) * f + sway, to.contact_y_m + above_m};
  };
  std::ofstream out(file);
  input::wiimote::ReplayWriter writer(out);
  for (Nanos t = 0; t <= script.end; t += 10 * kMs) {
    const Vec2 screen = rig.scene.screen_to_world.unmap(hand_at(t));
    const int cx = std::clamp(static_cast<int>(std::lround((1.0 - screen.x) * 1023)), 0, 1023);
    const int cy = std::clamp(static_cast<int>(std::lround(screen.y * 767)), 0, 767);
    writer.write(t, input::wiimote::extended_ir_report(cx, cy));
  }
  out.close();
  if (!out) throw std::runtime_error("bench latency: cannot write " + file.string());
  return script;
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

  // Take over from the attract mode's ghost: a first sample anchors, a second moves.
  rig.hand->move_to(kWidth / 2, kHeight / 6);
  sleep_ms(40);
  rig.hand->move_to(kWidth / 2, kHeight / 6 + 30);
  sleep_ms(400);

  const Hand hand{rig};
  const double above_m = 0.04, below_m = 0.03;
  const double speeds[] = {1.0, 1.5, 2.0, 1.25, 1.75};
  // One stroke on bar b at v m/s: hover above it, a straight downswing (an event every
  // 1 ms) to 3 cm below the contact plane, a pause there (`on_hold` may look at the screen
  // meanwhile), back up. Returns the true contact (−1 if the path never crossed).
  auto stroke = [&](const Bar& b, double v, const std::function<void()>& on_hold) -> Nanos {
    const double top = b.contact_y_m + above_m, bottom = b.contact_y_m - below_m;
    hand.move(b.x_m, top);
    sleep_ms(15);
    hand.move(b.x_m, top);
    sleep_ms(150);
    std::vector<std::pair<Nanos, double>> path;  // (when sent, world y the kiosk sees)
    const Nanos t0 = monotonic_now() + kMs;
    for (int k = 0;; ++k) {
      const Nanos due = t0 + k * kMs;
      const double y = std::max(bottom, top - v * to_seconds(due - t0));
      sleep_until(due);
      int row = 0;
      const Nanos sent = hand.move(b.x_m, y, &row);
      path.emplace_back(sent, rig.map.y_of_row(row));
      if (y <= bottom) break;
    }
    // The crossing of the contact plane, interpolated between the two events around it.
    Nanos contact = -1;
    for (std::size_t k = 1; k < path.size() && contact < 0; ++k) {
      const auto [ta, ya] = path[k - 1];
      const auto [tb, yb] = path[k];
      if (ya > b.contact_y_m && yb <= b.contact_y_m)
        contact =
            ta + static_cast<Nanos>(std::llround((ya - b.contact_y_m) / (ya - yb) * static_cast<double>(tb - ta)));
    }
    sleep_ms(80);
    if (on_hold) on_hold();
    for (int k = 1; k <= 20; ++k) {  // back up at ≈1 m/s
      hand.move(b.x_m, bottom + (top - bottom) * k / 20.0);
      sleep_ms(3.5);
    }
    return contact;
  };

  // Warm-up: one stroke per bar, and while the hand is held below it, where the head rests
  // at the bar in the picture (the contact solver holds it at the surface).
  for (std::size_t i = 0; i < rig.bars.size(); ++i) {
    deadline.check();
    std::optional<int> rest;
    stroke(rig.bars[i], 1.0, [&] {
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
    const double v = speeds[static_cast<std::size_t>(s) % 5];
    const Nanos contact = stroke(rig.bars[static_cast<std::size_t>(bar)], v, {});
    if (contact >= 0) rec.contacts.push_back({contact, bar, v});
    rig.recorder->drain(track);
    sleep_until(started + 600 * kMs);
  }
  sleep_ms(400);
  const Nanos end = monotonic_now();
  rig.recorder->drain(track);
  return finish_run(rig, kiosk, *log, rec, track, begin, end, xruns_before, result);
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five;
  in >> one >> five;
  return in ? one + " / " + five : std::string("unknown");
}

std::string cell(const std::optional<double>& v) {
  if (!v) return "nan";
  return fmt::format("{:.3f}", *v);
}

}  // namespace

void run_bench_latency(const LatencyOptions& options) {
  // The servers, named by their Debian packages when they are missing.
  require_x_and_jack("bench latency");
  StopSignals signals;
  const int strokes = options.strokes > 0 ? options.strokes : options.quick ? 6 : 20;
  const std::vector<std::string> presets =
      options.quick ? std::vector<std::string>{"balanced"} : std::vector<std::string>{"balanced", "exact"};
  const std::vector<std::string> aligns = {"asap", "picture"};
  const std::vector<std::string> sources = {"mouse", "remote"};
  const std::size_t configs = presets.size() * aligns.size() * sources.size();
  // Start-up ≈ 15 s, a configuration ≈ 10 s + 0.6 s a stroke: the bound is well above that.
  Deadline deadline{monotonic_now() + (40 + static_cast<Nanos>(configs) * (60 + strokes)) * kNanosPerSecond};
  std::filesystem::create_directories(options.out);

  Rig rig;
  rig.scene_file = still_scene(rig.folders.temp.path());
  rig.scene = config::load_scene(rig.scene_file);
  for (const Material& m : rig.scene.materials)
    if (m.visual.amplitude != 0.0) throw std::runtime_error("bench latency: the still scene still has a bounce");
  rig.map.scene = &rig.scene;
  rig.bars = choose_bars(rig.scene, rig.map);

  rig.x = std::make_unique<VirtualDisplay>(kWidth, kHeight);
  deadline.check();
  rig.jack = std::make_unique<JackServer>("mallet-bench-" + std::to_string(getpid()), kRate, kPeriod);
  deadline.check();
  rig.recorder = std::make_unique<JackRecorder>(rig.jack->name(), 2);
  rig.hand = std::make_unique<FakePointer>(rig.x->name());
  rig.eye = std::make_unique<ScreenReader>(rig.x->name());
  std::vector<PixelBox> strips;
  for (const Bar& b : rig.bars) strips.push_back(b.strip);
  rig.watch = std::make_unique<PictureWatch>(rig.x->name(), strips, kPictureTolerancePx);

  std::printf("mallet bench latency: true contact → each cue, measured on `mallet run --windowed` "
              "(a child process)\n");
  std::printf(
      "  X: Xvfb %s, %dx%d; JACK: dummy driver, %d Hz, %d-frame cycles (%.2f ms), playback latency %.2f ms, "
      "JACK clock − monotonic %+.3f ms\n",
      rig.x->name().c_str(), kWidth, kHeight, rig.recorder->rate(), rig.recorder->period(),
      1e3 * rig.recorder->period() / rig.recorder->rate(), to_seconds(rig.recorder->playback_latency_ns()) * 1e3,
      to_seconds(rig.recorder->clock_offset_ns()) * 1e3);
  std::printf("  strokes: %d per configuration on %s and %s, 1.0–2.0 m/s, one every 600 ms\n", strokes,
              rig.bars[0].name.c_str(), rig.bars[1].name.c_str());
  std::fflush(stdout);

  std::vector<ConfigResult> results;
  for (const std::string& preset : presets)
    for (const std::string& align : aligns)
      for (const std::string& source : sources) {  // the mouse first: its warm-up finds where the head rests
        deadline.check();
        std::printf("  running: %s, quality %s, align %s ...\n", source.c_str(), preset.c_str(), align.c_str());
        std::fflush(stdout);
        results.push_back(run_config(rig, {preset, align, source, {}}, strokes, options.device, deadline));
        for (const std::string& line : results.back().kiosk_status) std::printf("    kiosk: %s\n", line.c_str());
        std::fflush(stdout);
      }
  const double poll_ms = rig.watch->mean_poll_ms();
  const std::uint64_t xruns = rig.recorder->xruns(), dropped = rig.recorder->dropped();

  // The table and the CSV. The table has two columns the CSV has not: n, the strikes the
  // cue was measured for, and the JACK xruns during the configuration's strokes.
  std::printf("\n| source | preset   | align   | cue              | median ms | p99 ms   | max ms   "
              "| strikes | false | missed |  n | xruns |\n");
  std::printf("|--------|----------|---------|------------------|-----------|----------|----------"
              "|---------|-------|--------|----|-------|\n");
  const std::filesystem::path csv_path = options.out / "latency.csv";
  std::ofstream csv(csv_path);
  csv << "source,preset,align,cue,median_ms,p99_ms,max_ms,strikes,false_strikes,missed_strikes\n";
  for (const ConfigResult& r : results)
    for (const CueSamples& c : r.matched.cues) {
      const Summary s = summarise(c.ms);
      std::printf("| %-6s | %-8s | %-7s | %-16s | %9s | %8s | %8s | %7d | %5d | %6d | %2zu | %5llu |\n",
                  r.config.source.c_str(), r.config.preset.c_str(), r.config.align.c_str(), c.cue.c_str(), cell(s.median).c_str(),
                  cell(s.p99).c_str(), cell(s.max).c_str(), r.matched.strikes, r.matched.false_strikes,
                  r.matched.missed_strikes, s.n, static_cast<unsigned long long>(r.xruns));
      csv << r.config.source << ',' << r.config.preset << ',' << r.config.align << ',' << c.cue << ',' << cell(s.median) << ','
          << cell(s.p99) << ',' << cell(s.max) << ',' << r.matched.strikes << ',' << r.matched.false_strikes << ','
          << r.matched.missed_strikes << '\n';
    }
  csv.close();
  if (!csv) throw std::runtime_error("cannot write " + csv_path.string());
  // Every strike, for a closer look (not part of the summary's contract).
  const std::filesystem::path strikes_path = options.out / "latency_strikes.csv";
  std::ofstream per(strikes_path);
  per << "source,preset,align,stroke,bar,speed_m_per_s,contact_s,strike_ms,actuator_ms,note_ms,picture_ms\n";
  for (const ConfigResult& r : results)
    for (std::size_t i = 0; i < r.matched.rows.size(); ++i) {
      const StrikeRow& row = r.matched.rows[i];
      const std::string t = fmt::format("{:.6f}", to_seconds(row.contact.t));
      per << r.config.source << ',' << r.config.preset << ',' << r.config.align << ',' << i << ','
          << rig.bars[static_cast<std::size_t>(row.contact.bar)].target << ',' << row.contact.speed << ',' << t << ','
          << cell(row.strike_ms) << ',' << cell(row.actuator_ms) << ',' << cell(row.note_ms) << ','
          << cell(row.picture_ms) << '\n';
    }
  per.close();
  if (!per) throw std::runtime_error("cannot write " + strikes_path.string());

  std::printf(
      "\nCue − true contact, ms. actuator-picture and note-actuator: signed differences per strike (positive: the\n"
      "first named cue comes later); max = the sample of largest magnitude, sign kept. Cues are counted for the\n"
      "strikes the kiosk logged within ±50 ms of a true contact.\n");
  std::printf(
      "  true contact: the injected pointer path (XTest motion every 1 ms, stamped on CLOCK_MONOTONIC when flushed)\n"
      "    crossing the contact plane (bar top + mallet radius), interpolated between the two events around it.\n");
  std::printf(
      "  actuator, note: the strike's first sample on its channel as the JACK recorder heard it, at its cycle's time\n"
      "    plus the playback latency (%.2f ms); over a bar still ringing, the first sample a linear predictor of\n"
      "    the ring does not explain.\n",
      to_seconds(rig.recorder->playback_latency_ns()) * 1e3);
  std::printf(
      "  picture: the first frame in the X server's framebuffer that shows the mallet at the bar (where the bounce\n"
      "    starts; the bench's scene has its visual amplitude set to 0): the head's lowest white pixel within %d px\n"
      "    of where it rests on the bar (rows %d, %d). Framebuffer polled every %.2f ms on average; detection\n"
      "    resolution ±1 px / v = ±%.2f ms at 1.0 m/s. Xvfb has no display: a panel's scan-out comes on top.\n",
      kPictureTolerancePx, results.empty() ? 0 : results[0].rest_row[0], results.empty() ? 0 : results[0].rest_row[1],
      poll_ms, results.empty() ? 0.0 : results[0].resolution_ms);
  std::error_code ec;
  std::printf(
      "  source remote = a recording played as a live Wii Remote ([input] source = \"replay\": the real device\n"
      "    start-up, reading thread, IR tracker and strike route; 100 Hz reports, contacts anywhere between two);\n"
      "    its true contact = the recorded path's crossing, placed on the kiosk's clock by the replay's start line.\n");
  std::printf(
      "  source mouse = the window system's pointer ([input] mouse = \"window\"). The evdev mouse is not measured:\n"
      "    injecting it needs /dev/uinput%s.\n",
      std::filesystem::exists("/dev/uinput", ec) ? " (present here, but the bench does not use it yet)"
                                                 : ", which this machine lacks");
  std::string disturbed;
  for (const ConfigResult& r : results)
    if (r.xruns > 0)
      disturbed += (disturbed.empty() ? "" : ", ") + r.config.source + "/" + r.config.preset + "/" + r.config.align;
  std::printf(
      "  JACK: %llu xruns in all (start-ups included), %llu cycles the recorder had no room for. This machine:\n"
      "    %ld CPUs online, load average %s.\n",
      static_cast<unsigned long long>(xruns), static_cast<unsigned long long>(dropped), sysconf(_SC_NPROCESSORS_ONLN),
      load_average().c_str());
  if (!disturbed.empty())
    std::printf(
        "  ! Audio rows of these ran with xruns (the machine could not keep JACK's cycles): %s.\n"
        "    A late cycle costs the dummy driver that time; the kiosk's audio stream re-anchors its clock\n"
        "    when its callback finds itself behind (OutputCounters::resyncs), so the loss does not add up,\n"
        "    but a strike near a late cycle is heard late. Strikes whose onset lies on such a seam are left\n"
        "    out (n). Rerun on an idle machine for the kiosk's own figures.\n",
        disturbed.c_str());
  std::printf("wrote %s and %s\n", csv_path.c_str(), strikes_path.c_str());
}

}  // namespace mallet::app::latency

namespace mallet::app {

void add_bench_latency(CLI::App& bench) {
  auto o = std::make_shared<latency::LatencyOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "latency", "Measured: true contact → actuator, note and picture on the real windowed kiosk (Xvfb + JACK)");
  cmd->footer(R"(Starts its own X server (Xvfb, Debian package xvfb) and JACK server (jackd2, dummy driver), runs
`mallet run --windowed` under them once per source (mouse, remote), quality preset (balanced, exact;
--quick: balanced) and [timing] align (asap, picture), strikes a metal and a wood bar with the X pointer (XTest; a straight
downswing at 1.0-2.0 m/s, 20 strokes per run, 6 with --quick) and measures, per strike, from the true
contact (the injected path crossing the bar's contact plane) to:
  actuator, note  the strike's first sample on each channel, recorded by a JACK client of the bench's
                  own. JACK's dummy driver is paced by a real-time timer, so its sample clock is wall
                  time; ALSA's file plugin (the other card-free path) is not paced: PortAudio writes into
                  it as fast as it can, so sample indices there carry no wall time.
  picture         the first frame in the X server's framebuffer showing the mallet at the bar (where the
                  bounce starts; the bench's scene copy has no visual vibration so nothing lifts it).
Output: a table on stdout and OUT/latency.csv (OUT defaults to the current directory), one row per
source x preset x align x cue (OUT/latency_strikes.csv has every stroke):
  source,preset,align,cue,median_ms,p99_ms,max_ms,strikes,false_strikes,missed_strikes
cue: actuator, note, picture (cue time - true contact), and the signed asynchronies actuator-picture
and note-actuator (per strike, first named minus second named; their max_ms is the value of largest
magnitude, sign kept). strikes: true contacts the kiosk logged a strike for within +-50 ms;
false_strikes: logged strikes with no true contact within +-50 ms; missed_strikes: true contacts with
none. A value that could not be measured is nan. source: "mouse" (the window system's pointer) or
"remote" (a recording of 100 Hz IR reports the bench writes, played by the kiosk as a live Wii Remote:
[input] source = "replay"); the evdev mouse cannot be injected without /dev/uinput.
Everything it starts is stopped on exit, on errors and on Ctrl+C. Exit status 1 when a server or the
kiosk cannot run here (the message names what is missing).)");
  cmd->add_option("--out", o->out, "Output directory for latency.csv (default: the current directory)")
      ->capture_default_str();
  cmd->add_flag("--quick", o->quick, "The balanced preset only, 6 strokes per run (a check that it works; ~1 min)");
  cmd->add_option("--strokes", o->strokes, "Strokes per configuration (default 20, 6 with --quick)")
      ->check(CLI::Range(2, 500));
  cmd->add_option("--device", o->device, "The kiosk's Vulkan device (substring of its name; default: its own choice)");
  cmd->callback([o] { latency::run_bench_latency(*o); });
}

}  // namespace mallet::app
