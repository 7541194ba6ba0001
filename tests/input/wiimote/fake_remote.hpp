#pragma once
// An in-process Wii Remote for the device logic's tests: a DeviceFinder whose remotes
// answer the host like the real one (acks, status), play scripted reports with scripted
// delays on a FakeClock, record every report written, and can go silent or vanish.
#include <algorithm>
#include <deque>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "input/wiimote/transport.hpp"
#include "wiimote_test_support.hpp"

namespace mallet::input::wiimote::test {

//! One remote's side, kept across connections (the test scripts it, the transports of
//! each connection share it).
struct FakeRemote {
  explicit FakeRemote(FakeClock& c) : clock(&c) {}

  FakeClock* clock;
  bool answers = true;   //!< ack and status answers (false: a remote that ignores the host)
  bool gone = false;     //!< reads and writes fail (the hidraw node vanished)
  Nanos answer_delay_ns = 1 * kMs;
  std::deque<std::pair<Nanos, Bytes>> script;  //!< (delay before it, report), in order
  std::deque<Bytes> answers_due;
  std::vector<Bytes> written;          //!< every report the host wrote, all connections
  std::vector<Nanos> delivered_at;     //!< the clock when each report was handed over
  std::vector<Bytes> delivered;
  int opens = 0;
  int open_now = 0;

  //! Queues `report` to arrive `delay_ns` after the previous scripted one is delivered.
  void send(Bytes report, Nanos delay_ns = 10 * kMs) { script.emplace_back(delay_ns, std::move(report)); }
  //! `count` IR reports 10 ms apart (100 Hz) with the LED at (x, y) moving by (dx, dy).
  void send_ir(int count, int x, int y, int dx = 0, int dy = 0, int size = 3) {
    for (int i = 0; i < count; ++i) send(ir_report({{x + i * dx, y + i * dy, size}}));
  }
  //! How many reports with this id were written (all connections).
  int count_written(std::uint8_t id) const {
    return static_cast<int>(std::count_if(written.begin(), written.end(),
                                          [id](const Bytes& b) { return !b.empty() && b[0] == id; }));
  }
};

class FakeTransport final : public Transport {
 public:
  explicit FakeTransport(std::shared_ptr<FakeRemote> remote) : remote_(std::move(remote)) {
    ++remote_->opens;
    ++remote_->open_now;
  }
  ~FakeTransport() override { --remote_->open_now; }

  bool write(std::span<const std::uint8_t> report) override {
    FakeRemote& r = *remote_;
    if (r.gone) return false;
    Bytes b(report.begin(), report.end());
    r.written.push_back(b);
    if (r.answers)
      if (auto answer = remote_answer(b)) r.answers_due.push_back(*answer);
    return true;
  }

  int read(std::span<std::uint8_t> buffer, int timeout_ms) override {
    FakeRemote& r = *remote_;
    if (r.gone) return -1;
    const Nanos timeout = Nanos{timeout_ms} * kMs;
    if (!r.answers_due.empty()) {
      r.clock->advance(std::min(r.answer_delay_ns, timeout));
      return deliver(buffer, r.answers_due);
    }
    if (r.script.empty()) {
      r.clock->advance(timeout);
      return 0;
    }
    auto& [delay, report] = r.script.front();
    if (delay > timeout) {
      delay -= timeout;
      r.clock->advance(timeout);
      return 0;
    }
    r.clock->advance(delay);
    std::deque<Bytes> one{report};
    r.script.pop_front();
    return deliver(buffer, one);
  }

 private:
  int deliver(std::span<std::uint8_t> buffer, std::deque<Bytes>& from) {
    Bytes b = std::move(from.front());
    from.pop_front();
    const std::size_t n = std::min(b.size(), buffer.size());
    std::copy_n(b.begin(), n, buffer.begin());
    remote_->delivered_at.push_back(remote_->clock->now());
    remote_->delivered.push_back(b);
    return static_cast<int>(n);
  }

  std::shared_ptr<FakeRemote> remote_;
};

class FakeFinder final : public DeviceFinder {
 public:
  explicit FakeFinder(FakeClock& clock) : clock_(&clock) {}

  //! Adds a remote that enumerate() lists from now on.
  std::shared_ptr<FakeRemote> add(const std::string& path, const std::string& serial = "00:1f:32:00:00:01",
                                  std::uint16_t product = kWiiRemoteProductId) {
    devices.push_back({path, kNintendoVendorId, product, serial, "Nintendo RVL-CNT-01"});
    remotes[path] = std::make_shared<FakeRemote>(*clock_);
    return remotes[path];
  }

  std::vector<HidDeviceInfo> enumerate() override {
    enumerated_at.push_back(clock_->now());
    return devices;
  }

  OpenResult open(const std::string& path) override {
    opened.push_back(path);
    OpenResult r;
    if (const auto e = open_errors.find(path); e != open_errors.end()) {
      r.error = e->second;
      return r;
    }
    const auto it = remotes.find(path);
    if (it == remotes.end()) {
      r.error = "no such device " + path;
      return r;
    }
    r.transport = std::make_unique<FakeTransport>(it->second);
    return r;
  }

  std::vector<HidDeviceInfo> devices;
  std::map<std::string, std::shared_ptr<FakeRemote>> remotes;
  std::map<std::string, std::string> open_errors;
  std::vector<Nanos> enumerated_at;
  std::vector<std::string> opened;

 private:
  FakeClock* clock_;
};

}  // namespace mallet::input::wiimote::test
