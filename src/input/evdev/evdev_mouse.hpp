#pragma once
// The mouse read at its source: the kernel's evdev node through libevdev (Debian:
// libevdev-dev), not the window system's cursor events. The kernel stamps every USB report
// when it arrives (CLOCK_MONOTONIC once asked, = the program's clock), and the node delivers
// every report at the mouse's native rate (125–1000 Hz and more), where a window system
// coalesces motion into one event per frame stamped when the frame gets round to it.
//
// Threads. start() reads on its own thread: poll() on the device and an eventfd, with a
// timeout, so stop() returns promptly; each batch of samples goes to the sink on that thread.
// A device that goes away (unplugged: ENODEV) is said so in status(), and the thread tries to
// open it again every reopen_interval_ns until stop() ("auto" looks for a mouse afresh, so a
// mouse plugged back in as another eventN is found). Nothing throws across the thread.
//
// This is the only file of the program that includes libevdev; it lives in its own library
// (mallet_evdev). The decoding is device-free (evdev_decoder.hpp) and tested on recordings.
#include <atomic>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/result.hpp"
#include "input/evdev/evdev_decoder.hpp"
#include "input/evdev/rate_meter.hpp"
#include "input/pointer_source.hpp"

namespace mallet::input::evdev {

inline constexpr const char* kDefaultInputDir = "/dev/input";
//! The device name that means "the first mouse find_mice() lists".
inline constexpr const char* kAutoDevice = "auto";

//! One evdev node.
struct EvdevDeviceInfo {
  std::string path;  //!< e.g. /dev/input/event3
  std::string name;  //!< the kernel's device name, e.g. "Logitech USB Optical Mouse"
  friend bool operator==(const EvdevDeviceInfo&, const EvdevDeviceInfo&) = default;
};

//! What a search of event nodes found, and what it could not look at.
struct MouseScan {
  std::vector<EvdevDeviceInfo> mice;
  int unreadable = 0;       //!< event nodes that could not be opened (usually permissions)
  std::string first_error;  //!< the first of those, e.g. "/dev/input/event3: Permission denied"
};

//! The mice among `dir`/event* (in event-number order): nodes with EV_REL REL_X and REL_Y
//! and EV_KEY BTN_LEFT. Anything else there (keyboards, touchpads, regular files, a missing
//! directory) is skipped, never an error.
MouseScan scan_mice(const std::filesystem::path& dir = kDefaultInputDir);
inline std::vector<EvdevDeviceInfo> find_mice(const std::filesystem::path& dir = kDefaultInputDir) {
  return scan_mice(dir).mice;
}

struct EvdevMouseConfig {
  int screen_width_px = EvdevDecoder::kDefaultScreenWidthPx;    //!< the screen the mouse moves over
  int screen_height_px = EvdevDecoder::kDefaultScreenHeightPx;
  double speed_px_per_count = EvdevDecoder::kDefaultSpeedPxPerCount;  //!< no acceleration (evdev_decoder.hpp)
  Nanos reopen_interval_ns = kNanosPerSecond;  //!< after the device went away, one attempt per interval
  int poll_timeout_ms = 100;  //!< one wait's bound: how stale status() and rate_hz() get while the mouse rests
  std::filesystem::path search_dir = kDefaultInputDir;  //!< where "auto" looks
};

//! The reading thread's latest state, for the operator page.
struct EvdevMouseStatus {
  bool connected = false;
  EvdevDeviceInfo device;      //!< the open node (or the last one)
  bool absolute = false;       //!< ABS_X/ABS_Y device (touchscreen, tablet) rather than a mouse
  bool clock_mapped = false;   //!< the kernel would not stamp CLOCK_MONOTONIC: REALTIME + an offset measured at open
  std::string problem;         //!< why not connected, e.g. "/dev/input/event3: the device went away (No such device); ..."
  EvdevDecoderCounters counters;  //!< over every connection (one decoder keeps the position across them)
  double rate_hz = 0;          //!< samples in the last second
  std::uint64_t reconnects = 0;
};

class EvdevMouse;
class EvdevNode;  //!< an open node: its fd and libevdev handle (evdev_mouse.cpp)

//! A mouse, or why none could be opened (one line a person can act on).
using EvdevOpenResult = Result<std::unique_ptr<EvdevMouse>, std::string>;

class EvdevMouse final : public PointerSource {
 public:
  //! Opens `device`, an event node's path, or "auto" (kAutoDevice): the first mouse of
  //! scan_mice(config.search_dir). An explicit node may also be an absolute pointer
  //! (ABS_X + ABS_Y: touchscreen, tablet). Errors, e.g.
  //!   "/dev/input/event3: Permission denied (is the user in the 'input' group?)"
  //!   "/tmp/x: not an input event device (a regular file); give a /dev/input/event* node or \"auto\""
  //!   "no mouse among /dev/input/event*"
  static EvdevOpenResult open(const std::string& device, EvdevMouseConfig config = {});

  ~EvdevMouse() override;
  EvdevMouse(const EvdevMouse&) = delete;
  EvdevMouse& operator=(const EvdevMouse&) = delete;

  //! No-op while running. May follow a stop().
  void start(PointerSink sink) override;
  void stop() override;
  //! "mouse via evdev /dev/input/event3 (Logitech USB Optical Mouse)"; "pointer via evdev
  //! ... (absolute)" for a touchscreen or tablet.
  std::string describe() const override;

  //! Samples per second over the last second (the mouse's native rate while it moves; 0
  //! at rest, as a mouse reports only motion). Any thread.
  double rate_hz() const { return rate_hz_.load(std::memory_order_relaxed); }
  //! Any thread.
  EvdevMouseStatus status() const;
  //! Puts the pointer at normalised (x, y) before the next sample (e.g. the centre when the
  //! kiosk returns to attract mode). Any thread.
  void warp(double x, double y);
  //! The screen's size in pixels changed (the normalised position is kept). Any thread.
  void set_screen(int width_px, int height_px);


 private:
  EvdevMouse(std::string spec, EvdevMouseConfig config, std::unique_ptr<EvdevNode> node);
  void run(PointerSink sink);
  void attach(std::unique_ptr<EvdevNode> node);
  void detach(const std::string& why);
  //! Reads what is pending into `batch`; fails with why when the device went away.
  Check read_events(std::vector<PointerSample>& batch);
  void apply_requests();
  void publish(bool force_strings);
  void wait_for_wake(int timeout_ms) const;

  const std::string spec_;  //!< the path asked for, or "auto"
  const EvdevMouseConfig config_;
  int wake_fd_ = -1;        //!< eventfd: stop() wakes the reading thread with it

  // Reading-thread state.
  std::unique_ptr<EvdevNode> node_;
  EvdevDecoder decoder_;
  RateMeter rate_;
  std::string problem_;
  std::uint64_t reconnects_ = 0;

  // Shared with other threads.
  mutable std::mutex mutex_;
  EvdevMouseStatus status_;
  std::optional<std::pair<double, double>> warp_request_;
  std::optional<std::pair<int, int>> screen_request_;
  std::atomic<bool> requests_{false};
  std::atomic<double> rate_hz_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace mallet::input::evdev
