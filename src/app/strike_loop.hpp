#pragma once
// The kiosk's heart, shared by the window and the headless run: hand positions in, the
// contact solver's impacts out, and at any instant the displayed mallet head (held on the
// surface, plus Eq. 1's visual vibration of the latest strike) — evaluated at the time
// the frame will be seen, on the int64 ns clock.
#include <optional>
#include <vector>

#include "core/app_config.hpp"
#include "core/attract_tune.hpp"
#include "core/mallet.hpp"
#include "core/scene.hpp"
#include "core/visual_vibration.hpp"

namespace mallet::app {

class StrikeLoop {
 public:
  StrikeLoop(const Scene& scene, const AppConfig& config);

  //! The hand (sphere centre, world metres) at t; the strike it made, if any.
  std::optional<Impact> feed(Nanos t, Vec2 hand);
  //! Forget the previous sample: the next one starts a new stroke (input source changed).
  void reset() { mallet_.reset(); }

  //! Where the head is drawn for a frame shown at `t_present`.
  Vec2 displayed(Nanos t_present) const;

  //! What a frame needs of the loop, as a value another thread may hold: where the head
  //! is held for a given hand (e.g. the 1€-filtered one), and the latest strike's bounce.
  struct View {
    Vec2 shown{0.0, 0.3};
    VisualVibration vibration;
    Vec2 displayed(Nanos t_present) const { return {shown.x, shown.y + vibration.offset_m(t_present)}; }
  };
  View view(Vec2 hand) const { return {mallet_.displayed_centre(hand), vibration_}; }
  const Mallet::Counters& counters() const { return mallet_.counters(); }

 private:
  const Scene& scene_;
  Mallet mallet_;
  VisualVibration vibration_;
  Vec2 hand_{0.0, 0.3};
};

//! The attract mode's ghost player, looping its phrase from `start` for as long as asked.
class AttractLoop {
 public:
  AttractLoop(const Scene& scene, Nanos start, double rate_hz = 250.0);
  //! The ghost hand's samples with start <= t <= until that were not returned before.
  std::vector<PointerSample> samples_until(Nanos until);

 private:
  const Scene& scene_;
  double rate_hz_;
  Nanos next_phrase_;
  std::vector<PointerSample> pending_;
  std::size_t next_ = 0;
};

}  // namespace mallet::app
