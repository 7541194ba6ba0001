#pragma once
// The IR camera's start-up sequence as a small pure state machine: no I/O and no clock of
// its own. The transport feeds it the time and every input report it receives, and sends
// whatever output reports it hands out. The sequence is the Linux driver's
// (hid-wiimote-modules.c, wiimod_ir_change), each step waiting for its 0x22 ack:
//
//   1. 13 06                    IR pixel clock on   (0x04 enable | 0x02 ack request)
//   2. 1A 06                    IR logic on         (same bits)
//   3. write B00030 = 01        camera on, not yet sending
//   4. write B00000 = 9 bytes   sensitivity block 1
//   5. write B0001A = 2 bytes   sensitivity block 2
//   6. write B00033 = mode      1 basic, 3 extended
//   7. write B00030 = 08        camera sending
//   8. 12 06 MM                 continuous reporting (0x04) of the matching data report,
//                               with the ack-request bit so this step is confirmed too
//
// Writes (0x16) are always acknowledged by the remote; 0x13, 0x1a and 0x12 only because we
// set bit 0x02 (the ack-request bit of every output report; Dolphin's emulated remote and
// wiibrew agree). Silence for `ack_timeout_ns` → the step's report is sent again, up to
// `max_resends` times, then failed() with a clear error. An ack carrying an error code sends
// the step again at once (the kernel's hid-wiimote writes too, and its refused writes are
// acked under the same report id), and fails only when every try was refused. Every 0x20 status report (solicited or not) resets the remote's
// reporting mode, so once running — or while the last step waits — 0x12 is sent again.
// Call start() after every (re)connect: the remote forgets all of this when it drops.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/enum_names.hpp"
#include "core/ir_camera_settings.hpp"
#include "core/time.hpp"
#include "input/wiimote/reports.hpp"

namespace mallet::input::wiimote {

// The sensitivity presets and the camera's modes are data the settings file names, so
// they live in the core (core/ir_camera_settings.hpp); the names stay usable here.
using mallet::find_sensitivity;
using mallet::IrMode;
using mallet::kDefaultSensitivity;
using mallet::kSensitivityPresets;
using mallet::SensitivityPreset;
using mallet::sensitivity_names;

//! The data report that carries the camera's format: 0x36 (buttons + 10 IR bytes) for
//! basic, 0x33 (buttons + accelerometer + 12 IR bytes) for extended.
constexpr DataMode data_mode_for(IrMode mode) {
  return mode == IrMode::basic ? InputReportId::buttons_ir10_ext9 : InputReportId::buttons_accel_ir12;
}

struct IrStartupConfig {
  IrMode mode = IrMode::extended;
  SensitivityPreset sensitivity = kSensitivityPresets[2];  //!< wii3
  Nanos ack_timeout_ns = 100'000'000;  //!< silence before a step is sent again
  int max_resends = 3;                 //!< per step; then failed()
  Rumble rumble = Rumble::off;         //!< the rumble bit of every report sent
};

enum class IrStartupStep : std::uint8_t {
  idle,            //!< not started (or after reset())
  pixel_clock,     //!< 13 06
  logic,           //!< 1A 06
  camera_on,       //!< B00030 = 01
  sensitivity1,    //!< B00000 = block 1
  sensitivity2,    //!< B0001A = block 2
  mode,            //!< B00033 = 1 or 3
  camera_ready,    //!< B00030 = 08
  reporting_mode,  //!< 12 06 MM
  running,         //!< IR data flows; 0x20 sends the reporting mode again
  failed,          //!< see error()
};
inline constexpr EnumNames<IrStartupStep, 11> kIrStartupStepNames{{
    {IrStartupStep::idle, "idle"}, {IrStartupStep::pixel_clock, "IR pixel clock (0x13)"},
    {IrStartupStep::logic, "IR logic (0x1a)"}, {IrStartupStep::camera_on, "camera on (write 0xb00030 = 0x01)"},
    {IrStartupStep::sensitivity1, "sensitivity block 1 (write 9 bytes at 0xb00000)"},
    {IrStartupStep::sensitivity2, "sensitivity block 2 (write 2 bytes at 0xb0001a)"},
    {IrStartupStep::mode, "IR mode (write 0xb00033)"},
    {IrStartupStep::camera_ready, "camera ready (write 0xb00030 = 0x08)"},
    {IrStartupStep::reporting_mode, "reporting mode (0x12)"}, {IrStartupStep::running, "running"},
    {IrStartupStep::failed, "failed"}}};

//! "reporting mode (12 06 33)" etc.
std::string_view to_string(IrStartupStep step);

class IrStartup {
 public:
  explicit IrStartup(IrStartupConfig config = {});

  //! (Re)starts the sequence from step 1, forgetting any previous state and queued
  //! output. Call on every (re)connect.
  void start(Nanos now_ns);
  //! Back to idle: nothing sent, nothing awaited (e.g. the device is gone).
  void reset();

  //! Every input report received, byte 0 = id. Unparseable reports are ignored (counted).
  void feed(std::span<const std::uint8_t> report, Nanos now_ns);
  //! Resends on silence; call regularly (e.g. after each read timeout).
  void tick(Nanos now_ns);
  //! The next output report to send, oldest first; nothing when none is due.
  std::optional<OutputReport> poll();

  //! The rumble bit of reports built from now on (the transport's rumble pulses).
  void set_rumble(Rumble rumble) { config_.rumble = rumble; }

  IrStartupStep step() const { return step_; }
  bool running() const { return step_ == IrStartupStep::running; }
  bool failed() const { return step_ == IrStartupStep::failed; }
  //! Why failed(): one line naming the step, e.g. "IR start-up: no acknowledgement for
  //! sensitivity block 1 (write 9 bytes at 0xb00000) after 4 tries, 100 ms apart".
  const std::string& error() const { return error_; }

  int resends() const { return resends_total_; }             //!< since start()
  int ignored_reports() const { return ignored_reports_; }   //!< unparseable, since start()
  int mode_resets() const { return mode_resets_; }           //!< 0x20 → 0x12 again, since start()
  const IrStartupConfig& config() const { return config_; }

 private:
  //! Steps 1..8: a report is out and its ack awaited.
  bool awaiting_ack() const {
    return step_ != IrStartupStep::idle && step_ != IrStartupStep::running && step_ != IrStartupStep::failed;
  }
  void enter(IrStartupStep step, Nanos now_ns);
  void send_current(Nanos now_ns);
  OutputReport build(IrStartupStep step) const;
  void fail(std::string message);
  void on_ack(const AckReport& ack, Nanos now_ns);
  void on_status(Nanos now_ns);

  IrStartupConfig config_;
  IrStartupStep step_ = IrStartupStep::idle;
  Nanos sent_at_ns_ = 0;
  int tries_ = 0;  //!< sends of the current step
  std::vector<OutputReport> queue_;
  std::string error_;
  int resends_total_ = 0;
  int ignored_reports_ = 0;
  int mode_resets_ = 0;
};

}  // namespace mallet::input::wiimote
