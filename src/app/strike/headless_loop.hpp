#pragma once
// The kiosk's loop on a simulated clock, without a window: a visitor's samples (replayed)
// or, when nobody has played for `idle_after`, the attract mode's ghost player; the
// contact solver; the audio engine rendering into a sink. The headless `mallet run` and the
// soak test drive it; time only moves when they say so, so a day of play can be compressed.
//
// Order of work: input is always fed up to a time before the audio up to that time is
// rendered, so every impact is posted before the block it falls in and starts on its own
// sample. Strikes go through the kiosk's one strike route (strike_route.hpp).
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>

#include "audio/audio_setup.hpp"
#include "core/strike_loop.hpp"
#include "app/strike/strike_route.hpp"
#include "core/app_config.hpp"
#include "core/scene.hpp"

namespace mallet::app {

class HeadlessLoop {
 public:
  struct Counters {
    std::uint64_t visitor_strikes = 0, ghost_strikes = 0;
    std::uint64_t audio_frames = 0;
    std::uint64_t non_finite_samples = 0;
    double peak = 0;                        //!< largest |sample| rendered
  };

  //! `idle_after` = kNoAttract: the ghost never plays (study mode).
  static constexpr Nanos kNoAttract = std::numeric_limits<Nanos>::max();
  //! `acoustic_enabled` false: the speaker channel stays silent.
  HeadlessLoop(const Scene& scene, const AppConfig& config, Nanos idle_after, bool acoustic_enabled = true);

  //! A visitor's hand (sphere centre, world metres) at t >= now(): takes over from the
  //! ghost at once. The strike it made, if any.
  std::optional<Strike> visitor(Nanos t, Vec2 hand);
  //! A strike made by the program, not the hand (a study stimulus) at impact.t_ns >= now():
  //! the audio up to it is rendered first, then both channels and the bounce start as for a
  //! visitor's strike.
  //! A program-made strike (a study's stimulus) through the route: when it is heard and shown.
  Strike present(const Impact& impact);
  //! Moves the clock to t: the ghost plays if idle, and the audio is rendered up to t.
  void advance(Nanos t);
  //! Renders audio up to t with no input at all (the tail after the last stroke).
  void drain_audio(Nanos t);

  Nanos now() const { return now_; }
  bool attract() const { return ghost_.has_value(); }
  Vec2 displayed(Nanos t_present) const { return route_.loop().displayed(t_present); }
  const StrikeLoop& strike_loop() const { return route_.loop(); }
  double visual_offset_m(Nanos t_present) const { return route_.loop().visual_offset_m(t_present); }
  const Counters& counters() const { return counters_; }
  const audio::AudioEngine& engine() const { return *rig_.engine; }
  //! The actuator calibration the engine applies, if any.
  const std::optional<ActuatorEq>& actuator_eq() const { return rig_.actuator_eq; }
  int sample_rate_hz() const { return rate_; }
  int channels() const { return channels_; }

  //! Each strike as the route delivered it (`ghost`: the attract mode's).
  std::function<void(const Strike&, bool ghost)> on_strike;
  std::function<void(std::span<const float>)> on_audio;  //!< interleaved frames

 private:
  void feed_ghost_until(Nanos t);
  void render_audio_until(Nanos t);

  const Scene& scene_;
  int rate_, channels_;
  Nanos idle_after_;
  audio::AudioRig rig_;
  StrikeRoute route_;
  std::optional<AttractLoop> ghost_;
  bool feeding_ghost_ = false;
  Nanos now_ = 0;
  Nanos last_visitor_;
  std::int64_t audio_pos_ = 0;
  std::vector<float> block_;
  Counters counters_;
};

}  // namespace mallet::app
