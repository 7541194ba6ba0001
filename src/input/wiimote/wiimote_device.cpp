#include "input/wiimote/wiimote_device.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <utility>

#include <fmt/format.h>

namespace mallet::input::wiimote {

namespace {

//! Longest wait of one step while disconnected: how quickly stop() is honoured.
constexpr Nanos kMaxIdleWaitNs = 50'000'000;

Nanos ms_to_ns(double ms) { return static_cast<Nanos>(std::llround(ms * 1e6)); }

std::string seconds_text(Nanos ns) {
  return fmt::format("{:.1f} s", to_seconds(ns));
}

}  // namespace

WiimoteDeviceConfig device_config(const AppConfig& app) {
  WiimoteDeviceConfig c;
  const WiimoteConfig& w = app.wiimote;
  c.device = w.device;
  c.ir.mode = w.ir_mode;
  c.ir.sensitivity = find_sensitivity(w.sensitivity).value_or(*find_sensitivity(kDefaultSensitivity));
  c.tracking = app.tracking;
  c.silence_timeout_ns = ms_to_ns(w.silence_timeout_ms);
  c.reconnect_min_ns = ms_to_ns(w.reconnect_min_ms);
  c.reconnect_max_ns = std::max(c.reconnect_min_ns, ms_to_ns(w.reconnect_max_ms));
  c.rumble_ns = ms_to_ns(w.rumble_ms);
  c.rumble_on_impact = w.rumble_on_impact;
  return c;
}

const char* to_string(LinkState state) { return name_in(kLinkStateNames, state); }

WiimoteDevice::WiimoteDevice(DeviceFinder& finder, Clock& clock, WiimoteDeviceConfig config)
    : finder_(finder),
      clock_(clock),
      config_(std::move(config)),
      startup_(config_.ir),
      reports_(config_.tracking),
      backoff_ns_(config_.reconnect_min_ns) {
  samples_.reserve(std::min<std::size_t>(config_.queue_capacity, 1024));
  state_.backoff_ns = backoff_ns_;
}

WiimoteDevice::~WiimoteDevice() { stop(); }

void WiimoteDevice::start() {
  if (thread_.joinable()) return;
  stop_.store(false);
  thread_ = std::thread([this] {
    while (!stop_.load(std::memory_order_acquire)) step();
  });
}

void WiimoteDevice::stop() {
  stop_.store(true, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
  transport_.reset();
}

// ---------------------------------------------------------------------------------------
// The reading thread

void WiimoteDevice::step() {
  try {
    if (!transport_) {
      step_disconnected(clock_.now());
      return;
    }
    if (!service_rumble(clock_.now())) return;
    if (!service_sensitivity(clock_.now())) return;

    std::array<std::uint8_t, kMaxRecordedReportSize> buffer{};
    const int n = transport_->read(buffer, config_.read_timeout_ms);
    // The report's time is taken the moment the read returns: the closest this process
    // gets to its arrival.
    const Nanos now = clock_.now();
    if (n < 0) {
      disconnect(now, "the remote is gone (read failed: switched off, out of range or unpaired)");
      return;
    }
    if (n > 0) on_report(now, std::span<const std::uint8_t>(buffer.data(), std::min<std::size_t>(n, buffer.size())));
    if (!transport_) return;

    startup_.tick(now);
    if (!flush_startup(now)) return;
    if (startup_.failed()) {
      disconnect(now, startup_.error());
      return;
    }
    if (reports_.poll(now) == IrTrackerEvent::lost) push_sample({now, IrTrackerEvent::lost, false, {}});
    if (now - last_rx_ns_ >= config_.silence_timeout_ns) {
      disconnect(now, "no report for " + seconds_text(now - last_rx_ns_) + " (the remote went silent)");
      return;
    }
    publish(now);
  } catch (const std::exception& e) {
    // Nothing here should throw but an allocation; never let the reading thread die.
    const Nanos now = clock_.now();
    if (transport_) disconnect(now, std::string("internal error: ") + e.what());
    else publish(now);
  }
}

void WiimoteDevice::step_disconnected(Nanos now) {
  if (next_attempt_ns_ && now < *next_attempt_ns_) {
    clock_.sleep_for(std::min(*next_attempt_ns_ - now, kMaxIdleWaitNs));
    publish(clock_.now());
    return;
  }
  try_connect(now);
}

void WiimoteDevice::try_connect(Nanos now) {
  const std::vector<HidDeviceInfo> seen = finder_.enumerate();
  const std::optional<HidDeviceInfo> found = first_matching(seen, config_.device);
  if (!found) {
    if (seen.empty()) {
      fail_attempt(now, "no Wii Remote found (is it paired and connected? `mallet wiimote list` shows what is seen)");
    } else {
      fail_attempt(now, "no Wii Remote matches \"" + config_.device + "\" (" + std::to_string(seen.size()) +
                            " seen; `mallet wiimote list` shows their paths and serials)");
    }
    return;
  }
  OpenResult opened = finder_.open(found->path);
  if (!opened.transport) {
    fail_attempt(now, opened.error.empty() ? "cannot open " + found->path : opened.error);
    return;
  }
  transport_ = std::move(opened.transport);
  device_ = *found;
  ++connects_;
  link_ = LinkState::starting;
  last_rx_ns_ = now;
  rumbling_ = false;
  startup_.set_rumble(Rumble::off);
  if (reports_.restart_tracking()) push_sample({now, IrTrackerEvent::lost, false, {}});
  // The player LED says "connected" (the remote blinks all four until told otherwise);
  // a status request proves it answers and gives the battery level. Its 0x20 answer
  // arrives during the start-up, which only re-sends 0x12 if that step is waiting.
  if (!send(set_leds(config_.leds, Rumble::off), now)) return;
  if (!send(request_status(Rumble::off), now)) return;
  startup_.start(now);
  if (!flush_startup(now)) return;
  publish(now);
}

void WiimoteDevice::schedule_retry(Nanos now) {
  next_attempt_ns_ = now + backoff_ns_;
  backoff_ns_ = std::min(backoff_ns_ > std::numeric_limits<Nanos>::max() / 2 ? config_.reconnect_max_ns
                                                                              : backoff_ns_ * 2,
                         config_.reconnect_max_ns);
}

void WiimoteDevice::fail_attempt(Nanos now, std::string why) {
  ++failed_attempts_;
  problem_ = std::move(why);
  link_ = LinkState::searching;
  schedule_retry(now);
  publish(now);
}

void WiimoteDevice::disconnect(Nanos now, std::string why) {
  transport_.reset();
  startup_.reset();
  ++disconnects_;
  last_drop_ = why;
  problem_ = std::move(why);
  link_ = LinkState::searching;
  rumbling_ = false;
  startup_.set_rumble(Rumble::off);
  if (reports_.restart_tracking()) push_sample({now, IrTrackerEvent::lost, false, {}});
  schedule_retry(now);
  publish(now);
}

bool WiimoteDevice::send(const OutputReport& report, Nanos now) {
  if (!transport_) return false;
  if (transport_->write(report.span())) return true;
  disconnect(now, "the remote is gone (write failed)");
  return false;
}

bool WiimoteDevice::flush_startup(Nanos now) {
  while (auto report = startup_.poll())
    if (!send(*report, now)) return false;
  return true;
}

bool WiimoteDevice::service_rumble(Nanos now) {
  const bool requested = rumble_request_.exchange(false, std::memory_order_acq_rel);
  if (requested) {
    ++rumble_pulses_;
    rumble_until_ns_ = now + config_.rumble_ns;
  }
  const bool want = requested || (rumbling_ && now < rumble_until_ns_);
  if (want == rumbling_) return true;
  rumbling_ = want;
  const Rumble r = want ? Rumble::on : Rumble::off;
  // Reports the start-up builds from now on carry the same bit, so none of them stops
  // (or restarts) the motor by accident.
  startup_.set_rumble(r);
  return send(set_leds(config_.leds, r), now);
}

bool WiimoteDevice::request_sensitivity(std::string_view preset) {
  for (std::size_t i = 0; i < kSensitivityPresets.size(); ++i)
    if (kSensitivityPresets[i].name == preset) {
      sensitivity_request_.store(static_cast<int>(i), std::memory_order_release);
      return true;
    }
  return false;
}

bool WiimoteDevice::service_sensitivity(Nanos now) {
  const int index = sensitivity_request_.exchange(-1, std::memory_order_acq_rel);
  if (index < 0) return true;
  IrStartupConfig c = startup_.config();
  c.sensitivity = kSensitivityPresets[static_cast<std::size_t>(index)];
  // The whole start-up again (the Linux driver's order): the camera takes new blocks only
  // while it is not sending. The link stays up; IR reports resume with the new blocks.
  startup_ = IrStartup(c);
  if (link_ != LinkState::searching) {
    startup_.start(now);
    return flush_startup(now);
  }
  return true;
}

void WiimoteDevice::on_report(Nanos t, std::span<const std::uint8_t> report) {
  last_rx_ns_ = t;
  if (config_.keep_raw_reports) {
    RawReport raw;
    raw.t_ns = t;
    raw.size = static_cast<std::uint8_t>(std::min(report.size(), raw.bytes.size()));
    std::copy_n(report.begin(), raw.size, raw.bytes.begin());
    pending_raw_.push_back(raw);
  }
  // The start-up machine sees every report (acks, and 0x20, after which the remote sends
  // no data until the reporting mode is set again: it queues 0x12 for us to send).
  const int resets_before = startup_.mode_resets();
  startup_.feed(report, t);
  mode_resets_ += static_cast<std::uint64_t>(std::max(0, startup_.mode_resets() - resets_before));
  if (link_ == LinkState::starting && startup_.running()) {
    link_ = LinkState::running;
    backoff_ns_ = config_.reconnect_min_ns;  // a good connection: the next drop retries soon
    problem_.clear();
  }

  if (reports_.poll(t) == IrTrackerEvent::lost) push_sample({t, IrTrackerEvent::lost, false, {}});
  const ReportOutcome outcome = reports_.feed(t, report);
  if (outcome.kind != ReportOutcome::Kind::ir) return;
  if (outcome.update.point || outcome.update.event != IrTrackerEvent::none || config_.every_frame) {
    LedSample s;
    // The camera's whole frame (the sensitivity tuner's) only once it is taken with the blocks
    // last asked for: while a switch waits to be serviced, or its start-up runs, the remote
    // goes on reporting with the old blocks, and a tuner fed those frames judged the old
    // preset as the new one (seen in the VM test, whose start-ups take seconds).
    s.has_frame = outcome.frame.has_value() && startup_.running() &&
                  sensitivity_request_.load(std::memory_order_acquire) < 0;
    if (s.has_frame) s.frame = *outcome.frame;
    s.t_ns = t;
    s.event = outcome.update.event;
    s.has_point = outcome.update.point.has_value();
    if (s.has_point) s.point = *outcome.update.point;
    push_sample(s);
  }
}

void WiimoteDevice::push_sample(const LedSample& sample) { pending_.push_back(sample); }

void WiimoteDevice::publish(Nanos now) {
  WiimoteState s;
  s.link = link_;
  s.device = device_;
  s.problem = problem_;
  s.last_drop = last_drop_;
  s.startup = startup_.step();
  s.tracking = reports_.tracker().tracking();
  s.point = reports_.tracker().last_point();
  s.remote = reports_.stats();
  s.rumbling = rumbling_;
  s.now_ns = now;
  s.next_attempt_ns = next_attempt_ns_.value_or(now);
  s.backoff_ns = backoff_ns_;
  s.connects = connects_;
  s.disconnects = disconnects_;
  s.failed_attempts = failed_attempts_;
  s.mode_resets = mode_resets_;
  s.rumble_pulses = rumble_pulses_;

  if (sink_) {
    sink_(pending_, now);
    pending_.clear();
  }
  std::lock_guard lock(mutex_);
  for (const LedSample& sample : pending_) {
    if (samples_.size() < config_.queue_capacity) samples_.push_back(sample);
    else ++dropped_;
  }
  for (const RawReport& raw : pending_raw_) {
    if (raw_.size() < config_.queue_capacity) raw_.push_back(raw);
    else ++dropped_;
  }
  s.dropped = dropped_;
  state_ = std::move(s);
  pending_.clear();
  pending_raw_.clear();
}

// ---------------------------------------------------------------------------------------
// The consumer

WiimoteState WiimoteDevice::state() const {
  std::lock_guard lock(mutex_);
  return state_;
}

std::size_t WiimoteDevice::drain(std::vector<LedSample>& out) {
  out.clear();
  std::lock_guard lock(mutex_);
  out.swap(samples_);
  return out.size();
}

std::size_t WiimoteDevice::drain_raw(std::vector<RawReport>& out) {
  out.clear();
  std::lock_guard lock(mutex_);
  out.swap(raw_);
  return out.size();
}

}  // namespace mallet::input::wiimote
