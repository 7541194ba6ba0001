#include "input/wiimote/ir_startup.hpp"

#include <cstdio>
#include <variant>

#include <fmt/format.h>

namespace mallet::input::wiimote {

namespace {

constexpr std::uint32_t kRegCameraEnable = 0xb00030;
constexpr std::uint32_t kRegSensitivity1 = 0xb00000;
constexpr std::uint32_t kRegSensitivity2 = 0xb0001a;
constexpr std::uint32_t kRegMode = 0xb00033;
constexpr std::uint8_t kCameraOn = 0x01;
constexpr std::uint8_t kCameraReady = 0x08;

//! The output report id a step's ack names.
std::uint8_t acked_id(IrStartupStep step) {
  switch (step) {
    case IrStartupStep::pixel_clock: return static_cast<std::uint8_t>(OutputReportId::ir_pixel_clock);
    case IrStartupStep::logic: return static_cast<std::uint8_t>(OutputReportId::ir_logic);
    case IrStartupStep::reporting_mode: return static_cast<std::uint8_t>(OutputReportId::reporting_mode);
    default: return static_cast<std::uint8_t>(OutputReportId::write_memory);
  }
}

IrStartupStep next(IrStartupStep step) {
  if (step == IrStartupStep::idle || step >= IrStartupStep::reporting_mode) return IrStartupStep::running;
  return static_cast<IrStartupStep>(static_cast<std::uint8_t>(step) + 1);
}

}  // namespace

std::string_view to_string(IrStartupStep step) { return name_in(kIrStartupStepNames, step); }

IrStartup::IrStartup(IrStartupConfig config) : config_(config) {}

void IrStartup::reset() {
  step_ = IrStartupStep::idle;
  queue_.clear();
  error_.clear();
  tries_ = 0;
  resends_total_ = 0;
  ignored_reports_ = 0;
  mode_resets_ = 0;
}

void IrStartup::start(Nanos now_ns) {
  reset();
  enter(IrStartupStep::pixel_clock, now_ns);
}

void IrStartup::enter(IrStartupStep step, Nanos now_ns) {
  step_ = step;
  tries_ = 0;
  if (awaiting_ack()) send_current(now_ns);
}

void IrStartup::send_current(Nanos now_ns) {
  queue_.push_back(build(step_));
  sent_at_ns_ = now_ns;
  ++tries_;
}

OutputReport IrStartup::build(IrStartupStep step) const {
  const Rumble r = config_.rumble;
  auto write = [r](std::uint32_t address, std::span<const std::uint8_t> data) {
    // The data are at most 9 bytes and the addresses fixed: write_memory cannot refuse.
    return *write_memory(AddressSpace::registers, address, data, r);
  };
  switch (step) {
    case IrStartupStep::pixel_clock: return set_ir_pixel_clock(true, r, Ack::request);
    case IrStartupStep::logic: return set_ir_logic(true, r, Ack::request);
    case IrStartupStep::camera_on: return write(kRegCameraEnable, std::span(&kCameraOn, 1));
    case IrStartupStep::sensitivity1: return write(kRegSensitivity1, config_.sensitivity.block1);
    case IrStartupStep::sensitivity2: return write(kRegSensitivity2, config_.sensitivity.block2);
    case IrStartupStep::mode: {
      const auto mode = static_cast<std::uint8_t>(config_.mode);
      return write(kRegMode, std::span(&mode, 1));
    }
    case IrStartupStep::camera_ready: return write(kRegCameraEnable, std::span(&kCameraReady, 1));
    default: return set_reporting_mode(data_mode_for(config_.mode), true, r, Ack::request);
  }
}

void IrStartup::fail(std::string message) {
  step_ = IrStartupStep::failed;
  error_ = "IR start-up: " + std::move(message);
}

std::optional<OutputReport> IrStartup::poll() {
  if (queue_.empty()) return std::nullopt;
  OutputReport out = queue_.front();
  queue_.erase(queue_.begin());
  return out;
}

void IrStartup::tick(Nanos now_ns) {
  if (!awaiting_ack()) return;
  if (now_ns - sent_at_ns_ < config_.ack_timeout_ns) return;
  if (tries_ > config_.max_resends) {
    const std::string ms = fmt::format("{:.0f} ms", static_cast<double>(config_.ack_timeout_ns) * 1e-6);
    fail("no acknowledgement for " + std::string(to_string(step_)) + " after " + std::to_string(tries_) +
         (tries_ == 1 ? " try" : " tries") + ", " + ms + " apart (is the remote still connected?)");
    return;
  }
  ++resends_total_;
  send_current(now_ns);
}

void IrStartup::feed(std::span<const std::uint8_t> report, Nanos now_ns) {
  const auto parsed = parse_input(report);
  if (!parsed) {
    ++ignored_reports_;
    return;
  }
  if (const auto* ack = std::get_if<AckReport>(&*parsed)) on_ack(*ack, now_ns);
  else if (std::holds_alternative<StatusReport>(*parsed)) on_status(now_ns);
}

void IrStartup::on_ack(const AckReport& ack, Nanos now_ns) {
  if (!awaiting_ack()) return;
  // An ack names only the report id. One for another id answers something else the
  // transport sent (LEDs, a status request): not ours. A late ack of a resent write may
  // be taken for the next write's: harmless, the remote applies reports in order and
  // the last step (0x12) has its own id.
  if (ack.report != acked_id(step_)) return;
  if (!ack.success()) {
    // Linux's hid-wiimote writes too (0x16: its extension and Motion Plus probes, every few
    // seconds), and a remote without them refuses those writes with error 7. Their ack names
    // the same report as ours, so a refusal may be the kernel's: the step is sent again, and
    // only a step refused on every try fails (found with the kernel's driver bound, in the
    // package's system test).
    if (tries_ > config_.max_resends) {
      fail("the remote refused " + std::string(to_string(step_)) + " (acknowledgement error code " +
           std::to_string(ack.error) + ")");
      return;
    }
    ++resends_total_;
    send_current(now_ns);
    return;
  }
  enter(next(step_), now_ns);
}

void IrStartup::on_status(Nanos now_ns) {
  // Linux (handler_status) does the same: after any 0x20 the remote sends no data
  // reports until the reporting mode is set again. Before step 8 nothing is lost: 0x12
  // comes at the end anyway.
  if (step_ == IrStartupStep::running) {
    ++mode_resets_;
    enter(IrStartupStep::reporting_mode, now_ns);
  } else if (step_ == IrStartupStep::reporting_mode) {
    // The 0x12 in flight may have been applied before the reset: send it again now
    // (a fresh timer; not counted as a resend for silence).
    ++mode_resets_;
    queue_.push_back(build(step_));
    sent_at_ns_ = now_ns;
  }
}

}  // namespace mallet::input::wiimote
