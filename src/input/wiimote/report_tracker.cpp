#include "input/wiimote/report_tracker.hpp"

#include <variant>

namespace mallet::input::wiimote {

const char* to_string(ReportOutcome::Kind kind) { return name_in(kReportKindNames, kind); }

ReportTracker::ReportTracker(IrTrackerConfig tracking) : tracker_(tracking) {}

ReportOutcome ReportTracker::feed(Nanos t_ns, std::span<const std::uint8_t> report) {
  ReportOutcome out;
  out.t_ns = t_ns;
  ++stats_.reports;
  stats_.last_report_ns = t_ns;
  const Parsed<InputReport> parsed = parse_input(report);
  if (!parsed) {
    ++stats_.malformed;
    out.kind = ReportOutcome::Kind::malformed;
    out.error = parsed.error();
    return out;
  }
  const InputReport& r = *parsed;
  if (const auto* ir = std::get_if<IrReport>(&r)) {
    out.kind = ReportOutcome::Kind::ir;
    out.frame = IrFrame{t_ns, ir->slots};
    out.update = tracker_.update(*out.frame);
    stats_.last_slots = ir->slots;
    count_ir(t_ns);
  } else if (const auto* status = std::get_if<StatusReport>(&r)) {
    out.kind = ReportOutcome::Kind::status;
    out.status = *status;
    ++stats_.status_reports;
    stats_.battery = status->battery;
    stats_.battery_low = status->battery_low;
  } else if (std::holds_alternative<AckReport>(r)) {
    out.kind = ReportOutcome::Kind::ack;
  } else if (std::holds_alternative<ReadDataReport>(r)) {
    out.kind = ReportOutcome::Kind::read_data;
  } else {
    out.kind = ReportOutcome::Kind::other;
  }
  return out;
}

void ReportTracker::count_ir(Nanos t_ns) {
  ++stats_.ir_reports;
  last_ir_ns_ = t_ns;
  // Intervals counted over a window of at least one second, then the window restarts at
  // this report: exact for a steady rate, and it follows a change within two seconds.
  if (!rate_window_start_ns_ || t_ns < *rate_window_start_ns_) {
    rate_window_start_ns_ = t_ns;
    rate_window_reports_ = 0;
    return;
  }
  ++rate_window_reports_;
  const Nanos elapsed = t_ns - *rate_window_start_ns_;
  if (elapsed >= kNanosPerSecond) {
    stats_.ir_rate_hz = static_cast<double>(rate_window_reports_) / to_seconds(elapsed);
    rate_window_start_ns_ = t_ns;
    rate_window_reports_ = 0;
  }
}

IrTrackerEvent ReportTracker::poll(Nanos now_ns) {
  if (last_ir_ns_ && now_ns - *last_ir_ns_ >= kNanosPerSecond) {
    stats_.ir_rate_hz = 0;
    rate_window_start_ns_.reset();
    rate_window_reports_ = 0;
  }
  return tracker_.poll(now_ns);
}

bool ReportTracker::restart_tracking() {
  const bool was_tracking = tracker_.tracking();
  tracker_.reset();
  stats_.ir_rate_hz = 0;
  stats_.last_slots = {};
  rate_window_start_ns_.reset();
  rate_window_reports_ = 0;
  return was_tracking;
}

}  // namespace mallet::input::wiimote
