#pragma once
// The strike route's one detector: the exact swept-contact solver (core/mallet.hpp) and
// contact prediction (core/contact_predictor.hpp) composed. Every caller that turns hand
// samples into strikes uses this class, so the kiosk, the headless run, replays and the
// benchmarks decide strikes the same way.
//
// Per accepted sample it returns at most one strike:
//  * the solver's, when the segment to this sample crossed a plane (as Mallet::update);
//  * otherwise, when the solver is armed and the predictor announces a crossing before
//    the next sample, a predicted strike: t_ns is the predicted contact time (in the
//    future), speed_m_per_s the predicted normal speed, predicted = true. The solver is
//    then disarmed for that zone (Mallet::disarm), so the real crossing that follows is
//    not a second note, and neither is a hand that stops just above the bar instead.
// With prediction off (horizon_ms = 0) it is Mallet, impact for impact, bit for bit.
#include <cstdint>
#include <optional>
#include <vector>

#include "core/contact_predictor.hpp"
#include "core/mallet.hpp"

namespace mallet {

class StrikeDetector {
 public:
  struct PredictionCounters {
    std::uint64_t predicted = 0;    //!< strikes decided from a prediction
    //! of those, the hand then really went below the plane of the zone predicted
    std::uint64_t confirmed = 0;
    //! of those, the hand re-armed (rose again), was reset, or touched another zone first:
    //! a note that should not have been played (or played on the wrong bar)
    std::uint64_t unconfirmed = 0;
    std::uint64_t clamped_speed = 0;  //!< predicted faster than max_impact_speed_m_per_s
  };

  StrikeDetector(const Scene& scene, ContactConfig contact, PredictionConfig prediction);

  //! Feeds the hand (sphere centre, world metres) at t: the strike decided now, if any.
  std::optional<Impact> update(Nanos t_ns, Vec2 hand);

  // What StrikeLoop needs of the solver, forwarded.
  Vec2 displayed_centre(Vec2 hand) const { return mallet_.displayed_centre(hand); }
  const std::vector<ContactZone>& zones() const { return mallet_.zones(); }
  const Mallet::Counters& counters() const { return mallet_.counters(); }
  bool armed() const { return mallet_.armed(); }
  void set_material(int target, int material) { mallet_.set_material(target, material); }
  int material_of(int target) const { return mallet_.material_of(target); }
  //! Forget the previous samples (tracking was lost, the source changed).
  void reset();

  const PredictionCounters& prediction_counters() const { return prediction_counters_; }
  const PredictionConfig& prediction() const { return predictor_.config(); }

 private:
  void confirm(Vec2 hand);

  ContactConfig contact_;
  Mallet mallet_;
  ContactPredictor predictor_;
  std::optional<std::size_t> pending_zone_;  //!< predicted, not yet confirmed or refuted
  PredictionCounters prediction_counters_;
};

}  // namespace mallet
