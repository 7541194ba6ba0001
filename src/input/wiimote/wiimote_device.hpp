#pragma once
// A live Wii Remote as a pointer source: finds and opens a remote, runs the IR camera's
// start-up sequence, reads its reports on its own thread, and publishes the stick's LED
// (raw camera coordinates, stamped at reception on the monotonic clock) to a consumer on
// another thread. It never gives up: a remote that is gone (read error), silent for
// `silence_timeout_ns`, or whose start-up fails is closed and looked for again, the wait
// between attempts doubling from `reconnect_min_ns` to `reconnect_max_ns`, forever; the
// start-up runs again on every connection (the remote forgets it when it drops).
//
// Threads. step() is the whole device logic, one bounded iteration (a read of at most
// `read_timeout_ms`, or a wait of at most 50 ms while disconnected); start() runs it in a
// loop on the reading thread, tests call it directly with a scripted transport and clock.
// The consumer's calls (state(), drain(), pulse_rumble()) take a mutex held only for a
// copy or a swap, or touch an atomic: the reading thread never waits on the consumer.
//
// Output reports leave only from the reading thread (the transport has one user); a
// rumble pulse is a request flag the thread services, so the consumer's impact path
// never writes to the device. The rumble bit (0x01 of byte 1) of every report sent
// carries the motor's wanted state: the remote applies it from any output report.
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "core/app_config.hpp"
#include "core/enum_names.hpp"
#include "core/ir_tracker.hpp"
#include "input/clock.hpp"
#include "input/wiimote/ir_startup.hpp"
#include "input/wiimote/report_tracker.hpp"
#include "input/wiimote/reports.hpp"
#include "input/wiimote/transport.hpp"

namespace mallet::input::wiimote {

struct WiimoteDeviceConfig {
  std::string device;  //!< see matches_device(); empty = the first remote found
  IrStartupConfig ir;
  IrTrackerConfig tracking;
  Nanos silence_timeout_ns = 3 * kNanosPerSecond;
  Nanos reconnect_min_ns = 500'000'000;
  Nanos reconnect_max_ns = 5 * kNanosPerSecond;
  int read_timeout_ms = 10;        //!< one read's wait: bounds stop(), rumble and time-out latency
  Nanos rumble_ns = 40'000'000;    //!< one pulse
  bool rumble_on_impact = false;   //!< on_impact() pulses only when set
  std::uint8_t leds = 0x01;        //!< player LEDs 1..4 (bits 0..3) lit while connected
  bool keep_raw_reports = false;   //!< queue every raw report for drain_raw() (`--record`)
  //! A sample for every IR report, carrying its frame (all four slots), even with no LED
  //! accepted: the sensitivity tuner counts dots and sizes. Off: samples only for the LED.
  bool every_frame = false;
  std::size_t queue_capacity = 4096;  //!< samples (and raw reports) kept for the consumer
};

//! [wiimote] and [tracking] of the settings file. The sensitivity name was checked by the
//! loader; an unknown one (a config built by hand) falls back to the default preset.
WiimoteDeviceConfig device_config(const AppConfig& app);

enum class LinkState : std::uint8_t {
  searching,  //!< no remote open: waiting for the next attempt
  starting,   //!< open, IR camera start-up in progress
  running,    //!< IR reports flow
};
inline constexpr EnumNames<LinkState, 3> kLinkStateNames{{
    {LinkState::searching, "searching"}, {LinkState::starting, "starting"}, {LinkState::running, "running"}}};

const char* to_string(LinkState state);

//! The latest state, for display and diagnostics.
struct WiimoteState {
  LinkState link = LinkState::searching;
  HidDeviceInfo device;  //!< the open remote (or the last one)
  std::string problem;   //!< why the last attempt failed or the link dropped; cleared once running
  std::string last_drop; //!< why the link last dropped (`disconnects`), kept once running again
  IrStartupStep startup = IrStartupStep::idle;
  bool tracking = false;
  std::optional<IrPoint> point;  //!< the last accepted LED position (kept after `lost`)
  RemoteStats remote;            //!< rate, battery, last dots, report counts
  bool rumbling = false;
  Nanos now_ns = 0;              //!< when this state was published
  Nanos next_attempt_ns = 0;     //!< while searching
  Nanos backoff_ns = 0;          //!< the wait after the next failed attempt
  std::uint64_t connects = 0;
  std::uint64_t disconnects = 0;
  std::uint64_t failed_attempts = 0;  //!< nothing found, open failed
  std::uint64_t mode_resets = 0;      //!< 0x20 status reports answered with 0x12 again
  std::uint64_t rumble_pulses = 0;
  std::uint64_t dropped = 0;          //!< samples or raw reports the consumer did not drain in time
};

//! One LED sample or tracking change, in reception order.
struct LedSample {
  Nanos t_ns = 0;
  IrTrackerEvent event = IrTrackerEvent::none;  //!< regained, lost, jumped, or none
  bool has_point = false;
  IrPoint point{};  //!< raw camera coordinates when has_point
  bool has_frame = false;  //!< every_frame only
  IrFrame frame{};         //!< the report's IR slots when has_frame
};

//! One report exactly as received (for `--record`).
struct RawReport {
  Nanos t_ns = 0;
  std::uint8_t size = 0;
  std::array<std::uint8_t, kMaxRecordedReportSize> bytes{};
  std::span<const std::uint8_t> span() const { return {bytes.data(), size}; }
};

class WiimoteDevice {
 public:
  //! `finder` and `clock` must outlive the device. Throws std::invalid_argument on a bad
  //! tracker config.
  WiimoteDevice(DeviceFinder& finder, Clock& clock, WiimoteDeviceConfig config = {});
  ~WiimoteDevice();
  WiimoteDevice(const WiimoteDevice&) = delete;
  WiimoteDevice& operator=(const WiimoteDevice&) = delete;

  //! Runs step() on the reading thread until stop(). No-op when running.
  void start();
  //! Stops the thread (within one step) and closes the remote.
  void stop();
  //! One iteration of the device logic. Only one thread may call it (the reading thread
  //! once start()ed).
  void step();

  // --- consumer side, any thread ---
  WiimoteState state() const;
  //! Replaces `out` with the samples since the last drain; returns how many.
  std::size_t drain(std::vector<LedSample>& out);
  //! The samples' consumer on the reading thread itself: after every step, `sink` gets that
  //! step's samples (often none) and the step's time. The kiosk's input path runs there,
  //! so a strike reaches the audio engine without waiting for a frame or a second thread.
  //! The samples then bypass drain(). The sink must not block for long (it delays the next
  //! read) and must not throw. Set it before start().
  using SampleSink = std::function<void(std::span<const LedSample> samples, Nanos now)>;
  void set_sample_sink(SampleSink sink) { sink_ = std::move(sink); }
  //! Replaces `out` with the raw reports since the last drain (keep_raw_reports only).
  std::size_t drain_raw(std::vector<RawReport>& out);
  //! Asks for one rumble pulse of rumble_ns (another request while one runs extends it).
  void pulse_rumble() { rumble_request_.store(true, std::memory_order_release); }
  //! Asks for the camera's sensitivity blocks of `preset` (a name from kSensitivityPresets;
  //! others are ignored): the reading thread runs the IR start-up again with them, and keeps
  //! them for every later reconnection. Returns whether the name is known.
  bool request_sensitivity(std::string_view preset);
  //! A strike happened: pulse_rumble() when rumble_on_impact.
  void on_impact() {
    if (config_.rumble_on_impact) pulse_rumble();
  }

  const WiimoteDeviceConfig& config() const { return config_; }

 private:
  void step_disconnected(Nanos now);
  void try_connect(Nanos now);
  void fail_attempt(Nanos now, std::string why);
  void disconnect(Nanos now, std::string why);
  void schedule_retry(Nanos now);
  void on_report(Nanos t, std::span<const std::uint8_t> report);
  bool send(const OutputReport& report, Nanos now);
  bool flush_startup(Nanos now);
  bool service_rumble(Nanos now);
  bool service_sensitivity(Nanos now);
  void push_sample(const LedSample& sample);
  void publish(Nanos now);

  DeviceFinder& finder_;
  Clock& clock_;
  const WiimoteDeviceConfig config_;

  // Reading-thread state.
  std::unique_ptr<Transport> transport_;
  IrStartup startup_;
  ReportTracker reports_;
  LinkState link_ = LinkState::searching;
  HidDeviceInfo device_;
  std::string problem_;
  std::string last_drop_;
  Nanos last_rx_ns_ = 0;
  std::optional<Nanos> next_attempt_ns_;  //!< nothing: attempt now
  Nanos backoff_ns_;
  bool rumbling_ = false;
  Nanos rumble_until_ns_ = 0;
  std::uint64_t connects_ = 0, disconnects_ = 0, failed_attempts_ = 0, mode_resets_ = 0, rumble_pulses_ = 0;
  std::vector<LedSample> pending_;   //!< this step's samples, handed over in publish()
  std::vector<RawReport> pending_raw_;
  SampleSink sink_;

  // Shared with the consumer.
  mutable std::mutex mutex_;
  WiimoteState state_;
  std::vector<LedSample> samples_;
  std::vector<RawReport> raw_;
  std::uint64_t dropped_ = 0;
  std::atomic<bool> rumble_request_{false};
  std::atomic<int> sensitivity_request_{-1};  //!< index in kSensitivityPresets, -1 none

  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace mallet::input::wiimote
