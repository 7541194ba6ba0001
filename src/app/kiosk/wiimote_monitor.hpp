#pragma once
// `mallet wiimote list` and `mallet wiimote monitor`: what the operator sees of a live
// Wii Remote (or of a recording). Device and clock are injected, so the loop runs against
// hidapi in the binary and against fakes in tests; output goes to a FILE*.
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/app_config.hpp"
#include "input/clock.hpp"
#include "input/wiimote/report_tracker.hpp"
#include "input/wiimote/transport.hpp"
#include "input/wiimote/wiimote_device.hpp"

namespace mallet::app {

//! `wiimote list`'s output: a table of path, product and serial, or "No Wii Remote found"
//! with the pairing and udev hints.
std::string format_device_list(const std::vector<input::wiimote::HidDeviceInfo>& devices);

//! One status line of `wiimote monitor` (every ~100 ms):
//!   "   1.200 s  running    100.0 Hz  battery 0xc8  tracking  led 512,384  dots 512,384,3 - - -"
struct MonitorLine {
  Nanos t_rel_ns = 0;          //!< since the monitor started (or the recording's first report)
  std::string link;            //!< searching, starting, running, replay
  std::string note;            //!< searching/starting: why, or what it waits for
  input::wiimote::RemoteStats remote;
  bool tracking = false;
  std::optional<IrPoint> point;
};
std::string format_monitor_line(const MonitorLine& line);

//! "   1.234 s  tracking regained at 512,384" etc. for a sample carrying an event.
std::string format_event_line(Nanos t_rel_ns, IrTrackerEvent event, const std::optional<IrPoint>& point);

struct MonitorOptions {
  double seconds = 0;       //!< 0 = until Ctrl+C (live) or the end (replay)
  double interval_s = 0.1;  //!< one status line per interval
  std::optional<std::filesystem::path> record;  //!< live only: every raw report, replay format
};

//! Live: runs `device` (started here, stopped on return) until `seconds` pass or
//! `interrupted` becomes true. Returns the exit status: 0 if a remote was connected at
//! some point, 1 if none was (the last problem printed on stderr... by the caller).
int run_live_monitor(input::wiimote::WiimoteDevice& device, input::Clock& clock, const MonitorOptions& options,
                     const std::atomic<bool>& interrupted, std::FILE* out);

//! Replay: the recording through the same parser and tracker, lines at the recorded
//! times (not paced). Throws FileError on a malformed recording. Returns 0.
int run_replay_monitor(const std::filesystem::path& recording, const IrTrackerConfig& tracking,
                       const MonitorOptions& options, std::FILE* out);

}  // namespace mallet::app
