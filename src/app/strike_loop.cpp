#include "app/strike_loop.hpp"

namespace mallet::app {

StrikeLoop::StrikeLoop(const Scene& scene, const AppConfig& config)
    : scene_(scene), mallet_(scene, config.contact), vibration_(config.bounce) {}

std::optional<Impact> StrikeLoop::feed(Nanos t, Vec2 hand) {
  hand_ = hand;
  std::optional<Impact> impact = mallet_.update(t, hand);
  if (impact) show(*impact);
  return impact;
}

void StrikeLoop::show(const Impact& impact) {
  vibration_.start(impact, scene_.materials.at(static_cast<std::size_t>(impact.material)).visual);
}

Vec2 StrikeLoop::displayed(Nanos t_present) const {
  const Vec2 shown = mallet_.displayed_centre(hand_);
  return {shown.x, shown.y + vibration_.offset_m(t_present)};
}

AttractLoop::AttractLoop(const Scene& scene, Nanos start, double rate_hz)
    : scene_(scene), rate_hz_(rate_hz), next_phrase_(start) {}

std::vector<PointerSample> AttractLoop::samples_until(Nanos until) {
  std::vector<PointerSample> out;
  for (;;) {
    while (next_ < pending_.size() && pending_[next_].t_ns <= until) out.push_back(pending_[next_++]);
    if (next_ < pending_.size() || next_phrase_ > until) return out;
    // The next phrase: its first strike one beat after the phrase starts, so the ghost
    // hand has time to come down from where the last phrase left it.
    const AttractTune tune;
    const std::vector<ScriptedStrike> strikes =
        attract_phrase(scene_, next_phrase_ + static_cast<Nanos>(tune.beat_s * 1e9), tune);
    pending_ = strikes.empty() ? std::vector<PointerSample>{} : ghost_player(scene_, strikes, rate_hz_).samples;
    next_ = 0;
    next_phrase_ += attract_period(scene_, tune);
    if (pending_.empty()) return out;
  }
}

}  // namespace mallet::app
