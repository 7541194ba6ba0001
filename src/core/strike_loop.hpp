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
#include "core/strike_detector.hpp"
#include "core/scene.hpp"
#include "core/texture_cursor.hpp"
#include "core/visual_vibration.hpp"

namespace mallet {

//! In a texture scene there is nothing to strike: the hand drives the Speed technique
//! and every sample yields a StripeMotion for the actuator's stripes. In a wall scene the
//! wall's material can be switched (operator) or cycled after every strike (attract).
class StrikeLoop {
 public:
  StrikeLoop(const Scene& scene, const AppConfig& config);

  //! The hand (sphere centre, world metres) at t; the strike it made, if any: seen by the
  //! swept solver, or predicted ([timing] predict_*; Impact::predicted, t_ns ahead of t).
  std::optional<Impact> feed(Nanos t, Vec2 hand);
  //! The texture scene's cursor motion from the last feed (for AudioEngine::post_motion).
  const std::optional<StripeMotion>& motion() const { return motion_; }
  //! A strike that did not come from the hand (a study stimulus): the bounce starts as
  //! for a real one.
  void show(const Impact& impact);
  //! Forget the previous sample: the next one starts a new stroke (input source changed).
  void reset();

  //! Where the head is drawn for a frame shown at `t_present`.
  Vec2 displayed(Nanos t_present) const;
  //! Eq. 1's visual displacement alone (metres along the normal) at `t_present`.
  double visual_offset_m(Nanos t_present) const { return vibration_.offset_m(t_present); }

  //! What a frame needs of the loop, as a value another thread may hold: where the head
  //! is held for a given hand (e.g. the 1€-filtered one), and the latest strike's bounce.
  struct View {
    Vec2 shown{0.0, 0.3};
    VisualVibration vibration;
    Vec2 displayed(Nanos t_present) const { return {shown.x, shown.y + vibration.offset_m(t_present)}; }
  };
  //! In a texture scene the head is the Speed technique's cursor (from the unfiltered hand).
  View view(Vec2 hand) const {
    return {texture_ ? texture_->cursor() : mallet_.displayed_centre(hand), vibration_};
  }
  //! The head where the latest hand sample puts it.
  View view() const { return view(hand_); }
  const Mallet::Counters& counters() const { return mallet_.counters(); }
  //! The Speed technique's gain of the last displacement (1 outside texture scenes).
  double gain() const { return texture_ ? texture_->gain() : 1.0; }

  //! The wall's material (index in Scene::materials), and switching it to the next of
  //! Scene::wall_materials; -1 / nothing in scenes without a wall.
  int wall_material() const;
  void next_wall_material();
  void set_wall_material(int material) {
    if (scene_.kind == SceneKind::wall) mallet_.set_material(0, material);
  }
  //! Attract mode: the wall's material moves on after every kTapsPerMaterial strikes (the
  //! ghost taps about twice a second: each material is felt and heard a few seconds, and its
  //! plaque stands still long enough to read, rather than flickering at every tap). Ending
  //! it puts back the material chosen before it began (the operator's M, or the scene's
  //! own): a visitor finds the wall the operator left, not wherever the attract mode stopped.
  static constexpr int kTapsPerMaterial = 8;
  void set_cycle_materials(bool on) {
    if (on && !cycle_materials_) {
      chosen_material_ = wall_material();
      cycle_taps_ = 0;
    }
    if (!on && cycle_materials_ && chosen_material_ >= 0) set_wall_material(chosen_material_);
    cycle_materials_ = on;
  }

 private:
  const Scene& scene_;
  StrikeDetector mallet_;
  VisualVibration vibration_;
  Vec2 hand_{0.0, 0.3};
  std::optional<TextureCursor> texture_;
  std::optional<StripeMotion> motion_;
  bool cycle_materials_ = false;
  int cycle_taps_ = 0;        //!< strikes on the current material while cycling
  int chosen_material_ = -1;  //!< the wall's material before the attract mode cycled it
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

}  // namespace mallet
