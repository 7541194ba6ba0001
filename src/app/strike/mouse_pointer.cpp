#include "app/strike/mouse_pointer.hpp"

#include "core/time.hpp"

namespace mallet::app {

MousePointer::MousePointer(const Scene& scene, const AppConfig& config, audio::AudioEngine& engine,
                           const PresentClock* picture, const ViewAspect* aspect)
    : scene_(scene),
      aspect_(aspect),
      route_(scene, config, &engine, picture, RouteOptions{audio::Producer::input, false, true}) {
  pending_.reserve(1024);
  route_.on_strike = [this](const Strike& s) {
    if (on_strike) on_strike(s);
  };
}

void MousePointer::on_samples(std::span<const PointerSample> samples) {
  const Nanos known = monotonic_now();
  const bool playing = playing_.load(std::memory_order_acquire);
  if (playing && !was_playing_) route_.reset();  // Play (re)started: a new stroke
  was_playing_ = playing;
  const ScreenToWorld view = framed(scene_.screen_to_world, aspect_);
  for (const PointerSample& s : samples)
    if (playing) route_.feed(s.t_ns, view.map(s.x, s.y), known);
  std::lock_guard lock(mutex_);
  for (const PointerSample& s : samples) {
    if (pending_.size() >= kMaxPending) pending_.erase(pending_.begin());
    pending_.push_back(s);
  }
}

void MousePointer::set_playing(bool playing) { playing_.store(playing, std::memory_order_release); }

std::vector<PointerSample> MousePointer::take() {
  std::vector<PointerSample> out;
  out.reserve(1024);
  std::lock_guard lock(mutex_);
  out.swap(pending_);
  return out;
}

}  // namespace mallet::app
