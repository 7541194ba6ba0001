// The stroke corpus that contact prediction is measured on: the same seed gives the same
// corpus bit for bit, every kind is made at every rate, the truth matches what each kind
// promises, and the camera model adds the noise, quantisation and drops it says.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "core/stroke_corpus.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

using test::percussion;

CorpusConfig small(std::uint32_t seed = 7) {
  CorpusConfig c;
  c.seed = seed;
  c.shapes_per_kind = 25;
  return c;
}

CorpusConfig noise_free(CorpusConfig c) {
  c.noise_px = 0;
  c.quantise_px = false;
  c.drop_probability = 0;
  return c;
}

bool same_samples(const std::vector<PointerSample>& a, const std::vector<PointerSample>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].t_ns != b[i].t_ns || std::memcmp(&a[i].x, &b[i].x, sizeof(double)) != 0 ||
        std::memcmp(&a[i].y, &b[i].y, sizeof(double)) != 0)
      return false;
  return true;
}

TEST(StrokeCorpus, SameSeedSameCorpusBitForBit) {
  const std::vector<Stroke> a = make_stroke_corpus(percussion(), small());
  const std::vector<Stroke> b = make_stroke_corpus(percussion(), small());
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(same_samples(a[i].samples, b[i].samples)) << i;
    ASSERT_EQ(a[i].contacts.size(), b[i].contacts.size()) << i;
    for (std::size_t k = 0; k < a[i].contacts.size(); ++k) {
      EXPECT_EQ(a[i].contacts[k].t_ns, b[i].contacts[k].t_ns);
      EXPECT_EQ(a[i].contacts[k].speed_m_per_s, b[i].contacts[k].speed_m_per_s);
    }
  }
}

TEST(StrokeCorpus, AnotherSeedAnotherCorpus) {
  const std::vector<Stroke> a = make_stroke_corpus(percussion(), small(7));
  const std::vector<Stroke> b = make_stroke_corpus(percussion(), small(8));
  ASSERT_EQ(a.size(), b.size());
  int differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differ += same_samples(a[i].samples, b[i].samples) ? 0 : 1;
  EXPECT_EQ(differ, static_cast<int>(a.size()));
}

TEST(StrokeCorpus, EveryKindAtEveryRate) {
  const CorpusConfig config = small();
  const std::vector<Stroke> corpus = make_stroke_corpus(percussion(), config);
  EXPECT_EQ(corpus.size(), static_cast<std::size_t>(config.shapes_per_kind * kStrokeKinds) * config.rates_hz.size());
  std::map<std::pair<int, double>, int> count;
  for (const Stroke& s : corpus) ++count[{static_cast<int>(s.kind), s.rate_hz}];
  for (int k = 0; k < kStrokeKinds; ++k)
    for (double rate : config.rates_hz)
      EXPECT_EQ((count[{k, rate}]), config.shapes_per_kind) << to_string(static_cast<StrokeKind>(k)) << " " << rate;
  // A shape's strokes at the two rates share the truth.
  for (std::size_t i = 0; i + 1 < corpus.size(); i += 2) {
    EXPECT_EQ(corpus[i].shape, corpus[i + 1].shape);
    ASSERT_EQ(corpus[i].contacts.size(), corpus[i + 1].contacts.size());
    for (std::size_t k = 0; k < corpus[i].contacts.size(); ++k)
      EXPECT_EQ(corpus[i].contacts[k].t_ns, corpus[i + 1].contacts[k].t_ns);
  }
}

TEST(StrokeCorpus, TruthIsWhatEachKindPromises) {
  const Scene& scene = percussion();
  for (const Stroke& s : make_stroke_corpus(scene, small())) {
    SCOPED_TRACE(std::string(to_string(s.kind)) + " shape " + std::to_string(s.shape));
    switch (s.kind) {
      case StrokeKind::strike:
      case StrokeKind::slow_approach:
        EXPECT_EQ(s.contacts.size(), 1u);
        break;
      case StrokeKind::double_tap:
        ASSERT_EQ(s.contacts.size(), 2u);
        EXPECT_EQ(s.contacts[0].target, s.contacts[1].target);
        EXPECT_GT(s.contacts[1].t_ns - s.contacts[0].t_ns, 50'000'000);
        break;
      case StrokeKind::stop_above:
        EXPECT_TRUE(s.contacts.empty());
        EXPECT_GT(s.min_clearance_m, 0.0);
        EXPECT_LE(s.min_clearance_m, 0.010);
        break;
      case StrokeKind::hover:
        EXPECT_TRUE(s.contacts.empty());
        EXPECT_GE(s.min_clearance_m, 0.0015);
        break;
      case StrokeKind::slide:
        EXPECT_LE(s.contacts.size(), 1u);
        break;
    }
    for (const TrueContact& c : s.contacts) {
      EXPECT_GE(c.target, 0);
      EXPECT_LT(c.target, static_cast<int>(scene.targets.size()));
      EXPECT_GT(c.speed_m_per_s, 0.01);
      EXPECT_LT(c.speed_m_per_s, 4.0 + 1e-9);
      ASSERT_FALSE(s.samples.empty());
      EXPECT_GT(c.t_ns, s.samples.front().t_ns);
      EXPECT_LT(c.t_ns, s.samples.back().t_ns);
    }
    if (s.kind == StrokeKind::strike) {
      EXPECT_GE(s.peak_speed_m_per_s, 0.05);  // the swing's peak (lengthened to respect 12 g)
      EXPECT_LE(s.peak_speed_m_per_s, 4.0 + 1e-9);
    }
  }
}

TEST(StrokeCorpus, SampledAtItsRateWithDropsAndCameraNoise) {
  const Scene& scene = percussion();
  const CorpusConfig noisy = small();
  const std::vector<Stroke> a = make_stroke_corpus(scene, noisy);
  const std::vector<Stroke> clean = make_stroke_corpus(scene, noise_free(noisy));
  ASSERT_EQ(a.size(), clean.size());
  const double m_per_px = metres_per_camera_px(scene, noisy);
  EXPECT_NEAR(m_per_px, 0.832 / 1024, 1e-12);  // the percussion scene's 0.832 m over 1024 camera px
  std::size_t kept = 0, grid = 0;
  double sum_sq = 0;
  std::size_t compared = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double period_ns = 1e9 / a[i].rate_hz;
    // Noise-free: every interval is one period (to the rounding of the grid).
    for (std::size_t k = 1; k < clean[i].samples.size(); ++k)
      EXPECT_NEAR(static_cast<double>(clean[i].samples[k].t_ns - clean[i].samples[k - 1].t_ns), period_ns, 1.0);
    grid += clean[i].samples.size();
    kept += a[i].samples.size();
    // The same seed draws the same shapes, phases and drops: match samples by time.
    std::size_t j = 0;
    for (const PointerSample& p : a[i].samples) {
      while (j < clean[i].samples.size() && clean[i].samples[j].t_ns < p.t_ns) ++j;
      ASSERT_LT(j, clean[i].samples.size());
      ASSERT_EQ(clean[i].samples[j].t_ns, p.t_ns);
      const double dy = p.y - clean[i].samples[j].y;
      sum_sq += dy * dy;
      ++compared;
      // Whole camera pixels.
      const double py = (scene.screen_to_world.top_m - p.y) / m_per_px;
      EXPECT_NEAR(py, std::round(py), 1e-6);
    }
  }
  const double dropped = 1.0 - static_cast<double>(kept) / static_cast<double>(grid);
  EXPECT_NEAR(dropped, noisy.drop_probability, 0.006);
  // σ 0.5 px of noise and the rounding to whole pixels (σ 1/√12 px) together.
  const double expected_px = std::sqrt(0.25 + 1.0 / 12.0);
  EXPECT_NEAR(std::sqrt(sum_sq / static_cast<double>(compared)) / m_per_px, expected_px, 0.05 * expected_px);
}

}  // namespace
}  // namespace mallet
