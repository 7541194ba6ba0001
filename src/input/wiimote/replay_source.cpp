#include "input/wiimote/replay_source.hpp"

#include <utility>

namespace mallet::input::wiimote {

ReplaySource::ReplaySource(Recording recording, IrTrackerConfig tracking)
    : recording_(std::move(recording)), tracker_(tracking) {}

ReplaySource ReplaySource::open(const std::filesystem::path& path, IrTrackerConfig tracking) {
  return ReplaySource(read_replay(path), tracking);
}

std::optional<Nanos> ReplaySource::next_time() const {
  if (done()) return std::nullopt;
  return recording_.reports[index_].t_ns;
}

std::optional<ReportOutcome> ReplaySource::next() {
  if (done()) return std::nullopt;
  const RecordedReport& r = recording_.reports[index_];
  if (tracker_.poll(r.t_ns) == IrTrackerEvent::lost) {
    ReportOutcome lost;
    lost.kind = ReportOutcome::Kind::timeout;
    lost.t_ns = r.t_ns;
    lost.update.event = IrTrackerEvent::lost;
    return lost;
  }
  ++index_;
  return tracker_.feed(r.t_ns, r.bytes);
}

}  // namespace mallet::input::wiimote
