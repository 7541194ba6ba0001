#include "input/wiimote/replay_transport.hpp"

#include <algorithm>

#include "core/file_error.hpp"

namespace mallet::input::wiimote {
namespace {

//! Data reports are 0x30..0x3f; everything else in a recording answered the recorder's host.
bool is_data_report(const RecordedReport& r) { return !r.bytes.empty() && r.bytes[0] >= 0x30 && r.bytes[0] <= 0x3f; }

class ReplayTransport final : public Transport {
 public:
  ReplayTransport(const std::vector<RecordedReport>& data, Nanos period_ns, Clock& clock)
      : data_(data), period_ns_(period_ns), clock_(clock), origin_ns_(clock.now()) {}

  Nanos origin() const { return origin_ns_; }  //!< when the recording's time 0 plays

  bool write(std::span<const std::uint8_t> report) override {
    if (report.size() < 2) return true;
    if (report[0] == 0x15) answers_.push_back({0x20, 0x00, 0x00, 0x08, 0x00, 0x00, 0xc8});  // IR on, battery full
    else if (report[0] == 0x16 || (report[1] & 0x02) != 0) answers_.push_back({0x22, 0x00, 0x00, report[0], 0x00});
    return true;
  }

  int read(std::span<std::uint8_t> buffer, int timeout_ms) override {
    if (!answers_.empty()) {
      const std::vector<std::uint8_t> b = std::move(answers_.front());
      answers_.pop_front();
      return copy(b, buffer);
    }
    const Nanos timeout = Nanos{timeout_ms} * 1'000'000;
    const Nanos due = origin_ns_ + loops_ * period_ns_ + data_[next_].t_ns;
    const Nanos now = clock_.now();
    if (due > now + timeout) {
      clock_.sleep_for(timeout);
      return 0;
    }
    clock_.sleep_for(due - now);
    const int n = copy(data_[next_].bytes, buffer);
    if (++next_ == data_.size()) {
      next_ = 0;
      ++loops_;
    }
    return n;
  }

 private:
  static int copy(const std::vector<std::uint8_t>& b, std::span<std::uint8_t> buffer) {
    const std::size_t n = std::min(b.size(), buffer.size());
    std::copy_n(b.begin(), n, buffer.begin());
    return static_cast<int>(n);
  }

  const std::vector<RecordedReport>& data_;
  Nanos period_ns_;
  Clock& clock_;
  Nanos origin_ns_;
  std::deque<std::vector<std::uint8_t>> answers_;
  std::size_t next_ = 0;
  Nanos loops_ = 0;
};

}  // namespace

ReplayFinder::ReplayFinder(Recording recording, std::string name, Clock& clock) : clock_(&clock) {
  for (RecordedReport& r : recording.reports)
    if (is_data_report(r)) data_.push_back(std::move(r));
  if (data_.empty()) throw FileError(name, 0, 0, "the recording holds no data (IR) report to replay");
  const Nanos first = data_.front().t_ns;
  for (RecordedReport& r : data_) r.t_ns -= first;
  // One report period after the last before the loop starts again (the remote's 100 Hz).
  period_ns_ = data_.back().t_ns + 10'000'000;
  device_ = {"replay:" + name, kNintendoVendorId, kWiiRemoteProductId, "replay", "recording " + name};
}

ReplayFinder ReplayFinder::open_file(const std::filesystem::path& path, Clock& clock) {
  return ReplayFinder(read_replay(path), path.string(), clock);
}

std::vector<HidDeviceInfo> ReplayFinder::enumerate() { return {device_}; }

OpenResult ReplayFinder::open(const std::string& path) {
  OpenResult r;
  if (path != device_.path) {
    r.error = "no such recording " + path;
    return r;
  }
  auto transport = std::make_unique<ReplayTransport>(data_, period_ns_, *clock_);
  origin_->store(transport->origin(), std::memory_order_release);
  r.transport = std::move(transport);
  return r;
}

}  // namespace mallet::input::wiimote
