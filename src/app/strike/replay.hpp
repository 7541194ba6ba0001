#pragma once
// A trajectory replayed through the core exactly as the kiosk feeds it: the impacts the
// contact solver finds, the hand's path, and — at any instant — where the mallet head is
// displayed (held on the surface, plus Eq. 1's visual vibration of the latest strike).
// `mallet simulate` writes these; `mallet render` draws them. The strikes come from the
// kiosk's one strike route (strike_route.hpp), detection only: nothing is posted or logged.
#include <memory>
#include <optional>
#include <vector>

#include "core/app_config.hpp"
#include "core/impact.hpp"
#include "app/strike/strike_route.hpp"
#include "core/mallet.hpp"
#include "core/present_clock.hpp"
#include "core/scene.hpp"
#include "core/visual_vibration.hpp"
#include "input/trajectory_csv.hpp"

namespace mallet::app {

enum class InputSpace { screen, world };

struct HandSample {
  Nanos t;
  Vec2 hand;
};

struct CursorState {
  Vec2 hand;     //!< where the hand is (world metres)
  Vec2 shown;    //!< the displayed head's centre, visual vibration included
  double offset; //!< Eq. 1 visual displacement along the normal (m)
  double gain = 1.0;  //!< texture scene: the Speed technique's gain over the current segment
};

//! The texture scene's cursor at one accepted sample.
struct TextureSample {
  Nanos t;
  Vec2 cursor;        //!< after the Speed technique
  double gain;        //!< of the segment ending here
  StripeMotion motion;
};

//! How the live kiosk would have known the trajectory (simulate --causal): each sample
//! only from its own time plus the input's delay, the frames paced by `picture`.
struct CausalTiming {
  Nanos input_delay_ns = 0;
  const PresentClock* picture = nullptr;  //!< must outlive the Replay's construction
};

class Replay {
 public:
  //! Throws FileError naming `trajectory_name` when no sample is usable. Without `causal`
  //! every strike counts as known at its contact (the stimuli, exact).
  Replay(const Scene& scene, const AppConfig& config, const input::Trajectory& trajectory, InputSpace space,
         const std::string& trajectory_name, std::optional<CausalTiming> causal = std::nullopt);

  const std::vector<Impact>& impacts() const { return impacts_; }
  //! The same strikes as the route delivered them: when decided, heard and shown.
  const std::vector<Strike>& strikes() const { return strikes_; }
  const std::vector<HandSample>& path() const { return path_; }
  const Mallet::Counters& counters() const { return counters_; }
  //! Texture scenes: the cursor after the Speed technique at every accepted sample.
  const std::vector<TextureSample>& texture_path() const { return texture_path_; }

  //! The hand's straight-line path between accepted samples (the solver's model).
  Vec2 hand_at(Nanos t) const;
  //! The displayed head at t: the latest strike at or before t drives the bounce.
  CursorState cursor_at(Nanos t) const;

 private:
  const Scene* scene_;
  BounceMode bounce_;
  Mallet held_;  //!< where the head is held on the surface (a pure function of the hand)
  Mallet::Counters counters_;
  std::vector<Impact> impacts_;
  std::vector<Strike> strikes_;
  std::vector<HandSample> path_;
  std::vector<TextureSample> texture_path_;
};

}  // namespace mallet::app
