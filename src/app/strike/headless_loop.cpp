#include "app/strike/headless_loop.hpp"

#include <algorithm>
#include <cmath>

#include "core/sample_clock.hpp"

namespace mallet::app {
namespace {
constexpr Nanos kStep = 20'000'000;  // input and audio advance together in 20 ms steps
constexpr int kMaxBlock = 4096;

//! The simulated clock knows every sample at its own time, so every strike is known at its
//! contact: nothing to predict (and the compressed runs stay exact).
AppConfig offline(AppConfig config) {
  config.timing.predict.horizon_ms = 0;
  return config;
}
}  // namespace

HeadlessLoop::HeadlessLoop(const Scene& scene, const AppConfig& config, Nanos idle_after, bool acoustic_enabled)
    : scene_(scene),
      rate_(config.audio.sample_rate_hz),
      channels_(config.audio.routing.channels),
      idle_after_(idle_after),
      rig_(audio::make_audio_rig(scene, config, config.audio.sample_rate_hz, acoustic_enabled)),
      route_(scene, offline(config), rig_.engine.get(), nullptr, RouteOptions{audio::Producer::main, false, false}),
      last_visitor_(idle_after == kNoAttract ? 0 : -idle_after) {
  route_.on_strike = [this](const Strike& s) {
    ++(feeding_ghost_ ? counters_.ghost_strikes : counters_.visitor_strikes);
    if (on_strike) on_strike(s, feeding_ghost_);
  };
}

void HeadlessLoop::feed_ghost_until(Nanos t) {
  if (idle_after_ == kNoAttract) return;
  if (!ghost_ && t - last_visitor_ >= idle_after_) {
    const Nanos start = std::max(now_, last_visitor_ + idle_after_);
    ghost_.emplace(scene_, start);
    route_.reset();
    route_.loop().set_cycle_materials(true);
  }
  if (!ghost_) return;
  feeding_ghost_ = true;
  for (const PointerSample& s : ghost_->samples_until(t)) route_.feed(s.t_ns, {s.x, s.y});
  feeding_ghost_ = false;
}

std::optional<Strike> HeadlessLoop::visitor(Nanos t, Vec2 hand) {
  // Everything before this sample's segment is settled; its own strike (at or before t)
  // must be posted before the audio up to t is rendered.
  if (t - kStep > now_) advance(t - kStep);
  feed_ghost_until(t);
  if (ghost_) {  // a visitor takes over from the ghost within this sample
    ghost_.reset();
    route_.reset();
    route_.loop().set_cycle_materials(false);
  }
  last_visitor_ = t;
  std::optional<Strike> strike = route_.feed(t, hand);
  render_audio_until(t);
  now_ = std::max(now_, t);
  return strike;
}

Strike HeadlessLoop::present(const Impact& impact) {
  advance(impact.t_ns);  // the audio before the stimulus's block is settled; its own block is not
  return route_.present(impact, impact.t_ns);
}

void HeadlessLoop::advance(Nanos t) {
  while (now_ < t) {
    const Nanos next = std::min(t, now_ + kStep);
    feed_ghost_until(next);
    render_audio_until(next);
    now_ = next;
  }
}

void HeadlessLoop::drain_audio(Nanos t) {
  render_audio_until(t);
  now_ = std::max(now_, t);
}

void HeadlessLoop::render_audio_until(Nanos t) {
  const std::int64_t end = align_to_sample(t, rate_).index;
  while (audio_pos_ < end) {
    const int n = static_cast<int>(std::min<std::int64_t>(kMaxBlock, end - audio_pos_));
    block_.resize(static_cast<std::size_t>(n * channels_));
    rig_.engine->process(block_.data(), n);
    for (float v : block_) {
      if (!std::isfinite(v)) ++counters_.non_finite_samples;
      else counters_.peak = std::max(counters_.peak, static_cast<double>(std::fabs(v)));
    }
    if (on_audio) on_audio(block_);
    audio_pos_ += n;
    counters_.audio_frames += static_cast<std::uint64_t>(n);
  }
}

}  // namespace mallet::app
