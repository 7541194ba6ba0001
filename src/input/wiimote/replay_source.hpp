#pragma once
// A recorded Wii Remote session played back: the reports of a `--record` file (the
// replay format of reports.hpp) go through the same ReportTracker as live ones, with
// their recorded reception times, so a recording reproduces the dots, the LED track and
// the tracking events exactly. For tests, demos and bug reports; pacing in real time is
// the caller's choice (next_time()).
#include <cstddef>
#include <filesystem>
#include <optional>

#include "input/wiimote/report_tracker.hpp"
#include "input/wiimote/reports.hpp"

namespace mallet::input::wiimote {

class ReplaySource {
 public:
  explicit ReplaySource(Recording recording, IrTrackerConfig tracking = {});
  //! Reads `path` (throws FileError "FILE:LINE:COL: problem" on a malformed line).
  static ReplaySource open(const std::filesystem::path& path, IrTrackerConfig tracking = {});

  //! The next recorded report through the parser and the tracker; nothing at the end.
  //! When the tracker's lost time-out ran out before the next report, first an outcome of
  //! kind `timeout` (event `lost`) at that report's time, without consuming it.
  std::optional<ReportOutcome> next();

  //! The reception time of the next report, or nothing at the end.
  std::optional<Nanos> next_time() const;
  bool done() const { return index_ >= recording_.reports.size(); }
  std::size_t position() const { return index_; }
  std::size_t size() const { return recording_.reports.size(); }
  const Recording& recording() const { return recording_; }
  const ReportTracker& tracker() const { return tracker_; }

 private:
  Recording recording_;
  ReportTracker tracker_;
  std::size_t index_ = 0;
};

}  // namespace mallet::input::wiimote
