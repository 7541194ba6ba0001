#pragma once
// A trajectory replayed through the core exactly as the kiosk feeds it: the impacts the
// contact solver finds, the hand's path, and — at any instant — where the mallet head is
// displayed (held on the surface, plus Eq. 1's visual vibration of the latest strike).
// `mallet simulate` writes these; `mallet render` draws them.
#include <vector>

#include "core/app_config.hpp"
#include "core/impact.hpp"
#include "core/mallet.hpp"
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

class Replay {
 public:
  //! Throws FileError naming `trajectory_name` when no sample is usable.
  Replay(const Scene& scene, const ContactConfig& contact, BounceMode bounce, const input::Trajectory& trajectory,
         InputSpace space, const std::string& trajectory_name);

  const std::vector<Impact>& impacts() const { return impacts_; }
  const std::vector<HandSample>& path() const { return path_; }
  const Mallet::Counters& counters() const { return mallet_.counters(); }
  //! Texture scenes: the cursor after the Speed technique at every accepted sample.
  const std::vector<TextureSample>& texture_path() const { return texture_path_; }

  //! The hand's straight-line path between accepted samples (the solver's model).
  Vec2 hand_at(Nanos t) const;
  //! The displayed head at t: the latest strike at or before t drives the bounce.
  CursorState cursor_at(Nanos t) const;

 private:
  const Scene* scene_;
  Mallet mallet_;
  BounceMode bounce_;
  std::vector<Impact> impacts_;
  std::vector<HandSample> path_;
  std::vector<TextureSample> texture_path_;
};

}  // namespace mallet::app
