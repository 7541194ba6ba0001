// `mallet bench prediction`: the latency that contact prediction buys
// and what it costs, on the stroke corpus. A program that prints a table; deterministic.
//
// Why the presets are what they are (measured with this bench, seed 20240611, 200 shapes
// per kind, Wii camera; re-measured when the V4L2 camera's rows came):
//  * The exact solver (horizon 0) decides a strike 4.45 ms after the contact at the median
//    at 100 Hz, 15.9 ms at the 99th percentile (2.08 / 7.76 ms at 200 Hz). The tail is not
//    the sample interval alone: 2 % of samples are dropped, gentle touches hide in the
//    camera's 0.5 px of noise, and a double tap's second downswing lasts 3 samples.
//  * No level moves that 99th percentile by more than 2.5 ms: the strokes in it cannot
//    be extrapolated (a rebound, a touch at 0.1 m/s, a missing sample). What prediction
//    buys is the median: 100 Hz 4.45 → 1.99 ms (balanced), 0.38 ms (eager).
//  * No level added a false or a missed note on this corpus (the `false` column is the
//    exact solver's own, from noise under hands that stop within ≈1 mm of a bar; on seeds
//    1 and 2 balanced added 0 and 0.11 %): could_stop and the other tests keep stops and
//    hovers out.
//  * The price is speed. A quadratic fitted while the hand is still speeding up reads the
//    contact speed 2–3× too high (eager: p99 speed error on strikes ≥ 1 m/s 155 % against
//    the solver's 44 %). "balanced" refuses a hand speeding up by more than 10 m/s² and
//    fits with more than 4 ms / 80 % of noise-only uncertainty: its speed error on fast
//    strikes stays near the solver's (45 % / 44 % at 100 Hz, 44 % / 42 % at 200 Hz) while it
//    predicts 28 % of strikes at 100 Hz and 27 % at 200 Hz. "exact" (no speed-up at all,
//    braking 120 m/s², half the uncertainty) predicts 106 strikes to balanced's 259 at
//    100 Hz, scheduled at most 4.1 ms early (p1) where balanced reaches 6.9 ms.
//  * Horizons beyond the sample interval change nothing: a crossing after the next sample
//    is that sample's to decide (so 10 = 15 ms at 100 Hz, and 5 = 10 = 15 ms at 200 Hz).
//  * The targets of the brief (100 Hz p99 ≤ 5 ms, 200 Hz ≤ 3 ms, speed error ≤ 3 %) are not
//    reached by any level: with σ 0.5 px the exact solver's own speed error is 43 % p99 on
//    fast strikes, and the p99 latency is set by strokes no extrapolation can call.
//
// The V4L2 camera (640 px over the screen, σ 0.1 px subpixel centroids, 0.5 % dropped; the
// same paths), with the same presets:
//  * 120 Hz: the solver alone 4.23 / 8.99 ms (median / p99), balanced 1.84 / 8.70, eager
//    0.51 / 8.70; 240 Hz: the solver 2.15 / 4.64, balanced 0.80 / 4.47, eager 0.16 / 4.41
//    (its sound 4.88: predictions scheduled late). The targets of the camera's issue
//    (240 Hz: contact → sound p99 ≤ 3 ms, none missed, ≤ 1 % false; 120 Hz: ≤ 5 ms) are not
//    met: p99 stays near one frame interval, because 18–25 % of contacts are decided by the
//    solver more than 3 (5) ms late, most of them a double tap's second downswing (2–3
//    frames at 120 Hz, too short to be seen turning into a straight fall), gentle touches at
//    0.1–0.3 m/s (below or near min_predicted_speed), slides and dropped frames. Loosening
//    every test at 240 Hz (a 15 ms fit window, speed-up allowed, 0.1 m/s, 0.2 mm overshoot)
//    still left 2.8 % of contacts over 3 ms (p99 3.9 ms), with the speed-up test off that
//    makes eager's speed error.
//  * No strike missed at either rate, and no level adds a false note; the solver's own false
//    notes are 1.01 % at 120 Hz and 1.23 % at 240 Hz (stops within ≈0.5 mm of a bar: the
//    lower noise moves that edge from ≈1 mm, more frames give it more chances).
//  * The speed error on fast strikes falls with the noise: the solver's p99 40.5 % at
//    120 Hz, 21.4 % at 240 Hz; balanced 40.5 / 40.8 %.
#include "app/bench/bench_prediction.hpp"
#include "app/bench/bench_report.hpp"

#include <iostream>
#include <memory>

#include "app/bench/bench_commands.hpp"
#include "core/data_paths.hpp"
#include "core/config/app_config_loader.hpp"
#include "core/config/scene_config.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>

#include <fmt/format.h>

#include "core/strike_detector.hpp"

namespace mallet::app {

namespace {

//! A strike is the true contact's if it is on the same bar within this of the contact.
constexpr Nanos kMatchWindowNs = 25'000'000;

double ms(Nanos dt) { return static_cast<double>(dt) * 1e-6; }

struct Decided {
  Nanos decided_ns;
  Impact impact;
};

PredictionBenchRow run_row(const Scene& scene, const ContactConfig& contact, const std::vector<Stroke>& corpus,
                           const CameraModel& camera, const PredictionConfig& config, const std::string& level) {
  PredictionBenchRow row;
  row.camera = std::string(camera.name);
  row.rate_hz = camera.rate_hz;
  row.horizon_ms = config.horizon_ms;
  row.level = level;
  row.false_by_kind.assign(kStrokeKinds, 0);
  std::vector<double> latency, sound, schedule, speed, speed_fast;
  int false_strikes = 0, missed = 0;
  const auto read_delay_ns = static_cast<Nanos>(std::llround(camera.read_delay_ms * 1e6));
  for (const Stroke& stroke : corpus) {
    if (stroke.camera != camera.name || stroke.rate_hz != camera.rate_hz) continue;
    StrikeDetector detector(scene, contact, config);
    std::vector<Decided> strikes;
    for (const PointerSample& s : stroke.samples)
      if (auto impact = detector.update(s.t_ns, {s.x, s.y})) strikes.push_back({s.t_ns + read_delay_ns, *impact});
    row.contacts += static_cast<int>(stroke.contacts.size());
    row.strikes += static_cast<int>(strikes.size());
    std::vector<bool> used(strikes.size(), false);
    for (const TrueContact& c : stroke.contacts) {
      std::optional<std::size_t> best;
      for (std::size_t i = 0; i < strikes.size(); ++i) {
        const Nanos err = std::llabs(strikes[i].impact.t_ns - c.t_ns);
        if (used[i] || strikes[i].impact.target != c.target || err > kMatchWindowNs) continue;
        if (!best || err < std::llabs(strikes[*best].impact.t_ns - c.t_ns)) best = i;
      }
      if (!best) {
        ++missed;
        continue;
      }
      used[*best] = true;
      const Decided& d = strikes[*best];
      latency.push_back(std::max(0.0, ms(d.decided_ns - c.t_ns)));
      sound.push_back(std::fabs(ms(std::max(d.impact.t_ns, d.decided_ns) - c.t_ns)));
      if (d.impact.predicted) {
        ++row.predicted;
        schedule.push_back(ms(d.impact.t_ns - c.t_ns));
      }
      const double err_pct = 100.0 * std::fabs(d.impact.speed_m_per_s - c.speed_m_per_s) / c.speed_m_per_s;
      speed.push_back(err_pct);
      if (c.speed_m_per_s >= 1.0) speed_fast.push_back(err_pct);
    }
    for (std::size_t i = 0; i < strikes.size(); ++i) {
      if (used[i]) continue;
      ++false_strikes;
      ++row.false_by_kind[static_cast<std::size_t>(stroke.kind)];
      if (strikes[i].impact.predicted) ++row.predicted;
    }
  }
  row.latency_median_ms = nearest_rank(latency, 0.5);
  row.latency_p99_ms = nearest_rank(latency, 0.99);
  row.latency_max_ms = nearest_rank(latency, 1.0);
  row.sound_p99_ms = nearest_rank(sound, 0.99);
  row.schedule_error_p1_ms = nearest_rank(schedule, 0.01);
  row.schedule_error_p99_ms = nearest_rank(schedule, 0.99);
  const double per = row.contacts > 0 ? 100.0 / row.contacts : 0.0;
  row.false_pct = false_strikes * per;
  row.missed_pct = missed * per;
  row.speed_error_p99_pct = nearest_rank(speed, 0.99);
  row.speed_error_p99_fast_pct = nearest_rank(speed_fast, 0.99);
  return row;
}

}  // namespace

std::vector<PredictionLevel> prediction_levels() {
  std::vector<PredictionLevel> levels;
  for (std::string_view name : kPredictionConfidences) levels.push_back({std::string(name), *prediction_confidence(name)});
  return levels;
}

std::vector<PredictionBenchRow> measure_prediction_trade(const Scene& scene, const ContactConfig& contact,
                                                         const CorpusConfig& corpus_config,
                                                         const std::vector<double>& horizons_ms,
                                                         const std::vector<PredictionLevel>& levels) {
  const std::vector<Stroke> corpus = make_stroke_corpus(scene, corpus_config);
  std::vector<PredictionBenchRow> rows;
  for (const CameraModel& camera : corpus_config.cameras) {
    for (double horizon : horizons_ms) {
      if (!(horizon > 0)) {
        rows.push_back(run_row(scene, contact, corpus, camera, prediction_off(), "off"));
        continue;
      }
      for (const PredictionLevel& level : levels) {
        PredictionConfig c = level.config;
        c.horizon_ms = horizon;
        rows.push_back(run_row(scene, contact, corpus, camera, c, level.name));
      }
    }
  }
  for (PredictionBenchRow& r : rows) {
    r.false_added_pct = r.false_pct;
    for (const PredictionBenchRow& off : rows)
      if (off.camera == r.camera && off.rate_hz == r.rate_hz && off.horizon_ms == 0)
        r.false_added_pct = r.false_pct - off.false_pct;
  }
  return rows;
}

int run_bench_prediction(const Scene& scene, const ContactConfig& contact, std::ostream& out) {
  CorpusConfig corpus;
  corpus.seed = kPredictionCorpusSeed;
  corpus.cameras = every_camera();
  const std::vector<PredictionBenchRow> rows =
      measure_prediction_trade(scene, contact, corpus, {0.0, 5.0, 10.0, 15.0}, prediction_levels());
  out << fmt::format("contact prediction on {} strokes per camera and rate ({} shapes × 6 kinds, the same paths for "
                     "each), seed {}; cameras:\n",
                     corpus.shapes_per_kind * kStrokeKinds, corpus.shapes_per_kind, corpus.seed);
  for (const CameraModel& c : corpus.cameras) {
    out << fmt::format("  {:<4} {:3.0f} Hz: σ {:.2f} px ({:.2f} mm), {:.0f} px over the screen, {}, {:.1f} % dropped, "
                       "read delay {:.1f} ms\n",
                       c.name, c.rate_hz, c.noise_px, c.noise_px * metres_per_camera_px(scene, c) * 1e3,
                       c.camera_width_px, c.quantise_px ? "whole pixels" : "subpixel centroid",
                       c.drop_probability * 100, c.read_delay_ms);
  }
  out << "camera rate  horizon  level     | latency ms med   p99   max | sound p99 | sched err ms p1   p99 | "
         "pred/strikes | false % (added) missed % | speed err p99 % (≥1 m/s)\n";
  for (const PredictionBenchRow& r : rows) {
    out << fmt::format(
        "{:<6} {:4.0f}  {:4.0f} ms  {:<9} |  {:5.2f} {:5.2f} {:5.2f} |  {:6.2f}   | {:7.2f} {:6.2f} | {:4}/{:<5} | "
        "{:5.2f} ({:+5.2f}) {:6.2f} | {:6.1f} {:7.1f}\n",
        r.camera, r.rate_hz, r.horizon_ms, r.level, r.latency_median_ms, r.latency_p99_ms, r.latency_max_ms,
        r.sound_p99_ms, r.schedule_error_p1_ms, r.schedule_error_p99_ms, r.predicted, r.strikes, r.false_pct,
        r.false_added_pct, r.missed_pct, r.speed_error_p99_pct, r.speed_error_p99_fast_pct);
  }
  out << "false strikes by stroke kind (strike slow_approach stop_above hover slide double_tap):\n";
  for (const PredictionBenchRow& r : rows) {
    out << fmt::format("{:<6} {:4.0f}  {:4.0f} ms  {:<9} |", r.camera, r.rate_hz, r.horizon_ms, r.level);
    for (int n : r.false_by_kind) out << ' ' << n;
    out << '\n';
  }
  return 0;
}

void add_bench_prediction(CLI::App& bench) {
  auto scene = std::make_shared<std::filesystem::path>(default_scene());
  auto settings = std::make_shared<std::filesystem::path>();
  CLI::App* cmd = bench.add_subcommand(
      "prediction", "Contact prediction's trade on human-like strokes: latency vs false, missed strikes, speed error");
  cmd->add_option("--scene", *scene, "Scene file")->capture_default_str()->check(CLI::ExistingFile);
  cmd->add_option("--config", *settings, "Settings file ([contact]; built-in defaults if absent)")
      ->check(CLI::ExistingFile);
  cmd->callback([scene, settings] {
    const AppConfig config = settings->empty() ? AppConfig{} : config::load_app_config(*settings);
    run_bench_prediction(config::load_scene(*scene), config.contact, std::cout);
  });
}

}  // namespace mallet::app
