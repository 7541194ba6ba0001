// The ghost player's scripted path, fed through the contact solver exactly as the kiosk
// feeds a hand: every scripted strike is one impact on its bar, at its time and speed,
// at any pointer rate; strikes scheduled too close together still sound once each, in
// order, as soon as the hand can get there.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/config/scene_config.hpp"
#include "core/ghost_player.hpp"
#include "core/mallet.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

using test::kDay;
using test::kMicrosecond;
using test::percussion;

struct Played {
  std::vector<PointerSample> path;
  std::vector<Nanos> contacts;  //!< what the ghost player says it played
  std::vector<Impact> impacts;
  Mallet::Counters counters;
};

//! The ghost's path for `strikes` at `rate_hz`, fed to a fresh solver; the path is in
//! world metres (the sphere centre), as ghost_player documents.
Played play(const Scene& scene, const std::vector<ScriptedStrike>& strikes, double rate_hz,
            const GhostPlayerStyle& style = {}) {
  Played p;
  GhostPath ghost = ghost_player(scene, strikes, rate_hz, style);
  p.path = std::move(ghost.samples);
  p.contacts = std::move(ghost.contacts);
  Mallet mallet(scene, ContactConfig{});
  for (const PointerSample& s : p.path)
    if (auto impact = mallet.update(s.t_ns, {s.x, s.y})) p.impacts.push_back(*impact);
  p.counters = mallet.counters();
  return p;
}

std::string describe(const ScriptedStrike& s) {
  std::ostringstream o;
  o << "target " << s.target << " at " << s.t_ns << " ns, " << s.speed_m_per_s << " m/s";
  return o.str();
}

//! The path is a pointer at `rate_hz`: finite, and one period (to the ns) between samples.
void expect_sampled_at(const std::vector<PointerSample>& path, double rate_hz) {
  ASSERT_FALSE(path.empty());
  const double period_ns = 1e9 / rate_hz;
  for (std::size_t i = 0; i < path.size(); ++i) {
    ASSERT_TRUE(std::isfinite(path[i].x) && std::isfinite(path[i].y)) << i;
    if (i > 0) {
      ASSERT_NEAR(static_cast<double>(path[i].t_ns - path[i - 1].t_ns), period_ns, 1.0) << i;
    }
  }
}

TEST(GhostPlayer, EveryScriptedStrikeIsOneImpactAtItsTimeAndSpeed) {
  const Scene& scene = percussion();
  // Both instruments, both ends of each, neighbours, the same bar twice, long jumps.
  const std::vector<int> targets = {0, 5, 7, 8, 11, 15, 15, 3, 12, 1};
  const std::vector<double> speeds = {0.5, 1.0, 1.7, 2.5, 3.6, 5.0};
  std::mt19937_64 rng(8);
  std::uniform_int_distribution<Nanos> jitter(0, 500'000'000);
  for (Nanos boot : {Nanos{0}, 30 * kDay}) {
    for (double rate : {30.0, 60.0, 100.0, 1000.0}) {
      for (std::size_t rotation = 0; rotation < speeds.size(); ++rotation) {
        // 3 s apart (plus up to 0.5 s) leaves time to lift and travel even at 5 m/s and
        // 30 Hz, where approach and follow-through are two sample intervals (1/3 m) long.
        std::vector<ScriptedStrike> script;
        for (std::size_t i = 0; i < targets.size(); ++i)
          script.push_back({targets[i], boot + 10 * kNanosPerSecond + static_cast<Nanos>(i) * 3 * kNanosPerSecond + jitter(rng),
                            speeds[(i + rotation) % speeds.size()]});
        const Played p = play(scene, script, rate);
        const std::string ctx = "rate " + std::to_string(rate) + " Hz, boot " + std::to_string(boot) + " ns";
        expect_sampled_at(p.path, rate);
        EXPECT_EQ(p.counters.ignored_non_finite, 0u) << ctx;
        EXPECT_EQ(p.counters.ignored_not_after_previous, 0u) << ctx;
        EXPECT_EQ(p.counters.touches_below_min_speed, 0u) << ctx;
        EXPECT_EQ(p.counters.clamped_speed, 0u) << ctx;
        ASSERT_EQ(p.impacts.size(), script.size()) << ctx;
        for (std::size_t i = 0; i < script.size(); ++i) {
          const ScriptedStrike& want = script[i];
          const Impact& got = p.impacts[i];
          const Target& bar = scene.targets[static_cast<std::size_t>(want.target)];
          EXPECT_EQ(got.target, want.target) << ctx << ", " << describe(want);
          EXPECT_EQ(got.note, bar.note) << ctx << ", " << describe(want);
          EXPECT_LT(std::llabs(got.t_ns - want.t_ns), kMicrosecond)
              << ctx << ", " << describe(want) << ": got " << got.t_ns;
          EXPECT_LE(std::fabs(got.speed_m_per_s - want.speed_m_per_s), 1e-6 * want.speed_m_per_s)
              << ctx << ", " << describe(want) << ": got " << got.speed_m_per_s;
          // The ghost strikes on the bar's top face.
          EXPECT_GE(got.x_m, bar.x_min) << ctx << ", " << describe(want);
          EXPECT_LE(got.x_m, bar.x_max) << ctx << ", " << describe(want);
        }
      }
    }
  }
}

TEST(GhostPlayer, OneStrikeAtAnyPhaseOfTheSamplingGrid) {
  // A single strike whose time falls anywhere relative to the ghost's sample grid.
  const Scene& scene = percussion();
  std::mt19937_64 rng(99);
  std::uniform_int_distribution<Nanos> offset(0, kNanosPerSecond);
  for (double rate : {30.0, 60.0, 100.0, 1000.0}) {
    for (double v : {0.5, 0.8, 2.0, 5.0}) {
      for (int trial = 0; trial < 20; ++trial) {
        const ScriptedStrike strike{trial % 16, 2 * kNanosPerSecond + offset(rng), v};
        const Played p = play(scene, {strike}, rate);
        ASSERT_EQ(p.impacts.size(), 1u) << rate << " Hz, " << describe(strike);
        EXPECT_EQ(p.impacts[0].target, strike.target);
        EXPECT_LT(std::llabs(p.impacts[0].t_ns - strike.t_ns), kMicrosecond) << rate << " Hz, " << describe(strike);
        EXPECT_LE(std::fabs(p.impacts[0].speed_m_per_s - v), 1e-6 * v) << rate << " Hz, " << describe(strike);
      }
    }
  }
}

//! The earliest the ghost can strike `next` after striking `prev` at `prev_contact`, from
//! its documented motion: follow through below the surface at the strike speed, lift to
//! the hover height at the lift speed, travel to the next bar at 1 m/s, come down at the
//! next strike speed. (At high rates hover and follow-through are exactly the style's.)
Nanos earliest_next_contact(const Scene& scene, const GhostPlayerStyle& style, Nanos prev_contact,
                            const ScriptedStrike& prev, const ScriptedStrike& next) {
  const Target& a = scene.targets[static_cast<std::size_t>(prev.target)];
  const Target& b = scene.targets[static_cast<std::size_t>(next.target)];
  const double travel_m = std::fabs(0.5 * (b.x_min + b.x_max) - 0.5 * (a.x_min + a.x_max));
  const double seconds = style.follow_through_m / prev.speed_m_per_s +
                         (style.follow_through_m + style.hover_height_m) / style.lift_speed_m_per_s +
                         travel_m / 1.0 + style.hover_height_m / next.speed_m_per_s;
  return prev_contact + static_cast<Nanos>(std::llround(seconds * 1e9));
}

TEST(GhostPlayer, StrikesScheduledTooCloseStillSoundOnceEachInOrder) {
  const Scene& scene = percussion();
  const GhostPlayerStyle style;
  const Nanos t0 = 5 * kNanosPerSecond + 123'456;
  // All at once, 50 ms apart, and 0.4 s apart (still too little to lift and travel);
  // the same bar repeated and far jumps.
  for (Nanos spacing : {Nanos{0}, Nanos{50'000'000}, Nanos{400'000'000}}) {
    for (double rate : {30.0, 60.0, 100.0, 1000.0}) {
      const std::vector<int> targets = {2, 2, 13, 0, 9, 6};
      const std::vector<double> speeds = {1.0, 2.0, 0.5, 1.5, 0.75, 1.25};
      std::vector<ScriptedStrike> script;
      for (std::size_t i = 0; i < targets.size(); ++i)
        script.push_back({targets[i], t0 + static_cast<Nanos>(i) * spacing, speeds[i]});
      const Played p = play(scene, script, rate, style);
      const std::string ctx = "spacing " + std::to_string(spacing) + " ns, rate " + std::to_string(rate) + " Hz";
      expect_sampled_at(p.path, rate);
      ASSERT_EQ(p.impacts.size(), script.size()) << ctx;
      // The first is on time; every later one is as soon as the hand can get there.
      EXPECT_LT(std::llabs(p.impacts[0].t_ns - script[0].t_ns), kMicrosecond) << ctx;
      ASSERT_EQ(p.contacts.size(), script.size()) << ctx;
      for (std::size_t i = 0; i < script.size(); ++i) {
        EXPECT_EQ(p.impacts[i].target, script[i].target) << ctx << ", strike " << i;
        // The reported contact time is the one the solver finds (late strikes included).
        EXPECT_LT(std::llabs(p.impacts[i].t_ns - p.contacts[i]), kMicrosecond) << ctx << ", strike " << i;
        EXPECT_GE(p.impacts[i].t_ns, script[i].t_ns - kMicrosecond) << ctx << ", strike " << i << ": never early";
        EXPECT_LE(std::fabs(p.impacts[i].speed_m_per_s - script[i].speed_m_per_s), 1e-6 * script[i].speed_m_per_s)
            << ctx << ", strike " << i;
        if (i == 0) continue;
        EXPECT_GT(p.impacts[i].t_ns, p.impacts[i - 1].t_ns) << ctx << ", strike " << i << ": in order";
        const Nanos earliest = earliest_next_contact(scene, style, p.impacts[i - 1].t_ns, script[i - 1], script[i]);
        EXPECT_GE(p.impacts[i].t_ns, earliest - kMicrosecond) << ctx << ", strike " << i;
        // At 1000 Hz with these speeds the approach and follow-through are exactly the
        // style's, so "as soon as it can" is exactly the earliest time.
        if (rate == 1000.0 && script[i].t_ns < earliest) {
          EXPECT_LT(std::llabs(p.impacts[i].t_ns - earliest), kMicrosecond) << ctx << ", strike " << i;
        }
      }
    }
  }
}

TEST(GhostPlayer, NoStrikesNoPath) {
  EXPECT_TRUE(ghost_player(percussion(), {}, 60.0).samples.empty());
  EXPECT_TRUE(ghost_player(percussion(), {{0, kNanosPerSecond, 1.0}}, 0.0).samples.empty());
}

}  // namespace
}  // namespace mallet
