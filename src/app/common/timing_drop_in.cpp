#include "app/common/timing_drop_in.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/data_paths.hpp"

namespace mallet::app {

std::filesystem::path write_timing_drop_in(const std::filesystem::path& dir, const char* name, const std::string& why,
                                           const char* key, double value) {
  std::filesystem::create_directories(dir);
  std::string text;
  for (std::size_t at = 0; at < why.size();) {  // each line of `why` a comment
    const std::size_t end = std::min(why.find('\n', at), why.size());
    text += "# " + why.substr(at, end - at) + "\n";
    at = end + 1;
  }
  text += std::string("[timing]\n") + key + " = " + fmt::format("{}", value) + "\n";  // the shortest that reads back the same
  write_file_atomically(dir / name, text);
  return dir / name;
}

std::filesystem::path keep_display_latency(const DisplayLatencyMeasurement& m) {
  const std::filesystem::path record = display_latency_path();
  std::filesystem::create_directories(record.parent_path());
  write_file_atomically(record, format_display_latency(m));
  if (!m.saved) return {};
  return write_timing_drop_in(measured_settings_dir(), kDisplayLatencyDropIn,
                              "Written by mallet's latency test at " + m.measured_utc +
                                  ", confirmed on the operator page:\nthe display's latency, measured by a "
                                  "photodiode on the screen's corner (median of " +
                                  std::to_string(m.squares_seen) + " squares).",
                              "display_latency_ms", m.display_latency_ms);
}

}  // namespace mallet::app
