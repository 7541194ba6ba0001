// `mallet bench report`: runs the speed-against-accuracy measurements in one process run
// (audio, renderer, pointer filter, latency budget) and writes the report with its plots.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <utility>

#include <fmt/format.h>

#include "app/bench/bench_prediction.hpp"
#include "app/bench/bench_report.hpp"
#include "app/bench/bench_commands.hpp"
#include "core/data_paths.hpp"
#include "core/felt_table_file.hpp"
#include "core/config/scene_config.hpp"
#include "core/quality.hpp"

namespace mallet::app {
namespace {

void measure_pointer(const Scene& scene, const ReportOptions& o, ReportSections& out) {
  std::vector<OneEuroConfig> configs;
  for (double beta : {0.0, 20.0, 100.0, 200.0, 500.0, 1000.0}) configs.push_back({1.0, beta, 1.0, false});
  const std::vector<PointerTradeRow> rows =
      measure_pointer_trade(scene, 20120505, o.quick ? 2 : 40, o.quick ? 2 : 12, configs);
  TradeTable t{"pointer", "Pointer filter (1€, min_cutoff 1 Hz, beta in 1/m): lag in strikes against still-cursor jitter",
               "lag in strikes, ms", "still jitter, mm", false, {}, ""};
  TextTable impacts{"Strikes found on the same tracks (speed and time error against the scripted truth)",
                    {"source", "speed |error| %", "time max |error| ms", "missed", "extra"}, {}, ""};
  const OneEuroConfig preset = quality_knobs(Quality::balanced).pointer;
  for (const PointerTradeRow& r : rows) {
    const bool is_preset = r.label != "raw" && r.cfg.beta_per_m == preset.beta_per_m &&
                           r.cfg.min_cutoff_hz == preset.min_cutoff_hz;
    const std::string b = fmt::format("aiming lag {:.1f} ms", r.slow_lag_ms);
    const std::string label = fmt::format("beta {:g}", r.cfg.beta_per_m);
    t.points.push_back({r.label == "raw" ? "raw" : label, std::max(0.01, r.lag_ms), r.jitter_mm,
                        is_preset ? "fast balanced exact" : "", b});
    impacts.rows.push_back({r.label == "raw" ? "raw swept segments (what the kiosk uses)" : "filtered: " + r.label,
                            fmt::format("{:.1f}", r.speed_abs_pct), fmt::format("{:.2f}", r.time_max_ms),
                            std::to_string(r.missed), std::to_string(r.extra)});
  }
  t.note = "Camera model of `mallet bench input` (0.82 mm/px, σ 0.5 px, 100 Hz). Strikes are detected on the raw "
           "samples in every preset, so the filter changes only what is shown.";
  t.log_time = true;
  out.trades.push_back(t);
  out.tables.push_back(impacts);
}

//! Contact prediction's trade (bench_prediction.cpp) at the Wii camera's 100 Hz: how soon
//! after the true contact a strike is decided, against the speed error of fast strikes; the
//! full rows (every camera and rate, false and missed strikes) in a table beside it.
void measure_prediction(const Scene& scene, const ReportOptions& o, ReportSections& out) {
  CorpusConfig corpus;
  corpus.seed = kPredictionCorpusSeed;
  corpus.cameras = every_camera();
  if (o.quick) corpus.shapes_per_kind = 4;
  const std::vector<PredictionBenchRow> rows =
      measure_prediction_trade(scene, AppConfig{}.contact, corpus, {0.0, 5.0, 10.0}, prediction_levels());
  TradeTable t{"prediction", "Contact prediction at 100 Hz: contact → strike decided against speed error",
               "contact → strike, median ms", "speed error p99 % (strikes ≥ 1 m/s)", false, {}, ""};
  TextTable full{"Contact prediction, every row (human-like stroke corpus)",
                 {"camera", "rate Hz", "horizon ms", "confidence", "median ms", "p99 ms", "max ms", "sound p99 ms",
                  "predicted", "false %", "false added %", "missed %", "speed err p99 % (≥1 m/s)"},
                 {},
                 ""};
  const double preset_horizon = quality_knobs(Quality::balanced).predict_horizon_ms;
  for (const PredictionBenchRow& r : rows) {
    auto cell = [](double v) {
      const std::string b = fmt::format("{:.2f}", v);
      return std::string(b);
    };
    full.rows.push_back({r.camera, cell(r.rate_hz), cell(r.horizon_ms), r.horizon_ms > 0 ? r.level : "off",
                         cell(r.latency_median_ms), cell(r.latency_p99_ms), cell(r.latency_max_ms),
                         cell(r.sound_p99_ms), std::to_string(r.predicted) + "/" + std::to_string(r.strikes),
                         cell(r.false_pct), cell(r.false_added_pct), cell(r.missed_pct), cell(r.speed_error_p99_fast_pct)});
    if (r.camera != wii_camera(100.0).name || r.rate_hz != 100.0) continue;
    const std::string presets = r.horizon_ms == 0                                          ? "exact"
                                : r.horizon_ms == preset_horizon && r.level == "balanced" ? "fast balanced"
                                                                                           : "";
    t.points.push_back({fmt::format("{} {:.0f} ms", r.horizon_ms > 0 ? r.level : "off", r.horizon_ms),
                        std::max(0.01, r.latency_median_ms), r.speed_error_p99_fast_pct, presets,
                        fmt::format("p99 {:.1f} ms, false +{:.2f} %", r.latency_p99_ms, r.false_added_pct)});
  }
  t.note = "The stroke corpus of `mallet bench prediction` (minimum-jerk downswings 0.2–4 m/s, slowing approaches, "
           "stops above a bar, hovers, slides, double taps) seen by the Wii camera (σ 0.5 px, whole pixels, 2 % "
           "dropped) and, in the table, by a 640×480 V4L2 camera (subpixel, 0.5 % dropped), through the strike route's "
           "detector. A prediction that turns out wrong is a note that cannot be taken back: see the false column.";
  out.trades.push_back(t);
  out.tables.push_back(full);
}

// The felt signal of the last `mallet calibrate actuator --verify` on this machine
// (core/felt_table_file.hpp), when the state folder keeps one: Table 1's strikes as the
// sensor on the stick felt them, without and with the actuator's inverse.
void felt_signal_part(const Scene&, const ReportOptions&, ReportSections& out) {
  const std::filesystem::path path = actuator_eq_path().parent_path() / "actuator_felt.csv";
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    out.skipped.push_back("the felt signal: no actuator calibration verified here (" + path.string() +
                          "; `mallet calibrate actuator --verify` with a sensor on the stick)");
    return;
  }
  const std::vector<FeltRecord> rows = read_felt_table(path);  // a malformed file: FileError, exit 2
  TextTable t;
  t.title = "The felt signal: Table 1's strikes through the actuator and stick";
  t.header = {"material", "v (m/s)", "B (1/s)", "f (Hz)", "B before", "f before", "B after", "f after"};
  const auto cell = [](double fitted, double table) {
    return std::isnan(fitted) ? std::string("-") : fmt::format("{:.1f} ({:+.1f} %)", fitted, 100 * (fitted - table) / table);
  };
  std::string calibration, verified;
  for (const FeltRecord& r : rows) {
    t.rows.push_back({r.material, fmt::format("{:.2f}", r.speed_m_per_s), fmt::format("{:.1f}", r.table_decay_per_s),
                      fmt::format("{:.1f}", r.table_freq_hz), cell(r.decay_before, r.table_decay_per_s),
                      cell(r.freq_before, r.table_freq_hz), cell(r.decay_after, r.table_decay_per_s),
                      cell(r.freq_after, r.table_freq_hz)});
    calibration = r.calibration;
    verified = r.verified_utc;
  }
  t.note = "Measured by `mallet calibrate actuator --verify` at " + verified + " (" + path.string() + "), " +
           (calibration.empty() ? std::string("with no calibration in force") : "the inverse of calibration " + calibration) +
           ": B and f fitted from the sensor on the stick (core/damped_sine_fit.hpp).";
  out.tables.push_back(t);
}

void run(const ReportOptions& o) {
  const Scene scene = config::load_scene(o.scene);
  ReportSections s;
  using Measure = void (*)(const Scene&, const ReportOptions&, ReportSections&);
  const std::pair<const char*, Measure> parts[] = {{"audio", measure_audio_trades},
                                                   {"renderer", measure_render_trades},
                                                   {"pointer filter", measure_pointer},
                                                   {"contact prediction", measure_prediction},
                                                   {"latency budget", measure_latency_budget},
                                                   {"the kiosk's CPU", measure_kiosk_cpu_part},
                                                   {"the felt signal", felt_signal_part}};
  for (const auto& [name, measure] : parts) {
    std::printf("bench report: %s ...\n", name);
    std::fflush(stdout);
    measure(scene, o, s);
  }
  for (const std::string& line : write_report(s, o)) std::printf("%s\n", line.c_str());
}

}  // namespace

double nearest_rank(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(v.size())));
  return v[std::clamp<std::size_t>(rank, 1, v.size()) - 1];
}

void add_bench_report(CLI::App& bench) {
  auto o = std::make_shared<ReportOptions>();
  o->scene = default_scene();
  CLI::App* cmd = bench.add_subcommand("report", "Every speed/accuracy trade in one run: report.md + PNG plots");
  cmd->footer(R"(Writes OUT/report.md, one OUT/<knob>.dat and (with gnuplot installed) OUT/<knob>.png per knob:
time against error, the Pareto front drawn, the fast/balanced/exact presets marked; the
synthesis peers side by side; the latency budget. --quick: tiny workloads (for tests, not numbers).)");
  cmd->add_option("--scene", o->scene, "Scene file")->capture_default_str()->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "Output directory")->capture_default_str();
  cmd->add_flag("--quick", o->quick, "Tiny workloads: checks that it runs, numbers meaningless");
  cmd->add_option("--device", o->device, "Vulkan device (substring of its name)");
  cmd->callback([o] { run(*o); });
}

}  // namespace mallet::app
