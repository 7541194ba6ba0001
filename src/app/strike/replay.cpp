#include "app/strike/replay.hpp"

#include <algorithm>

#include "core/file_error.hpp"
#include "core/texture_cursor.hpp"

namespace mallet::app {

Replay::Replay(const Scene& scene, const AppConfig& config, const input::Trajectory& trajectory, InputSpace space,
               const std::string& trajectory_name, std::optional<CausalTiming> causal)
    : scene_(&scene), bounce_(config.bounce), held_(scene, config.contact) {
  // Offline, every strike is known at its contact: nothing to predict, nothing to wait for.
  AppConfig c = config;
  if (!causal) {
    c.timing.align = CueAlign::asap;
    c.timing.predict.horizon_ms = 0;
  }
  StrikeRoute route(scene, c, nullptr, causal ? causal->picture : nullptr,
                    RouteOptions{audio::Producer::main, false, false});
  route.on_strike = [this](const Strike& s) {
    strikes_.push_back(s);
    impacts_.push_back(s.impact);
  };
  for (const PointerSample& s : trajectory.samples) {
    const Vec2 hand = space == InputSpace::screen ? scene.screen_to_world.map(s.x, s.y) : Vec2{s.x, s.y};
    const auto accepted_before = route.loop().counters().accepted;
    if (causal) route.feed(s.t_ns, hand, s.t_ns + causal->input_delay_ns);
    else route.feed(s.t_ns, hand);
    if (route.loop().counters().accepted != accepted_before) path_.push_back({s.t_ns, hand});
  }
  counters_ = route.loop().counters();
  if (path_.empty()) throw FileError(trajectory_name, 0, 0, "no usable sample (every position is nan or inf)");
  if (scene.texture) {
    TextureCursor cursor(*scene.texture);
    for (const HandSample& h : path_) {
      const StripeMotion m = cursor.update(h.t, h.hand);
      texture_path_.push_back({h.t, cursor.cursor(), cursor.gain(), m});
    }
  }
}

Vec2 Replay::hand_at(Nanos t) const {
  if (t <= path_.front().t) return path_.front().hand;
  if (t >= path_.back().t) return path_.back().hand;
  const auto it = std::upper_bound(path_.begin(), path_.end(), t,
                                   [](Nanos v, const HandSample& s) { return v < s.t; });
  const HandSample& b = *it;
  const HandSample& a = *(it - 1);
  const double s = static_cast<double>(t - a.t) / static_cast<double>(b.t - a.t);
  return lerp(a.hand, b.hand, s);
}

CursorState Replay::cursor_at(Nanos t) const {
  if (!texture_path_.empty()) {  // the cursor on the straight line between two samples
    const std::vector<TextureSample>& p = texture_path_;
    const Vec2 hand = hand_at(t);
    if (t <= p.front().t) return {hand, p.front().cursor, 0.0, 1.0};
    if (t >= p.back().t) return {hand, p.back().cursor, 0.0, 1.0};
    const auto it = std::upper_bound(p.begin(), p.end(), t, [](Nanos v, const TextureSample& s) { return v < s.t; });
    const TextureSample& b = *it;
    const TextureSample& a = *(it - 1);
    const double s = static_cast<double>(t - a.t) / static_cast<double>(b.t - a.t);
    return {hand, lerp(a.cursor, b.cursor, s), 0.0, b.gain};
  }
  VisualVibration vibration(bounce_);
  const auto after = std::upper_bound(impacts_.begin(), impacts_.end(), t,
                                      [](Nanos v, const Impact& i) { return v < i.t_ns; });
  if (after != impacts_.begin()) {
    const Impact& latest = *(after - 1);
    vibration.start(latest, scene_->materials[latest.material].visual);
  }
  const Vec2 hand = hand_at(t);
  const Vec2 shown = held_.displayed_centre(hand);
  const double offset = vibration.offset_m(t);
  return {hand, {shown.x, shown.y + offset}, offset};
}

}  // namespace mallet::app
