// `mallet simulate` end to end: a scripted strike on wood and one on metal produce the
// expected events, cursor trace and audio; bad input exits 2 with nothing written.
#include <cmath>
#include <csignal>
#include <fstream>
#include <numbers>

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "app/offline/analyze.hpp"
#include "core/csv_file.hpp"
#include "app/offline/simulate.hpp"
#include "audio/wav_file.hpp"
#include "core/config/scene_config.hpp"
#include "run_cli.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

namespace fs = std::filesystem;

// Two straight downward strikes in world space (sphere centre): bar 2 (E5, wood) at
// 1.2 m/s and bar 11 (F6, metal) at 0.8 m/s, sampled at 60 Hz; contact times follow
// from the geometry: the centre crosses top_y + r.
struct Scripted {
  fs::path csv;
  double t_wood, v_wood = 1.2, t_metal, v_metal = 0.8;
};

Scripted write_two_strikes(const fs::path& dir, const Scene& scene) {
  Scripted s;
  s.csv = dir / "traj.csv";
  std::ofstream f(s.csv);
  f << "t,x,y\n";
  const double plane = scene.targets[2].top_y + scene.mallet_radius_m;
  const double x_wood = 0.5 * (scene.targets[2].x_min + scene.targets[2].x_max);
  const double x_metal = 0.5 * (scene.targets[11].x_min + scene.targets[11].x_max);
  const double y0 = plane + 0.1;
  f.precision(17);
  // Wood: y = y0 − v·t from t = 0 to 0.2 s, then rise.
  for (int k = 0; k <= 12; ++k) f << k / 60.0 << ',' << x_wood << ',' << y0 - s.v_wood * (k / 60.0) << '\n';
  s.t_wood = 0.1 / s.v_wood;
  f << 0.4 << ',' << x_wood << ',' << y0 << '\n';
  // Metal: move over, then y = y0 − v·(t − 1).
  for (int k = 0; k <= 15; ++k)
    f << 1.0 + k / 60.0 << ',' << x_metal << ',' << y0 - s.v_metal * (k / 60.0) << '\n';
  s.t_metal = 1.0 + 0.1 / s.v_metal;
  return s;
}

TEST(Simulate, ScriptedWoodAndMetalStrikesGiveExactStimuli) {
  const fs::path dir = test::scratch_dir();
  const Scene scene = config::load_scene(test::percussion_scene());
  const Scripted s = write_two_strikes(dir, scene);
  SimulateOptions o;
  o.scene = test::percussion_scene();
  o.input = s.csv;
  o.out_dir = dir / "out";
  o.input_space = InputSpace::world;
  const SimulateResult r = run_simulate(o);
  ASSERT_EQ(r.impacts.size(), 2u);

  // events.csv
  const csv::Table events = csv::read(o.out_dir / "events.csv");
  EXPECT_EQ(events.header, (std::vector<std::string>{"t", "target", "instrument", "material", "note", "velocity"}));
  ASSERT_EQ(events.rows.size(), 2u);
  EXPECT_NEAR(events.number(0, 0), s.t_wood, 1e-6);
  EXPECT_EQ(events.rows[0][1], "2");
  EXPECT_EQ(events.rows[0][2], "xylophone");
  EXPECT_EQ(events.rows[0][3], "wood");
  EXPECT_EQ(events.rows[0][4], "76");
  // Speeds are exact up to the nanosecond quantisation of the sample times (1 ns in 16.7 ms).
  EXPECT_NEAR(events.number(0, 5), s.v_wood, 1e-7 * s.v_wood);
  EXPECT_NEAR(events.number(1, 0), s.t_metal, 1e-6);
  EXPECT_EQ(events.rows[1][3], "metal");
  EXPECT_EQ(events.rows[1][4], "89");
  EXPECT_NEAR(events.number(1, 5), s.v_metal, 1e-7 * s.v_metal);

  // audio.wav: channel 1 is Eq. 1 with the actuator triple from the impact's own
  // sample; channel 0 is the note, starting on the same sample.
  const audio::WavData wav = audio::read_wav(o.out_dir / "audio.wav");
  ASSERT_EQ(wav.channels, 2);
  ASSERT_EQ(wav.sample_rate_hz, 48000);
  const auto acoustic = wav.channel(0), actuator = wav.channel(1);
  const double gain = AppConfig{}.actuator.gain;
  const Impact& wood = r.impacts[0];
  const auto first = static_cast<std::size_t>(std::ceil(static_cast<double>(wood.t_ns) * 48e-6));
  for (std::size_t n = 0; n < first; ++n) {
    ASSERT_EQ(actuator[n], 0.0) << n;
    ASSERT_EQ(acoustic[n], 0.0) << n;
  }
  EXPECT_NE(acoustic[first], 0.0);
  double note_energy = 0;
  for (std::size_t n = first; n < first + 4800; ++n) note_energy += acoustic[n] * acoustic[n];
  EXPECT_GT(note_energy, 1.0);  // a clearly audible note, not a click
  for (std::size_t n = first; n < first + 4800; ++n) {
    const double t = static_cast<double>(n) / 48000 - static_cast<double>(wood.t_ns) * 1e-9;
    const double want = gain * 1.0 * s.v_wood * std::exp(-80 * t) * std::sin(2 * std::numbers::pi * 100 * t);
    ASSERT_NEAR(actuator[n], want, 2e-7) << n;
  }

  // cursor.csv: offset is the visual Eq. 1 of the latest impact; while the hand is
  // below the surface the displayed head rests on it (plus the offset).
  const csv::Table cursor = csv::read(o.out_dir / "cursor.csv");
  EXPECT_EQ(cursor.header,
            (std::vector<std::string>{"t", "hand_x", "hand_y", "cursor_x", "cursor_y", "offset"}));
  const double plane = scene.targets[2].top_y + scene.mallet_radius_m;
  int checked_held = 0;
  for (std::size_t row = 0; row < cursor.rows.size(); ++row) {
    const double t = cursor.number(row, 0);
    if (t < s.t_wood || t >= s.t_metal) continue;
    const double since = t - static_cast<double>(wood.t_ns) * 1e-9;
    const double want = 0.009 * s.v_wood * std::exp(-8 * since) * std::sin(2 * std::numbers::pi * 5 * since);
    ASSERT_NEAR(cursor.number(row, 5), want, 1e-9) << "t=" << t;
    if (cursor.number(row, 2) < plane) {
      ASSERT_NEAR(cursor.number(row, 4), plane + cursor.number(row, 5), 1e-9);
      ++checked_held;
    }
  }
  EXPECT_GT(checked_held, 10);
  EXPECT_EQ(cursor.number(1, 0) - cursor.number(0, 0), 0.001);  // --trace-rate 1000
}

TEST(Simulate, ScreenSpaceInputIsMappedThroughTheScene) {
  const fs::path dir = test::scratch_dir();
  const Scene scene = config::load_scene(test::percussion_scene());
  const Target& bar = scene.targets[12];
  const double x = scene.screen_to_world.unmap({0.5 * (bar.x_min + bar.x_max), 0}).x;
  const double y_above = scene.screen_to_world.unmap({0, 0.2}).y;
  const double y_below = scene.screen_to_world.unmap({0, -0.05}).y;
  std::ofstream f(dir / "t.csv");
  f.precision(17);
  f << "t,x,y\n0," << x << ',' << y_above << "\n0.25," << x << ',' << y_below << '\n';
  f.close();
  SimulateOptions o;
  o.scene = test::percussion_scene();
  o.input = dir / "t.csv";
  o.out_dir = dir / "out";
  const SimulateResult r = run_simulate(o);
  ASSERT_EQ(r.impacts.size(), 1u);
  EXPECT_EQ(r.impacts[0].target, 12);
  // 0.25 m at 1 m/s from 0.2 to −0.05: contact when the centre is r above the bar.
  EXPECT_NEAR(r.impacts[0].speed_m_per_s, 1.0, 1e-9);
  EXPECT_NEAR(static_cast<double>(r.impacts[0].t_ns) * 1e-9, 0.2 - scene.mallet_radius_m, 1e-9);
}

TEST(Simulate, MonoRoutingMixesBothIntoOneChannel) {
  const fs::path dir = test::scratch_dir();
  const Scene scene = config::load_scene(test::percussion_scene());
  const Scripted s = write_two_strikes(dir, scene);
  std::ofstream(dir / "mono.toml") << "[audio.routing]\nchannels = 1\nacoustic = 0\nactuator = 0\n";
  SimulateOptions o;
  o.scene = test::percussion_scene();
  o.input = s.csv;
  o.out_dir = dir / "out";
  o.input_space = InputSpace::world;
  o.config = dir / "mono.toml";
  o.sample_rate_hz = 8000;
  run_simulate(o);
  const audio::WavData wav = audio::read_wav(o.out_dir / "audio.wav");
  EXPECT_EQ(wav.channels, 1);
  EXPECT_EQ(wav.sample_rate_hz, 8000);
  double energy = 0;
  for (float x : wav.samples) energy += double(x) * x;
  EXPECT_GT(energy, 0.0);
}

//! The first sample of a channel that is not zero.
std::int64_t onset_of(const std::vector<float>& channel) {
  for (std::size_t n = 0; n < channel.size(); ++n)
    if (channel[n] != 0.0f) return static_cast<std::int64_t>(n);
  return -1;
}

//! One straight strike on bar 2 at 1.1 m/s (its contact between two samples), sampled at
//! `rate_hz` from 50 ms (60 Hz: a window system's mouse; 100 Hz: the Wii Remote's camera).
fs::path write_one_strike(const fs::path& dir, const Scene& scene, double rate_hz) {
  const fs::path csv = dir / "one.csv";
  std::ofstream f(csv);
  f.precision(17);
  f << "t,x,y\n";
  const double plane = scene.targets[2].top_y + scene.mallet_radius_m;
  const double x = 0.5 * (scene.targets[2].x_min + scene.targets[2].x_max);
  for (int k = 0; k <= static_cast<int>(0.2 * rate_hz); ++k)
    f << 0.05 + k / rate_hz << ',' << x << ',' << plane + 0.1 - 1.1 * (k / rate_hz) << '\n';
  return csv;
}

struct CausalRun {
  csv::Table events;
  std::vector<float> actuator, acoustic;
};

//! With `camera`, as the kiosk's camera route (--camera: the read-out as the input delay).
CausalRun run_causal(const fs::path& dir, const std::string& name, const std::string& settings, double delay_ms,
                     double rate_hz = 60.0, bool camera = false) {
  const Scene scene = config::load_scene(test::percussion_scene());
  std::ofstream(dir / (name + ".toml")) << settings;
  SimulateOptions o;
  o.scene = test::percussion_scene();
  o.input = write_one_strike(dir, scene, rate_hz);
  o.out_dir = dir / name;
  o.input_space = InputSpace::world;
  o.config = dir / (name + ".toml");
  o.causal = true;
  o.input_delay_ms = delay_ms;
  o.camera = camera;
  run_simulate(o);
  const audio::WavData wav = audio::read_wav(o.out_dir / "audio.wav");
  const auto a = wav.channel(1), n = wav.channel(0);
  return {csv::read(o.out_dir / "events.csv"), {a.begin(), a.end()}, {n.begin(), n.end()}};
}

TEST(SimulateCausal, AsapSoundsWhenTheSampleAfterTheContactArrives) {
  const fs::path dir = test::scratch_dir();
  const CausalRun r = run_causal(dir, "asap", "[timing]\nalign = \"asap\"\npredict_horizon_ms = 0\n", 8.0);
  EXPECT_EQ(r.events.header, (std::vector<std::string>{"t", "target", "instrument", "material", "note", "velocity",
                                                        "contact_t", "sound_t", "shown_t", "predicted"}));
  ASSERT_EQ(r.events.rows.size(), 1u);
  const double contact = r.events.number(0, 6), sound = r.events.number(0, 7), shown = r.events.number(0, 8);
  EXPECT_EQ(r.events.number(0, 0), contact);
  EXPECT_EQ(r.events.rows[0][9], "0");
  // Known at the first sample past the contact (60 Hz from 50 ms) plus the 8 ms delay.
  const double first_after = 0.05 + std::ceil((contact - 0.05) * 60.0) / 60.0;
  EXPECT_NEAR(sound, first_after + 0.008, 1e-6);
  // Both channels start in audio.wav at sound_t, on its own sample.
  EXPECT_NEAR(static_cast<double>(onset_of(r.actuator)), sound * 48000, 1.0);
  EXPECT_EQ(onset_of(r.acoustic), onset_of(r.actuator));
  // The first 60 Hz FIFO frame started after the decision is on screen two refreshes later.
  const double period = 1.0 / 60.0;
  EXPECT_NEAR(shown, std::ceil(sound / period - 1e-9) * period + 2 * period, 2e-6);
}

TEST(SimulateCausal, PictureAlignmentSoundsWithTheFrameThatShowsTheBounce) {
  const fs::path dir = test::scratch_dir();
  const CausalRun r = run_causal(dir, "picture", "[timing]\nalign = \"picture\"\ndisplay_latency_ms = 4\n", 8.0);
  ASSERT_EQ(r.events.rows.size(), 1u);
  const double sound = r.events.number(0, 7), shown = r.events.number(0, 8);
  EXPECT_NEAR(sound, shown + 0.004, 1e-9);
  EXPECT_NEAR(static_cast<double>(onset_of(r.actuator)), sound * 48000, 1.0);
  EXPECT_EQ(onset_of(r.acoustic), onset_of(r.actuator));
}

TEST(SimulateCausal, APredictedStrikeSoundsAtItsPredictedContactBeforeTheSampleShowsIt) {
  const fs::path dir = test::scratch_dir();
  // The 100 Hz camera, each sample known at once: the sample 0.9 ms before the contact
  // predicts the constant-speed downswing's crossing (the next sample is 9.1 ms after it).
  const CausalRun r = run_causal(dir, "predict", "[timing]\npredict_horizon_ms = 10\n", 0.0, 100.0);
  ASSERT_EQ(r.events.rows.size(), 1u);
  EXPECT_EQ(r.events.rows[0][9], "1");
  const double contact = r.events.number(0, 6), sound = r.events.number(0, 7);
  const double plane_crossing = 0.05 + 0.1 / 1.1;  // the true contact
  EXPECT_NEAR(contact, plane_crossing, 1e-4);
  EXPECT_NEAR(sound, contact, 1e-9);  // scheduled at the predicted contact, not at the next sample
  EXPECT_LT(sound, 0.15);  // the sample that would have shown it
  EXPECT_NEAR(static_cast<double>(onset_of(r.actuator)), sound * 48000, 1.0);
  EXPECT_NEAR(r.events.number(0, 5), 1.1, 0.011);  // the predicted speed, within 1 %
}

TEST(SimulateCausal, TheCameraRouteHoldsAFrameAfterItsReadOutAndPredictsAcrossIt) {
  // The kiosk's camera route at 240 Hz, 500 µs: a frame is held 0.25 + 4.1667 ms after
  // its mid-exposure time (core/camera_model.hpp), unless --input-delay-ms says otherwise.
  const fs::path dir = test::scratch_dir();
  auto run = [&](const std::string& name, const std::string& settings, bool camera) {
    return run_causal(dir, name, settings, 0.0, 240.0, camera).events;
  };
  const std::string camera = "[camera]\nrate_hz = 240\nexposure_us = 500\n";
  const csv::Table solver = run("solver", "[timing]\npredict_horizon_ms = 0\n" + camera, true);
  ASSERT_EQ(solver.rows.size(), 1u);
  EXPECT_EQ(solver.rows[0][9], "0");
  const double contact = solver.number(0, 6);
  const double first_after = 0.05 + std::ceil((contact - 0.05) * 240.0) / 240.0;
  EXPECT_NEAR(solver.number(0, 7), first_after + 0.00025 + 1.0 / 240.0, 1e-6);
  // With the presets' prediction the straight downswing is called before its contact's
  // frame is held, and scheduled at the predicted contact.
  const csv::Table tuned = run("tuned", "[timing]\npredict_horizon_ms = 10\n" + camera, true);
  ASSERT_EQ(tuned.rows.size(), 1u);
  EXPECT_EQ(tuned.rows[0][9], "1");
  EXPECT_NEAR(tuned.number(0, 7), 0.05 + 0.1 / 1.1, 2e-4);
  // Without --camera the same settings are the Wii's route: no read-out, the preset as it is.
  const csv::Table plain = run("plain", "[timing]\npredict_horizon_ms = 0\n" + camera, false);
  EXPECT_NEAR(plain.number(0, 7), first_after, 1e-6);
}

TEST(SimulateCausal, WithoutCausalTheTimingSettingsChangeNothing) {
  const fs::path dir = test::scratch_dir();
  const Scene scene = config::load_scene(test::percussion_scene());
  const Scripted s = write_two_strikes(dir, scene);
  std::ofstream(dir / "timing.toml") << "[timing]\nalign = \"picture\"\ndisplay_latency_ms = 20\npredict_horizon_ms = 20\n";
  auto run = [&](const std::string& name, bool timing) {
    SimulateOptions o;
    o.scene = test::percussion_scene();
    o.input = s.csv;
    o.out_dir = dir / name;
    o.input_space = InputSpace::world;
    if (timing) o.config = dir / "timing.toml";
    run_simulate(o);
    return o.out_dir;
  };
  const fs::path plain = run("plain", false), timed = run("timed", true);
  for (const char* file : {"events.csv", "cursor.csv", "audio.wav"}) {
    std::ifstream a(plain / file, std::ios::binary), b(timed / file, std::ios::binary);
    const std::string da((std::istreambuf_iterator<char>(a)), {}), db((std::istreambuf_iterator<char>(b)), {});
    EXPECT_FALSE(da.empty()) << file;
    EXPECT_EQ(da, db) << file;
  }
}

TEST(SimulateCli, BadInputExitsTwoWithOneLineAndWritesNothing) {
  const fs::path dir = test::scratch_dir();
  std::ofstream(dir / "unsorted.csv") << "t,x,y\n0,0.5,0.5\n0.2,0.5,0.5\n0.1,0.5,0.5\n";
  std::ofstream(dir / "empty.csv") << "";
  std::ofstream(dir / "nocol.csv") << "t,x\n0,0\n";
  std::ofstream(dir / "nant.csv") << "t,x,y\n0,0,0\nnan,0,0\n";
  std::ofstream(dir / "broken.toml") << "name = \"x\"\nmallet_radius_m = [\n";
  const std::string good = (dir / "unsorted.csv").string();
  const struct {
    std::string args, expect;
  } cases[] = {
      {"--input " + good, "unsorted.csv:4: t = 0.1 is before the previous row's t = 0.2"},
      {"--input " + (dir / "empty.csv").string(), "empty.csv: empty file"},
      {"--input " + (dir / "nocol.csv").string(), "nocol.csv:1: missing column \"y\""},
      {"--input " + (dir / "nant.csv").string(), "nant.csv:3: t is not a finite number"},
      {"--input " + (dir / "nocol.csv").string() + " --scene " + (dir / "broken.toml").string(), "broken.toml:"},
  };
  for (const auto& c : cases) {
    const fs::path out = dir / "out";
    const test::CliResult r = test::run_mallet("simulate " + c.args + " --out " + out.string());
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

TEST(SimulateCli, ActuatorAboveNyquistIsRefused) {
  const fs::path dir = test::scratch_dir();
  std::ofstream(dir / "t.csv") << "t,x,y\n0,0.5,0.2\n0.1,0.5,0.9\n";
  // The shipped scene with a metal whose actuator frequency is above 24 kHz.
  std::ifstream scene_in(test::percussion_scene());
  std::string scene((std::istreambuf_iterator<char>(scene_in)), std::istreambuf_iterator<char>());
  scene.replace(scene.find("../materials.toml"), 17, "materials.toml");
  std::ofstream(dir / "scene.toml") << scene;
  std::ofstream(dir / "materials.toml")
      << "[material.wood]\nvisual = { amplitude_s = 0.009, decay_per_s = 8.0, freq_hz = 5.0 }\n"
         "actuator = { amplitude = 1.0, decay_per_s = 80.0, freq_hz = 100.0 }\n"
         "[material.metal]\nvisual = { amplitude_s = 0.02, decay_per_s = 9.0, freq_hz = 15.0 }\n"
         "actuator = { amplitude = 2.0, decay_per_s = 90.0, freq_hz = 30000.0 }\n";
  const test::CliResult r = test::run_mallet("simulate --input " + (dir / "t.csv").string() + " --scene " +
                                             (dir / "scene.toml").string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("Nyquist"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(SimulateCli, NonFiniteSamplesAreIgnoredAndCounted) {
  const fs::path dir = test::scratch_dir();
  std::ofstream(dir / "t.csv") << "t,x,y\n0,0.3,0.2\n0.05,nan,0.5\n0.1,0.3,inf\n0.1,0.3,0.3\n0.2,0.3,0.9\n";
  const test::CliResult r = test::run_mallet("simulate --input " + (dir / "t.csv").string() + " --out " +
                                             (dir / "out").string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("1 impact from 3 samples (ignored: 2 non-finite, 0 not after the previous sample)"),
            std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "audio.wav"));
}

// 522 samples at 100 Hz, 5.21 s of strokes, with t written in milliseconds: 5210 "seconds".
// Line 1 is a comment, line 2 the header, sample k on line 3 + k.
fs::path write_milliseconds_trajectory(const fs::path& dir) {
  const fs::path csv = dir / "ms.csv";
  std::ofstream f(csv);
  f << "# recorded with t in ms\nt,x,y\n";
  for (int k = 0; k < 522; ++k) f << 10 * k << ",0.5," << (k % 100 < 50 ? 0.3 : 0.5) << '\n';
  return csv;
}

// Small rates, so that even a run that is not refused writes little.
const std::string kSmallOutputs = " --sample-rate 1000 --trace-rate 1 --tail 0";

TEST(SimulateCli, ATrajectoryPastAnHourIsRefusedAtItsRow) {
  const fs::path dir = test::scratch_dir();
  const fs::path csv = write_milliseconds_trajectory(dir);
  const test::CliResult r =
      test::run_mallet("simulate --input " + csv.string() + " --out " + (dir / "out").string() + kSmallOutputs);
  EXPECT_EQ(r.status, 2) << r.output;
  // The first row past 3600 s: t = 3610, sample 361, line 364.
  EXPECT_NE(r.output.find("ms.csv:364: t = 3610 s is more than an hour after t = 0 (is t in milliseconds?"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("--allow-long"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(SimulateCli, AllowLongSimulatesATrajectoryPastAnHour) {
  const fs::path dir = test::scratch_dir();
  const fs::path csv = write_milliseconds_trajectory(dir);
  const test::CliResult r = test::run_mallet("simulate --allow-long --input " + csv.string() + " --out " +
                                             (dir / "out").string() + kSmallOutputs);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("from 522 samples"), std::string::npos) << r.output;
  const audio::WavData wav = audio::read_wav(dir / "out" / "audio.wav");
  EXPECT_EQ(wav.sample_rate_hz, 1000);
  EXPECT_EQ(wav.samples.size() / static_cast<std::size_t>(wav.channels), 5'210'000u);  // t = 5210 s
  EXPECT_TRUE(fs::exists(dir / "out" / "cursor.csv"));
  EXPECT_TRUE(fs::exists(dir / "out" / "events.csv"));
}

// `mallet simulate` as a child whose cursor.csv.partial is a FIFO this test reads: the child
// is certainly in the middle of writing when the signal is sent (it cannot finish that file
// before the test has read it all), and no wait is timed. Returns the child's wait status.
int simulate_signalled_mid_write(const fs::path& dir, int signal, std::string& stderr_text) {
  const fs::path csv = dir / "ten-minutes.csv";
  std::ofstream(csv) << "t,x,y\n0,0.5,0.3\n600,0.5,0.3\n";  // 600 000 cursor rows at 1000/s
  const fs::path out = dir / "out";
  fs::create_directories(out);
  const fs::path fifo = out / "cursor.csv.partial";
  if (mkfifo(fifo.c_str(), 0600) != 0) return -1;
  const fs::path err = dir / "stderr.txt";
  const std::string input = csv.string(), out_dir = out.string();
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    dup2(fd, 1);
    dup2(fd, 2);
    execl(MALLET_TEST_BINARY, MALLET_TEST_BINARY, "simulate", "--input", input.c_str(), "--out", out_dir.c_str(),
          "--sample-rate", "1000", static_cast<char*>(nullptr));
    _exit(127);
  }
  // Non-blocking, so that a child that never opens the FIFO cannot hang the test.
  const int fd = open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  bool data = false, signalled = false;
  char buf[65536];
  for (int guard = 0; guard < 1'000'000; ++guard) {
    pollfd p{fd, POLLIN, 0};
    const int ready = poll(&p, 1, 100);
    if (ready > 0 && (p.revents & POLLIN)) {
      const ssize_t n = read(fd, buf, sizeof buf);
      if (n > 0) {
        data = true;
        if (!signalled) signalled = kill(pid, signal) == 0;  // rows have come: mid-write
        continue;
      }
      if (n == 0 && data) break;  // the writer is gone
    } else if (ready > 0 && (p.revents & POLLHUP)) {
      break;
    } else if (!data && waitpid(pid, nullptr, WNOHANG) == pid) {
      close(fd);
      return -1;  // it ended without writing the cursor
    }
  }
  close(fd);
  int status = 0;
  waitpid(pid, &status, 0);
  std::ifstream in(err);
  stderr_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return signalled ? status : -1;
}

TEST(SimulateCli, ASignalWhileWritingRemovesThePartialFilesAndExits128PlusIt) {
  for (const int signal : {SIGTERM, SIGINT}) {
    SCOPED_TRACE(signal == SIGTERM ? "SIGTERM" : "SIGINT");
    const fs::path dir = test::scratch_dir();
    std::string err;
    const int status = simulate_signalled_mid_write(dir, signal, err);
    ASSERT_NE(status, -1) << err;
    // Nothing left behind: no *.partial (the FIFO included), no output.
    std::string left;
    for (const auto& e : fs::directory_iterator(dir / "out")) left += e.path().filename().string() + " ";
    EXPECT_EQ(left, "");
    EXPECT_FALSE(WIFSIGNALED(status)) << "killed by signal " << WTERMSIG(status);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 128 + signal) << err;  // 143, 130
    EXPECT_NE(err.find(signal == SIGTERM ? "stopped by SIGTERM" : "stopped by SIGINT"), std::string::npos) << err;
  }
}

TEST(AnalyzeCli, FitsTheShippedDemoBackToTableOne) {
  const fs::path dir = test::scratch_dir();
  const std::string demo = (test::config_dir() / "trajectories" / "demo.csv").string();
  ASSERT_EQ(test::run_mallet("simulate --input " + demo + " --out " + (dir / "out").string()).status, 0);
  const test::CliResult r = test::run_mallet("analyze --dir " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const auto results = analyze_simulation(dir / "out", 1);
  ASSERT_GE(results.size(), 10u);
  const Scene scene = config::load_scene(test::percussion_scene());
  for (const ImpactAnalysis& a : results) {
    const Material& m = *(a.material == "wood" ? &scene.materials[0] : &scene.materials[1]);
    ASSERT_TRUE(a.visual.ok && a.actuator.ok);
    EXPECT_NEAR(a.visual.decay_per_s, m.visual.decay_per_s, 0.01 * m.visual.decay_per_s);
    EXPECT_NEAR(a.visual.freq_hz, m.visual.freq_hz, 0.01 * m.visual.freq_hz);
    EXPECT_NEAR(a.visual.amplitude / a.velocity, m.visual.amplitude, 0.01 * m.visual.amplitude);
    EXPECT_NEAR(a.actuator.decay_per_s, m.actuator.decay_per_s, 0.01 * m.actuator.decay_per_s);
    EXPECT_NEAR(a.actuator.freq_hz, m.actuator.freq_hz, 0.01 * m.actuator.freq_hz);
  }
}

}  // namespace
}  // namespace mallet::app
