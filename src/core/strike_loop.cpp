#include "core/strike_loop.hpp"

#include <algorithm>

namespace mallet {

StrikeLoop::StrikeLoop(const Scene& scene, const AppConfig& config)
    : scene_(scene), mallet_(scene, config.contact, config.timing.predict), vibration_(config.bounce) {
  if (scene.texture) texture_.emplace(*scene.texture);
}

void StrikeLoop::reset() {
  mallet_.reset();
  if (texture_) texture_->reset();
}

std::optional<Impact> StrikeLoop::feed(Nanos t, Vec2 hand) {
  hand_ = hand;
  // The solver sees every sample, in a texture scene too (nothing to strike there): its
  // counters say which samples were usable.
  std::optional<Impact> impact = mallet_.update(t, hand);
  if (texture_) {
    motion_ = texture_->update(t, hand);
    return std::nullopt;
  }
  // A bar only the program strikes: the hand rests on it, as after a touch.
  if (impact && !scene_.targets.at(static_cast<std::size_t>(impact->target)).hand_strikes) impact.reset();
  if (impact) {
    show(*impact);
    if (cycle_materials_ && ++cycle_taps_ == kTapsPerMaterial) {
      cycle_taps_ = 0;
      next_wall_material();
    }
  }
  return impact;
}

void StrikeLoop::show(const Impact& impact) {
  vibration_.start(impact, scene_.materials.at(static_cast<std::size_t>(impact.material)).visual);
}

int StrikeLoop::wall_material() const {
  return scene_.kind == SceneKind::wall && !scene_.targets.empty() ? mallet_.material_of(0) : -1;
}

void StrikeLoop::next_wall_material() {
  const std::vector<int>& list = scene_.wall_materials;
  if (scene_.kind != SceneKind::wall || list.empty()) return;
  const auto it = std::find(list.begin(), list.end(), mallet_.material_of(0));
  const std::size_t next = it == list.end() ? 0 : static_cast<std::size_t>(it - list.begin() + 1) % list.size();
  mallet_.set_material(0, list[next]);
}

Vec2 StrikeLoop::displayed(Nanos t_present) const {
  if (texture_) return texture_->cursor();
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
    if (scene_.kind == SceneKind::texture) {
      pending_ = attract_sweep(scene_, next_phrase_, rate_hz_);
      next_ = 0;
      next_phrase_ += attract_sweep_period(scene_);
      if (pending_.empty()) return out;
      continue;
    }
    const AttractTune tune;
    const std::vector<ScriptedStrike> strikes =
        attract_phrase(scene_, next_phrase_ + static_cast<Nanos>(tune.beat_s * 1e9), tune);
    pending_ = strikes.empty() ? std::vector<PointerSample>{} : ghost_player(scene_, strikes, rate_hz_).samples;
    next_ = 0;
    next_phrase_ += attract_period(scene_, tune);
    if (pending_.empty()) return out;
  }
}

}  // namespace mallet
