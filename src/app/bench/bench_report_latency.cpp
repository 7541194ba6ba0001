// The latency budget of `mallet bench report`, through the real code paths: an IR report
// as received → report parser and IR tracker (input/wiimote/report_tracker) → camera to
// world → the kiosk's strike loop (contact solver) → the audio engine's ring → the
// engine's process() → the first sample of the strike in the output buffer. CPU times
// are measured (wall clock, this machine); waiting for the next audio callback is on the
// sample clock; the frame that shows the bounce is a model from the measured frame time.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <fmt/format.h>

#include "audio/audio_setup.hpp"
#include "app/bench/bench_report.hpp"
#include "core/csv_file.hpp"
#include "app/strike/strike_route.hpp"
#include "core/quality.hpp"
#include "input/wiimote/report_tracker.hpp"

namespace mallet::app {
namespace {

using Clock = std::chrono::steady_clock;

std::string ms(double v) {
  return fmt::format("{:.3f}", v);
}

struct Measured {
  std::vector<double> path_ms, process_ms, stream_ms;
  std::uint64_t late = 0;
};

//! Strikes at 2 m/s seen by the camera at 100 Hz, the contact at a random point between
//! two camera frames and the report at a random point of the audio block being played.
//! Per strike: the wall time of the report that makes it (parse → track → map → solve →
//! post) and of the process() call that writes its first sample, and on the stream's
//! sample clock the time from the report to that sample (the engine's own scheduling:
//! the next callback, schedule_ahead_ms, late strikes).
Measured measure(const Scene& scene, const AppConfig& config, int strikes) {
  Measured m;
  const ScreenToWorld& v = scene.screen_to_world;
  const int block = config.audio.frames_per_buffer;
  const int fs = config.audio.sample_rate_hz;
  const Target& bar = scene.targets.at(scene.targets.size() / 2);
  const double x = 0.5 * (bar.x_min + bar.x_max);
  const double contact_y = bar.top_y + scene.mallet_radius_m;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < strikes; ++k) {
    input::wiimote::ReportTracker tracker(config.tracking);
    audio::AudioRig rig = audio::make_audio_rig(scene, config, fs);
    StrikeRoute route(scene, config, rig.engine.get(), nullptr, RouteOptions{audio::Producer::input, false, false});
    std::vector<float> out(static_cast<std::size_t>(block * config.audio.routing.channels));
    const double phase_s = unit(rng) * 0.01;  // where between camera frames the contact falls
    for (int f = 0; f < 40; ++f) {
      const Nanos t = kNanosPerSecond + f * 10'000'000LL;
      const double y = contact_y + 0.05 - 2.0 * (f * 0.01 + phase_s);  // 2 m/s down
      const Vec2 screen = v.unmap({x, y});
      const auto report = input::wiimote::extended_ir_report(std::clamp(static_cast<int>(std::lround(screen.x * 1023)), 0, 1023),
                                    std::clamp(static_cast<int>(std::lround(screen.y * 767)), 0, 767));
      const auto t0 = Clock::now();
      const input::wiimote::ReportOutcome r = tracker.feed(t, report);
      std::optional<Impact> impact;
      if (r.update.point) {
        const Vec2 world = v.map(r.update.point->x / 1023.0, r.update.point->y / 767.0);
        if (const std::optional<Strike> s = route.feed(t, world, t)) impact = s->impact;
      }
      const auto t1 = Clock::now();
      if (!impact) continue;
      m.path_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      // The stream: the next callback renders from position P, due (1 − u) blocks after the report.
      const double next_callback_s = (1.0 - unit(rng)) * block / fs;
      const std::int64_t p = rig.engine->position();
      const Nanos origin = t + static_cast<Nanos>(std::llround((next_callback_s - static_cast<double>(p) / fs) * 1e9));
      rig.engine->set_origin(origin);
      for (int b = 0; b < 1000; ++b) {
        const std::int64_t base = rig.engine->position();
        const auto p0 = Clock::now();
        rig.engine->process(out.data(), block);
        const auto p1 = Clock::now();
        int first = -1;
        for (int i = 0; i < block && first < 0; ++i)
          if (out[static_cast<std::size_t>(i * config.audio.routing.channels + config.audio.routing.actuator)] != 0.0f) first = i;
        if (first >= 0) {
          // Sample 0 of a strike is sin(0) = 0: its first sample is the one before the first non-zero.
          const double due_ns = static_cast<double>(origin) + static_cast<double>(base + first - 1) * 1e9 / fs;
          m.stream_ms.push_back((due_ns - static_cast<double>(t)) * 1e-6);
          m.process_ms.push_back(std::chrono::duration<double, std::milli>(p1 - p0).count());
          break;
        }
      }
      m.late += rig.engine->counters().late;
      break;
    }
  }
  return m;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}
double maximum(const std::vector<double>& v) { return v.empty() ? 0 : *std::max_element(v.begin(), v.end()); }

}  // namespace

//! The measured end-to-end figures of `mallet bench latency`, when a latency.csv from it lies
//! in the report's folder: the model above against what a real windowed kiosk did.
static void include_measured_latency(const ReportOptions& o, ReportSections& out) {
  const std::filesystem::path csv = o.out / "latency.csv";
  std::error_code ec;
  if (!std::filesystem::exists(csv, ec)) {
    out.skipped.push_back("measured latency: run `mallet bench latency --out " + o.out.string() +
                          "` before the report to include it");
    return;
  }
  const csv::Table t = csv::read(csv);
  TextTable measured{"Measured end to end (mallet bench latency): true contact → cue, the real windowed kiosk",
                     {"source", "preset", "align", "cue", "median ms", "p99 ms", "max ms", "strikes", "false",
                      "missed"},
                     {},
                     ""};
  for (const csv::Row& row : t.rows) measured.rows.push_back(row.fields);
  measured.note =
      "Measured, not modelled: Xvfb (no vblank, no panel) and a JACK dummy server as the sound card (2.7 ms "
      "cycles plus 5.3 ms playback latency). Where it differs from the model above: the model's FIFO frame waits "
      "for a 60 Hz vblank, Xvfb has none, so the picture comes 2–5 ms after the contact (balanced; 10–17 ms with exact's 4x MSAA on every frame) instead of 25–33 ms; "
      "the audio then comes after the picture, by the sound card's own buffering, which the model leaves out "
      "and which align = \"picture\" cannot shorten (it can only delay a cue).";
  out.tables.push_back(measured);
}

void measure_latency_budget(const Scene& scene, const ReportOptions& o, ReportSections& out) {
  if (scene.targets.empty()) return;
  TextTable audio{"Latency budget: IR report received → strike → its first audio sample in the output buffer",
                  {"preset (block, schedule_ahead_ms)", "report → strike → ring, median / max ms (wall)",
                   "report → first sample due, median / max ms (sample clock)",
                   "process() of that block, median / max ms (wall)", "late strikes", "worst total ms",
                   "≤ 5 ms?"},
                  {}, ""};
  const int strikes = o.quick ? 4 : 400;
  struct Row {
    std::string name;
    AppConfig config;
  };
  std::vector<Row> rows;
  for (const auto& [q, quality] : kQualityNames) {
    AppConfig c;
    apply_quality(q, c);
    rows.push_back({quality, c});
  }
  rows.push_back({"not a preset", rows.back().config});
  rows.back().config.audio.schedule_ahead_ms = 5.0;  // shorter than a camera frame: what exact would be without it
  for (const Row& row : rows) {
    const AppConfig& c = row.config;
    const Measured m = measure(scene, c, strikes);
    const double total = maximum(m.path_ms) + maximum(m.stream_ms) + maximum(m.process_ms);
    const std::string head = fmt::format("{} ({}, {:g})", row.name.c_str(), c.audio.frames_per_buffer,
                                         c.audio.schedule_ahead_ms);
    audio.rows.push_back({head, ms(median(m.path_ms)) + " / " + ms(maximum(m.path_ms)),
                          ms(median(m.stream_ms)) + " / " + ms(maximum(m.stream_ms)),
                          ms(median(m.process_ms)) + " / " + ms(maximum(m.process_ms)),
                          std::to_string(m.late) + " of " + std::to_string(m.stream_ms.size()), ms(total),
                          c.audio.schedule_ahead_ms > 0 ? "constant delay by design" : (total <= 5.0 ? "yes" : "no")});
  }
  audio.note =
      "Through the real code: report parser + IR tracker (ReportTracker), camera → world, the kiosk's StrikeLoop "
      "(contact solver), AudioEngine::post → process(). The report arrives at a random point of the audio block being "
      "played; the contact at a random point between two camera frames (100 Hz), i.e. up to 10 ms before its report: "
      "a constant schedule_ahead_ms counts from the contact, so one shorter than a camera frame makes strikes late "
      "(they then sound as soon as possible). Not included: the device's own output buffering (PortAudio reports it "
      "per device; 8 ms for ALSA's file plugin at 64 frames) and the Bluetooth link.";
  out.tables.push_back(audio);

  TextTable video{"Strike → first frame that shows the bounce (model from the measured frame time)",
                  {"present mode", "refresh Hz", "mean ms", "worst ms"}, {}, ""};
  const double r = out.frame_ms_balanced > 0 ? out.frame_ms_balanced : 10.0;
  for (const char* mode : {"fifo", "mailbox", "immediate"})
    for (double hz : {60.0, 120.0, 144.0}) {
      const double T = 1e3 / hz;
      double mean = 0, worst = 0;
      if (std::string(mode) == "fifo") {  // wait for the next frame start, render, wait for the vblank after it
        const double to_vblank = std::ceil(r / T) * T;
        mean = T / 2 + to_vblank;
        worst = T + to_vblank;
      } else if (std::string(mode) == "mailbox") {  // unthrottled: the frame being drawn, ours, then the vblank
        mean = r / 2 + r + T / 2;
        worst = 2 * r + T;
      } else {  // immediate: shown as soon as drawn (tearing)
        mean = r / 2 + r;
        worst = 2 * r;
      }
      video.rows.push_back({mode, ms(hz).substr(0, ms(hz).find('.')), ms(mean), ms(worst)});
    }
  const std::string note = fmt::format(
      "Computed, not measured on a display: r = {:.2f} ms, the balanced preset's measured frame time above; "
      "T = 1/refresh. Eq. 1 is evaluated at each frame's predicted present time, so the bounce's phase is "
      "right whatever this latency.",
      r);
  video.note = note;
  out.tables.push_back(video);
  include_measured_latency(o, out);
}

}  // namespace mallet::app
