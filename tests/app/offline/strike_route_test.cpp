// The one strike route: every product delivers a scripted strike identically (the
// headless run, simulate, the route as the kiosk and the study drive it), and the cues are
// scheduled as [timing] says: as soon as the strike is known, or with the picture.
#include <cmath>
#include <fstream>
#include <vector>

#include <gtest/gtest.h>

#include "audio/audio_setup.hpp"
#include "core/csv_file.hpp"
#include "app/strike/headless_loop.hpp"
#include "app/offline/simulate.hpp"
#include "app/strike/strike_route.hpp"
#include "audio/wav_file.hpp"
#include "core/present_clock.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

namespace fs = std::filesystem;
constexpr Nanos kMs = 1'000'000;

//! A straight downswing at 1.5 m/s onto bar 2's middle, sampled at 100 Hz from t0.
std::vector<PointerSample> downswing(Nanos t0) {
  const Target& bar = test::percussion().targets[2];
  const double x = 0.5 * (bar.x_min + bar.x_max);
  const double plane = bar.top_y + test::percussion().mallet_radius_m;
  std::vector<PointerSample> out;
  for (int k = 0; k <= 20; ++k) out.push_back({t0 + k * 10 * kMs, x, plane + 0.0437 - 1.5 * k * 0.01});
  out.push_back({t0 + 300 * kMs, x, plane + 0.05});  // back up
  return out;
}

//! Renders `frames` frames of an engine from frame 0 (origin 0) and returns its actuator channel.
std::vector<float> actuator_of(audio::AudioEngine& engine, const AppConfig& c, std::int64_t frames) {
  const int ch = c.audio.routing.channels;
  std::vector<float> block(static_cast<std::size_t>(256 * ch)), out;
  for (std::int64_t done = 0; done < frames; done += 256) {
    engine.process(block.data(), 256);
    for (int i = 0; i < 256; ++i) out.push_back(block[static_cast<std::size_t>(i * ch + c.audio.routing.actuator)]);
  }
  return out;
}

std::int64_t first_non_zero(const std::vector<float>& v) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (v[i] != 0.0f) return static_cast<std::int64_t>(i);
  return -1;
}

TEST(StrikeRoute, HeadlessRunSimulateAndTheRouteDeliverAStrikeIdentically) {
  const Scene& scene = test::percussion();
  const AppConfig config;
  const std::vector<PointerSample> stroke = downswing(200 * kMs);

  // The route as the kiosk's threads drive it, offline (known at the contact).
  audio::AudioRig rig = audio::make_audio_rig(scene, config, config.audio.sample_rate_hz);
  StrikeRoute route(scene, config, rig.engine.get(), nullptr, RouteOptions{audio::Producer::input, false, false});
  std::vector<Strike> by_route;
  route.on_strike = [&](const Strike& s) { by_route.push_back(s); };
  for (const PointerSample& s : stroke) route.feed(s.t_ns, {s.x, s.y});
  const std::vector<float> route_audio = actuator_of(*rig.engine, config, 48000 / 2);

  // The headless run (the soak test's and `mallet run --headless`'s loop).
  HeadlessLoop headless(scene, config, HeadlessLoop::kNoAttract);
  std::vector<Strike> by_headless;
  std::vector<float> headless_audio;
  headless.on_strike = [&](const Strike& s, bool) { by_headless.push_back(s); };
  headless.on_audio = [&](std::span<const float> block) {
    for (std::size_t i = static_cast<std::size_t>(config.audio.routing.actuator); i < block.size();
         i += static_cast<std::size_t>(headless.channels()))
      headless_audio.push_back(block[i]);
  };
  for (const PointerSample& s : stroke) headless.visitor(s.t_ns, {s.x, s.y});
  headless.drain_audio(500 * kMs);

  // simulate, from a file.
  const fs::path dir = test::scratch_dir();
  {
    std::ofstream f(dir / "traj.csv");
    f.precision(17);
    f << "t,x,y\n";
    for (const PointerSample& s : stroke) f << static_cast<double>(s.t_ns) * 1e-9 << ',' << s.x << ',' << s.y << '\n';
  }
  SimulateOptions o;
  o.scene = test::percussion_scene();
  o.input = dir / "traj.csv";
  o.out_dir = dir / "out";
  o.input_space = InputSpace::world;
  const SimulateResult sim = run_simulate(o);
  const audio::WavData wav = audio::read_wav(o.out_dir / "audio.wav");
  const auto sim_audio = wav.channel(config.audio.routing.actuator);

  ASSERT_EQ(by_route.size(), 1u);
  ASSERT_EQ(by_headless.size(), 1u);
  ASSERT_EQ(sim.impacts.size(), 1u);
  for (const Impact& i : {by_headless[0].impact, sim.impacts[0]}) {
    // The file carries the times to a nanosecond's rounding of its seconds.
    EXPECT_NEAR(static_cast<double>(i.t_ns), static_cast<double>(by_route[0].impact.t_ns), 2.0);
    EXPECT_EQ(i.target, by_route[0].impact.target);
    EXPECT_EQ(i.material, by_route[0].impact.material);
    EXPECT_NEAR(i.speed_m_per_s, by_route[0].impact.speed_m_per_s, 1e-6);
    EXPECT_EQ(i.delay_ns, 0);
  }
  const std::int64_t onset = first_non_zero(route_audio);
  ASSERT_GT(onset, 0);
  EXPECT_EQ(first_non_zero(headless_audio), onset);
  EXPECT_EQ(first_non_zero(std::vector<float>(sim_audio.begin(), sim_audio.end())), onset);
  EXPECT_NEAR(static_cast<double>(onset), static_cast<double>(by_route[0].impact.t_ns) * 48e-6, 1.0);
  for (std::int64_t n = onset; n < onset + 4800; ++n) {
    const auto i = static_cast<std::size_t>(n);
    ASSERT_NEAR(headless_audio[i], route_audio[i], 1e-6) << n;
    ASSERT_NEAR(sim_audio[i], route_audio[i], 1e-6) << n;
  }
}

TEST(StrikeRoute, AsapSoundsWhenTheStrikeIsKnownNeverBeforeItsContact) {
  const Scene& scene = test::percussion();
  const AppConfig config;
  audio::AudioRig rig = audio::make_audio_rig(scene, config, 48000);
  StrikeRoute route(scene, config, rig.engine.get(), nullptr, RouteOptions{audio::Producer::main, false, false});
  std::vector<Strike> got;
  route.on_strike = [&](const Strike& s) { got.push_back(s); };
  // Each sample known 4 ms after its time (a camera's transfer).
  for (const PointerSample& s : downswing(100 * kMs)) route.feed(s.t_ns, {s.x, s.y}, s.t_ns + 4 * kMs);
  ASSERT_EQ(got.size(), 1u);
  const Strike& s = got[0];
  EXPECT_FALSE(s.impact.predicted);
  EXPECT_GT(s.decided_ns, s.impact.t_ns);           // seen at the first sample past the contact
  EXPECT_EQ(s.decided_ns % (10 * kMs), 4 * kMs);    // ... plus the transfer
  EXPECT_EQ(s.heard_ns, s.decided_ns);
  EXPECT_EQ(s.impact.delay_ns, s.heard_ns - s.impact.t_ns);
  const std::int64_t onset = first_non_zero(actuator_of(*rig.engine, config, 24000));
  EXPECT_NEAR(static_cast<double>(onset), static_cast<double>(s.heard_ns) * 48e-6, 1.0);
  EXPECT_EQ(route.strikes(), 1u);
}

TEST(StrikeRoute, ScheduleAheadCoversTheDecisionSoTheLatencyStaysConstant) {
  const Scene& scene = test::percussion();
  AppConfig config;
  config.audio.schedule_ahead_ms = 12;
  StrikeRoute route(scene, config, nullptr, nullptr, RouteOptions{audio::Producer::main, false, false});
  std::optional<Strike> s;
  for (const PointerSample& p : downswing(0))
    if (auto got = route.feed(p.t_ns, {p.x, p.y}, p.t_ns + 1 * kMs)) s = got;
  ASSERT_TRUE(s);
  EXPECT_EQ(s->heard_ns, s->impact.t_ns);  // + 12 ms in the engine, whatever the sample phase
  EXPECT_EQ(s->impact.delay_ns, 0);
}

TEST(StrikeRoute, PictureAlignmentHearsTheStrikeWithTheFirstFrameThatShowsIt) {
  const Scene& scene = test::percussion();
  AppConfig config;
  config.timing.align = CueAlign::picture;
  config.timing.display_latency_ms = 5;
  PresentClock picture(60.0, PresentPacing::fifo);
  picture.frame_started(0);
  const Nanos period = picture.period_ns();
  audio::AudioRig rig = audio::make_audio_rig(scene, config, 48000);
  StrikeRoute route(scene, config, rig.engine.get(), &picture, RouteOptions{audio::Producer::main, false, false});
  std::optional<Strike> s;
  for (const PointerSample& p : downswing(100 * kMs))
    if (auto got = route.feed(p.t_ns, {p.x, p.y}, p.t_ns + 2 * kMs)) s = got;
  ASSERT_TRUE(s);
  // The first frame starting after the decision, two refreshes later (FIFO).
  const Nanos next_start = (s->decided_ns + period - 1) / period * period;
  EXPECT_EQ(s->shown_ns, next_start + 2 * period);
  EXPECT_EQ(s->heard_ns, s->shown_ns + 5 * kMs);
  const std::int64_t onset = first_non_zero(actuator_of(*rig.engine, config, 24000));
  EXPECT_NEAR(static_cast<double>(onset), static_cast<double>(s->heard_ns) * 48e-6, 1.0);
  // The bounce is Eq. 1 from the contact: the frame that shows it sees a displacement.
  EXPECT_NE(route.view().vibration.offset_m(s->shown_ns), 0.0);
}

TEST(StrikeRoute, AStimulusGetsTheSameThreeCuesAsAHandsStrike) {
  const Scene& scene = test::percussion();
  const AppConfig config;
  audio::AudioRig rig = audio::make_audio_rig(scene, config, 48000);
  StrikeRoute route(scene, config, rig.engine.get(), nullptr, RouteOptions{audio::Producer::main, false, false});
  const Impact stimulus = test::strike(11, 50 * kMs, 0.8);
  const Strike s = route.present(stimulus, 40 * kMs);
  EXPECT_TRUE(s.stimulus);
  EXPECT_EQ(s.heard_ns, stimulus.t_ns);
  EXPECT_EQ(route.strikes(), 1u);
  EXPECT_EQ(route.view().vibration.offset_m(stimulus.t_ns), 0.0);
  EXPECT_NE(route.view().vibration.offset_m(stimulus.t_ns + 20 * kMs), 0.0);
  const std::int64_t onset = first_non_zero(actuator_of(*rig.engine, config, 9600));
  EXPECT_NEAR(static_cast<double>(onset), 50e-3 * 48000, 1.0);
}

TEST(StrikeRoute, TheHeadlessStudysStimulusIsTheRoutesStimulus) {
  // The study presents its stimuli through HeadlessLoop::present (headless) or the window's
  // route (StrikeRoute::present): the same strike, the same samples.
  const Scene& scene = test::percussion();
  const AppConfig config;
  const Impact stimulus = test::strike(11, 120 * kMs, 0.8);
  audio::AudioRig rig = audio::make_audio_rig(scene, config, config.audio.sample_rate_hz);
  StrikeRoute route(scene, config, rig.engine.get(), nullptr, RouteOptions{audio::Producer::main, false, false});
  route.present(stimulus, stimulus.t_ns);
  const std::vector<float> by_route = actuator_of(*rig.engine, config, 48000 / 2);

  HeadlessLoop study(scene, config, HeadlessLoop::kNoAttract);
  std::vector<Strike> delivered;
  std::vector<float> by_study;
  study.on_strike = [&](const Strike& s, bool ghost) {
    EXPECT_FALSE(ghost);
    delivered.push_back(s);
  };
  study.on_audio = [&](std::span<const float> block) {
    for (std::size_t i = static_cast<std::size_t>(config.audio.routing.actuator); i < block.size();
         i += static_cast<std::size_t>(study.channels()))
      by_study.push_back(block[i]);
  };
  study.present(stimulus);
  study.drain_audio(500 * kMs);
  ASSERT_EQ(delivered.size(), 1u);
  EXPECT_TRUE(delivered[0].stimulus);
  EXPECT_EQ(delivered[0].heard_ns, stimulus.t_ns);
  const std::int64_t onset = first_non_zero(by_route);
  ASSERT_GT(onset, 0);
  EXPECT_EQ(first_non_zero(by_study), onset);
  for (std::int64_t n = onset; n < onset + 4800; ++n)
    ASSERT_NEAR(by_study[static_cast<std::size_t>(n)], by_route[static_cast<std::size_t>(n)], 1e-6) << n;
  EXPECT_EQ(study.visual_offset_m(stimulus.t_ns + 20 * kMs), route.view().vibration.offset_m(stimulus.t_ns + 20 * kMs));
}

TEST(StrikeRoute, TheWallsMaterialRequestAppliesFromTheNextSample) {
  const Scene& wall = test::wall();
  StrikeRoute route(wall, AppConfig{}, nullptr, nullptr, RouteOptions{audio::Producer::main, false, false});
  const int before = route.loop().wall_material();
  const int other = wall.wall_materials.back() == before ? wall.wall_materials.front() : wall.wall_materials.back();
  route.request_wall_material(other);
  EXPECT_EQ(route.loop().wall_material(), before);  // nothing applied off the feeding thread
  route.feed(0, {0.0, 0.3});
  EXPECT_EQ(route.loop().wall_material(), other);
}

}  // namespace
}  // namespace mallet::app
