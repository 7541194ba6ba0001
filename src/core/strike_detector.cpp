#include "core/strike_detector.hpp"

namespace mallet {

StrikeDetector::StrikeDetector(const Scene& scene, ContactConfig contact, PredictionConfig prediction)
    : contact_(contact), mallet_(scene, contact), predictor_(prediction) {}

void StrikeDetector::reset() {
  mallet_.reset();
  predictor_.reset();
  if (pending_zone_) ++prediction_counters_.unconfirmed;
  pending_zone_.reset();
}

void StrikeDetector::confirm(Vec2 hand) {
  if (!pending_zone_) return;
  const ContactZone& predicted = mallet_.zones()[*pending_zone_];
  const ContactZone* under = mallet_.zone_at(hand);
  if (under && under->holds(hand)) {
    ++(under == &predicted ? prediction_counters_.confirmed : prediction_counters_.unconfirmed);
    pending_zone_.reset();
  } else if (mallet_.armed()) {
    ++prediction_counters_.unconfirmed;
    pending_zone_.reset();
  }
}

std::optional<Impact> StrikeDetector::update(Nanos t_ns, Vec2 hand) {
  const std::uint64_t accepted_before = mallet_.counters().accepted;
  std::optional<Impact> impact = mallet_.update(t_ns, hand);
  if (!(predictor_.config().horizon_ms > 0) || mallet_.counters().accepted == accepted_before) return impact;
  predictor_.add(t_ns, hand);
  confirm(hand);
  if (impact || !mallet_.armed()) return impact;

  const std::optional<PredictedContact> p = predictor_.predict(mallet_.zones());
  if (!p || p->speed_m_per_s < contact_.min_impact_speed_m_per_s) return std::nullopt;
  const ContactZone& zone = mallet_.zones()[p->zone];
  double speed = p->speed_m_per_s;
  if (speed > contact_.max_impact_speed_m_per_s) {
    speed = contact_.max_impact_speed_m_per_s;
    ++prediction_counters_.clamped_speed;
  }
  Impact out = mallet_.impact_on(zone, p->t_ns, speed, p->x_m);
  out.predicted = true;
  mallet_.disarm(zone, hand.y);
  pending_zone_ = p->zone;
  ++prediction_counters_.predicted;
  return out;
}

}  // namespace mallet
