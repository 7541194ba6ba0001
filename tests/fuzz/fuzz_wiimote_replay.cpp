// The replay-file reader on arbitrary text: it either returns a recording or throws
// FileError naming a line; a recording it returns survives a write/read round trip.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string_view>

#include "core/file_error.hpp"
#include "input/wiimote/reports.hpp"

namespace wm = mallet::input::wiimote;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  wm::Recording rec;
  try {
    rec = wm::parse_replay(text, "fuzz.txt");
  } catch (const mallet::FileError& e) {
    if (e.file() != "fuzz.txt") std::abort();
    return 0;
  }
  std::ostringstream out;
  wm::ReplayWriter writer(out);
  for (const auto& r : rec.reports) {
    if (r.bytes.empty() || r.bytes.size() > wm::kMaxRecordedReportSize || r.t_ns < 0) std::abort();
    writer.write(r.t_ns, r.bytes);
    (void)wm::parse_input(r.bytes);
  }
  const wm::Recording again = wm::parse_replay(out.str(), "again.txt");  // must not throw
  if (again.reports != rec.reports) std::abort();
  return 0;
}
