// `mallet bench latency`'s pure parts: where a strike starts in a recorded channel (over
// silence, over a bar still ringing, across a seam), how contacts, strikes and cues are
// paired, and the summary's statistics. The bench itself runs as the CTest
// bench.latency_quick; nothing here times anything.
#include "app/bench/bench_latency.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "app/bench/bench_latency_onset.hpp"

namespace mallet::app::latency {
namespace {

constexpr double kRate = 48000.0;
constexpr double kPi = 3.14159265358979323846;

//! A modal strike starting at sample `at`: damped sines at f·ratio, written in float as the
//! kiosk's engine writes them (sample `at` itself is sin(0) = 0).
void add_strike(std::vector<float>& x, std::size_t at, double amplitude, double f,
                std::vector<std::pair<double, double>> modes) {  // (ratio, decay per s)
  for (std::size_t n = at; n < x.size(); ++n) {
    const double t = static_cast<double>(n - at) / kRate;
    double v = 0;
    for (const auto& [ratio, decay] : modes) v += std::exp(-decay * t) * std::sin(2 * kPi * f * ratio * t) / ratio;
    x[n] += static_cast<float>(amplitude * v);
  }
}

const std::vector<std::pair<double, double>> kMetal = {{1.0, 2.3}, {2.756, 4.5}, {5.404, 9.0}, {8.933, 16.0}};
const std::vector<std::pair<double, double>> kWood = {{1.0, 12.0}, {3.0, 30.0}, {6.0, 60.0}};

TEST(BenchLatencyOnset, OverSilenceItIsTheFirstNonZeroSample) {
  std::vector<float> x(48000, 0.0f);
  add_strike(x, 20000, 0.2, 100.0, {{1.0, 80.0}});
  EXPECT_EQ(find_onset(x, 10000, 30000), std::optional<std::size_t>(20001));
  EXPECT_EQ(find_onset(x, 21000, 30000), std::nullopt);  // no new strike after it
}

TEST(BenchLatencyOnset, AQuietStrikeOverALouderRingIsFoundOnItsFirstSample) {
  // A fast glockenspiel strike 0.6 s earlier still rings louder than a slow xylophone one.
  std::vector<float> x(96000, 0.0f);
  add_strike(x, 1000, 0.4, 1567.98, kMetal);
  const std::size_t at = 1000 + 28800;
  add_strike(x, at, 0.05, 783.99, kWood);
  double ring = 0;
  for (std::size_t n = at - 480; n < at; ++n) ring = std::max(ring, std::fabs(static_cast<double>(x[n])));
  ASSERT_GT(ring, 0.05);  // the case a level threshold gets wrong
  EXPECT_EQ(find_onset(x, at - 2400, at + 14400), std::optional<std::size_t>(at + 1));
  EXPECT_EQ(find_onset(x, at - 7200, at - 100), std::nullopt);  // the ring alone is no strike
}

TEST(BenchLatencyOnset, TheSameBarStruckAgainIsFound) {
  std::vector<float> x(96000, 0.0f);
  add_strike(x, 1000, 0.4, 1567.98, kMetal);
  const std::size_t at = 1000 + 57600;
  add_strike(x, at, 0.1, 1567.98, kMetal);
  EXPECT_EQ(find_onset(x, at - 2400, at + 14400), std::optional<std::size_t>(at + 1));
}

TEST(BenchLatencyOnset, ASeamInTheRingIsNoStrike) {
  // A cycle the kiosk skipped: the ring jumps ahead by 128 samples inside a known gap.
  std::vector<float> ring(96000, 0.0f), x(90000, 0.0f);
  add_strike(ring, 0, 0.4, 1567.98, kMetal);
  const std::size_t seam = 30000;
  for (std::size_t n = 0; n < x.size(); ++n) x[n] = ring[n < seam ? n : n + 128];
  const std::vector<Gap> gaps = {{seam - 128, seam + 256}};
  EXPECT_EQ(find_onset(x, seam - 2400, seam + 4800, {}, gaps), std::nullopt);
  EXPECT_EQ(find_onset(x, seam - 2400, seam + 4800), std::optional<std::size_t>(seam));  // without the gap: fooled
  const std::size_t at = seam + 2400;
  add_strike(x, at, 0.1, 783.99, kWood);
  EXPECT_EQ(find_onset(x, seam - 2400, seam + 4800, {}, gaps), std::optional<std::size_t>(at + 1));
}

TEST(BenchLatencyMatch, PairsContactsStrikesAndCues) {
  constexpr Nanos ms = 1'000'000;
  Recording r;
  r.contacts = {{1000 * ms, 0, 1.0}, {1600 * ms, 1, 1.5}, {2200 * ms, 0, 2.0}};
  r.strikes = {1003 * ms, 1640 * ms, 1900 * ms};  // the third contact missed; 1900 ms is false
  r.actuator = {1012 * ms, 1660 * ms};
  r.note = {1012 * ms, 1661 * ms};
  r.picture = {{1005 * ms}, {1590 * ms}};  // the second before its contact: a predicted frame
  const Matched m = match_recording(r);
  EXPECT_EQ(m.strikes, 2);
  EXPECT_EQ(m.missed_strikes, 1);
  EXPECT_EQ(m.false_strikes, 1);
  ASSERT_EQ(m.cues.size(), 5u);
  EXPECT_EQ(m.cues[0].cue, "actuator");
  EXPECT_EQ(m.cues[0].ms, (std::vector<double>{12.0, 60.0}));
  EXPECT_EQ(m.cues[1].ms, (std::vector<double>{12.0, 61.0}));
  EXPECT_EQ(m.cues[2].ms, (std::vector<double>{5.0, -10.0}));
  EXPECT_EQ(m.cues[3].ms, (std::vector<double>{7.0, 70.0}));  // actuator − picture
  EXPECT_EQ(m.cues[4].ms, (std::vector<double>{0.0, 1.0}));   // note − actuator
  ASSERT_EQ(m.rows.size(), 3u);
  EXPECT_FALSE(m.rows[2].strike_ms.has_value());
}

TEST(BenchLatencySummary, MedianNearestRankP99AndSignedMax) {
  std::vector<double> v;
  for (int i = 1; i <= 100; ++i) v.push_back(i);
  v.push_back(-500.0);
  const Summary s = summarise(v);
  EXPECT_EQ(s.n, 101u);
  EXPECT_DOUBLE_EQ(*s.median, 50.0);
  EXPECT_DOUBLE_EQ(*s.p99, 99.0);
  EXPECT_DOUBLE_EQ(*s.max, -500.0);
  EXPECT_FALSE(summarise({}).median.has_value());
}

}  // namespace
}  // namespace mallet::app::latency
