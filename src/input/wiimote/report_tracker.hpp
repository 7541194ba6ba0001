#pragma once
// Received reports → the stick's LED: the one path every Wii Remote report takes, live
// (WiimoteDevice) or recorded (ReplaySource), so a recording plays back exactly as it was
// seen. Parses each report (reports.hpp), feeds IR frames to the IrTracker
// (core/ir_tracker.hpp) with the report's reception time, and keeps what the operator
// wants to see: the last dots, the IR report rate, the battery.
#include <cstdint>
#include <optional>
#include <span>

#include "core/enum_names.hpp"
#include "core/ir_tracker.hpp"
#include "input/wiimote/reports.hpp"

namespace mallet::input::wiimote {

//! What one received report was, and what it did to the tracking.
struct ReportOutcome {
  enum class Kind : std::uint8_t {
    ir,         //!< a data report with IR (0x33, 0x36, 0x37): `frame` and `update` are set
    status,     //!< 0x20: `status` is set
    ack,        //!< 0x22
    read_data,  //!< 0x21
    other,      //!< a data report without IR
    malformed,  //!< not a valid input report: `error` says why (counted, otherwise ignored)
    timeout,    //!< no report: tracking was lost for lack of a dot (`update.event` = lost)
  };
  Kind kind = Kind::malformed;
  Nanos t_ns = 0;
  std::optional<IrFrame> frame;
  IrTrackerUpdate update;
  std::optional<StatusReport> status;
  std::optional<ReportError> error;
};
inline constexpr EnumNames<ReportOutcome::Kind, 7> kReportKindNames{{
    {ReportOutcome::Kind::ir, "ir"}, {ReportOutcome::Kind::status, "status"}, {ReportOutcome::Kind::ack, "ack"},
    {ReportOutcome::Kind::read_data, "read_data"}, {ReportOutcome::Kind::other, "other"},
    {ReportOutcome::Kind::malformed, "malformed"}, {ReportOutcome::Kind::timeout, "timeout"}}};

const char* to_string(ReportOutcome::Kind kind);

//! What the operator sees of the remote (`mallet wiimote monitor`).
struct RemoteStats {
  std::uint64_t reports = 0;     //!< every report fed, malformed included
  std::uint64_t ir_reports = 0;
  std::uint64_t status_reports = 0;
  std::uint64_t malformed = 0;
  double ir_rate_hz = 0;         //!< IR reports per second over the last full second; 0 when none for 1 s
  std::optional<std::uint8_t> battery;  //!< raw level of the last status report (≈0xc8 fresh)
  bool battery_low = false;
  IrSlots last_slots{};          //!< the last IR report's four slots
  std::optional<Nanos> last_report_ns;
};

class ReportTracker {
 public:
  //! Throws std::invalid_argument on a bad tracker config (see validate()).
  explicit ReportTracker(IrTrackerConfig tracking = {});

  //! One report as received at `t_ns` (byte 0 = report id).
  ReportOutcome feed(Nanos t_ns, std::span<const std::uint8_t> report);
  //! Time passes without a report: the tracker's lost time-out, and the rate falls to 0
  //! after a second without IR. Returns `lost` once when tracking was lost.
  IrTrackerEvent poll(Nanos now_ns);
  //! The remote is gone or a new one is connected: tracking starts over. Returns true if
  //! it was tracking (the caller reports `lost`). Counters and the battery are kept.
  bool restart_tracking();

  const IrTracker& tracker() const { return tracker_; }
  const RemoteStats& stats() const { return stats_; }

 private:
  void count_ir(Nanos t_ns);

  IrTracker tracker_;
  RemoteStats stats_;
  std::optional<Nanos> rate_window_start_ns_;
  std::uint64_t rate_window_reports_ = 0;
  std::optional<Nanos> last_ir_ns_;
};

}  // namespace mallet::input::wiimote
