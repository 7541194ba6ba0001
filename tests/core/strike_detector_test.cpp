// The strike route's detector: with prediction off it is the contact solver, impact for
// impact and bit for bit; with prediction on, a predicted strike is the only note of its
// stroke, and a hand that stops just above the bar after a wrong prediction makes no
// second note while it hovers there.
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "core/strike_detector.hpp"
#include "core/stroke_corpus.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

using test::percussion;

constexpr Nanos kDetectorT0 = 40 * 86'400 * kNanosPerSecond;
constexpr Nanos kPeriod = 10'000'000;  // 100 Hz

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool identical(const Impact& a, const Impact& b) {
  return a.t_ns == b.t_ns && a.target == b.target && a.material == b.material && a.note == b.note &&
         same_bits(a.speed_m_per_s, b.speed_m_per_s) && same_bits(a.x_m, b.x_m) && a.delay_ns == b.delay_ns &&
         a.predicted == b.predicted;
}

bool identical(const Mallet::Counters& a, const Mallet::Counters& b) {
  return a.accepted == b.accepted && a.ignored_non_finite == b.ignored_non_finite &&
         a.ignored_not_after_previous == b.ignored_not_after_previous && a.impacts == b.impacts &&
         a.touches_below_min_speed == b.touches_below_min_speed && a.clamped_speed == b.clamped_speed;
}

double plane_of(int target) {
  return percussion().targets[static_cast<std::size_t>(target)].top_y + percussion().mallet_radius_m;
}
double centre_x(int target) {
  const Target& t = percussion().targets[static_cast<std::size_t>(target)];
  return 0.5 * (t.x_min + t.x_max);
}

TEST(StrikeDetector, PredictionOffIsTheSolverBitForBit) {
  const Scene& scene = percussion();
  CorpusConfig corpus;
  corpus.seed = 3;
  corpus.shapes_per_kind = 40;
  std::vector<PointerSample> stream;
  for (const Stroke& s : make_stroke_corpus(scene, corpus)) {
    // One long stream: strokes back to back, with the oddities a live pointer sends.
    const Nanos shift = (stream.empty() ? 0 : stream.back().t_ns + kPeriod) - s.samples.front().t_ns;
    for (const PointerSample& p : s.samples) stream.push_back({p.t_ns + shift, p.x, p.y});
    stream.push_back(stream.back());                                              // a duplicate
    stream.push_back({stream.back().t_ns + 1, std::numeric_limits<double>::quiet_NaN(), 0.1});
    stream.push_back({stream.back().t_ns - kPeriod, 0.0, 0.0});                   // out of order
  }
  const ContactConfig contact{0.003, 0.005, 2.0};  // a low clamp, so clamping happens too
  Mallet mallet(scene, contact);
  StrikeDetector detector(scene, contact, prediction_off());
  int impacts = 0;
  for (std::size_t i = 0; i < stream.size(); ++i) {
    if (i == stream.size() / 2) {  // tracking lost once
      mallet.reset();
      detector.reset();
    }
    const auto a = mallet.update(stream[i].t_ns, {stream[i].x, stream[i].y});
    const auto b = detector.update(stream[i].t_ns, {stream[i].x, stream[i].y});
    ASSERT_EQ(a.has_value(), b.has_value()) << i;
    if (a) {
      EXPECT_TRUE(identical(*a, *b)) << i;
      ++impacts;
    }
    ASSERT_EQ(mallet.armed(), detector.armed()) << i;
    const Vec2 hand{stream[i].x, stream[i].y};
    if (std::isfinite(hand.x)) {
      EXPECT_EQ(mallet.displayed_centre(hand), detector.displayed_centre(hand));
    }
  }
  EXPECT_GT(impacts, 100);
  EXPECT_TRUE(identical(mallet.counters(), detector.counters()));
  EXPECT_GT(detector.counters().clamped_speed, 0u);
  EXPECT_EQ(detector.prediction_counters().predicted, 0u);
  EXPECT_EQ(detector.zones().size(), mallet.zones().size());
}

TEST(StrikeDetector, ForwardsMaterials) {
  StrikeDetector detector(percussion(), ContactConfig{}, prediction_balanced());
  detector.set_material(0, 1);
  EXPECT_EQ(detector.material_of(0), 1);
}

//! A straight descent onto `target` at `v` m/s, samples every 10 ms, the last one at
//! `last_above_m` above the plane; returns the samples.
std::vector<PointerSample> descent(int target, double v, double last_above_m, int samples) {
  std::vector<PointerSample> out;
  for (int k = 0; k < samples; ++k) {
    const int back = samples - 1 - k;
    out.push_back({kDetectorT0 + k * kPeriod, centre_x(target), plane_of(target) + last_above_m + v * back * 0.01});
  }
  return out;
}

// A stroke at constant speed through the bar: predicted once, before the contact, and the
// real crossing that follows makes no second note.
TEST(StrikeDetector, PredictedStrikeIsTheOnlyNoteOfItsStroke) {
  StrikeDetector detector(percussion(), ContactConfig{}, prediction_balanced());
  const int target = 4;
  // 1.5 m/s; the last sample before the contact is 6 mm above: the contact is 4 ms later.
  std::vector<PointerSample> path = descent(target, 1.5, 0.006, 8);
  const Nanos contact = path.back().t_ns + 4'000'000;
  for (int k = 1; k <= 5; ++k)  // on through the bar, then it stays below
    path.push_back({path.back().t_ns + kPeriod, centre_x(target), plane_of(target) + 0.006 - 1.5 * k * 0.01});
  std::vector<std::pair<Nanos, Impact>> strikes;
  for (const PointerSample& p : path)
    if (auto i = detector.update(p.t_ns, {p.x, p.y})) strikes.push_back({p.t_ns, *i});
  ASSERT_EQ(strikes.size(), 1u);
  const Impact& i = strikes[0].second;
  EXPECT_TRUE(i.predicted);
  EXPECT_EQ(strikes[0].first, contact - 4'000'000);  // decided at the sample before the contact
  EXPECT_NEAR(static_cast<double>(i.t_ns - contact), 0.0, 1'000.0);  // to the microsecond
  EXPECT_NEAR(i.speed_m_per_s, 1.5, 1e-6);
  EXPECT_EQ(i.target, target);
  EXPECT_EQ(i.note, percussion().targets[target].note);
  EXPECT_EQ(i.material, percussion().targets[target].material);
  EXPECT_NEAR(i.x_m, centre_x(target), 1e-9);
  EXPECT_EQ(detector.prediction_counters().predicted, 1u);
  EXPECT_EQ(detector.prediction_counters().confirmed, 1u);
  EXPECT_EQ(detector.prediction_counters().unconfirmed, 0u);
  EXPECT_EQ(detector.counters().impacts, 0u);  // the solver made none
  // Lifting re-arms as after any strike (rearm_height_m above the plane): a new stroke sounds.
  std::vector<PointerSample> again = descent(target, 1.5, 0.006, 8);
  for (PointerSample& p : again) p.t_ns += path.back().t_ns + kPeriod - kDetectorT0;
  int more = 0;
  for (const PointerSample& p : again) more += detector.update(p.t_ns, {p.x, p.y}) ? 1 : 0;
  EXPECT_EQ(more, 1);
}

// A hand that the predictor calls, then stops dead 5 mm above the bar and hovers there
// with 0.4 mm of jitter: one (false) note, none while it hovers, and the stroke after a
// lift sounds again.
TEST(StrikeDetector, FalsePredictionThenHoverDoesNotStrikeAgain) {
  const Scene& scene = percussion();
  StrikeDetector detector(scene, ContactConfig{}, prediction_balanced());
  const int target = 2;
  std::vector<PointerSample> path = descent(target, 1.0, 0.008, 8);  // contact predicted 8 ms ahead
  for (int k = 1; k <= 300; ++k) {
    const double jitter = 0.0004 * std::sin(k * 2.1);
    path.push_back({path.back().t_ns + kPeriod, centre_x(target), plane_of(target) + 0.005 + jitter});
  }
  std::vector<Impact> strikes;
  for (const PointerSample& p : path)
    if (auto i = detector.update(p.t_ns, {p.x, p.y})) strikes.push_back(*i);
  ASSERT_EQ(strikes.size(), 1u);
  EXPECT_TRUE(strikes[0].predicted);
  EXPECT_FALSE(detector.armed());
  EXPECT_EQ(detector.prediction_counters().confirmed, 0u);
  EXPECT_EQ(detector.prediction_counters().unconfirmed, 0u);  // not known yet: still hovering
  // Lift 5 cm: re-armed, the wrong prediction is counted, and the next stroke sounds.
  Nanos t = path.back().t_ns;
  for (int k = 1; k <= 10; ++k)
    detector.update(t += kPeriod, {centre_x(target), plane_of(target) + 0.005 + 0.005 * k});
  EXPECT_TRUE(detector.armed());
  EXPECT_EQ(detector.prediction_counters().unconfirmed, 1u);
  int more = 0;
  for (int k = 1; k <= 12; ++k)
    more += detector.update(t += kPeriod, {centre_x(target), plane_of(target) + 0.055 - 0.01 * k}) ? 1 : 0;
  EXPECT_EQ(more, 1);
}

// Mallet::disarm on its own: re-armed only rearm_height_m above max(hand, plane).
TEST(StrikeDetector, DisarmRearmsAboveTheHandOrThePlane) {
  const Scene& scene = percussion();
  const ContactConfig config{};
  Mallet mallet(scene, config);
  const ContactZone& zone = mallet.zones()[1];
  const double x = 0.5 * (zone.lo + zone.hi);
  mallet.update(kDetectorT0, {x, zone.plane_y + 0.02});
  mallet.disarm(zone, zone.plane_y + 0.010);
  EXPECT_FALSE(mallet.armed());
  mallet.update(kDetectorT0 + kPeriod, {x, zone.plane_y + 0.012});  // below 10 + 3 mm
  EXPECT_FALSE(mallet.armed());
  mallet.update(kDetectorT0 + 2 * kPeriod, {x, zone.plane_y + 0.0131});
  EXPECT_TRUE(mallet.armed());
  // A hand below the plane: the plane's own hysteresis.
  mallet.disarm(zone, zone.plane_y - 0.01);
  mallet.update(kDetectorT0 + 3 * kPeriod, {x, zone.plane_y + 0.0029});
  EXPECT_FALSE(mallet.armed());
  mallet.update(kDetectorT0 + 4 * kPeriod, {x, zone.plane_y + 0.0031});
  EXPECT_TRUE(mallet.armed());
}

// On the noisy corpus (camera noise, drops, both rates), every preset: the strikes match
// the truth one to one where the solver's would, and none is doubled.
TEST(StrikeDetector, NoDoubleStrikesOnTheCorpus) {
  CorpusConfig corpus;
  corpus.seed = 11;
  corpus.shapes_per_kind = 60;
  const std::vector<Stroke> strokes = make_stroke_corpus(percussion(), corpus);
  for (const PredictionConfig& config : {prediction_balanced(), prediction_exact(), prediction_eager()}) {
    std::uint64_t predicted = 0;
    for (const Stroke& s : strokes) {
      StrikeDetector off(percussion(), ContactConfig{}, prediction_off());
      StrikeDetector on(percussion(), ContactConfig{}, config);
      int n_off = 0, n_on = 0;
      for (const PointerSample& p : s.samples) {
        n_off += off.update(p.t_ns, {p.x, p.y}) ? 1 : 0;
        n_on += on.update(p.t_ns, {p.x, p.y}) ? 1 : 0;
      }
      EXPECT_EQ(n_on, n_off) << to_string(s.kind) << " shape " << s.shape << " at " << s.rate_hz << " Hz";
      predicted += on.prediction_counters().predicted;
    }
    EXPECT_GT(predicted, 50u);
  }
}

}  // namespace
}  // namespace mallet
