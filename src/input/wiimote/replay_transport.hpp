#pragma once
// A recorded Wii Remote session as a live remote: a DeviceFinder that lists one device
// whose transport plays the recording's data reports (IR) back in real time on the given
// Clock, looping at the end, and answers the host like a remote does (an ack for every
// register write and every report with the ack-request bit, a status report for 0x15).
// Under WiimoteDevice it goes through the very same start-up, tracker, sample sink and
// kiosk path as a live remote: the kiosk's `input.source = "replay"` (demos, soak runs,
// bug reports played back). The recording's own acks and status reports are skipped: the
// host's start-up gets fresh ones.
#include <atomic>
#include <cstdint>
#include <memory>
#include <deque>
#include <filesystem>
#include <string>
#include <vector>

#include "input/clock.hpp"
#include "input/wiimote/reports.hpp"
#include "input/wiimote/transport.hpp"

namespace mallet::input::wiimote {

class ReplayFinder final : public DeviceFinder {
 public:
  //! Throws FileError when the recording holds no data report at all.
  ReplayFinder(Recording recording, std::string name, Clock& clock);
  //! Reads `path` (FileError "FILE:LINE:COL: problem" on a malformed line).
  static ReplayFinder open_file(const std::filesystem::path& path, Clock& clock);

  //! One device: path "replay:NAME", serial "replay".
  std::vector<HidDeviceInfo> enumerate() override;
  OpenResult open(const std::string& path) override;

  const HidDeviceInfo& device() const { return device_; }
  //! When the recording's time 0 was last played (the latest open), on the Clock; −1
  //! before the first. Any thread: a benchmark maps the recording's times onto the kiosk's.
  Nanos last_origin() const { return origin_->load(std::memory_order_acquire); }

 private:
  std::vector<RecordedReport> data_;  //!< the data reports, times relative to the first
  Nanos period_ns_ = 0;               //!< one loop
  HidDeviceInfo device_;
  Clock* clock_;
  std::shared_ptr<std::atomic<Nanos>> origin_ = std::make_shared<std::atomic<Nanos>>(-1);
};

}  // namespace mallet::input::wiimote
