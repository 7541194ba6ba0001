#include "core/kiosk_states.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/visitor_language.hpp"

namespace mallet {

namespace {

bool positive_seconds(double s) { return std::isfinite(s) && s > 0 && from_seconds(s).has_value(); }

}  // namespace

Check validate(const KioskStatesConfig& c) {
  if (!positive_seconds(c.idle_after_s)) return refused("idle_after_s must be a finite number of seconds > 0");
  if (!std::isfinite(c.dead_band_screen_units) || c.dead_band_screen_units < 0)
    return refused("dead_band_screen_units must be a finite number >= 0");
  if (!std::isfinite(c.lost_hint_after_s) || c.lost_hint_after_s < 0 || !from_seconds(c.lost_hint_after_s))
    return refused("lost_hint_after_s must be a finite number of seconds >= 0");
  if (!positive_seconds(c.close_notice_s)) return refused("close_notice_s must be a finite number of seconds > 0");
  if (!positive_seconds(c.operator_page_timeout_s))
    return refused("operator_page_timeout_s must be a finite number of seconds > 0");
  if (!positive_seconds(c.quit_confirm_s)) return refused("quit_confirm_s must be a finite number of seconds > 0");
  return {};
}

const char* to_string(KioskState state) { return name_in(kKioskStateNames, state); }

std::string_view hint_text(KioskHint hint, SceneKind scene, bool mouse) {
  switch (hint) {
    case KioskHint::none: return "";
    case KioskHint::invitation:
      if (mouse)  // no mallet to pick up: the mouse moves it, and a click does nothing
        return scene == SceneKind::texture ? tr("Move the mouse over the disc")
               : scene == SceneKind::wall  ? tr("Move the mouse onto the wall to tap it")
                                           : tr("Move the mouse down onto a bar to strike it");
      return scene == SceneKind::texture ? tr("Pick up the mallet and move it over the disc")
             : scene == SceneKind::wall  ? tr("Pick up the mallet and tap the wall")
                                         : tr("Pick up the mallet and strike a bar");
    case KioskHint::point_at_screen: return tr("Point the mallet at the screen");
    case KioskHint::close_needs_chord: return tr("This kiosk closes from the operator page only");
    // The attract mode's ghost mallet plays on meanwhile: the words say what a visitor can
    // do, not that a mallet is resting while one moves on the screen.
    case KioskHint::remote_missing: return tr("To play, please ask a member of staff");
  }
  return "";
}

KioskStates::KioskStates(KioskStatesConfig config, Nanos now_ns) : config_(config) {
  if (const Check problem = validate(config_); !problem) throw std::invalid_argument(problem.error());
  idle_after_ns_ = *from_seconds(config_.idle_after_s);
  lost_hint_ns_ = *from_seconds(config_.lost_hint_after_s);
  close_notice_ns_ = *from_seconds(config_.close_notice_s);
  page_timeout_ns_ = *from_seconds(config_.operator_page_timeout_s);
  quit_confirm_ns_ = *from_seconds(config_.quit_confirm_s);
  since_ = now_ = last_movement_ = lost_since_ = now_ns;
}

Nanos KioskStates::advance(Nanos t_ns) {
  now_ = std::max(now_, t_ns);
  if (state_ == KioskState::play && now_ - last_movement_ >= idle_after_ns_) enter(KioskState::attract, now_);
  if (close_refused_ && now_ - close_refused_at_ >= close_notice_ns_) close_refused_ = false;
  if (quit_asked_ && now_ - quit_asked_at_ >= quit_confirm_ns_) quit_asked_ = false;
  if (state_ == KioskState::operator_page && now_ - page_key_at_ >= page_timeout_ns_) {
    // Nobody at the page: back to the visitors (or to the calibration it remembered).
    ++page_timeouts_;
    quit_asked_ = false;
    const bool calibrate = calibration_pending_ && source_ != InputSource::mouse;
    calibration_pending_ = false;
    calibration_from_operator_ = false;
    enter(calibrate ? KioskState::calibration : KioskState::attract, now_);
  }
  return now_;
}

bool KioskStates::enter(KioskState next, Nanos t_ns) {
  if (next == state_) return false;
  state_ = next;
  since_ = t_ns;
  return true;
}

void KioskStates::play_from(Nanos t_ns) {
  last_movement_ = t_ns;
  enter(KioskState::play, t_ns);
}

bool KioskStates::tick(Nanos now_ns) {
  const KioskState before = state_;
  advance(now_ns);
  return state_ != before;
}

bool KioskStates::pointer(Nanos t_ns, Vec2 screen) {
  const KioskState before = state_;
  const Nanos t = advance(t_ns);
  if (!std::isfinite(screen.x) || !std::isfinite(screen.y)) return state_ != before;
  if (!tracking_) tracking_ = true;  // a sample is the dot, seen
  const bool real = !have_anchor_ || std::hypot(screen.x - anchor_.x, screen.y - anchor_.y) > config_.dead_band_screen_units;
  if (!real) return state_ != before;
  // The very first sample only sets where the stick rests: it is no movement yet.
  const bool first = !have_anchor_;
  have_anchor_ = true;
  anchor_ = screen;
  if (first) return state_ != before;
  if (state_ == KioskState::attract || state_ == KioskState::play) play_from(t);
  return state_ != before;
}

void KioskStates::pointer_rests(Vec2 screen) {
  if (!std::isfinite(screen.x) || !std::isfinite(screen.y)) return;
  have_anchor_ = true;
  anchor_ = screen;
}

bool KioskStates::tracking_lost(Nanos t_ns) {
  const KioskState before = state_;
  const Nanos t = advance(t_ns);
  if (source_ != InputSource::mouse && tracking_) {
    tracking_ = false;
    lost_since_ = t;
  }
  return state_ != before;
}

bool KioskStates::tracking_regained(Nanos t_ns) {
  const KioskState before = state_;
  advance(t_ns);
  tracking_ = true;
  return state_ != before;
}

bool KioskStates::input_source(Nanos t_ns, InputSource source) {
  const KioskState before = state_;
  const Nanos t = advance(t_ns);
  if (source != source_) {
    source_ = source;
    have_anchor_ = false;  // another device's coordinates say nothing about this one's rest
    tracking_ = source == InputSource::mouse;
    lost_since_ = t;
  }
  return state_ != before;
}

bool KioskStates::remote_connected(Nanos t_ns, bool connected) {
  const KioskState before = state_;
  const Nanos t = advance(t_ns);
  remote_connected_ = connected;
  if (!connected && live_ir_tracker(source_)) {
    if (tracking_) {
      tracking_ = false;
      lost_since_ = t;
    }
    if (state_ == KioskState::play) enter(KioskState::attract, t);
  }
  return state_ != before;
}

bool KioskStates::operator_chord(Nanos t_ns) {
  const Nanos t = advance(t_ns);
  if (state_ == KioskState::operator_page) return false;
  page_key_at_ = t;
  quit_asked_ = false;
  return enter(KioskState::operator_page, t);
}

bool KioskStates::recalibrate(Nanos t_ns) {
  const Nanos t = advance(t_ns);
  if (state_ != KioskState::operator_page) return false;
  calibration_from_operator_ = true;
  calibration_pending_ = false;
  return enter(KioskState::calibration, t);
}

bool KioskStates::calibration_needed(Nanos t_ns) {
  const KioskState before = state_;
  const Nanos t = advance(t_ns);
  if (source_ == InputSource::mouse) return state_ != before;
  if (state_ == KioskState::operator_page) {
    calibration_pending_ = true;
    return false;
  }
  if (state_ == KioskState::calibration) return state_ != before;
  calibration_from_operator_ = false;
  enter(KioskState::calibration, t);
  return state_ != before;
}

bool KioskStates::calibration_accepted(Nanos t_ns) {
  const Nanos t = advance(t_ns);
  if (state_ != KioskState::calibration) return false;
  play_from(t);
  return true;
}

bool KioskStates::calibration_cancelled(Nanos t_ns) {
  const Nanos t = advance(t_ns);
  if (state_ != KioskState::calibration) return false;
  if (calibration_from_operator_) return enter(KioskState::operator_page, t);
  play_from(t);
  return true;
}

bool KioskStates::operator_page_closed(Nanos t_ns) {
  const Nanos t = advance(t_ns);
  if (state_ != KioskState::operator_page) return false;
  if (calibration_pending_ && source_ != InputSource::mouse) {
    calibration_pending_ = false;
    calibration_from_operator_ = false;
    return enter(KioskState::calibration, t);
  }
  calibration_pending_ = false;
  play_from(t);
  return true;
}

bool KioskStates::quit_requested(Nanos t_ns) {
  const Nanos t = advance(t_ns);
  if (state_ == KioskState::operator_page) {
    page_key_at_ = t;
    if (quit_asked_) {
      quit_ = true;
      return true;
    }
    quit_asked_ = true;  // a single Q may be a slip: ask first
    quit_asked_at_ = t;
    return false;
  }
  close_refused_ = true;
  close_refused_at_ = t;
  return false;
}

bool KioskStates::window_close_requested(Nanos t_ns) {
  advance(t_ns);
  if (state_ != KioskState::operator_page) return quit_requested(t_ns);  // refused, with its notice
  quit_ = true;  // a window's close is deliberate: no question
  return true;
}

bool KioskStates::operator_key(Nanos t_ns) {
  const Nanos t = advance(t_ns);
  if (state_ != KioskState::operator_page) return false;
  page_key_at_ = t;
  quit_asked_ = false;
  return false;
}

KioskOverlay KioskStates::overlay() const {
  KioskOverlay o;
  o.invitation = state_ == KioskState::attract;
  o.point_at_screen = state_ == KioskState::play && !tracking_ && now_ - lost_since_ >= lost_hint_ns_;
  o.mouse_notice = (state_ == KioskState::attract || state_ == KioskState::play) && source_ == InputSource::mouse;
  o.close_needs_chord = close_refused_ && now_ - close_refused_at_ < close_notice_ns_;
  o.remote_missing = (state_ == KioskState::attract || state_ == KioskState::play) &&
                     live_ir_tracker(source_) && !remote_connected_;
  return o;
}

KioskHint KioskStates::hint() const {
  const KioskOverlay o = overlay();
  if (o.remote_missing) return KioskHint::remote_missing;
  if (o.point_at_screen) return KioskHint::point_at_screen;
  if (o.invitation) return KioskHint::invitation;
  return KioskHint::none;
}

}  // namespace mallet
