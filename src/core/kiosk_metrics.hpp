#pragma once
// What the kiosk tells Prometheus ([metrics] textfile): counters, histograms and gauges of
// one kiosk run, and their rendering in Prometheus' text exposition format (version 0.0.4,
// the format node_exporter's textfile collector reads). Pure: the kiosk loop (window or
// headless) feeds it on its own thread from what it already knows; src/app/metrics_file.*
// writes the text atomically.
//
// Names follow Prometheus' conventions: the unit in the name (`_seconds`, `_ratio`),
// `_total` on counters, base units (seconds, not milliseconds). Times are kept as int64
// nanoseconds (a kiosk runs for weeks; see core/time.hpp) and printed as seconds.
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/kiosk_states.hpp"
#include "core/time.hpp"

namespace mallet {

//! A Prometheus histogram with fixed upper bounds (nanoseconds, ascending). observe() is
//! O(buckets) and never allocates.
class DurationHistogram {
 public:
  //! Throws std::invalid_argument unless the bounds are > 0 and strictly ascending.
  explicit DurationHistogram(std::vector<Nanos> upper_bounds_ns);
  void observe(Nanos duration_ns);  //!< negative durations count as 0

  const std::vector<Nanos>& upper_bounds_ns() const { return bounds_; }
  //! How many observations were ≤ bound i (cumulative, as `le` means); the last is count().
  std::uint64_t cumulative(std::size_t i) const;
  std::uint64_t count() const { return count_; }
  Nanos sum_ns() const { return sum_ns_; }

 private:
  std::vector<Nanos> bounds_;
  std::vector<std::uint64_t> per_bucket_;  //!< not cumulative; one more than bounds (+Inf)
  std::uint64_t count_ = 0;
  Nanos sum_ns_ = 0;
};

//! From 2 ms (a 500 Hz panel) to 1 s, finer around 60 Hz (16.7 ms) and its missed vsyncs
//! (33 ms, 50 ms): a kiosk on lavapipe draws in 2–13 ms, a hiccup shows above 25 ms.
std::vector<Nanos> frame_seconds_buckets();
//! From 5 s (a passer-by's tap) to an hour: museum visits at one exhibit last seconds to
//! minutes.
std::vector<Nanos> visitor_session_seconds_buckets();

//! Strikes by (instrument, material) label values.
using StrikeCounts = std::map<std::pair<std::string, std::string>, std::uint64_t>;

//! One kiosk run's metrics.
class KioskMetrics {
 public:
  KioskMetrics();

  // --- fed by the kiosk loop
  void count_frame(Nanos frame_ns);  //!< one frame drawn, `frame_ns` after the previous one
  //! The kiosk's state now, when it was entered and the visitor's last real movement
  //! (KioskStates::state/since/last_movement), once a frame. An Attract → Play change opens a
  //! visitor session; the next Attract closes it: its length runs from entering Play to the
  //! last real movement, so the idle wait before Attract (attract.idle_after_s) is left out.
  void observe_state(KioskState state, Nanos since, Nanos last_movement);
  //! Whether the stick's LED counts as lost now (the caller decides: a remote connected,
  //! the kiosk in Play, no LED). Time from one call to the next counts while it was lost.
  void observe_tracking(bool lost, Nanos now);

  StrikeCounts strikes;           //!< mallet_strikes_total{instrument, material}
  //! mallet_visitor_study_sessions_total{outcome}: the visitor micro-study's sessions (a
  //! visitor struck "Yes" on its offer) by how they ended: completed, abandoned (walked away),
  //! declined (struck "No" at the consent). Each outcome is always there, from 0.
  std::map<std::string, std::uint64_t> visitor_study{{"completed", 0}, {"abandoned", 0}, {"declined", 0}};
  std::uint64_t audio_xruns = 0;  //!< mallet_audio_xruns_total
  std::uint64_t render_devices_lost = 0;  //!< mallet_render_device_lost_total
  //! Gauges; NaN = unknown (no audio device, no remote, no battery report yet).
  double audio_output_latency_s = std::numeric_limits<double>::quiet_NaN();
  //! Device memory the renderer holds (render::device_memory_bytes); NaN: nothing renders.
  double vulkan_device_memory_bytes = std::numeric_limits<double>::quiet_NaN();
  bool remote_connected = false;
  //! mallet_settings_refused: the operator's settings were refused at start and the kiosk
  //! runs on its last good settings or the shipped defaults (until a reload loads them).
  bool settings_refused = false;
  //! mallet_state_folder_writable: 0 while writes into the state folder fail (full, read-only).
  bool state_folder_writable = true;
  double remote_battery_ratio = std::numeric_limits<double>::quiet_NaN();
  Nanos uptime_ns = 0;
  std::uint64_t restarts = 0;  //!< how many times the kiosk started before this run
  std::string version;         //!< mallet_build_info{version}

  // --- read back (tests, the text below)
  std::uint64_t frames() const { return frames_; }
  const DurationHistogram& frame_histogram() const { return frame_; }
  std::uint64_t visitor_sessions() const { return sessions_; }
  const DurationHistogram& session_histogram() const { return session_; }
  KioskState state() const { return state_; }
  Nanos tracking_lost_ns() const { return tracking_lost_ns_; }

 private:
  std::uint64_t frames_ = 0;
  DurationHistogram frame_;
  std::uint64_t sessions_ = 0;
  DurationHistogram session_;
  KioskState state_ = KioskState::attract;
  bool in_session_ = false;
  Nanos session_start_ = 0;
  bool lost_ = false;
  Nanos lost_since_ = 0;
  Nanos tracking_lost_ns_ = 0;
};

//! A label value escaped for the text format: backslash, double quote and line feed.
std::string escape_label_value(std::string_view value);
//! A sample value: the shortest text that reads back to the same double; NaN, +Inf, -Inf.
std::string format_sample_value(double value);

//! The whole text exposition (HELP and TYPE lines, every family, a final line feed).
std::string render_prometheus_text(const KioskMetrics& metrics);

}  // namespace mallet
