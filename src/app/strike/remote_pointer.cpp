#include "app/strike/remote_pointer.hpp"

#include <algorithm>
#include <cmath>

#include "core/ir_camera_settings.hpp"

namespace mallet::app {

std::string kiosk_sensitivity(const AppConfig& config, const std::optional<Calibration>& calibration) {
  return calibration && !calibration->ir_sensitivity.empty() ? calibration->ir_sensitivity
                                                             : config.wiimote.sensitivity;
}

input::wiimote::WiimoteDeviceConfig kiosk_device_config(const AppConfig& config,
                                                        const std::optional<Calibration>& calibration) {
  input::wiimote::WiimoteDeviceConfig dc = input::wiimote::device_config(config);
  if (const auto preset = find_sensitivity(kiosk_sensitivity(config, calibration))) dc.ir.sensitivity = *preset;
  return dc;
}

RemotePointer::RemotePointer(const Scene& scene, const AppConfig& config, audio::AudioEngine& engine,
                             const PresentClock* picture, const ViewAspect* aspect)
    : scene_(scene),
      aspect_(aspect),
      route_(scene, config, &engine, picture, RouteOptions{audio::Producer::input, true, true}) {
  pending_.reserve(256);
  route_.on_strike = [this](const Strike& s) {
    if (on_strike) on_strike(s.impact);
  };
}

void RemotePointer::feed_point(Nanos t, Nanos now, Vec2 camera, RemoteSample& out) {
  std::optional<Homography> h;
  {
    std::lock_guard lock(mutex_);
    h = camera_to_screen_;
  }
  if (!h) return;
  const std::optional<Vec2> screen = h->try_map(camera);
  if (!screen || !std::isfinite(screen->x) || !std::isfinite(screen->y)) return;  // off the map: no position
  out.screen = screen;
  const Vec2 hand = framed(scene_.screen_to_world, aspect_).map(screen->x, screen->y);
  const bool playing = playing_.load(std::memory_order_acquire);
  const std::uint64_t generation = generation_.load(std::memory_order_acquire);
  if (generation != seen_generation_) {  // Play (re)started, or a new calibration: a new stroke
    seen_generation_ = generation;
    route_.reset();
  }
  if (playing) route_.feed(t, hand, now);
}

void RemotePointer::on_samples(std::span<const input::wiimote::LedSample> samples, Nanos now) {
  for (const input::wiimote::LedSample& s : samples) {
    RemoteSample out;
    out.t_ns = s.t_ns;
    out.event = s.event;
    if (s.has_frame) out.frame = s.frame;
    if (s.event == IrTrackerEvent::lost || s.event == IrTrackerEvent::jumped) {
      // The next dot starts a new stroke: no swept contact across the gap or the jump.
      route_.reset();
    }
    if (s.has_point) {
      out.camera_px = Vec2{s.point.x, s.point.y};
      feed_point(s.t_ns, std::max(now, s.t_ns), *out.camera_px, out);
    }
    std::lock_guard lock(mutex_);
    if (s.event == IrTrackerEvent::lost) tracking_ = false;
    else if (s.has_point) tracking_ = true;
    if (pending_.size() >= kMaxPending) {
      pending_.erase(pending_.begin());
      ++dropped_;
    }
    pending_.push_back(out);
  }
}

void RemotePointer::set_calibration(std::optional<Calibration> calibration) {
  {
    std::lock_guard lock(mutex_);
    camera_to_screen_ = calibration ? std::optional<Homography>(calibration->camera_to_screen) : std::nullopt;
  }
  generation_.fetch_add(1, std::memory_order_acq_rel);
}

void RemotePointer::set_playing(bool playing) {
  if (playing_.exchange(playing, std::memory_order_acq_rel) != playing && playing)
    generation_.fetch_add(1, std::memory_order_acq_rel);
}

std::vector<RemoteSample> RemotePointer::take() {
  std::vector<RemoteSample> out;
  out.reserve(256);
  std::lock_guard lock(mutex_);
  out.swap(pending_);
  return out;
}

StrikeLoop::View RemotePointer::view() const { return route_.view(); }

bool RemotePointer::tracking() const {
  std::lock_guard lock(mutex_);
  return tracking_;
}

std::uint64_t RemotePointer::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

}  // namespace mallet::app
