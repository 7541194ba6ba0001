#include "input/camera/camera_device.hpp"

#include <array>

#include <fmt/format.h>

namespace mallet::input::camera {

std::string mode_text(const CameraMode& mode) {
  return fmt::format("{}x{} {} at {}", mode.width, mode.height, name_in(kPixelFormatNames, mode.format),
                     mode.rate_hz > 0 ? fmt::format("{:.4g} Hz", mode.rate_hz) : std::string("? Hz"));
}

CameraDeviceConfig camera_device_config(const AppConfig& config) {
  CameraDeviceConfig c;
  c.lost_after_ms = config.tracking.lost_after_ms;
  return c;
}

CameraDevice::CameraDevice(std::unique_ptr<FrameGrabber> grabber, Clock& clock, CameraDeviceConfig config)
    : grabber_(std::move(grabber)), clock_(clock), config_(config), tracker_(config.finder, config.lost_after_ms) {
  status_.problem = "not opened yet";
}

CameraDevice::~CameraDevice() { stop(); }

void CameraDevice::start() {
  if (thread_.joinable()) return;
  stop_.store(false);
  thread_ = std::thread([this] { run(); });
}

void CameraDevice::stop() {
  stop_.store(true);
  grabber_->wake();
  if (thread_.joinable()) thread_.join();
}

CameraStatus CameraDevice::status() const {
  std::lock_guard lock(mutex_);
  return status_;
}

std::string CameraDevice::describe() const {
  const CameraStatus s = status();
  if (s.mode.device.empty()) return "camera: " + s.problem;
  return fmt::format("camera {} ({}, {}) {}", s.mode.device, s.mode.name, s.mode.driver, mode_text(s.mode));
}

void CameraDevice::publish(bool connected, const std::string& problem) {
  const Nanos now = clock_.now();
  std::lock_guard lock(mutex_);
  status_.connected = connected;
  if (!problem.empty() || connected) status_.problem = problem;
  status_.rate_hz = rate_.rate_hz(now);
  status_.led_seen = tracker_.tracking();
  status_.led = tracker_.last_point();
  if (const LedBlob* b = tracker_.last_blob()) status_.led_area_px = b->area_px;
  status_.counters = tracker_.counters();
  status_.last_bad_frame = tracker_.bad_frame();
  if (status_.mode.stamping.empty()) status_.mode.stamping = grabber_->stamping();
  status_.reconnects = reconnects_;
  status_.losses = losses_;
  status_.last_loss = last_loss_;
}

bool CameraDevice::connect() {
  const Result<CameraMode, std::string> mode = grabber_->open();
  if (!mode) {
    publish(false, mode.error());
    return false;
  }
  if (ever_connected_) ++reconnects_;
  ever_connected_ = true;
  tracker_.restart();
  rate_.clear();
  {
    std::lock_guard lock(mutex_);
    status_.mode = *mode;
  }
  publish(true, "");
  return true;
}

void CameraDevice::run() {
  bool open = false;
  Nanos next_attempt = 0;
  CameraFrame frame;
  std::array<wiimote::LedSample, 1> one;
  Nanos last_publish = 0;
  while (!stop_.load()) {
    if (!open) {
      if (clock_.now() >= next_attempt) {
        open = connect();
        next_attempt = clock_.now() + config_.reopen_interval_ns;
      }
      if (!open) {
        const Nanos wait = std::min<Nanos>(next_attempt - clock_.now(), Nanos(config_.wait_ms) * 1'000'000);
        clock_.sleep_for(wait);
        continue;
      }
    }
    const Result<bool, GrabError> got = grabber_->next(config_.wait_ms, frame);
    std::optional<wiimote::LedSample> sample;
    if (!got) {
      grabber_->close();
      open = false;
      // Gone or failing: either way the next open waits, so a camera that opens and then
      // fails at once is not reopened in a busy loop.
      next_attempt = clock_.now() + config_.reopen_interval_ns;
      sample = tracker_.lose(clock_.now());
      ++losses_;
      last_loss_ = got.error().message;
      publish(false, got.error().message);
    } else if (*got) {
      rate_.add(frame.t_ns);
      sample = tracker_.on_frame(frame);
    } else {
      sample = tracker_.poll(clock_.now());
    }
    if (sample && sink_) {
      one[0] = *sample;
      sink_(one, clock_.now());
    }
    const Nanos now = clock_.now();
    if (open && now - last_publish >= 50'000'000) {  // the status, 20 times a second
      publish(true, "");
      last_publish = now;
    }
  }
  grabber_->close();
  publish(false, open ? "stopped" : "");  // never opened: why stays the last open's
}

}  // namespace mallet::input::camera
