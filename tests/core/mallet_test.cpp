// The contact solver against geometry: straight-line strikes at any speed and pointer
// rate give exactly one impact at the analytic contact time and speed; jitter, edges,
// gaps, sideways entries, clamping, bad samples and 30 days of uptime behave as the
// contact model in core/mallet.hpp documents.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/config/scene_config.hpp"
#include "core/mallet.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

using test::kDay;
using test::kMicrosecond;
using test::percussion;

//! The sphere centre's height when its bottom meets the top of `target`.
double contact_plane(const Scene& scene, int target) {
  return scene.targets.at(static_cast<std::size_t>(target)).top_y + scene.mallet_radius_m;
}

double centre_x(const Target& t) { return 0.5 * (t.x_min + t.x_max); }

//! One hand sample as the kiosk feeds it to the solver.
struct HandSample {
  Nanos t;
  Vec2 hand;
};

struct FeedResult {
  std::vector<Impact> impacts;
  bool all_finite = true;  //!< every impact field and every displayed centre was finite
};

bool finite(Vec2 v) { return std::isfinite(v.x) && std::isfinite(v.y); }

//! Feeds every sample to `mallet`, collecting impacts and checking nothing non-finite
//! comes out (the displayed centre is checked for the finite hands only: it is a pure
//! function of the hand).
FeedResult feed(Mallet& mallet, const std::vector<HandSample>& samples) {
  FeedResult r;
  for (const HandSample& s : samples) {
    if (auto impact = mallet.update(s.t, s.hand)) {
      r.all_finite = r.all_finite && std::isfinite(impact->speed_m_per_s) && std::isfinite(impact->x_m);
      r.impacts.push_back(*impact);
    }
    if (finite(s.hand)) r.all_finite = r.all_finite && finite(mallet.displayed_centre(s.hand));
  }
  return r;
}

//! Sample times of a pointer running at `rate_hz` whose grid is shifted by `phase` (a
//! fraction of one period, 0..1) from `origin`: origin + round((k + phase) / rate), every
//! such time in [from, to].
std::vector<Nanos> sample_times(Nanos origin, double rate_hz, double phase, Nanos from, Nanos to) {
  const double period_ns = 1e9 / rate_hz;
  auto at = [&](long long k) {
    return origin + static_cast<Nanos>(std::llround((static_cast<double>(k) + phase) * period_ns));
  };
  long long k = static_cast<long long>(std::floor(static_cast<double>(from - origin) / period_ns)) - 1;
  std::vector<Nanos> out;
  for (; at(k) <= to; ++k)
    if (at(k) >= from) out.push_back(at(k));
  return out;
}

//! A straight-line motion of the sphere centre through `contact` at `t_contact`.
struct Line {
  Vec2 contact;
  Vec2 velocity;  //!< m/s; velocity.y < 0 goes down
  Nanos t_contact;

  //! Exact position at t: the time difference is an integer, converted once.
  Vec2 at(Nanos t) const {
    const double s = to_seconds(t - t_contact);
    return {contact.x + velocity.x * s, contact.y + velocity.y * s};
  }
};

//! Samples of `line` taken by a pointer at `rate_hz` with grid phase `phase`, from
//! `above_m` above the contact to `below_m` below it — but always at least two periods on
//! each side, so that the contact lies strictly inside the sampled stretch.
std::vector<HandSample> sample_line(const Line& line, double rate_hz, double phase, double above_m = 0.05,
                                    double below_m = 0.01, Nanos grid_origin = 0) {
  const double vy = std::fabs(line.velocity.y);
  const double period_s = 1.0 / rate_hz;
  const auto before = static_cast<Nanos>(std::llround(std::max(above_m / vy, 2 * period_s) * 1e9));
  const auto after = static_cast<Nanos>(std::llround(std::max(below_m / vy, 2 * period_s) * 1e9));
  std::vector<HandSample> out;
  for (Nanos t : sample_times(grid_origin, rate_hz, phase, line.t_contact - before, line.t_contact + after))
    out.push_back({t, line.at(t)});
  return out;
}

//! "Strike straight down at speed v on x, sampled at rate r with phase φ": the sphere
//! falls vertically and its bottom meets the bar top (centre at `plane_y`) at t_contact.
std::vector<HandSample> strike_down(double x, double plane_y, double v, Nanos t_contact, double rate_hz,
                                    double phase, double above_m = 0.05, double below_m = 0.01,
                                    Nanos grid_origin = 0) {
  return sample_line({{x, plane_y}, {0.0, -v}, t_contact}, rate_hz, phase, above_m, below_m, grid_origin);
}

//! Samples at `rate_hz` of a linear move from the last sample's position to `to`, ending at
//! `t_end` (times strictly after the last sample).
void move_to(std::vector<HandSample>& path, Vec2 to, Nanos t_end, double rate_hz) {
  const HandSample from = path.back();
  const Line line{to, {(to.x - from.hand.x) / to_seconds(t_end - from.t), (to.y - from.hand.y) / to_seconds(t_end - from.t)},
                  t_end};
  for (Nanos t : sample_times(from.t, rate_hz, 0.0, from.t + 1, t_end)) path.push_back({t, line.at(t)});
  if (path.back().t != t_end) path.push_back({t_end, to});
}

void append(std::vector<HandSample>& path, const std::vector<HandSample>& more) {
  path.insert(path.end(), more.begin(), more.end());
}

std::string where(int target, double v, double rate, double phase) {
  std::ostringstream s;
  s << "target " << target << ", v " << v << " m/s, rate " << rate << " Hz, phase " << phase;
  return s.str();
}

// --- 1. straight-line strikes --------------------------------------------------------

TEST(MalletStrike, StraightDownAtAnySpeedAndRateIsOneExactImpact) {
  const Scene& scene = percussion();
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> phase_dist(0.0, 1.0);
  std::uniform_int_distribution<Nanos> offset_dist(0, 999'999'999);
  for (const Target& bar : scene.targets) {
    const double plane = contact_plane(scene, bar.id);
    for (double v : {0.05, 0.3, 1.0, 3.0, 8.0}) {
      for (double rate : {30.0, 60.0, 100.0, 250.0, 500.0, 1000.0}) {
        for (int trial = 0; trial < 3; ++trial) {
          const double phase = phase_dist(rng);
          // A contact time that is not a whole number of anything.
          const Nanos t_contact = 5 * kNanosPerSecond + offset_dist(rng);
          Mallet mallet(scene, ContactConfig{});
          const FeedResult r = feed(mallet, strike_down(centre_x(bar), plane, v, t_contact, rate, phase));
          const std::string ctx = where(bar.id, v, rate, phase);
          ASSERT_EQ(r.impacts.size(), 1u) << ctx;
          const Impact& hit = r.impacts[0];
          EXPECT_EQ(hit.target, bar.id) << ctx;
          EXPECT_EQ(hit.note, bar.note) << ctx;
          EXPECT_EQ(hit.material, bar.material) << ctx;
          EXPECT_LT(std::llabs(hit.t_ns - t_contact), kMicrosecond) << ctx << ": got " << hit.t_ns << " want " << t_contact;
          EXPECT_LE(std::fabs(hit.speed_m_per_s - v), 1e-9 * v) << ctx << ": got " << hit.speed_m_per_s;
          EXPECT_DOUBLE_EQ(hit.x_m, centre_x(bar)) << ctx;
          EXPECT_TRUE(r.all_finite) << ctx;
          EXPECT_EQ(mallet.counters().impacts, 1u) << ctx;
          EXPECT_FALSE(mallet.armed()) << ctx << ": the hand ends below the surface";
        }
      }
    }
  }
}

TEST(MalletStrike, ObliqueStrikeUsesTheNormalSpeedAndTheCrossingPoint) {
  // Moving sideways while descending: the impact speed is the downward component only,
  // and the impact x is where the line crosses the contact plane.
  const Scene& scene = percussion();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> phase_dist(0.0, 1.0);
  for (int id : {1, 6, 9, 14}) {
    const Target& bar = scene.targets[static_cast<std::size_t>(id)];
    for (double vx : {-0.4, 0.25}) {
      for (double vy : {0.3, 2.0}) {
        for (double rate : {60.0, 250.0, 1000.0}) {
          const double phase = phase_dist(rng);
          const Nanos t_contact = 2 * kNanosPerSecond + 123'457;
          // Short excursions keep the whole line above the bar's own zone.
          const Line line{{centre_x(bar), contact_plane(scene, id)}, {vx, -vy}, t_contact};
          Mallet mallet(scene, ContactConfig{});
          const FeedResult r = feed(mallet, sample_line(line, rate, phase, 0.006, 0.003));
          const std::string ctx = where(id, vy, rate, phase) + ", vx " + std::to_string(vx);
          ASSERT_EQ(r.impacts.size(), 1u) << ctx;
          EXPECT_EQ(r.impacts[0].target, id) << ctx;
          EXPECT_LT(std::llabs(r.impacts[0].t_ns - t_contact), kMicrosecond) << ctx;
          EXPECT_LE(std::fabs(r.impacts[0].speed_m_per_s - vy), 1e-9 * vy) << ctx;
          // The crossing x is exact up to the ns rounding of the impact time.
          EXPECT_NEAR(r.impacts[0].x_m, centre_x(bar), 1e-9) << ctx;
        }
      }
    }
  }
}

// --- 2. jitter and re-arming ---------------------------------------------------------

TEST(MalletRearm, JitterAroundTheSurfaceAfterAStrikeIsNoSecondStrike) {
  const Scene& scene = percussion();
  const ContactConfig config;
  ASSERT_GT(config.rearm_height_m, 0.001) << "the jitter below must stay under the re-arm height";
  for (int id : {2, 11}) {
    const Target& bar = scene.targets[static_cast<std::size_t>(id)];
    const double plane = contact_plane(scene, id);
    for (double rate : {60.0, 1000.0}) {
      std::mt19937_64 rng(static_cast<unsigned>(id * 1000 + static_cast<int>(rate)));
      std::uniform_real_distribution<double> noise(-0.001, 0.001);
      const Nanos t1 = 1 * kNanosPerSecond;
      std::vector<HandSample> path = strike_down(centre_x(bar), plane, 1.0, t1, rate, 0.37, 0.05, 0.0005);
      // The hand rests on the bar for 4 s: ±1 mm around the surface, both ways across it.
      const Nanos rest_end = path.back().t + 4 * kNanosPerSecond;
      for (Nanos t : sample_times(path.back().t, rate, 0.0, path.back().t + 1, rest_end))
        path.push_back({t, {centre_x(bar) + noise(rng), plane + noise(rng)}});
      Mallet mallet(scene, config);
      FeedResult r = feed(mallet, path);
      ASSERT_EQ(r.impacts.size(), 1u) << "rate " << rate;
      EXPECT_LT(std::llabs(r.impacts[0].t_ns - t1), kMicrosecond);
      EXPECT_FALSE(mallet.armed());

      // Lifting clear of the re-arm height and striking again is a second strike.
      std::vector<HandSample> again;
      again.push_back(path.back());
      move_to(again, {centre_x(bar), plane + 0.05}, rest_end + kNanosPerSecond / 2, rate);
      const Nanos t2 = rest_end + 2 * kNanosPerSecond;
      append(again, strike_down(centre_x(bar), plane, 0.7, t2, rate, 0.81, 0.05, 0.01, rest_end));
      again.erase(again.begin());  // already fed
      r = feed(mallet, again);
      ASSERT_EQ(r.impacts.size(), 1u) << "rate " << rate;
      EXPECT_EQ(r.impacts[0].target, id);
      EXPECT_LT(std::llabs(r.impacts[0].t_ns - t2), kMicrosecond);
      EXPECT_LE(std::fabs(r.impacts[0].speed_m_per_s - 0.7), 1e-9);
      EXPECT_EQ(mallet.counters().impacts, 2u);
    }
  }
}

TEST(MalletRearm, RearmsExactlyAtTheRearmHeight) {
  // After a strike, rising to just under plane + rearm_height_m and coming down again is
  // no strike; rising to plane + rearm_height_m is.
  const Scene& scene = percussion();
  const ContactConfig config;
  const int id = 4;
  const double x = centre_x(scene.targets[id]);
  const double plane = contact_plane(scene, id);
  const double rate = 100.0;
  const Nanos period = 10'000'000;
  Mallet mallet(scene, config);
  ASSERT_EQ(feed(mallet, strike_down(x, plane, 0.5, kNanosPerSecond, rate, 0.5)).impacts.size(), 1u);
  Nanos t = kNanosPerSecond + 100 * period;

  // Up to 99.9 % of the re-arm height (one sample), then down through the plane.
  t += period;
  EXPECT_FALSE(mallet.update(t, {x, plane + 0.999 * config.rearm_height_m}));
  EXPECT_FALSE(mallet.armed());
  t += period;
  EXPECT_FALSE(mallet.update(t, {x, plane - 0.001})) << "the hand never rose clear of the surface";
  EXPECT_EQ(mallet.counters().touches_below_min_speed, 0u) << "disarmed: not even a touch";

  // Up to exactly the re-arm height: armed; down through the plane again: a strike.
  t += period;
  EXPECT_FALSE(mallet.update(t, {x, plane + config.rearm_height_m}));
  EXPECT_TRUE(mallet.armed());
  t += period;
  const auto hit = mallet.update(t, {x, plane - config.rearm_height_m});
  ASSERT_TRUE(hit);
  // Half way down the segment: a symmetric crossing.
  EXPECT_LE(std::llabs(hit->t_ns - (t - period / 2)), 1);
  EXPECT_NEAR(hit->speed_m_per_s, 2 * config.rearm_height_m / 0.01, 1e-12);
}

TEST(MalletRearm, SlidingAlongTheBarsIsNoStrike) {
  // After a strike the hand slides across the whole xylophone, just below and then just
  // above the surface (under the re-arm height): the zones are contiguous, so no strike.
  const Scene& scene = percussion();
  const double plane = contact_plane(scene, 0);
  const Target& first = scene.targets[0];
  const Target& last = scene.targets[7];
  ASSERT_EQ(first.instrument, last.instrument);
  for (double dy : {-0.001, 0.001}) {
    Mallet mallet(scene, ContactConfig{});
    std::vector<HandSample> path = strike_down(centre_x(first), plane, 1.0, kNanosPerSecond, 250.0, 0.2, 0.05, 0.0);
    move_to(path, {centre_x(first), plane + dy}, path.back().t + 100'000'000, 250.0);
    move_to(path, {centre_x(last), plane + dy}, path.back().t + 2 * kNanosPerSecond, 250.0);
    move_to(path, {centre_x(first), plane + dy}, path.back().t + 2 * kNanosPerSecond, 250.0);
    const FeedResult r = feed(mallet, path);
    EXPECT_EQ(r.impacts.size(), 1u) << "dy " << dy;
    EXPECT_EQ(mallet.counters().touches_below_min_speed, 0u) << "dy " << dy;
  }
}

// --- 3. a sample exactly on the contact plane ----------------------------------------

TEST(MalletStrike, SampleExactlyOnThePlaneIsOneImpactAtThatSample) {
  const Scene& scene = percussion();
  const int id = 10;
  const double x = centre_x(scene.targets[id]);
  const double plane = contact_plane(scene, id);
  const Nanos period = 10'000'000;  // 100 Hz
  const double step = 0.002;        // 2 mm per sample: 0.2 m/s
  // The next sample after the one on the plane: still on it, a hair below, 1 mm below.
  for (double next_dy : {0.0, -1e-12, -0.001}) {
    Mallet mallet(scene, ContactConfig{});
    std::vector<Impact> impacts;
    Nanos t = 3 * kNanosPerSecond;
    for (int k = 5; k >= 1; --k, t += period)
      if (auto hit = mallet.update(t, {x, plane + k * step})) impacts.push_back(*hit);
    const Nanos t_on_plane = t;
    if (auto hit = mallet.update(t_on_plane, {x, plane})) impacts.push_back(*hit);
    if (auto hit = mallet.update(t_on_plane + period, {x, plane + next_dy})) impacts.push_back(*hit);
    if (auto hit = mallet.update(t_on_plane + 2 * period, {x, plane + next_dy})) impacts.push_back(*hit);
    ASSERT_EQ(impacts.size(), 1u) << "next dy " << next_dy;
    EXPECT_EQ(impacts[0].t_ns, t_on_plane);
    EXPECT_EQ(impacts[0].target, id);
    EXPECT_LE(std::fabs(impacts[0].speed_m_per_s - step / 0.01), 1e-9 * step / 0.01);
    EXPECT_EQ(mallet.displayed_centre({x, plane + next_dy}).y, plane);
  }
}

// --- 4. edges and gaps ---------------------------------------------------------------

//! Strikes straight down at x on the shipped scene (1 m/s, 250 Hz) and returns the impacts.
std::vector<Impact> strike_at(double x, Mallet& mallet, const Scene& scene) {
  return feed(mallet, strike_down(x, contact_plane(scene, 0), 1.0, kNanosPerSecond, 250.0, 0.4)).impacts;
}

std::optional<int> struck_target(double x, const Scene& scene = percussion()) {
  Mallet mallet(scene, ContactConfig{});
  const auto impacts = strike_at(x, mallet, scene);
  EXPECT_LE(impacts.size(), 1u) << "x " << x;
  if (impacts.empty()) return std::nullopt;
  return impacts[0].target;
}

TEST(MalletEdges, SceneIsAsTheseTestsAssume) {
  // The geometry the edge tests rely on: two rows of 8 bars at one height, a gap
  // narrower than 2r inside each instrument and one far wider between them.
  const Scene& scene = percussion();
  ASSERT_EQ(scene.targets.size(), 16u);
  const double r = scene.mallet_radius_m;
  for (std::size_t i = 0; i + 1 < scene.targets.size(); ++i) {
    const Target& a = scene.targets[i];
    const Target& b = scene.targets[i + 1];
    EXPECT_EQ(a.top_y, b.top_y);
    EXPECT_LT(a.x_max, b.x_min);
    if (a.instrument == b.instrument) {
      EXPECT_LT(b.x_min - a.x_max, 2 * r);
    }
  }
  EXPECT_NEAR(scene.targets[7].x_max, 0.004, 1e-12);
  EXPECT_NEAR(scene.targets[8].x_min, 0.09, 1e-12);
  EXPECT_GT(scene.targets[8].x_min - scene.targets[7].x_max, 2 * r);
}

TEST(MalletEdges, SphereTouchingABarCornerStrikesThatBar) {
  // Centre outside the bar's x range but within r of it: the sphere's edge meets the
  // corner. Beyond r it misses (at the instruments' outer ends there is no other bar).
  const Scene& scene = percussion();
  const double r = scene.mallet_radius_m;
  for (int id : {0, 7, 8, 15}) {
    const Target& bar = scene.targets[static_cast<std::size_t>(id)];
    const bool left_end = id == 0 || id == 8;
    const double edge = left_end ? bar.x_min : bar.x_max;
    const double out = left_end ? -1.0 : 1.0;
    EXPECT_EQ(struck_target(edge + out * 0.5 * r), id);
    EXPECT_EQ(struck_target(edge + out * 0.999 * r), id);
    EXPECT_EQ(struck_target(edge + out * 1.001 * r), std::nullopt) << "bar " << id;
  }
}

TEST(MalletEdges, InAGapBetweenBarsTheNearerBarIsStruckAndTheMidpointGoesRight) {
  const Scene& scene = percussion();
  for (std::size_t i = 0; i + 1 < scene.targets.size(); ++i) {
    const Target& a = scene.targets[i];
    const Target& b = scene.targets[i + 1];
    if (a.instrument != b.instrument) continue;
    const double gap = b.x_min - a.x_max;
    const double mid = 0.5 * (a.x_max + b.x_min);
    EXPECT_EQ(struck_target(a.x_max), a.id);
    EXPECT_EQ(struck_target(a.x_max + 0.25 * gap), a.id);
    EXPECT_EQ(struck_target(std::nextafter(mid, -1.0)), a.id) << "just left of the midpoint";
    EXPECT_EQ(struck_target(mid), b.id) << "the midpoint belongs to the bar on the right";
    EXPECT_EQ(struck_target(a.x_max + 0.75 * gap), b.id);
    EXPECT_EQ(struck_target(b.x_min), b.id);
  }
}

//! Sweeps each instrument of `scene` (plus r beyond both ends) in 0.1 mm steps: exactly
//! one zone contains x, it is the nearest bar of the whole scene (with a big head the
//! other instrument's end may be nearer; a tie, the gap's midpoint, goes right), zone_at
//! agrees, and a strike straight down at x sounds that bar.
void expect_every_x_names_the_nearest_bar(const Scene& scene) {
  Mallet mallet(scene, ContactConfig{});
  const double r = scene.mallet_radius_m;
  for (const Instrument& inst : scene.instruments) {
    const Target& first = scene.targets[static_cast<std::size_t>(inst.targets.front())];
    const Target& last = scene.targets[static_cast<std::size_t>(inst.targets.back())];
    int failures = 0;
    for (double x = first.x_min - 0.99 * r; x <= last.x_max + 0.99 * r && failures < 5; x += 0.0001) {
      int nearest = -1;
      double best = std::numeric_limits<double>::infinity();
      for (const Target& t : scene.targets) {  // in x order: `<=` sends a tie right
        const double d = std::max({t.x_min - x, x - t.x_max, 0.0});
        if (d <= best) {
          best = d;
          nearest = t.id;
        }
      }
      std::vector<int> containing;
      for (const ContactZone& z : mallet.zones())
        if (z.contains(x)) containing.push_back(z.target);
      const ContactZone* z = mallet.zone_at({x, 0.0});
      const std::optional<int> struck = struck_target(x, scene);
      const bool ok = containing == std::vector<int>{nearest} && z && z->target == nearest && struck == nearest;
      if (!ok) ++failures;
      EXPECT_TRUE(ok) << inst.name << ", r " << r << ", x " << x << ": nearest bar " << nearest << ", "
                      << containing.size() << " zones contain x (first " << (containing.empty() ? -1 : containing[0])
                      << "), zone_at " << (z ? z->target : -1) << ", strike sounds " << struck.value_or(-1);
    }
  }
}

TEST(MalletEdges, EveryXOnAnInstrumentNamesExactlyOneBarTheNearest) {
  expect_every_x_names_the_nearest_bar(percussion());
}

TEST(MalletEdges, EveryXNamesTheNearestBarForAnyMalletHead) {
  // The contact model holds for any mallet_radius_m a scene file may set: "every x inside
  // an instrument names exactly one bar". From r = 37 mm on the glockenspiel (53 mm on
  // the xylophone), r exceeds a bar plus one and a half gaps, so the widened zones of bars
  // two apart overlap too, not only those of neighbours.
  for (double r : {0.006, 0.020, 0.030, 0.040, 0.060}) {
    Scene scene = percussion();
    scene.mallet_radius_m = r;
    expect_every_x_names_the_nearest_bar(scene);
  }
}

TEST(MalletEdges, TheGapBetweenTheInstrumentsLetsTheMalletPass) {
  const Scene& scene = percussion();
  const double r = scene.mallet_radius_m;
  const double xylophone_end = scene.targets[7].x_max;
  const double glockenspiel_start = scene.targets[8].x_min;
  for (double x : {0.5 * (xylophone_end + glockenspiel_start), xylophone_end + 1.001 * r,
                   glockenspiel_start - 1.001 * r}) {
    Mallet mallet(scene, ContactConfig{});
    // All the way down, 5 cm below the bars' tops.
    const auto path = strike_down(x, contact_plane(scene, 7), 1.0, kNanosPerSecond, 250.0, 0.3, 0.05, 0.065);
    const FeedResult result = feed(mallet, path);
    EXPECT_TRUE(result.impacts.empty()) << "x " << x;
    EXPECT_EQ(mallet.counters().touches_below_min_speed, 0u);
    EXPECT_TRUE(mallet.armed()) << "nothing was touched";
    for (const HandSample& s : path) EXPECT_EQ(mallet.displayed_centre(s.hand), s.hand) << "nothing to rest on";
  }
}

TEST(MalletEdges, EnteringABarSidewaysFromBelowIsNoStrikeAndTheSphereIsHeldOnTop) {
  const Scene& scene = percussion();
  const double gap_mid = 0.5 * (scene.targets[7].x_max + scene.targets[8].x_min);
  // The height of the sideways move relative to the contact plane: under the bar's top
  // (-20 mm), between the top and the plane (-5 mm), and exactly on the plane (touching).
  for (const auto& [into, dy] : {std::pair{8, -0.020}, std::pair{7, -0.020}, std::pair{8, -0.005}, std::pair{15, 0.0}}) {
    const Target& bar = scene.targets[static_cast<std::size_t>(into)];
    const double plane = contact_plane(scene, into);
    const double below = plane + dy;
    // Down through a gap (between the instruments, or past the glockenspiel's right end)
    // to `below`, then sideways at that height onto the bar, 250 Hz.
    const double gap_x = into == 15 ? bar.x_max + 2 * scene.mallet_radius_m : gap_mid;
    std::vector<HandSample> path = strike_down(gap_x, plane, 1.0, kNanosPerSecond, 250.0, 0.0, 0.05, 0.02);
    path.back().hand.y = below;
    move_to(path, {centre_x(bar), below}, path.back().t + kNanosPerSecond, 250.0);
    Mallet mallet(scene, ContactConfig{});
    const FeedResult r = feed(mallet, path);
    const std::string ctx = "into bar " + std::to_string(into) + " at y " + std::to_string(below);
    EXPECT_TRUE(r.impacts.empty()) << ctx;
    EXPECT_EQ(mallet.counters().touches_below_min_speed, 0u) << ctx;
    EXPECT_FALSE(mallet.armed()) << ctx << ": a sideways entry is a contact";
    int held = 0;
    for (const HandSample& s : path) {
      const ContactZone* z = mallet.zone_at(s.hand);
      if (!z) continue;
      EXPECT_EQ(z->target, into) << ctx;
      EXPECT_EQ(mallet.displayed_centre(s.hand), (Vec2{s.hand.x, plane})) << ctx << " x " << s.hand.x;
      ++held;
    }
    EXPECT_GT(held, 10) << ctx;

    // Wobbling there (under the re-arm height) is still no strike; rising clear and
    // coming down is.
    std::vector<HandSample> more{path.back()};
    move_to(more, {centre_x(bar), plane + 0.002}, path.back().t + 100'000'000, 250.0);
    move_to(more, {centre_x(bar), plane - 0.002}, more.back().t + 100'000'000, 250.0);
    move_to(more, {centre_x(bar), plane + 0.05}, more.back().t + 500'000'000, 250.0);
    const Nanos t_contact = more.back().t + kNanosPerSecond;
    append(more, strike_down(centre_x(bar), plane, 1.5, t_contact, 250.0, 0.66, 0.05, 0.01, more.back().t));
    more.erase(more.begin());
    const FeedResult r2 = feed(mallet, more);
    ASSERT_EQ(r2.impacts.size(), 1u) << ctx;
    EXPECT_EQ(r2.impacts[0].target, into);
    EXPECT_LT(std::llabs(r2.impacts[0].t_ns - t_contact), kMicrosecond) << ctx;
  }
}

TEST(MalletRearm, AStrikeThatEndsOffTheBarStillDisarms) {
  // A fast oblique strike near the xylophone's right end: the segment crosses the plane
  // over the bar's zone, but the sample after it is already in the gap between the
  // instruments, where no zone disarms. The strike itself must disarm: coming back over
  // the bar without rising rearm_height_m above the plane is no second strike.
  const Scene& scene = percussion();
  const Target& bar = scene.targets[7];
  const double plane = contact_plane(scene, 7);
  const double zone_end = bar.x_max + scene.mallet_radius_m;
  const Nanos period = 10'000'000;  // 100 Hz
  const Nanos t0 = kNanosPerSecond;
  Mallet mallet(scene, ContactConfig{});
  // From over the bar, 5 mm above the plane, to 15 mm past the zone's end, 5 mm below:
  // the plane is crossed half way, 5 mm inside the zone.
  EXPECT_FALSE(mallet.update(t0, {zone_end - 0.025, plane + 0.005}));
  const auto hit = mallet.update(t0 + period, {zone_end + 0.015, plane - 0.005});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->target, 7);
  EXPECT_NEAR(hit->x_m, zone_end - 0.005, 1e-12);
  EXPECT_EQ(mallet.zone_at({zone_end + 0.015, plane - 0.005}), nullptr) << "the premise: the hand ends off every zone";
  EXPECT_FALSE(mallet.armed());
  // Up 1 mm above the plane in the gap, back over the bar, and down again.
  EXPECT_FALSE(mallet.update(t0 + 2 * period, {zone_end + 0.015, plane + 0.001}));
  EXPECT_FALSE(mallet.update(t0 + 3 * period, {centre_x(bar), plane + 0.001}));
  EXPECT_FALSE(mallet.update(t0 + 4 * period, {centre_x(bar), plane - 0.005})) << "no re-arm without rising";
  EXPECT_EQ(mallet.counters().impacts, 1u);
}

TEST(MalletEdges, DiagonalEntryCrossingThePlaneOverTheBarIsAStrike) {
  // From the gap, above the plane, diagonally onto the glockenspiel's first bar: the line
  // crosses the plane at x inside the bar's zone, so that is a strike at the crossing.
  const Scene& scene = percussion();
  const Target& bar = scene.targets[8];
  const double plane = contact_plane(scene, 8);
  const double cross_x = bar.x_min - 0.5 * scene.mallet_radius_m;  // over the widened zone
  const Nanos t_contact = kNanosPerSecond;
  const Line line{{cross_x, plane}, {0.8, -0.6}, t_contact};
  Mallet mallet(scene, ContactConfig{});
  const FeedResult r = feed(mallet, sample_line(line, 100.0, 0.45, 0.02, 0.01));
  ASSERT_EQ(r.impacts.size(), 1u);
  EXPECT_EQ(r.impacts[0].target, 8);
  EXPECT_LT(std::llabs(r.impacts[0].t_ns - t_contact), kMicrosecond);
  EXPECT_NEAR(r.impacts[0].speed_m_per_s, 0.6, 1e-9 * 0.6);
  EXPECT_NEAR(r.impacts[0].x_m, cross_x, 1e-9);
}

// --- 5. the displayed sphere -----------------------------------------------------------

TEST(MalletDisplay, SphereRestsOnTheSurfaceWhileTheHandIsBelowIt) {
  const Scene& scene = percussion();
  Mallet mallet(scene, ContactConfig{});
  for (const Target& bar : scene.targets) {
    const double plane = contact_plane(scene, bar.id);
    for (double x : {bar.x_min, centre_x(bar), bar.x_max}) {
      for (double dy : {-0.5, -0.02, -1e-9}) {
        const Vec2 shown = mallet.displayed_centre({x, plane + dy});
        EXPECT_EQ(shown, (Vec2{x, plane})) << "bar " << bar.id << " dy " << dy;
        // Resting on the surface: the sphere's bottom is exactly at the bar's top.
        EXPECT_NEAR(shown.y - scene.mallet_radius_m, bar.top_y, 1e-15);
      }
      for (double dy : {0.0, 1e-9, 0.002, 0.3}) EXPECT_EQ(mallet.displayed_centre({x, plane + dy}), (Vec2{x, plane + dy}));
    }
  }
  // Following a strike through: the display never goes under the plane and follows the
  // hand exactly while it is above.
  const double plane = contact_plane(scene, 3);
  for (const HandSample& s : strike_down(centre_x(scene.targets[3]), plane, 2.0, kNanosPerSecond, 500.0, 0.1)) {
    const Vec2 shown = mallet.displayed_centre(s.hand);
    EXPECT_EQ(shown.x, s.hand.x);
    EXPECT_EQ(shown.y, std::max(s.hand.y, plane));
  }
}

// --- 6. speed limits -----------------------------------------------------------------

TEST(MalletSpeed, FasterThanTheMaximumIsClampedAndCounted) {
  const Scene& scene = percussion();
  const ContactConfig config;
  const int id = 12;
  const Nanos t_contact = 4 * kNanosPerSecond + 31'337;
  Mallet mallet(scene, config);
  const FeedResult r = feed(mallet, strike_down(centre_x(scene.targets[id]), contact_plane(scene, id), 100.0,
                                                t_contact, 1000.0, 0.27));
  ASSERT_EQ(r.impacts.size(), 1u);
  EXPECT_EQ(r.impacts[0].speed_m_per_s, config.max_impact_speed_m_per_s);
  EXPECT_EQ(mallet.counters().clamped_speed, 1u);
  EXPECT_EQ(r.impacts[0].target, id);
  EXPECT_LT(std::llabs(r.impacts[0].t_ns - t_contact), kMicrosecond) << "clamping changes the speed, not the time";

  // Just under the maximum is not clamped.
  Mallet under(scene, config);
  const double v = 0.99 * config.max_impact_speed_m_per_s;
  const FeedResult r2 = feed(under, strike_down(centre_x(scene.targets[id]), contact_plane(scene, id), v,
                                                t_contact, 1000.0, 0.27));
  ASSERT_EQ(r2.impacts.size(), 1u);
  EXPECT_LE(std::fabs(r2.impacts[0].speed_m_per_s - v), 1e-9 * v);
  EXPECT_EQ(under.counters().clamped_speed, 0u);
}

TEST(MalletSpeed, SlowerThanTheMinimumIsATouchThatDisarms) {
  const Scene& scene = percussion();
  const ContactConfig config;
  const int id = 5;
  const double x = centre_x(scene.targets[id]);
  const double plane = contact_plane(scene, id);
  const double slow = 0.8 * config.min_impact_speed_m_per_s;
  Mallet mallet(scene, config);
  // A slow descent to 1 mm below the surface at 60 Hz.
  std::vector<HandSample> path = strike_down(x, plane, slow, kNanosPerSecond, 60.0, 0.5, 0.002, 0.001);
  FeedResult r = feed(mallet, path);
  EXPECT_TRUE(r.impacts.empty());
  EXPECT_EQ(mallet.counters().touches_below_min_speed, 1u);
  EXPECT_EQ(mallet.counters().impacts, 0u);
  EXPECT_FALSE(mallet.armed());

  // Disarmed: lifting 2 mm (under the re-arm height) and coming down fast is no strike.
  std::vector<HandSample> more{path.back()};
  move_to(more, {x, plane + 0.002}, path.back().t + 200'000'000, 60.0);
  move_to(more, {x, plane - 0.02}, more.back().t + 20'000'000, 60.0);
  more.erase(more.begin());
  r = feed(mallet, more);
  EXPECT_TRUE(r.impacts.empty());
  EXPECT_EQ(mallet.counters().touches_below_min_speed, 1u);

  // Just over the minimum is a strike.
  Mallet other(scene, config);
  const double v = 1.25 * config.min_impact_speed_m_per_s;
  r = feed(other, strike_down(x, plane, v, kNanosPerSecond, 60.0, 0.5, 0.002, 0.001));
  ASSERT_EQ(r.impacts.size(), 1u);
  EXPECT_LE(std::fabs(r.impacts[0].speed_m_per_s - v), 1e-9 * v);
  EXPECT_EQ(other.counters().touches_below_min_speed, 0u);
}

// --- 7. bad samples ------------------------------------------------------------------

TEST(MalletSamples, NonFiniteSamplesAreIgnoredAndCounted) {
  const Scene& scene = percussion();
  const int id = 9;
  const double x = centre_x(scene.targets[id]);
  const double plane = contact_plane(scene, id);
  const Nanos t_contact = 2 * kNanosPerSecond + 4'321;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<HandSample> clean = strike_down(x, plane, 1.2, t_contact, 100.0, 0.3);
  // After every clean sample, a bad one at a later time (which must not count as "the
  // previous sample" either): the segment across the contact still joins clean samples.
  const std::vector<Vec2> bad = {{nan, plane - 0.01}, {x, nan}, {inf, plane - 0.01}, {x, -inf},
                                 {-inf, inf},          {nan, nan}, {x, inf}};
  std::vector<HandSample> dirty;
  for (std::size_t i = 0; i < clean.size(); ++i) {
    dirty.push_back(clean[i]);
    dirty.push_back({clean[i].t + 3'000'000, bad[i % bad.size()]});
  }
  Mallet mallet(scene, ContactConfig{});
  const FeedResult r = feed(mallet, dirty);
  ASSERT_EQ(r.impacts.size(), 1u);
  EXPECT_TRUE(r.all_finite);
  EXPECT_EQ(r.impacts[0].target, id);
  EXPECT_LT(std::llabs(r.impacts[0].t_ns - t_contact), kMicrosecond);
  EXPECT_LE(std::fabs(r.impacts[0].speed_m_per_s - 1.2), 1e-9 * 1.2);
  EXPECT_EQ(r.impacts[0].x_m, x);
  EXPECT_EQ(mallet.counters().ignored_non_finite, clean.size());
  EXPECT_EQ(mallet.counters().accepted, clean.size());
  EXPECT_EQ(mallet.counters().ignored_not_after_previous, 0u);

  // Only bad samples: nothing at all happens.
  Mallet only_bad(scene, ContactConfig{});
  Nanos t = 0;
  for (const Vec2& p : bad) EXPECT_FALSE(only_bad.update(t += 1'000'000, p));
  EXPECT_EQ(only_bad.counters().ignored_non_finite, bad.size());
  EXPECT_EQ(only_bad.counters().accepted, 0u);
  EXPECT_TRUE(only_bad.armed());
  // ...and the first good one after them is a first sample, not a segment from garbage.
  EXPECT_FALSE(only_bad.update(t += 1'000'000, {x, plane - 0.01}));
  EXPECT_EQ(only_bad.counters().impacts, 0u);
}

TEST(MalletSamples, DuplicateAndDecreasingTimestampsAreIgnoredAndCounted) {
  const Scene& scene = percussion();
  const int id = 13;
  const double x = centre_x(scene.targets[id]);
  const double plane = contact_plane(scene, id);
  const Nanos t_contact = 2 * kNanosPerSecond + 999'999;
  const std::vector<HandSample> clean = strike_down(x, plane, 0.9, t_contact, 250.0, 0.6);
  // After every clean sample: one with the same time and one from the past, both well
  // below the surface (on the bar and on the neighbour) — a strike if they were taken.
  std::vector<HandSample> dirty;
  for (const HandSample& s : clean) {
    dirty.push_back(s);
    dirty.push_back({s.t, {x, plane - 0.03}});
    dirty.push_back({s.t - 1, {centre_x(scene.targets[id - 1]), plane - 0.03}});
    dirty.push_back({s.t - 2 * kNanosPerSecond, {x, -1.0}});
  }
  Mallet mallet(scene, ContactConfig{});
  const FeedResult r = feed(mallet, dirty);
  ASSERT_EQ(r.impacts.size(), 1u);
  EXPECT_TRUE(r.all_finite);
  EXPECT_EQ(r.impacts[0].target, id);
  EXPECT_LT(std::llabs(r.impacts[0].t_ns - t_contact), kMicrosecond);
  EXPECT_LE(std::fabs(r.impacts[0].speed_m_per_s - 0.9), 1e-9 * 0.9);
  EXPECT_EQ(mallet.counters().ignored_not_after_previous, 3 * clean.size());
  EXPECT_EQ(mallet.counters().accepted, clean.size());
  EXPECT_EQ(mallet.counters().ignored_non_finite, 0u);
}

// --- 8. uptime -------------------------------------------------------------------------

TEST(MalletUptime, ThirtyDaysAfterBootTheSameStrikeIsTheSame) {
  // The same hand motion, with the whole clock shifted by 30 days: the impact is at the
  // same offset to the nanosecond, with the same speed, for every rate and phase.
  const Scene& scene = percussion();
  const Nanos shift = 30 * kDay;
  ASSERT_EQ(shift, static_cast<Nanos>(30 * 86400e9));
  std::mt19937_64 rng(30);
  std::uniform_real_distribution<double> phase_dist(0.0, 1.0);
  for (int id : {0, 8, 15}) {
    const double x = centre_x(scene.targets[static_cast<std::size_t>(id)]);
    const double plane = contact_plane(scene, id);
    for (double v : {0.05, 1.0, 8.0}) {
      for (double rate : {30.0, 60.0, 1000.0}) {
        const double phase = phase_dist(rng);
        const Nanos t_contact = 1 * kNanosPerSecond + 777'777;
        std::vector<Impact> impacts[2];
        for (int shifted = 0; shifted < 2; ++shifted) {
          const Nanos boot = shifted ? shift : 0;
          Mallet mallet(scene, ContactConfig{});
          impacts[shifted] = feed(mallet, strike_down(x, plane, v, boot + t_contact, rate, phase, 0.05, 0.01, boot)).impacts;
          ASSERT_EQ(impacts[shifted].size(), 1u) << where(id, v, rate, phase) << " boot " << boot;
        }
        const std::string ctx = where(id, v, rate, phase);
        EXPECT_EQ(impacts[1][0].t_ns - shift, impacts[0][0].t_ns) << ctx;
        EXPECT_EQ(impacts[1][0].speed_m_per_s, impacts[0][0].speed_m_per_s) << ctx;
        EXPECT_EQ(impacts[1][0].x_m, impacts[0][0].x_m) << ctx;
        EXPECT_LT(std::llabs(impacts[1][0].t_ns - shift - t_contact), kMicrosecond) << ctx;
        EXPECT_LE(std::fabs(impacts[1][0].speed_m_per_s - v), 1e-9 * v) << ctx;
      }
    }
  }
}

}  // namespace
}  // namespace mallet
