#pragma once
// What the Wii Remote device tests share: a scripted clock, report builders written from
// the protocol description, and the Linux driver's IR start-up sequence.
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/ir_dot.hpp"
#include "input/clock.hpp"

namespace mallet::input::wiimote::test {

using Bytes = std::vector<std::uint8_t>;

inline constexpr Nanos kMs = 1'000'000;

//! Time that passes only when told: a read's time-out, a sleep, a scripted delay.
//! Atomic so a device thread and the test may both read it.
class FakeClock final : public Clock {
 public:
  explicit FakeClock(Nanos start = 1'000 * kNanosPerSecond) : now_(start) {}
  Nanos now() override { return now_.load(); }
  void sleep_for(Nanos duration_ns) override {
    sleeps_.fetch_add(1);
    if (duration_ns > 0) now_.fetch_add(duration_ns);
  }
  void advance(Nanos ns) { now_.fetch_add(ns); }
  int sleeps() const { return sleeps_.load(); }

 private:
  std::atomic<Nanos> now_;
  std::atomic<int> sleeps_{0};
};

//! 0x33 (buttons, accelerometer, 12 extended IR bytes): up to four dots, the rest empty
//! (ff ff ff). Each dot: [X7..0, Y7..0, Y9..8 X9..8 S3..0].
inline Bytes ir_report(const std::vector<IrDot>& dots) {
  Bytes b = {0x33, 0x00, 0x00, 0x80, 0x80, 0x80};
  for (std::size_t i = 0; i < 4; ++i) {
    if (i < dots.size()) {
      const IrDot& d = dots[i];
      b.push_back(static_cast<std::uint8_t>(d.x & 0xff));
      b.push_back(static_cast<std::uint8_t>(d.y & 0xff));
      b.push_back(static_cast<std::uint8_t>(((d.y >> 8) & 0x03) << 6 | ((d.x >> 8) & 0x03) << 4 | (d.size & 0x0f)));
    } else {
      b.insert(b.end(), {0xff, 0xff, 0xff});
    }
  }
  return b;
}

inline Bytes ack_report(std::uint8_t report, std::uint8_t error = 0) { return {0x22, 0x00, 0x00, report, error}; }

//! 0x20 with the IR flag and a battery level.
inline Bytes status_report(std::uint8_t battery = 0xc8, bool low = false) {
  return {0x20, 0x00, 0x00, static_cast<std::uint8_t>(0x08 | (low ? 0x01 : 0x00)), 0x00, 0x00, battery};
}

inline Bytes write_reg(std::uint32_t address, Bytes data, std::uint8_t flags = 0x04) {
  Bytes b = {0x16, flags, static_cast<std::uint8_t>(address >> 16), static_cast<std::uint8_t>(address >> 8),
             static_cast<std::uint8_t>(address), static_cast<std::uint8_t>(data.size())};
  b.insert(b.end(), data.begin(), data.end());
  b.resize(22, 0x00);
  return b;
}

//! What the device sends on every connection: player LED 1 (11 10), a status request
//! (15 00), then the Linux driver's IR start-up for extended mode and sensitivity "wii3".
inline std::vector<Bytes> connect_sequence() {
  return {
      {0x11, 0x10},
      {0x15, 0x00},
      {0x13, 0x06},
      {0x1a, 0x06},
      write_reg(0xb00030, {0x01}),
      write_reg(0xb00000, {0x02, 0x00, 0x00, 0x71, 0x01, 0x00, 0xaa, 0x00, 0x64}),
      write_reg(0xb0001a, {0x63, 0x03}),
      write_reg(0xb00033, {0x03}),
      write_reg(0xb00030, {0x08}),
      {0x12, 0x06, 0x33},
  };
}

//! The remote's side of a report the host sent: an ack when asked for (bit 0x02) or
//! for any memory write, a status report for a status request.
inline std::optional<Bytes> remote_answer(const Bytes& sent) {
  if (sent.size() < 2) return std::nullopt;
  if (sent[0] == 0x15) return status_report();
  if (sent[0] == 0x16 || (sent[1] & 0x02) != 0) return ack_report(sent[0]);
  return std::nullopt;
}

}  // namespace mallet::input::wiimote::test
