// The stroke corpus that contact prediction is measured on: the same seed gives the same
// corpus bit for bit, every kind is made for every camera, the truth matches what each kind
// promises, each camera model adds the noise, quantisation and drops it says, every camera
// sees the same paths, and the Wii's strokes are what they were before the V4L2 camera came.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
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
  c.cameras = every_camera();
  return c;
}

CorpusConfig noise_free(CorpusConfig c) {
  for (CameraModel& camera : c.cameras) {
    camera.noise_px = 0;
    camera.quantise_px = false;
    camera.drop_probability = 0;
  }
  return c;
}

const CameraModel& camera_of(const CorpusConfig& c, const Stroke& s) {
  for (const CameraModel& camera : c.cameras)
    if (camera.name == s.camera && camera.rate_hz == s.rate_hz) return camera;
  ADD_FAILURE() << "no camera " << s.camera << " at " << s.rate_hz << " Hz";
  return c.cameras.front();
}

//! FNV-1a over what a stroke is, its positions in whole camera pixels (so a last-bit
//! difference in a C library's log or sin cannot change it; the Wii's are whole pixels).
struct Fnv {
  std::uint64_t h = 1469598103934665603ull;
  void add(std::int64_t v) {
    for (int i = 0; i < 8; ++i) {
      h ^= static_cast<std::uint64_t>(v >> (8 * i)) & 0xff;
      h *= 1099511628211ull;
    }
  }
};
std::uint64_t pixel_checksum(const Scene& scene, const std::vector<Stroke>& corpus, const CameraModel& wii) {
  const double m = metres_per_camera_px(scene, wii);
  const ScreenToWorld& v = scene.screen_to_world;
  Fnv f;
  for (const Stroke& s : corpus) {
    if (s.camera != wii.name) continue;
    f.add(s.shape);
    f.add(static_cast<int>(s.kind));
    f.add(std::llround(s.rate_hz));
    f.add(static_cast<std::int64_t>(s.samples.size()));
    for (const PointerSample& p : s.samples) {
      f.add(p.t_ns);
      f.add(std::llround((p.x - v.left_m) / m));
      f.add(std::llround((v.top_m - p.y) / m));
    }
    f.add(static_cast<std::int64_t>(s.contacts.size()));
    for (const TrueContact& c : s.contacts) {
      f.add(c.t_ns);
      f.add(c.target);
    }
  }
  return f.h;
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

TEST(StrokeCorpus, EveryKindForEveryCamera) {
  const CorpusConfig config = small();
  ASSERT_EQ(config.cameras.size(), 4u);
  const std::vector<Stroke> corpus = make_stroke_corpus(percussion(), config);
  EXPECT_EQ(corpus.size(), static_cast<std::size_t>(config.shapes_per_kind * kStrokeKinds) * config.cameras.size());
  std::map<std::pair<int, double>, int> count;
  for (const Stroke& s : corpus) ++count[{static_cast<int>(s.kind), s.rate_hz}];
  for (int k = 0; k < kStrokeKinds; ++k)
    for (const CameraModel& camera : config.cameras)
      EXPECT_EQ((count[{k, camera.rate_hz}]), config.shapes_per_kind)
          << to_string(static_cast<StrokeKind>(k)) << " " << camera.name << " " << camera.rate_hz;
  // A shape's strokes, one per camera in the config's order, share the truth.
  const std::size_t n = config.cameras.size();
  for (std::size_t i = 0; i + n <= corpus.size(); i += n) {
    for (std::size_t c = 0; c < n; ++c) {
      const Stroke& s = corpus[i + c];
      EXPECT_EQ(s.camera, config.cameras[c].name);
      EXPECT_EQ(s.rate_hz, config.cameras[c].rate_hz);
      EXPECT_EQ(s.shape, corpus[i].shape);
      EXPECT_EQ(s.min_clearance_m, corpus[i].min_clearance_m);
      ASSERT_EQ(s.contacts.size(), corpus[i].contacts.size());
      for (std::size_t k = 0; k < s.contacts.size(); ++k) EXPECT_EQ(s.contacts[k].t_ns, corpus[i].contacts[k].t_ns);
    }
  }
}

// Without noise, every camera's samples lie on one continuous path per shape: each sample
// of the slower cameras is within linear interpolation's error (a·h²/8 ≤ 0.26 mm at 12 g
// over 4.2 ms) of the 240 Hz camera's path around it.
TEST(StrokeCorpus, EveryCameraSeesTheSamePaths) {
  const CorpusConfig config = noise_free(small());
  const std::vector<Stroke> corpus = make_stroke_corpus(percussion(), config);
  const std::size_t n = config.cameras.size();
  ASSERT_EQ(config.cameras.back().rate_hz, 240.0);
  std::size_t compared = 0;
  for (std::size_t i = 0; i + n <= corpus.size(); i += n) {
    const std::vector<PointerSample>& ref = corpus[i + n - 1].samples;
    for (std::size_t c = 0; c + 1 < n; ++c) {
      for (const PointerSample& p : corpus[i + c].samples) {
        const auto after = std::lower_bound(ref.begin(), ref.end(), p.t_ns,
                                            [](const PointerSample& r, Nanos t) { return r.t_ns < t; });
        if (after == ref.begin() || after == ref.end()) continue;
        const PointerSample& a = *(after - 1);
        const PointerSample& b = *after;
        const double u = static_cast<double>(p.t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
        ASSERT_NEAR(p.x, a.x + u * (b.x - a.x), 0.0003) << "shape " << corpus[i].shape << " camera " << c;
        ASSERT_NEAR(p.y, a.y + u * (b.y - a.y), 0.0003) << "shape " << corpus[i].shape << " camera " << c;
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 10'000u);
}

// The Wii's strokes for a seed are what they were before the corpus had a camera list (the
// checksum was taken then, with rates_hz = {100, 200}), and adding the V4L2 camera changes
// none of them; removing one V4L2 rate changes nothing at the other.
TEST(StrokeCorpus, WiiStrokesUnchangedAndCamerasIndependent) {
  const Scene& scene = percussion();
  CorpusConfig wii_only = small();
  wii_only.cameras = {wii_camera(100.0), wii_camera(200.0)};
  const std::vector<Stroke> before = make_stroke_corpus(scene, wii_only);
  EXPECT_EQ(pixel_checksum(scene, before, wii_camera(100.0)), 0x7d3b5b9e1c50f06full);

  const std::vector<Stroke> all = make_stroke_corpus(scene, small());
  CorpusConfig without_120 = small();
  without_120.cameras.erase(without_120.cameras.begin() + 2);
  const std::vector<Stroke> fewer = make_stroke_corpus(scene, without_120);
  ASSERT_EQ(all.size(), 2 * before.size());
  for (std::size_t shape = 0; shape < before.size() / 2; ++shape) {
    for (std::size_t c = 0; c < 2; ++c)
      EXPECT_TRUE(same_samples(before[2 * shape + c].samples, all[4 * shape + c].samples)) << shape;
    EXPECT_TRUE(same_samples(fewer[3 * shape + 2].samples, all[4 * shape + 3].samples)) << shape;
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

// Each camera as its model says: a sample every period, the configured share dropped, the
// configured noise; the Wii in whole pixels, the V4L2 camera's centroids between them.
TEST(StrokeCorpus, SampledAtItsRateWithDropsAndCameraNoise) {
  const Scene& scene = percussion();
  const CorpusConfig noisy = small();
  const std::vector<Stroke> a = make_stroke_corpus(scene, noisy);
  const std::vector<Stroke> clean = make_stroke_corpus(scene, noise_free(noisy));
  ASSERT_EQ(a.size(), clean.size());
  EXPECT_NEAR(metres_per_camera_px(scene, wii_camera(100)), 0.832 / 1024, 1e-12);  // 0.832 m over 1024 px
  EXPECT_NEAR(metres_per_camera_px(scene, v4l2_camera(240)), 0.832 / 640, 1e-12);  // over 640 px
  struct Tally {
    std::size_t kept = 0, grid = 0, compared = 0, whole = 0;
    double sum_sq = 0;
  };
  std::map<std::pair<std::string, double>, Tally> tally;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const CameraModel& camera = camera_of(noisy, a[i]);
    const double m_per_px = metres_per_camera_px(scene, camera);
    Tally& t = tally[{std::string(camera.name), camera.rate_hz}];
    const double period_ns = 1e9 / a[i].rate_hz;
    // Noise-free: every interval is one period (to the rounding of the grid).
    for (std::size_t k = 1; k < clean[i].samples.size(); ++k)
      EXPECT_NEAR(static_cast<double>(clean[i].samples[k].t_ns - clean[i].samples[k - 1].t_ns), period_ns, 1.0);
    t.grid += clean[i].samples.size();
    t.kept += a[i].samples.size();
    // The same seed draws the same shapes, phases and drops: match samples by time.
    std::size_t j = 0;
    for (const PointerSample& p : a[i].samples) {
      while (j < clean[i].samples.size() && clean[i].samples[j].t_ns < p.t_ns) ++j;
      ASSERT_LT(j, clean[i].samples.size());
      ASSERT_EQ(clean[i].samples[j].t_ns, p.t_ns);
      const double dy = p.y - clean[i].samples[j].y;
      t.sum_sq += dy * dy / (m_per_px * m_per_px);
      ++t.compared;
      const double py = (scene.screen_to_world.top_m - p.y) / m_per_px;
      t.whole += std::fabs(py - std::round(py)) < 1e-6 ? 1 : 0;
    }
  }
  for (const CameraModel& camera : noisy.cameras) {
    SCOPED_TRACE(std::string(camera.name) + " " + std::to_string(camera.rate_hz));
    const Tally& t = tally[{std::string(camera.name), camera.rate_hz}];
    ASSERT_GT(t.compared, 10'000u);
    const double dropped = 1.0 - static_cast<double>(t.kept) / static_cast<double>(t.grid);
    // Binomial: the standard error is ≤ 0.1 % here, the tolerance several times it.
    EXPECT_NEAR(dropped, camera.drop_probability, camera.quantise_px ? 0.006 : 0.002);
    const double rms_px = std::sqrt(t.sum_sq / static_cast<double>(t.compared));
    if (camera.quantise_px) {
      EXPECT_EQ(t.whole, t.compared);  // whole camera pixels
      // σ 0.5 px of noise and the rounding to whole pixels (σ 1/√12 px) together.
      const double expected_px = std::sqrt(camera.noise_px * camera.noise_px + 1.0 / 12.0);
      EXPECT_NEAR(rms_px, expected_px, 0.05 * expected_px);
    } else {
      // Subpixel: hardly any sample on a whole pixel; the noise alone (its estimate's
      // standard error 1/√(2n) < 0.5 %, the tolerance 5 %).
      EXPECT_LT(t.whole * 100, t.compared);
      EXPECT_NEAR(rms_px, camera.noise_px, 0.05 * camera.noise_px);
    }
  }
}

}  // namespace
}  // namespace mallet
