#pragma once
// `mallet bench report`: every speed-against-accuracy measurement in one process run,
// written as bench-report/report.md with one gnuplot PNG per knob (time against error,
// the Pareto front drawn, the three quality presets marked). The measurements live in
// bench_report_{audio,render,latency}.cpp and bench_input.cpp; this header is their
// shared vocabulary.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "core/one_euro_filter.hpp"
#include "core/scene.hpp"
#include "render/image.hpp"

namespace mallet::app {

//! One setting of one knob: what it costs and how far it is from the reference.
struct TradePoint {
  std::string setting;
  double time = 0;     //!< in TradeTable::time_unit (lower is faster)
  double error = 0;    //!< in TradeTable::error_unit (lower is more exact)
  std::string presets; //!< "fast", "balanced exact", ... — the presets that use it
  std::string note;
  bool front = false;  //!< on the Pareto front (set by mark_front)
};

struct TradeTable {
  std::string id;  //!< file stem of its data and plot
  std::string title;
  std::string time_label, error_label;
  bool log_error = false;
  std::vector<TradePoint> points;
  std::string note;  //!< what was measured, how (printed under the table)
  bool log_time = false;
};

//! Marks the points no other point beats in both time and error.
void mark_front(TradeTable& table);

//! A plain table (peers side by side, the latency budget): header and rows of cells.
struct TextTable {
  std::string title;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::string note;
};

//! The table as the report writes it: its title as a heading, the Markdown table, its note.
std::string markdown(const TextTable& table);

struct ReportOptions {
  std::filesystem::path scene;
  std::filesystem::path out = "bench-report";
  bool quick = false;  //!< a few ms of work per row: for tests, not for numbers
  std::string device;  //!< Vulkan device substring
};

struct ReportSections {
  std::vector<TradeTable> trades;
  std::vector<TextTable> tables;
  std::vector<std::string> skipped;  //!< parts that could not run here, and why
  double frame_ms_balanced = 0;      //!< the balanced preset's measured render time (for the frame latency model)
};

void measure_audio_trades(const Scene& scene, const ReportOptions& o, ReportSections& out);
void measure_render_trades(const Scene& scene, const ReportOptions& o, ReportSections& out);
//! The real kiosk's CPU at 1080p, capped and uncapped, idle and playing (bench_kiosk_cpu.hpp).
void measure_kiosk_cpu_part(const Scene& scene, const ReportOptions& o, ReportSections& out);
void measure_latency_budget(const Scene& scene, const ReportOptions& o, ReportSections& out);

//! The 1€ filter's trade on bench input's synthetic camera tracks (bench_input.cpp): per
//! configuration, still-cursor jitter, lag in strikes, and the strikes' speed and time
//! errors. `configs` empty: the raw track only.
struct PointerTradeRow {
  std::string label;
  OneEuroConfig cfg;
  double jitter_mm = 0, lag_ms = 0, slow_lag_ms = 0;
  double speed_abs_pct = 0, time_max_ms = 0;
  int missed = 0, extra = 0;
};
std::vector<PointerTradeRow> measure_pointer_trade(const Scene& scene, std::uint64_t seed, int strikes_per_track,
                                                   int still_tracks, const std::vector<OneEuroConfig>& configs);

//! A supersampled image box-filtered down by `factor` in linear light (bench_render.cpp).
render::Image downsample_linear_light(const render::Image& image, int factor);

//! The nearest-rank percentile (p in (0, 1]): the smallest sample with at least p of the
//! samples at or below it; 0 for none. The benches' medians, p99s and maxima.
double nearest_rank(std::vector<double> v, double p);

//! MSAA samples per pixel as the renderer takes them: 2, 4 or 8; anything else 1 (bench_render.cpp).
VkSampleCountFlagBits samples_of(int n);

//! Writes report.md, the .dat files and (if gnuplot is installed) the PNGs. Returns the
//! lines to print.
std::vector<std::string> write_report(const ReportSections& s, const ReportOptions& o);

}  // namespace mallet::app
