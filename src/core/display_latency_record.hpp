#pragma once
// What `mallet calibrate latency --photodiode` measured of the display, kept in the state
// folder (display_latency.toml) so that `mallet doctor` can say when it was last measured
// and whether [timing] display_latency_ms is what was found:
//
//   format_version = 1
//   measured_utc = "2026-12-06T09:30:00Z"
//   display_latency_ms = 23.4   # from a frame's present to light on the panel: the median
//   min_ms = 22.9               # the squares' spread
//   max_ms = 24.1
//   squares_seen = 10
//   squares = 10
//   input_device = "USB Audio"
//   photodiode_channel = 1      # from 1
//   saved = true                # the operator confirmed it as [timing] display_latency_ms
#include <filesystem>
#include <optional>
#include <string>

namespace mallet {

struct DisplayLatencyMeasurement {
  std::string measured_utc;
  double display_latency_ms = 0;
  double min_ms = 0, max_ms = 0;
  int squares_seen = 0, squares = 0;
  std::string input_device;
  int photodiode_channel = 1;
  bool saved = false;
};

//! display_latency.toml's text, and the file read back (none when absent; a FileError naming
//! the file, the place and the key when malformed).
std::string format_display_latency(const DisplayLatencyMeasurement& m);
std::optional<DisplayLatencyMeasurement> load_display_latency(const std::filesystem::path& path);

}  // namespace mallet
