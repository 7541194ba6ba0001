// The kiosk's states: every row of the transition table in kiosk_states.hpp, the idle timer
// to the nanosecond, the dead-band that keeps a resting stick's jitter from waking the kiosk,
// and a close request that only the operator page grants. All time is passed in.
#include <cmath>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/kiosk_states.hpp"

namespace mallet {

void PrintTo(KioskState s, std::ostream* os) { *os << to_string(s); }

namespace {

constexpr Nanos kStart = 1'000 * kNanosPerSecond;  // any clock origin
constexpr Nanos kIdle = 45 * kNanosPerSecond;       // the default attract.idle_after_s
constexpr Nanos kMs = 1'000'000;

using S = KioskState;

// A machine driven into `state` at kStart + 1 s by the ordinary route.
KioskStates in(S state, KioskStatesConfig config = {}) {
  KioskStates k(config, kStart);
  const Nanos t = kStart + kNanosPerSecond;
  switch (state) {
    case S::attract: k.pointer(t, {0.5, 0.5}); break;  // the stick rests: not movement
    case S::play:
      k.pointer(t - kMs, {0.5, 0.5});
      k.pointer(t, {0.6, 0.5});
      break;
    case S::calibration: k.calibration_needed(t); break;
    case S::operator_page: k.operator_chord(t); break;
  }
  EXPECT_EQ(k.state(), state);
  return k;
}

TEST(KioskStates, StartsInAttractWithTheGhostAndTheInvitation) {
  const KioskStates k({}, kStart);
  EXPECT_EQ(k.state(), S::attract);
  EXPECT_EQ(k.since(), kStart);
  EXPECT_TRUE(k.ghost_plays());
  EXPECT_TRUE(k.attract_volume());
  EXPECT_FALSE(k.visitor_plays());
  EXPECT_FALSE(k.may_quit());
  EXPECT_TRUE(k.overlay().invitation);
  EXPECT_EQ(k.hint(), KioskHint::invitation);
  EXPECT_EQ(hint_text(k.hint()), "Pick up the mallet and strike a bar");
}

TEST(KioskStates, TheInvitationAsksForWhatTheSceneIsPlayedWith) {
  EXPECT_EQ(hint_text(KioskHint::invitation, SceneKind::percussion), "Pick up the mallet and strike a bar");
  EXPECT_EQ(hint_text(KioskHint::invitation, SceneKind::texture), "Pick up the mallet and move it over the disc");
  EXPECT_EQ(hint_text(KioskHint::invitation, SceneKind::wall), "Pick up the mallet and tap the wall");
  // Neither second-paper scene has bars to strike.
  for (SceneKind kind : {SceneKind::texture, SceneKind::wall})
    EXPECT_EQ(hint_text(KioskHint::invitation, kind).find("bar"), std::string_view::npos) << to_string(kind);
}

TEST(KioskStates, WithTheMouseTheInvitationAsksForAMoveNotAMalletToPickUp) {
  for (SceneKind kind : {SceneKind::percussion, SceneKind::texture, SceneKind::wall}) {
    const std::string_view said = hint_text(KioskHint::invitation, kind, true);
    EXPECT_EQ(said.find("Pick up"), std::string_view::npos) << said;
    EXPECT_EQ(said.rfind("Move the mouse", 0), 0u) << said;
    EXPECT_NE(said, hint_text(KioskHint::invitation, kind, false));
  }
  EXPECT_NE(hint_text(KioskHint::invitation, SceneKind::percussion, true).find("bar"), std::string_view::npos);
  // The other hints do not depend on the input.
  EXPECT_EQ(hint_text(KioskHint::remote_missing, SceneKind::percussion, true), hint_text(KioskHint::remote_missing));
}

using Event = std::function<bool(KioskStates&, Nanos)>;

struct Row {
  S from;
  std::string event;
  Event apply;
  S to;
  bool granted_quit = false;  //!< the call returns true for this (a granted quit) though the state stays
};

// Every row of the table, each from a fresh machine in its `from` state.
TEST(KioskStates, EveryTransitionOfTheTable) {
  const Nanos t = kStart + 2 * kNanosPerSecond;
  auto chord = [](KioskStates& k, Nanos at) { return k.operator_chord(at); };
  auto needed = [](KioskStates& k, Nanos at) { return k.calibration_needed(at); };
  auto move = [](KioskStates& k, Nanos at) { return k.pointer(at, {0.9, 0.1}); };
  auto lost = [](KioskStates& k, Nanos at) { return k.tracking_lost(at); };
  auto regained = [](KioskStates& k, Nanos at) { return k.tracking_regained(at); };
  auto accepted = [](KioskStates& k, Nanos at) { return k.calibration_accepted(at); };
  auto cancelled = [](KioskStates& k, Nanos at) { return k.calibration_cancelled(at); };
  auto recal = [](KioskStates& k, Nanos at) { return k.recalibrate(at); };
  auto closed = [](KioskStates& k, Nanos at) { return k.operator_page_closed(at); };
  auto close = [](KioskStates& k, Nanos at) { return k.window_close_requested(at); };
  auto quit = [](KioskStates& k, Nanos at) { return k.quit_requested(at); };
  auto quit_twice = [](KioskStates& k, Nanos at) { return !k.quit_requested(at) && k.quit_requested(at); };
  auto source = [](KioskStates& k, Nanos at) { return k.input_source(at, InputSource::replay); };
  const std::vector<Row> rows{
      {S::attract, "real movement", move, S::play},
      {S::play, "real movement", move, S::play},
      {S::attract, "chord", chord, S::operator_page},
      {S::play, "chord", chord, S::operator_page},
      {S::attract, "calibration needed", needed, S::calibration},
      {S::play, "calibration needed", needed, S::calibration},
      {S::operator_page, "recalibrate", recal, S::calibration},
      {S::operator_page, "calibration needed", needed, S::operator_page},
      {S::operator_page, "page closed", closed, S::play},
      {S::operator_page, "quit (asked first)", quit, S::operator_page},
      {S::operator_page, "quit, and again", quit_twice, S::operator_page, true},
      {S::operator_page, "window close", close, S::operator_page, true},
      {S::operator_page, "chord", chord, S::operator_page},
      {S::calibration, "accepted", accepted, S::play},
      {S::calibration, "cancelled (automatic)", cancelled, S::play},
      {S::calibration, "chord", chord, S::operator_page},
      {S::calibration, "calibration needed", needed, S::calibration},
      {S::attract, "window close", close, S::attract},
      {S::play, "window close", close, S::play},
      {S::calibration, "window close", close, S::calibration},
      {S::attract, "quit", quit, S::attract},
      {S::play, "quit", quit, S::play},
      {S::calibration, "quit", quit, S::calibration},
  };
  for (const Row& r : rows) {
    SCOPED_TRACE(std::string(to_string(r.from)) + " + " + r.event);
    KioskStates k = in(r.from);
    const Nanos before = k.since();
    EXPECT_EQ(r.apply(k, t), r.to != r.from || r.granted_quit);
    EXPECT_EQ(k.state(), r.to);
    EXPECT_EQ(k.should_quit(), r.granted_quit);
    EXPECT_EQ(k.since(), r.to == r.from ? before : t);
  }
  // Flags only, in every state; and the events that belong to another state are ignored.
  for (S from : {S::attract, S::play, S::calibration, S::operator_page}) {
    SCOPED_TRACE(to_string(from));
    for (const auto& ev : std::vector<Event>{lost, regained, source}) {
      KioskStates k = in(from);
      EXPECT_FALSE(ev(k, t));
      EXPECT_EQ(k.state(), from);
    }
    for (const auto& ev : std::vector<Event>{accepted, cancelled}) {
      if (from == S::calibration) continue;
      KioskStates k = in(from);
      EXPECT_FALSE(ev(k, t));
      EXPECT_EQ(k.state(), from);
    }
    for (const auto& ev : std::vector<Event>{recal, closed}) {
      if (from == S::operator_page) continue;
      KioskStates k = in(from);
      EXPECT_FALSE(ev(k, t));
      EXPECT_EQ(k.state(), from);
    }
  }
}

TEST(KioskStates, CancellingARecalibrationGoesBackToTheOperatorPage) {
  KioskStates k = in(S::operator_page);
  const Nanos t = kStart + 5 * kNanosPerSecond;
  EXPECT_TRUE(k.recalibrate(t));
  EXPECT_EQ(k.state(), S::calibration);
  EXPECT_TRUE(k.calibration_cancelled(t + kMs));
  EXPECT_EQ(k.state(), S::operator_page);
  EXPECT_EQ(k.since(), t + kMs);
  // Accepting one instead goes to Play.
  EXPECT_TRUE(k.recalibrate(t + 2 * kMs));
  EXPECT_TRUE(k.calibration_accepted(t + 3 * kMs));
  EXPECT_EQ(k.state(), S::play);
}

TEST(KioskStates, CalibrationNeededOnTheOperatorPageWaitsForItToClose) {
  KioskStates k = in(S::operator_page);
  const Nanos t = kStart + 5 * kNanosPerSecond;
  EXPECT_FALSE(k.calibration_needed(t));
  EXPECT_TRUE(k.calibration_pending());
  EXPECT_EQ(k.state(), S::operator_page);
  EXPECT_TRUE(k.operator_page_closed(t + kMs));
  EXPECT_EQ(k.state(), S::calibration);
  EXPECT_FALSE(k.calibration_pending());
  // That calibration was automatic: cancelling it goes to Play, not back to the page.
  EXPECT_TRUE(k.calibration_cancelled(t + 2 * kMs));
  EXPECT_EQ(k.state(), S::play);
}

TEST(KioskStates, AttractExactlyAtTheIdleBoundary) {
  KioskStates k({}, kStart);
  k.pointer(kStart + 10 * kMs, {0.2, 0.2});
  const Nanos moved = kStart + 20 * kMs;
  EXPECT_TRUE(k.pointer(moved, {0.3, 0.2}));
  EXPECT_EQ(k.state(), S::play);
  EXPECT_EQ(k.last_movement(), moved);
  EXPECT_FALSE(k.tick(moved + kIdle - 1));
  EXPECT_EQ(k.state(), S::play);
  EXPECT_TRUE(k.tick(moved + kIdle));
  EXPECT_EQ(k.state(), S::attract);
  EXPECT_EQ(k.since(), moved + kIdle);
  EXPECT_TRUE(k.ghost_plays());
}

TEST(KioskStates, TheIdleTimeIsConfigAndRealMovementRestartsIt) {
  KioskStatesConfig c;
  c.idle_after_s = 2.5;
  const Nanos idle = 2'500 * kMs;
  KioskStates k(c, kStart);
  k.pointer(kStart, {0.5, 0.5});
  k.pointer(kStart + kMs, {0.6, 0.5});
  EXPECT_EQ(k.state(), S::play);
  k.pointer(kStart + 2 * kNanosPerSecond, {0.7, 0.5});  // real movement 2 s later
  EXPECT_FALSE(k.tick(kStart + kMs + idle));             // the first timer would have run out
  EXPECT_EQ(k.state(), S::play);
  EXPECT_FALSE(k.tick(kStart + 2 * kNanosPerSecond + idle - 1));
  EXPECT_TRUE(k.tick(kStart + 2 * kNanosPerSecond + idle));
  EXPECT_EQ(k.state(), S::attract);
}

TEST(KioskStates, JitterWithinTheDeadBandNeitherLeavesAttractNorKeepsPlayAlive) {
  KioskStates k({}, kStart);
  const double band = k.config().dead_band_screen_units;
  const Vec2 rest{0.4, 0.6};
  k.pointer(kStart, rest);
  // A resting stick: ±0.4 of the band around its rest, for a minute at 100 Hz.
  for (int i = 1; i <= 6000; ++i) {
    const double dx = (i % 2 ? 0.4 : -0.4) * band, dy = (i % 3 ? -0.3 : 0.3) * band;
    EXPECT_FALSE(k.pointer(kStart + i * 10 * kMs, {rest.x + dx, rest.y + dy}));
  }
  EXPECT_EQ(k.state(), S::attract);
  // A real move leaves Attract within the same event.
  const Nanos t = kStart + 61 * kNanosPerSecond;
  EXPECT_TRUE(k.pointer(t, {rest.x + 1.5 * band, rest.y}));
  EXPECT_EQ(k.state(), S::play);
  EXPECT_EQ(k.since(), t);
  EXPECT_TRUE(k.visitor_plays());
  EXPECT_FALSE(k.attract_volume());
  // Jitter in Play does not postpone Attract.
  const Vec2 now_rest{rest.x + 1.5 * band, rest.y};
  for (int i = 1; i < 4500; ++i) k.pointer(t + i * 10 * kMs, {now_rest.x + (i % 2 ? 0.3 : -0.3) * band, now_rest.y});
  EXPECT_TRUE(k.tick(t + kIdle));
  EXPECT_EQ(k.state(), S::attract);
}

TEST(KioskStates, ASlowDriftAddsUpToRealMovement) {
  KioskStates k({}, kStart);
  const double band = k.config().dead_band_screen_units;
  k.pointer(kStart, {0.5, 0.5});
  int woke = 0;
  for (int i = 1; i <= 10 && woke == 0; ++i)
    if (k.pointer(kStart + i * 10 * kMs, {0.5 + i * 0.3 * band, 0.5})) woke = i;
  EXPECT_EQ(k.state(), S::play);
  EXPECT_EQ(woke, 4);  // 1.2 bands from the rest point is the first beyond the band
}

TEST(KioskStates, EveryEventRunsTheIdleTimerFirst) {
  KioskStates k = in(S::play);
  const Nanos moved = k.last_movement();
  // No tick: a jitter sample at the boundary finds the kiosk idle.
  k.pointer(moved + kIdle, {0.6 + 1e-4, 0.5});
  EXPECT_EQ(k.state(), S::attract);
  EXPECT_EQ(k.since(), moved + kIdle);
}

TEST(KioskStates, TheFirstSampleAndANewSourceOnlySetTheRestPoint) {
  KioskStates k({}, kStart);
  EXPECT_FALSE(k.pointer(kStart + kMs, {0.9, 0.9}));  // first sample ever
  EXPECT_EQ(k.state(), S::attract);
  EXPECT_FALSE(k.input_source(kStart + 2 * kMs, InputSource::mouse));
  EXPECT_FALSE(k.pointer(kStart + 3 * kMs, {0.1, 0.1}));  // the mouse's first sample
  EXPECT_EQ(k.state(), S::attract);
  EXPECT_TRUE(k.pointer(kStart + 4 * kMs, {0.2, 0.1}));
  EXPECT_EQ(k.state(), S::play);
}

TEST(KioskStates, NonFiniteSamplesAreIgnored) {
  KioskStates k({}, kStart);
  k.pointer(kStart, {0.5, 0.5});
  EXPECT_FALSE(k.pointer(kStart + kMs, {std::nan(""), 0.5}));
  EXPECT_FALSE(k.pointer(kStart + 2 * kMs, {0.5, std::numeric_limits<double>::infinity()}));
  EXPECT_EQ(k.state(), S::attract);
}

TEST(KioskStates, ThePointAtTheScreenHintShowsInPlayAfterTrackingIsLostForAWhile) {
  KioskStates k = in(S::play);
  const Nanos t = kStart + 2 * kNanosPerSecond;
  const Nanos after = 500 * kMs;  // the default lost_hint_after_s
  EXPECT_FALSE(k.tracking_lost(t));
  EXPECT_FALSE(k.tracking());
  EXPECT_EQ(k.state(), S::play);  // losing the stick does not end Play
  k.tick(t + after - 1);
  EXPECT_FALSE(k.overlay().point_at_screen);
  EXPECT_EQ(k.hint(), KioskHint::none);
  k.tick(t + after);
  EXPECT_TRUE(k.overlay().point_at_screen);
  EXPECT_EQ(k.hint(), KioskHint::point_at_screen);
  EXPECT_EQ(hint_text(k.hint()), "Point the mallet at the screen");
  k.tracking_regained(t + after + kMs);
  EXPECT_EQ(k.hint(), KioskHint::none);
  // A pointer sample also says the dot is seen again.
  k.tracking_lost(t + 2 * after);
  k.tick(t + 4 * after);
  EXPECT_EQ(k.hint(), KioskHint::point_at_screen);
  k.pointer(t + 4 * after + kMs, {0.6, 0.5});
  EXPECT_TRUE(k.tracking());
  EXPECT_EQ(k.hint(), KioskHint::none);
  // Still lost at the idle time: Attract, with its invitation (the remote-lost fallback).
  k.tracking_lost(t + 5 * after);
  k.tick(t + 5 * after + kIdle);
  EXPECT_EQ(k.state(), S::attract);
  EXPECT_EQ(k.hint(), KioskHint::invitation);
  EXPECT_FALSE(k.overlay().point_at_screen);
}

TEST(KioskStates, TheMouseFallbackIsSaidOnScreenAndNeverLosesTracking) {
  KioskStates k({}, kStart);
  k.input_source(kStart, InputSource::mouse);
  EXPECT_EQ(k.source(), InputSource::mouse);
  EXPECT_TRUE(k.overlay().mouse_notice);  // Attract
  k.pointer(kStart + kMs, {0.5, 0.5});
  k.pointer(kStart + 2 * kMs, {0.6, 0.5});
  EXPECT_EQ(k.state(), S::play);
  EXPECT_TRUE(k.overlay().mouse_notice);
  k.tracking_lost(kStart + 3 * kMs);
  k.tick(kStart + 2 * kNanosPerSecond);
  EXPECT_TRUE(k.tracking());
  EXPECT_FALSE(k.overlay().point_at_screen);
  k.operator_chord(kStart + 3 * kNanosPerSecond);
  EXPECT_FALSE(k.overlay().mouse_notice);  // the operator page says the input itself
  // Start-up never asks the mouse to calibrate (it has no IR camera) ...
  k.operator_page_closed(kStart + 4 * kNanosPerSecond);
  EXPECT_FALSE(k.calibration_needed(kStart + 5 * kNanosPerSecond));
  EXPECT_EQ(k.state(), S::play);
  // ... but the operator may run the screen with the mouse standing in for the IR dot.
  k.operator_chord(kStart + 5 * kNanosPerSecond);
  EXPECT_TRUE(k.recalibrate(kStart + 5 * kNanosPerSecond));
  EXPECT_EQ(k.state(), S::calibration);
  EXPECT_TRUE(k.calibration_cancelled(kStart + 6 * kNanosPerSecond));
  EXPECT_EQ(k.state(), S::operator_page);
  k.operator_page_closed(kStart + 6 * kNanosPerSecond);
  EXPECT_EQ(k.state(), S::play);
  // Back on the remote: no notice.
  k.input_source(kStart + 7 * kNanosPerSecond, InputSource::wiimote);
  EXPECT_FALSE(k.overlay().mouse_notice);
}

TEST(KioskStates, TheCloseRequestIsRefusedOutsideOperatorAndSaysWhy) {
  for (S from : {S::attract, S::play, S::calibration}) {
    SCOPED_TRACE(to_string(from));
    KioskStates k = in(from);
    const Nanos t = kStart + 3 * kNanosPerSecond;
    EXPECT_FALSE(k.may_quit());
    EXPECT_FALSE(k.window_close_requested(t));
    EXPECT_FALSE(k.should_quit());
    EXPECT_EQ(k.state(), from);
    EXPECT_TRUE(k.overlay().close_needs_chord);
    // The staff's note, in a corner: the visitors' line stays what it was.
    EXPECT_NE(k.hint(), KioskHint::close_needs_chord);
    k.tick(t + 4 * kNanosPerSecond - 1);  // the default close_notice_s
    EXPECT_TRUE(k.overlay().close_needs_chord);
    k.tick(t + 4 * kNanosPerSecond);
    EXPECT_FALSE(k.overlay().close_needs_chord);
    EXPECT_FALSE(k.quit_requested(t + 5 * kNanosPerSecond));
    EXPECT_FALSE(k.should_quit());
  }
  KioskStates k = in(S::operator_page);
  EXPECT_TRUE(k.may_quit());
  EXPECT_TRUE(k.window_close_requested(kStart + 3 * kNanosPerSecond));
  EXPECT_TRUE(k.should_quit());
  KioskStates q = in(S::operator_page);
  EXPECT_FALSE(q.quit_requested(kStart + 3 * kNanosPerSecond));
  EXPECT_TRUE(q.quit_asked());
  EXPECT_TRUE(q.quit_requested(kStart + 4 * kNanosPerSecond));
  EXPECT_TRUE(q.should_quit());
}

TEST(KioskStates, QAsksFirstAndAnyOtherKeyOrTheTimeWithdrawsTheQuestion) {
  const Nanos t = kStart + 3 * kNanosPerSecond;
  {  // Q, Q within quit_confirm_s (5 s): quit.
    KioskStates k = in(S::operator_page);
    EXPECT_FALSE(k.quit_requested(t));
    EXPECT_TRUE(k.quit_asked());
    EXPECT_FALSE(k.should_quit());
    EXPECT_TRUE(k.quit_requested(t + 5 * kNanosPerSecond - 1));
    EXPECT_TRUE(k.should_quit());
  }
  {  // Q, then 5 s: the question is gone, and the next Q asks again.
    KioskStates k = in(S::operator_page);
    EXPECT_FALSE(k.quit_requested(t));
    k.tick(t + 5 * kNanosPerSecond);
    EXPECT_FALSE(k.quit_asked());
    EXPECT_FALSE(k.quit_requested(t + 6 * kNanosPerSecond));
    EXPECT_FALSE(k.should_quit());
    EXPECT_TRUE(k.quit_asked());
  }
  {  // Q, another key, Q: asked again, not quit.
    KioskStates k = in(S::operator_page);
    EXPECT_FALSE(k.quit_requested(t));
    k.operator_key(t + kNanosPerSecond);
    EXPECT_FALSE(k.quit_asked());
    EXPECT_FALSE(k.quit_requested(t + 2 * kNanosPerSecond));
    EXPECT_FALSE(k.should_quit());
  }
  {  // Reopening the page starts without the question.
    KioskStates k = in(S::operator_page);
    EXPECT_FALSE(k.quit_requested(t));
    k.operator_page_closed(t + kNanosPerSecond);
    k.operator_chord(t + 2 * kNanosPerSecond);
    EXPECT_FALSE(k.quit_asked());
  }
}

TEST(KioskStates, WithTheRestingPointerKnownTheFirstMoveEndsTheAttractMode) {
  // The window system's cursor at start-up: the first sample away from it is a visitor's.
  KioskStates k({}, kStart);
  k.pointer_rests({0.5, 0.5});
  EXPECT_TRUE(k.pointer(kStart + kNanosPerSecond, {0.52, 0.5}));
  EXPECT_EQ(k.state(), S::play);
  // Without it, the first sample only says where the stick rests (an IR dot first seen).
  KioskStates ir({}, kStart);
  EXPECT_FALSE(ir.pointer(kStart + kNanosPerSecond, {0.52, 0.5}));
  EXPECT_EQ(ir.state(), S::attract);
  // A jitter inside the dead-band around the resting place is still no movement.
  KioskStates still({}, kStart);
  still.pointer_rests({0.5, 0.5});
  EXPECT_FALSE(still.pointer(kStart + kNanosPerSecond, {0.502, 0.5}));
  EXPECT_EQ(still.state(), S::attract);
}

TEST(KioskStates, TheOperatorPageClosesByItselfAfterItsTimeoutWithoutAKey) {
  KioskStates k = in(S::operator_page);
  const Nanos opened = k.since();
  const Nanos timeout = 180 * kNanosPerSecond;  // the default operator_page_timeout_s
  k.operator_key(opened + 100 * kNanosPerSecond);  // a key restarts its timer
  EXPECT_FALSE(k.tick(opened + 100 * kNanosPerSecond + timeout - 1));
  EXPECT_EQ(k.state(), S::operator_page);
  EXPECT_EQ(k.page_timeouts(), 0);
  EXPECT_TRUE(k.tick(opened + 100 * kNanosPerSecond + timeout));
  EXPECT_EQ(k.state(), S::attract) << "nobody is at the page: back to the visitors";
  EXPECT_EQ(k.page_timeouts(), 1);
  EXPECT_FALSE(k.should_quit());
  // A calibration remembered while the page was open runs when it times out, as on Esc.
  KioskStates c = in(S::operator_page);
  c.calibration_needed(c.since() + kNanosPerSecond);
  EXPECT_TRUE(c.tick(c.since() + timeout));
  EXPECT_EQ(c.state(), S::calibration);
}

TEST(KioskStates, TheOperatorPageRestartsTheIdleTimerWhenClosed) {
  KioskStatesConfig long_visit;
  long_visit.operator_page_timeout_s = 3600;  // the page's own timeout is another test's
  KioskStates k = in(S::operator_page, long_visit);
  const Nanos closed = kStart + 600 * kNanosPerSecond;  // a long visit: no Attract behind the page
  k.tick(closed - 1);
  EXPECT_EQ(k.state(), S::operator_page);
  EXPECT_TRUE(k.operator_page_closed(closed));
  EXPECT_EQ(k.state(), S::play);
  EXPECT_EQ(k.last_movement(), closed);
  k.tick(closed + kIdle - 1);
  EXPECT_EQ(k.state(), S::play);
  k.tick(closed + kIdle);
  EXPECT_EQ(k.state(), S::attract);
}

TEST(KioskStates, TimeNeverRunsBackwards) {
  KioskStates k = in(S::play);
  const Nanos moved = k.last_movement();
  k.tick(moved + kIdle);
  EXPECT_EQ(k.state(), S::attract);
  // A late event stamped earlier is taken at the latest time: the real move still counts.
  EXPECT_TRUE(k.pointer(moved + kMs, {0.1, 0.1}));
  EXPECT_EQ(k.state(), S::play);
  EXPECT_EQ(k.since(), moved + kIdle);
}

TEST(KioskStates, ABadConfigIsRefusedWithItsKey) {
  KioskStatesConfig c;
  EXPECT_TRUE(validate(c));
  c.idle_after_s = 0;
  EXPECT_NE(why_not(validate(c)).find("idle_after_s"), std::string::npos);
  EXPECT_THROW(KioskStates(c, 0), std::invalid_argument);
  c = {};
  c.dead_band_screen_units = -1;
  EXPECT_NE(why_not(validate(c)).find("dead_band_screen_units"), std::string::npos);
  c = {};
  c.lost_hint_after_s = std::nan("");
  EXPECT_NE(why_not(validate(c)).find("lost_hint_after_s"), std::string::npos);
  c = {};
  c.close_notice_s = 1e300;
  EXPECT_NE(why_not(validate(c)).find("close_notice_s"), std::string::npos);
  EXPECT_STREQ(to_string(S::operator_page), "operator");
}

TEST(KioskStates, ALostRemoteEndsPlayAtOnceAndSaysSoUntilItIsBack) {
  KioskStates k({}, kStart);
  k.input_source(kStart, InputSource::wiimote);
  k.pointer(kStart + kMs, {0.5, 0.5});
  k.pointer(kStart + 2 * kMs, {0.6, 0.5});
  ASSERT_EQ(k.state(), S::play);
  EXPECT_TRUE(k.remote_connected(kStart + 3 * kMs, false));
  EXPECT_EQ(k.state(), S::attract);
  EXPECT_FALSE(k.tracking());
  EXPECT_TRUE(k.overlay().remote_missing);
  EXPECT_EQ(k.hint(), KioskHint::remote_missing);
  EXPECT_EQ(hint_text(KioskHint::remote_missing), "To play, please ask a member of staff");
  // The operator page says the link itself; the hint comes back with Attract.
  k.operator_chord(kStart + 4 * kMs);
  EXPECT_FALSE(k.overlay().remote_missing);
  k.operator_page_closed(kStart + 5 * kMs);
  EXPECT_EQ(k.state(), S::play);
  EXPECT_TRUE(k.overlay().remote_missing);
  // Back: the invitation again once Attract returns, no Play without movement.
  EXPECT_FALSE(k.remote_connected(kStart + 6 * kMs, true));
  EXPECT_FALSE(k.overlay().remote_missing);
  k.tick(kStart + 6 * kMs + 45 * kNanosPerSecond);
  EXPECT_EQ(k.hint(), KioskHint::invitation);
}

TEST(KioskStates, ALostCameraIsALostRemote) {
  // The V4L2 camera is the IR tracker in the remote's place: unplugged, the mallet rests.
  KioskStates k({}, kStart);
  k.input_source(kStart, InputSource::camera);
  EXPECT_FALSE(k.tracking());  // a camera, like the remote, tracks only once it sees the LED
  k.pointer(kStart + kMs, {0.5, 0.5});
  k.pointer(kStart + 2 * kMs, {0.6, 0.5});
  ASSERT_EQ(k.state(), S::play);
  EXPECT_TRUE(k.remote_connected(kStart + 3 * kMs, false));
  EXPECT_EQ(k.state(), S::attract);
  EXPECT_EQ(k.hint(), KioskHint::remote_missing);
  k.remote_connected(kStart + 4 * kMs, true);
  EXPECT_FALSE(k.overlay().remote_missing);
  EXPECT_TRUE(live_ir_tracker(InputSource::camera));
  EXPECT_FALSE(live_ir_tracker(InputSource::replay));
  EXPECT_FALSE(live_ir_tracker(InputSource::mouse));
}

TEST(KioskStates, TheMouseHasNoRemoteToMiss) {
  KioskStates k({}, kStart);
  k.input_source(kStart, InputSource::mouse);
  k.pointer(kStart + kMs, {0.5, 0.5});
  k.pointer(kStart + 2 * kMs, {0.6, 0.5});
  EXPECT_FALSE(k.remote_connected(kStart + 3 * kMs, false));
  EXPECT_EQ(k.state(), S::play);
  EXPECT_FALSE(k.overlay().remote_missing);
}

}  // namespace
}  // namespace mallet
