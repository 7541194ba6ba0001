#pragma once
// Linux evdev events → pointer samples, without a device: the part of the mouse that is
// pure, so it is tested on recorded event streams (this CI has no /dev/uinput and no mouse).
//
// The kernel delivers a pointer's state in frames: EV_REL / EV_ABS / EV_KEY events, then
// EV_SYN SYN_REPORT. The decoder accumulates a frame and, at its SYN_REPORT, moves its
// pointer and emits one sample stamped with the SYN_REPORT's own kernel timestamp (every
// event of a frame carries the same one). That is the time the kernel saw the USB report,
// the earliest honest time the program can have; the reader sets CLOCK_MONOTONIC as the
// event clock, so it is the program's clock and the offset is 0.
//
// Relative devices (mice) move a position in pixels of a screen of a given size by
// counts × speed, with NO acceleration: the kiosk must be predictable. The same hand
// movement moves the mallet the same distance whether it is fast or slow, so the strike
// speed the solver measures (which sets the note's loudness and the bounce, Eq. 1's A·v) is
// what the visitor's hand did, not an acceleration curve's reading of it; and a visitor
// walking up to the kiosk finds it behaving the same as for the one before.
// Absolute devices (touchscreens, tablets) report ABS_X / ABS_Y in a range; the decoder maps
// the range onto the screen (speed does not apply).
#include <cstdint>
#include <optional>

#include <linux/input.h>

#include "core/pointer_sample.hpp"
#include "core/time.hpp"

namespace mallet::input::evdev {

//! One absolute axis's range as the device reports it (libevdev_get_abs_minimum/maximum).
struct AbsAxisRange {
  int min = 0;
  int max = 0;
};

struct EvdevDecoderCounters {
  std::uint64_t reports = 0;           //!< SYN_REPORTs accepted (every frame, moved or not)
  std::uint64_t dropped_syncs = 0;     //!< SYN_DROPPEDs: the kernel's buffer overflowed, events were lost
  std::uint64_t discarded_events = 0;  //!< events thrown away because of a SYN_DROPPED (their SYN_REPORT included)
  std::uint64_t samples = 0;           //!< samples emitted
  friend bool operator==(const EvdevDecoderCounters&, const EvdevDecoderCounters&) = default;
};

//! The kernel's timestamp of an event in nanoseconds (exact: seconds and microseconds are
//! converted separately in int64).
constexpr Nanos event_time_ns(const input_event& event) {
  return static_cast<Nanos>(event.input_event_sec) * kNanosPerSecond +
         static_cast<Nanos>(event.input_event_usec) * 1000;
}

class EvdevDecoder {
 public:
  static constexpr int kDefaultScreenWidthPx = 1920;
  static constexpr int kDefaultScreenHeightPx = 1080;
  static constexpr double kDefaultSpeedPxPerCount = 1.0;

  //! The pointer starts at the screen's centre.
  EvdevDecoder() = default;

  //! The screen the relative motion moves over, in pixels. The normalised position is kept.
  //! False (and nothing changes) unless both are > 0.
  bool set_screen(int width_px, int height_px);
  //! Pixels per mouse count, the same at every speed. False (nothing changes) unless finite
  //! and > 0.
  bool set_speed(double px_per_count);
  //! Added to every kernel timestamp: a mapping from the event clock to the program's
  //! monotonic clock when the kernel could not be told to stamp CLOCK_MONOTONIC; else 0.
  void set_clock_offset(Nanos offset_ns) { clock_offset_ns_ = offset_ns; }
  //! The range of ABS_X or ABS_Y (other codes are ignored); an axis without a range (or
  //! with max <= min) is ignored.
  void set_abs_range(std::uint16_t code, AbsAxisRange range);
  //! Puts the pointer at normalised (x, y), clamped to the screen. The next sample starts
  //! from there; no sample is emitted.
  void warp(double x, double y);

  //! Takes the next event in reading order. At a SYN_REPORT whose frame moved the pointer
  //! (non-zero REL_X/REL_Y counts, or an ABS_X/ABS_Y value of a ranged axis), returns the
  //! new position stamped with that SYN_REPORT's time plus the clock offset.
  //!
  //! SYN_DROPPED (the kernel's buffer overflowed): as the kernel's documentation says, the
  //! events since the last SYN_REPORT and every event up to and including the next
  //! SYN_REPORT are discarded (they belong to incomplete frames), and it is counted. The
  //! relative motion they carried is lost; the pointer does not jump.
  std::optional<PointerSample> feed(const input_event& event);

  //! libevdev's own SYN_DROPPED handling already discarded the stale events and now
  //! delivers the device's current state as a frame (LIBEVDEV_READ_FLAG_SYNC): call this
  //! after feeding the SYN_DROPPED so that frame is taken instead of discarded. Also when
  //! a device is (re)opened: a frame the old one left half-read is forgotten.
  void resynced() {
    clear_frame();
    discarding_ = false;
  }

  //! The current position (normalised, clamped to 0..1) at the time of the last sample
  //! (0 before any).
  PointerSample position() const;
  bool left_button() const { return left_button_; }
  const EvdevDecoderCounters& counters() const { return counters_; }
  double speed_px_per_count() const { return speed_px_per_count_; }
  int screen_width_px() const { return width_px_; }
  int screen_height_px() const { return height_px_; }

 private:
  void clear_frame();
  void clamp_position();

  int width_px_ = kDefaultScreenWidthPx;
  int height_px_ = kDefaultScreenHeightPx;
  double speed_px_per_count_ = kDefaultSpeedPxPerCount;
  Nanos clock_offset_ns_ = 0;
  std::optional<AbsAxisRange> abs_x_, abs_y_;

  // The position, in pixels, clamped to [0, width] × [0, height].
  double x_px_ = kDefaultScreenWidthPx / 2.0;
  double y_px_ = kDefaultScreenHeightPx / 2.0;
  Nanos last_t_ns_ = 0;
  bool left_button_ = false;

  // The frame being accumulated (since the last SYN_REPORT).
  std::int64_t rel_x_counts_ = 0;
  std::int64_t rel_y_counts_ = 0;
  std::optional<int> abs_x_value_, abs_y_value_;
  std::optional<bool> left_button_value_;
  std::uint64_t frame_events_ = 0;
  bool discarding_ = false;  //!< after a SYN_DROPPED, until the next SYN_REPORT

  EvdevDecoderCounters counters_;
};

}  // namespace mallet::input::evdev
