#include "app/strike/strike_route.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/journal.hpp"
#include "core/strike_line.hpp"

namespace mallet::app {

StrikeRoute::StrikeRoute(const Scene& scene, const AppConfig& config, audio::AudioEngine* engine,
                         const PresentClock* picture, RouteOptions options)
    : scene_(scene),
      engine_(engine),
      picture_(picture ? picture : &fallback_picture_),
      options_(options),
      timing_(config.timing),
      ahead_ns_(static_cast<Nanos>(std::llround(config.audio.schedule_ahead_ms * 1e6))),
      loop_(scene, config),
      filter_(config.pointer) {}

void StrikeRoute::reset() {
  loop_.reset();
  filter_.reset();
}

Strike StrikeRoute::deliver(const Impact& impact, Nanos known, bool stimulus) {
  Strike s;
  s.impact = impact;
  s.decided_ns = known;
  s.stimulus = stimulus;
  // The bounce is evaluated from the contact, so the first frame that shows it is the first
  // one recorded after the strike is known and presented no earlier than the contact.
  s.shown_ns = picture_->first_shown(known, impact.t_ns);
  const Nanos display = static_cast<Nanos>(std::llround(timing_.display_latency_ms * 1e6));
  // heard_ns + schedule_ahead is when the sound leaves the speaker; never before it is known.
  const Nanos wanted = timing_.align == CueAlign::picture ? s.shown_ns + display - ahead_ns_ : impact.t_ns;
  s.heard_ns = std::max(wanted, known - ahead_ns_);
  s.impact.delay_ns = s.heard_ns - impact.t_ns;
  if (engine_) engine_->post(s.impact, options_.producer);
  strikes_.fetch_add(1, std::memory_order_relaxed);
  if (options_.log) journal::info("{}", strike_line(scene_, s.impact).c_str());
  if (on_strike) on_strike(s);
  return s;
}

std::optional<Strike> StrikeRoute::feed(Nanos t, Vec2 hand, std::optional<Nanos> known) {
  if (const int m = wall_material_.exchange(-1, std::memory_order_acq_rel); m >= 0) loop_.set_wall_material(m);
  std::optional<Strike> out;
  if (const std::optional<Impact> impact = loop_.feed(t, hand))
    out = deliver(*impact, known ? std::max(*known, t) : impact->t_ns, false);
  if (engine_ && loop_.motion()) engine_->post_motion(*loop_.motion(), options_.producer);
  publish(t, hand);
  return out;
}

Strike StrikeRoute::present(const Impact& impact, Nanos known) {
  loop_.show(impact);
  const Strike s = deliver(impact, known, true);
  std::lock_guard lock(view_mutex_);
  view_.vibration = loop_.view(view_.shown).vibration;
  return s;
}

void StrikeRoute::publish(Nanos t, Vec2 hand) {
  const Vec2 shown = options_.smooth_view ? filter_.update(t, hand).value_or(hand) : hand;
  const StrikeLoop::View v = loop_.view(shown);
  std::lock_guard lock(view_mutex_);
  view_ = v;
}

StrikeLoop::View StrikeRoute::view() const {
  std::lock_guard lock(view_mutex_);
  return view_;
}

}  // namespace mallet::app
