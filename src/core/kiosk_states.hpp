#pragma once
// The kiosk's states (issue 6): Attract, Play, Calibration, Operator. Pure: every input is
// an event stamped on the program's int64 nanosecond clock, and `tick(now)` lets timers run
// without one. The kiosk loop feeds it and reads back what to show and what to play.
//
// Transitions (every event first runs the timers up to its own time, as tick() would):
//
// | from        | event                                   | to          | notes                                         |
// |-------------|-----------------------------------------|-------------|-----------------------------------------------|
// | (start)     | constructed at t                        | Attract     | nobody is there yet                           |
// | Attract     | pointer: real movement                  | Play        | in the same call; the idle timer starts at t  |
// | Attract     | pointer within the dead-band (jitter)   | Attract     |                                               |
// | Play        | real movement                           | Play        | the idle timer restarts at t                  |
// | Play        | time ≥ last real movement + idle_after  | Attract     | exactly at the boundary (≥), at that tick     |
// | Attract/Play| operator chord                          | Operator    |                                               |
// | Attract/Play| calibration needed                      | Calibration | ignored with the mouse as input (no IR)       |
// | Operator    | recalibrate                             | Calibration | with the mouse too: it stands in for the dot  |
// | Operator    | calibration needed                      | Operator    | remembered: closing the page calibrates       |
// | Operator    | page closed                             | Play        | Calibration instead if one was remembered     |
// | Operator    | quit requested (Q), not asked           | Operator    | asked: "Q again quits" for quit_confirm_s     |
// | Operator    | quit requested while asked              | Operator    | accepted: should_quit() becomes true          |
// | Operator    | any other page key                      | Operator    | the question withdrawn; the page timer restarts|
// | Operator    | window close                            | Operator    | accepted at once (a deliberate act)           |
// | Operator    | no key for operator_page_timeout_s      | Attract     | Calibration instead if one was remembered     |
// | Operator    | operator chord                          | Operator    | no-op: only the page's close action leaves it |
// | Calibration | calibration accepted                    | Play        |                                               |
// | Calibration | calibration cancelled                   | Operator    | if it was entered from Operator, else Play    |
// | Calibration | operator chord                          | Operator    | the calibration is abandoned (old one stays)  |
// | Calibration | calibration needed                      | Calibration | no-op                                         |
// | not Operator| window close / quit requested           | (unchanged) | refused; the close notice shows for a while   |
// | Play        | remote disconnected                     | Attract     | at once, with the remote-missing hint         |
// | any other   | remote disconnected / connected         | (unchanged) | flags only (the remote-missing hint)          |
// | any         | tracking lost / regained, input source  | (unchanged) | flags only (hint, mouse notice)               |
// | any         | accepted / cancelled / recalibrate / page closed outside their state | (unchanged) | ignored |
//
// Losing the stick does not end Play at once (a visitor may dip it out of view); with no
// real movement the idle rule brings Attract, as the style guide's "remote lost → attract
// mode with an on-screen hint" asks. A remote that is gone altogether (unplugged, out of
// battery, out of range) ends Play at once: nobody can play, and the attract screen then
// says so instead of inviting people to pick up the mallet. Entering Play from Operator or Calibration restarts
// the idle timer there. Times earlier than the latest event are taken as the latest (the
// clock is monotonic; visitor input is never asserted on).
#include <string>
#include <string_view>

#include "core/enum_names.hpp"
#include "core/geometry.hpp"
#include "core/result.hpp"
#include "core/scene.hpp"
#include "core/time.hpp"

namespace mallet {

struct KioskStatesConfig {
  double idle_after_s = 45.0;  //!< attract.idle_after_s: no real movement for this long → Attract
  //! A pointer sample is real movement only when it lies farther than this from the last
  //! one that was (normalised screen units, Euclidean): a resting stick's camera jitter
  //! (1–2 camera px ≈ 0.002) stays inside, a visitor's gesture does not.
  double dead_band_screen_units = 0.005;
  double lost_hint_after_s = 0.5;  //!< tracking lost this long → "Point the mallet at the screen"
  double close_notice_s = 4.0;     //!< how long a refused window close shows its notice
  //! The operator page closes by itself after this long without a key (an operator walked
  //! away: strikes do nothing and the attract mode never returns while it is open).
  double operator_page_timeout_s = 180.0;
  double quit_confirm_s = 5.0;  //!< Q asks first: a second Q within this long quits
};

//! Passes when `config` is usable; otherwise fails with one line naming the bad key and why.
Check validate(const KioskStatesConfig& config);

enum class KioskState { attract, play, calibration, operator_page };
inline constexpr EnumNames<KioskState, 4> kKioskStateNames{{
    {KioskState::attract, "attract"}, {KioskState::play, "play"}, {KioskState::calibration, "calibration"},
    {KioskState::operator_page, "operator"}}};
const char* to_string(KioskState state);

//! camera: a V4L2 camera as the IR tracker, in every state the same as the Wii Remote.
enum class InputSource { wiimote, mouse, replay, camera };
//! A live IR tracker (the remote or the camera): missing = the mallet rests, staff is asked.
constexpr bool live_ir_tracker(InputSource s) { return s == InputSource::wiimote || s == InputSource::camera; }

//! What the overlay may show besides the state's own screen; several may be true at once.
struct KioskOverlay {
  bool invitation = false;         //!< Attract: "Pick up the mallet and strike a bar"
  bool point_at_screen = false;    //!< Play, tracking lost ≥ lost_hint_after_s
  bool mouse_notice = false;       //!< Attract or Play with the mouse fallback as input
  bool close_needs_chord = false;  //!< a window close was refused less than close_notice_s ago
  bool remote_missing = false;     //!< Attract or Play with the Wii Remote as input and not connected
};

//! The one line to show the visitors, most urgent first: remote missing, point-at-screen,
//! invitation. close_needs_chord is the staff's, never the visitors' line: its words
//! (hint_text) show as a corner note while KioskOverlay::close_needs_chord holds.
enum class KioskHint { none, invitation, point_at_screen, close_needs_chord, remote_missing };
//! "" for none. The invitation asks for what the scene is played with: a bar to strike, the
//! disc to move over (texture), the wall to tap; with the `mouse` as the input, to move the
//! mouse (there is no mallet to pick up). In the visitor's language (tr()).
std::string_view hint_text(KioskHint hint, SceneKind scene = SceneKind::percussion, bool mouse = false);

class KioskStates {
 public:
  //! Starts in Attract at `now_ns`. Throws std::invalid_argument when validate(config) fails.
  explicit KioskStates(KioskStatesConfig config = {}, Nanos now_ns = 0);

  // Events. Each returns whether the state changed.
  bool tick(Nanos now_ns);
  bool pointer(Nanos t_ns, Vec2 screen);  //!< a pointer sample, normalised screen coordinates
  //! Where the pointer is known to rest without a sample (the window system's cursor when the
  //! kiosk starts): the first sample away from it is movement. Without it the first sample
  //! only says where the stick rests.
  void pointer_rests(Vec2 screen);
  bool tracking_lost(Nanos t_ns);
  bool tracking_regained(Nanos t_ns);  //!< also implied by any pointer sample
  bool input_source(Nanos t_ns, InputSource source);  //!< the mouse never loses tracking
  //! The Wii Remote's link came up (true) or went down (false); meaningless for the mouse.
  //! At construction the remote counts as connected: say so when it is not.
  bool remote_connected(Nanos t_ns, bool connected);
  bool operator_chord(Nanos t_ns);
  bool recalibrate(Nanos t_ns);         //!< the operator page's "recalibrate"
  bool calibration_needed(Nanos t_ns);  //!< start-up: no valid calibration, or the remote changed
  bool calibration_accepted(Nanos t_ns);
  bool calibration_cancelled(Nanos t_ns);
  bool operator_page_closed(Nanos t_ns);
  //! The operator page's "quit", or the window's close request: granted only in Operator.
  //! Returns whether it was granted (then should_quit() is true).
  //! Q on the page asks first: the first arms the question (quit_asked()), a second within
  //! quit_confirm_s quits.
  bool quit_requested(Nanos t_ns);
  bool window_close_requested(Nanos t_ns);
  //! Any other key on the operator page: withdraws the quit question, restarts the page's timer.
  bool operator_key(Nanos t_ns);

  // What the kiosk loop reads.
  KioskState state() const { return state_; }
  Nanos since() const { return since_; }             //!< when the current state was entered
  bool may_quit() const { return state_ == KioskState::operator_page; }
  bool should_quit() const { return quit_; }
  bool quit_asked() const { return quit_asked_; }  //!< "Q again quits the kiosk" is showing
  //! How many times the operator page closed by itself (its timeout): the loop logs each.
  int page_timeouts() const { return page_timeouts_; }
  bool ghost_plays() const { return state_ == KioskState::attract; }
  bool attract_volume() const { return state_ == KioskState::attract; }  //!< audio at the attract volume
  bool visitor_plays() const { return state_ == KioskState::play; }      //!< the pointer drives the mallet
  bool tracking() const { return tracking_; }
  bool remote_present() const { return remote_connected_; }
  InputSource source() const { return source_; }
  bool calibration_pending() const { return calibration_pending_; }
  //! When the last real movement happened (or Play was last entered; construction at first).
  Nanos last_movement() const { return last_movement_; }
  KioskOverlay overlay() const;
  KioskHint hint() const;
  const KioskStatesConfig& config() const { return config_; }

 private:
  Nanos advance(Nanos t_ns);  //!< clamps t to the latest time, runs the idle timer; returns t
  bool enter(KioskState next, Nanos t_ns);
  void play_from(Nanos t_ns);  //!< enter Play with a fresh idle timer

  KioskStatesConfig config_;
  Nanos idle_after_ns_;
  Nanos lost_hint_ns_;
  Nanos close_notice_ns_;
  Nanos page_timeout_ns_;
  Nanos quit_confirm_ns_;
  KioskState state_ = KioskState::attract;
  Nanos since_ = 0;
  Nanos now_ = 0;
  Nanos last_movement_ = 0;
  bool have_anchor_ = false;
  Vec2 anchor_;  //!< the last sample that counted as real movement
  bool tracking_ = false;  //!< nothing seen yet at start-up; a pointer sample proves tracking
  Nanos lost_since_ = 0;
  InputSource source_ = InputSource::wiimote;
  bool calibration_from_operator_ = false;
  bool calibration_pending_ = false;
  bool remote_connected_ = true;
  bool quit_ = false;
  bool quit_asked_ = false;
  Nanos quit_asked_at_ = 0;
  Nanos page_key_at_ = 0;  //!< the page's last key (or its opening)
  int page_timeouts_ = 0;
  bool close_refused_ = false;
  Nanos close_refused_at_ = 0;
};

}  // namespace mallet
