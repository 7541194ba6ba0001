// The windowed kiosk's Wii Remote path without a window, a sound card or a remote: an
// in-process fake remote (tests/input/wiimote/fake_remote.hpp) on a scripted clock feeds
// the real WiimoteDevice, whose sample sink runs RemotePointer as the reading thread would
// (here the test calls step() itself). Checked: the calibration screen's whole flow from IR
// reports to the atomically saved file; strikes posted to the engine's input ring only
// while playing and calibrated. No test sleeps or measures time.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "audio/audio_setup.hpp"
#include "app/kiosk/calibration_screen.hpp"
#include "core/data_paths.hpp"
#include "app/strike/remote_pointer.hpp"
#include "core/homography.hpp"
#include "input/wiimote/fake_remote.hpp"
#include "input/wiimote/replay_transport.hpp"
#include "input/wiimote/wiimote_device.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

using input::wiimote::LedSample;
using input::wiimote::LinkState;
using input::wiimote::WiimoteDevice;
namespace fake = input::wiimote::test;

// The camera sees the screen mirrored left-right: the calibration must own orientation.
Vec2 camera_of(Vec2 screen) { return {900.0 - screen.x * 800.0, 80.0 + screen.y * 600.0}; }
Vec2 screen_of(Vec2 camera) { return {(900.0 - camera.x) / 800.0, (camera.y - 80.0) / 600.0}; }

std::filesystem::path scratch(const std::string& name) {
  const auto dir = test::scratch_root() / ("remote-kiosk-" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

input::wiimote::WiimoteDeviceConfig device_config(bool every_frame) {
  input::wiimote::WiimoteDeviceConfig c = input::wiimote::device_config(AppConfig{});
  c.every_frame = every_frame;
  return c;
}

struct Rig {
  fake::FakeClock clock;
  fake::FakeFinder finder{clock};
  std::shared_ptr<fake::FakeRemote> remote = finder.add("/dev/hidraw3", "00:1f:32:aa:bb:cc");
  AppConfig config;
  audio::AudioRig audio = audio::make_audio_rig(test::percussion(), config, 48000);
  RemotePointer pointer{test::percussion(), config, *audio.engine};
  WiimoteDevice device;

  explicit Rig(bool every_frame = false) : device(finder, clock, device_config(every_frame)) {
    device.set_sample_sink([this](std::span<const LedSample> s, Nanos now) { pointer.on_samples(s, now); });
    for (int i = 0; i < 100'000 && device.state().link != LinkState::running; ++i) device.step();
  }
  //! Steps the device until the scripted reports are all delivered.
  void play_script() {
    for (int i = 0; i < 1'000'000 && !remote->script.empty(); ++i) device.step();
    device.step();
  }
  void hold(Vec2 camera, int reports) {
    remote->send_ir(reports, static_cast<int>(camera.x), static_cast<int>(camera.y));
  }
};

CalibrationSessionConfig session_config() {
  CalibrationSessionConfig c;
  c.screen = {1280, 720};
  return c;
}

TEST(RemoteKiosk, TheCalibrationScreenGoesFromIrReportsToASavedFile) {
  Rig rig;
  ASSERT_EQ(rig.device.state().link, LinkState::running);
  const auto dir = scratch("flow");
  const auto file = dir / "state" / "calibration.toml";  // the folder is made on saving
  CalibrationScreen screen(session_config(), file, "00:1f:32:aa:bb:cc");
  // The stick lies still somewhere, then the visitor (or operator) holds it on each target
  // for 2 s (the grace, then the dwell), at 100 reports/s.
  rig.hold({20, 20}, 10);
  for (const Vec2 target : screen.session().targets()) rig.hold(camera_of(target), 200);
  rig.play_script();
  for (const RemoteSample& s : rig.pointer.take()) {
    EXPECT_FALSE(s.screen);  // no calibration yet: no screen position, no strikes
    if (s.camera_px) screen.feed(s.t_ns, *s.camera_px);
  }
  ASSERT_EQ(screen.outcome(), CalibrationScreen::Outcome::accepted) << screen.message();
  EXPECT_NE(screen.message().find("saved"), std::string::npos) << screen.message();
  const Calibration saved = load_calibration(file);
  EXPECT_EQ(saved.remote, "00:1f:32:aa:bb:cc");
  EXPECT_EQ(saved.points, 9);
  EXPECT_LE(saved.max_error_screen_px, 10.0);
  for (const Vec2 cam : {Vec2{500, 380}, Vec2{200, 100}, Vec2{850, 650}}) {
    const Vec2 s = saved.camera_to_screen.map(cam);
    EXPECT_NEAR(s.x, screen_of(cam).x, 1e-6);
    EXPECT_NEAR(s.y, screen_of(cam).y, 1e-6);
  }
  EXPECT_EQ(rig.pointer.strikes(), 0u);
}

TEST(RemoteKiosk, TheScreenFirstPicksTheSensitivityThatShowsOneCleanDot) {
  Rig rig(/*every_frame=*/true);
  const auto dir = scratch("tuning");
  CalibrationScreen screen(session_config(), dir / "calibration.toml", "00:1f:32:aa:bb:cc");
  screen.tune_sensitivity({}, "wii3");
  ASSERT_TRUE(screen.tuning());
  // The visitor holds the light up: one clean dot of size 3 whatever the preset (a fake
  // camera), then the targets.
  rig.hold({500, 380}, 150);
  for (const Vec2 target : screen.session().targets()) rig.hold(camera_of(target), 200);
  std::vector<std::string> requested;
  for (int i = 0; i < 1'000'000 && !rig.remote->script.empty(); ++i) {
    rig.device.step();
    for (const RemoteSample& s : rig.pointer.take()) {
      if (s.frame) screen.frame(*s.frame);
      if (s.camera_px) screen.feed(s.t_ns, *s.camera_px);
    }
    if (auto preset = screen.sensitivity_request()) {
      requested.push_back(*preset);
      rig.device.request_sensitivity(*preset);
    }
  }
  EXPECT_FALSE(screen.tuning());
  EXPECT_EQ(screen.sensitivity(), "wii1");  // the least sensitive that is clean
  EXPECT_EQ(requested, (std::vector<std::string>{"wii1", "wii1"}));  // tried, then kept
  ASSERT_EQ(screen.outcome(), CalibrationScreen::Outcome::accepted) << screen.message();
  const Calibration saved = load_calibration(dir / "calibration.toml");
  EXPECT_EQ(saved.points, 9);
  // Saved with the calibration, so the kiosk starts with it after a restart.
  EXPECT_EQ(saved.ir_sensitivity, "wii1");
  EXPECT_EQ(kiosk_sensitivity(rig.config, saved), "wii1");
  EXPECT_EQ(kiosk_device_config(rig.config, saved).ir.sensitivity.name, "wii1");
}

TEST(RemoteKiosk, FramesTakenBeforeThePresetReachesTheCameraAreNotJudgedAsItsOwn) {
  Rig rig(/*every_frame=*/true);
  CalibrationScreen screen(session_config(), std::nullopt, "00:1f:32:aa:bb:cc");
  screen.tune_sensitivity({}, "wii3");
  std::vector<std::string> requested;
  // The kiosk's poll of the remote, in its order: the samples since the last pass, then the
  // preset asked for handed to the device.
  auto poll = [&] {
    for (const RemoteSample& s : rig.pointer.take())
      if (s.frame) screen.frame(*s.frame);
    if (auto preset = screen.sensitivity_request()) {
      requested.push_back(*preset);
      rig.device.request_sensitivity(*preset);
    }
  };
  // The pass that opened the screen draws its first frame before the next poll: seconds
  // under a CPU rasteriser in a slow guest, and 3 s of reports (the configured preset still)
  // wait meanwhile, more than one preset's whole observation.
  rig.hold({500, 380}, 300);
  rig.play_script();
  poll();
  EXPECT_TRUE(screen.tuning());  // none of them was taken with wii1
  EXPECT_EQ(requested, (std::vector<std::string>{"wii1"}));
  // wii1's own frames, once its start-up is done: kept, and set once more.
  rig.hold({500, 380}, 300);
  rig.play_script();
  poll();
  EXPECT_FALSE(screen.tuning());
  EXPECT_EQ(screen.sensitivity(), "wii1");
  EXPECT_EQ(requested, (std::vector<std::string>{"wii1", "wii1"}));  // two start-ups: tried, then chosen
}

TEST(RemoteKiosk, WithoutAChosenSensitivityTheKioskStartsWithTheConfiguredOne) {
  AppConfig config;
  config.wiimote.sensitivity = "marcan";
  EXPECT_EQ(kiosk_device_config(config, std::nullopt).ir.sensitivity.name, "marcan");
  Calibration c;
  EXPECT_EQ(kiosk_device_config(config, c).ir.sensitivity.name, "marcan");
  c.ir_sensitivity = "max";
  EXPECT_EQ(kiosk_device_config(config, c).ir.sensitivity.name, "max");
}

TEST(RemoteKiosk, WithTwoDotsNoSensitivityIsCleanAndTheConfiguredOneIsPutBack) {
  CalibrationScreen screen(session_config(), std::nullopt, "r");
  screen.tune_sensitivity({}, "wii3");
  std::vector<std::string> requested;
  for (int i = 0; i < 2000 && screen.tuning(); ++i) {
    IrFrame f;
    f.t_ns = Nanos{i + 1} * 10'000'000;
    f.slots[0] = IrDot{500, 380, 3};
    f.slots[1] = IrDot{100, 100, 2};  // a lamp
    screen.frame(f);
    if (auto p = screen.sensitivity_request()) requested.push_back(*p);
  }
  EXPECT_FALSE(screen.tuning());
  EXPECT_EQ(screen.sensitivity(), "wii3");
  ASSERT_FALSE(requested.empty());
  EXPECT_EQ(requested.back(), "wii3");
  EXPECT_EQ(requested.size(), kSensitivityPresets.size() + 1);
  // The targets, with the mouse's kind of input (no device): what is kept has no sensitivity
  // of its own, so the configured one stays the kiosk's after a restart.
  Nanos t = 100 * kNanosPerSecond;
  screen.feed(t, {20, 20});  // where the dot rests when the targets begin
  for (const Vec2 target : screen.session().targets())
    for (int i = 0; i < 200; ++i) screen.feed(t += 10'000'000, camera_of(target));
  ASSERT_EQ(screen.outcome(), CalibrationScreen::Outcome::accepted) << screen.message();
  EXPECT_EQ(screen.result()->ir_sensitivity, "");
}

TEST(RemoteKiosk, ThePreviousCalibrationStaysUntilTheNewOneIsAccepted) {
  Rig rig;
  const auto dir = scratch("previous");
  const auto file = dir / "calibration.toml";
  std::ofstream(file) << "previous";
  CalibrationScreen screen(session_config(), file, "00:1f:32:aa:bb:cc");
  const std::vector<Vec2>& targets = screen.session().targets();
  rig.hold({20, 20}, 10);
  for (std::size_t i = 0; i < 4; ++i) rig.hold(camera_of(targets[i]), 200);  // abandoned after 4 of 9
  rig.play_script();
  for (const RemoteSample& s : rig.pointer.take())
    if (s.camera_px) screen.feed(s.t_ns, *s.camera_px);
  EXPECT_EQ(screen.outcome(), CalibrationScreen::Outcome::measuring);
  EXPECT_EQ(screen.session().current_target(), 4);
  EXPECT_EQ(slurp(file), "previous");
}

TEST(RemoteKiosk, AnUnsavableCalibrationFailsAndSaysWhy) {
  const auto dir = scratch("unsavable");
  std::ofstream(dir / "not-a-folder") << "x";
  CalibrationScreen screen(session_config(), dir / "not-a-folder" / "calibration.toml", "r");
  Nanos t = 0;
  screen.feed(t += 10'000'000, {20, 20});  // where the dot rests when the targets begin
  for (const Vec2 target : screen.session().targets())
    for (int i = 0; i < 200; ++i) screen.feed(t += 10'000'000, camera_of(target));
  EXPECT_EQ(screen.outcome(), CalibrationScreen::Outcome::failed);
  EXPECT_FALSE(screen.result());
  EXPECT_NE(screen.message().find("Calibration not saved: "), std::string::npos) << screen.message();
}

TEST(RemoteKiosk, TheMouseStandsInForTheDotAndSavesNothing) {
  CalibrationScreen screen(session_config(), std::nullopt, "mouse");
  Nanos t = 0;
  screen.feed(t += 16'666'667, mouse_as_camera_px({0.5, 0.97}));  // where the pointer rests after R
  for (const Vec2 target : screen.session().targets())
    for (int i = 0; i < 120; ++i) screen.feed(t += 16'666'667, mouse_as_camera_px(target));  // 60 Hz frames
  ASSERT_EQ(screen.outcome(), CalibrationScreen::Outcome::accepted) << screen.message();
  EXPECT_NE(screen.message().find("mouse: not saved"), std::string::npos) << screen.message();
}

//! Carries the stick in from the sensor's corner, then holds its dot on `camera` (100
//! reports/s, at most 4 s) until the screen moves on to another target or ends.
CalibrationStep carry_and_hold(CalibrationScreen& screen, Nanos& t, Vec2 camera) {
  CalibrationStep step = screen.feed(t += 10'000'000, {20, 20});
  for (int i = 0; i < 400; ++i) {
    step = screen.feed(t += 10'000'000, camera);
    if (step == CalibrationStep::target_measured || step == CalibrationStep::round_rejected ||
        step == CalibrationStep::accepted || step == CalibrationStep::failed)
      break;
  }
  return step;
}

TEST(RemoteKiosk, TheCalibrationLabelNamesTheTargetBeingMeasuredAndItsRound) {
  CalibrationScreen screen(session_config(), std::nullopt, "r");
  screen.dot_seen(true);
  EXPECT_EQ(screen.status_line(), "Target 1 of 9, round 1   light seen");
  Nanos t = kNanosPerSecond;
  const std::vector<Vec2>& targets = screen.session().targets();
  // Round 1: target 5 (the centre) is missed by a wide margin, so it alone comes again.
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (i == 2) {
      EXPECT_EQ(screen.status_line(), "Target 3 of 9, round 1   light seen");
    }
    carry_and_hold(screen, t, camera_of(i == 4 ? Vec2{0.62, 0.31} : targets[i]));
  }
  ASSERT_EQ(screen.outcome(), CalibrationScreen::Outcome::measuring) << screen.message();
  ASSERT_EQ(screen.session().round(), 1);
  ASSERT_EQ(screen.session().current_target(), 4);
  // Eight targets are measured, but the one asked again is the fifth, not a ninth.
  EXPECT_EQ(screen.status_line(), "Target 5 of 9, round 2   light seen");
  EXPECT_EQ(carry_and_hold(screen, t, camera_of(targets[4])), CalibrationStep::accepted);
  EXPECT_EQ(screen.outcome(), CalibrationScreen::Outcome::accepted) << screen.message();
  EXPECT_EQ(screen.status_line(), screen.message());
}

TEST(RemoteKiosk, AFailedCalibrationSaysWhatToDoInPlainWordsAndTheJournalGetsTheFitsReason) {
  // The two top corners' lights swapped (a fold: each round's fit refused or far off), or
  // each hold 5 % of the screen off its target, a new way each time (far off).
  for (const bool swapped : {false, true}) {
    CalibrationScreen screen(session_config(), std::nullopt, "r");
    Nanos t = kNanosPerSecond;
    const std::vector<Vec2>& targets = screen.session().targets();
    for (int guard = 0; guard < 200 && screen.outcome() == CalibrationScreen::Outcome::measuring; ++guard) {
      const int i = screen.session().current_target().value_or(0);
      const Vec2 target = targets[static_cast<std::size_t>(i)];
      const Vec2 held = swapped ? (i == 0 ? targets[2] : i == 2 ? targets[0] : target)
                                : Vec2{target.x + 0.05 * std::sin(guard * 1.7), target.y + 0.05 * std::cos(guard * 2.3)};
      carry_and_hold(screen, t, camera_of(held));
    }
    ASSERT_EQ(screen.outcome(), CalibrationScreen::Outcome::failed) << swapped << ": " << screen.message();
    const std::string said = screen.message();
    for (const char* jargon : {"vanishing", "homography", "reprojection", "folds", "rank", "singular"})
      EXPECT_EQ(said.find(jargon), std::string::npos) << said;
    EXPECT_NE(said.find("try again"), std::string::npos) << said;
    EXPECT_NE(said.find("the previous calibration stays"), std::string::npos) << said;
    EXPECT_FALSE(screen.session().failure().empty()) << "the fit's own reason, for the journal";
    if (!swapped) {
      EXPECT_NE(said.find("did not hold still"), std::string::npos) << said;
    }
  }
}

//! A calibration that maps camera_of() back exactly.
Calibration mirrored_calibration() {
  std::vector<Vec2> cam, scr;
  for (const Vec2 s : {Vec2{0.1, 0.1}, Vec2{0.9, 0.1}, Vec2{0.9, 0.9}, Vec2{0.1, 0.9}, Vec2{0.5, 0.5}}) {
    cam.push_back(camera_of(s));
    scr.push_back(s);
  }
  const auto fit = fit_homography(cam, scr, {1280, 720});
  return calibration_from_fit(fit.value(), "test");
}

//! A downward stroke through bar `target`'s top, in camera pixels, one report per 10 ms.
void stroke(Rig& rig, int target) {
  const Scene& scene = test::percussion();
  const Target& bar = scene.targets[static_cast<std::size_t>(target)];
  const double x = (bar.x_min + bar.x_max) / 2;
  for (int i = 0; i <= 20; ++i) {
    const Vec2 screen = scene.screen_to_world.unmap({x, bar.top_y + 0.10 - 0.006 * i});
    const Vec2 cam = camera_of(screen);
    rig.remote->send(fake::ir_report({{static_cast<int>(std::lround(cam.x)), static_cast<int>(std::lround(cam.y)), 3}}));
  }
  rig.hold(camera_of(scene.screen_to_world.unmap({x, bar.top_y + 0.10})), 30);  // back up
}

TEST(RemoteKiosk, StrikesGoFromTheReadingThreadToTheEnginesInputRingOnlyWhilePlaying) {
  Rig rig;
  std::vector<Impact> struck;
  rig.pointer.on_strike = [&](const Impact& i) { struck.push_back(i); };
  rig.pointer.set_calibration(mirrored_calibration());

  stroke(rig, 3);  // not playing (Attract, Calibration, Operator): no sound from the visitor
  rig.play_script();
  EXPECT_TRUE(struck.empty());
  const std::vector<RemoteSample> seen = rig.pointer.take();
  ASSERT_FALSE(seen.empty());
  ASSERT_TRUE(seen.back().screen);  // calibrated: the kiosk's states see the movement

  rig.pointer.set_playing(true);
  stroke(rig, 3);
  rig.play_script();
  ASSERT_EQ(struck.size(), 1u);
  EXPECT_EQ(struck[0].target, 3);
  EXPECT_GT(struck[0].speed_m_per_s, 0.1);
  EXPECT_EQ(rig.pointer.strikes(), 1u);
  // The engine has it without the render loop: the next callback takes it from the ring.
  std::vector<float> out(2 * 256);
  rig.audio.engine->process(out.data(), 256);
  EXPECT_EQ(rig.audio.engine->counters().impacts, 1u);
  // The displayed head follows the filtered hand near where the stroke ended.
  const Vec2 shown = rig.pointer.view().shown;
  EXPECT_GT(shown.y, test::percussion().targets[3].top_y);

  // Without a calibration nothing strikes (the calibration screen would be up).
  rig.pointer.set_calibration(std::nullopt);
  stroke(rig, 3);
  rig.play_script();
  EXPECT_EQ(struck.size(), 1u);
}

TEST(RemoteKiosk, TrackingFollowsTheRemotesLostAndRegainedEvents) {
  Rig rig;
  rig.hold({500, 380}, 10);
  rig.play_script();
  EXPECT_TRUE(rig.pointer.tracking());
  rig.remote->gone = true;
  for (int i = 0; i < 1000 && rig.device.state().link == LinkState::running; ++i) rig.device.step();
  EXPECT_FALSE(rig.pointer.tracking());
  const std::vector<RemoteSample> seen = rig.pointer.take();
  ASSERT_FALSE(seen.empty());
  EXPECT_EQ(seen.front().event, IrTrackerEvent::regained);
  EXPECT_EQ(seen.back().event, IrTrackerEvent::lost);
}

TEST(RemoteKiosk, ARecordingPlaysAsALiveRemoteThroughTheSameDeviceAndLoops) {
  // A recording as `mallet wiimote monitor --record` writes it: the recorder's host's acks
  // and status among the IR reports (they are skipped; the replay answers this host).
  input::wiimote::Recording rec;
  rec.reports.push_back({5'000'000'000, fake::ack_report(0x16)});
  for (int i = 0; i < 20; ++i) rec.reports.push_back({6'000'000'000 + i * 10'000'000, fake::ir_report({{400 + i, 300, 3}})});
  rec.reports.push_back({6'300'000'000, fake::status_report()});
  fake::FakeClock clock;
  input::wiimote::ReplayFinder finder(rec, "visit.replay", clock);
  EXPECT_EQ(finder.enumerate().size(), 1u);
  EXPECT_EQ(finder.device().path, "replay:visit.replay");
  WiimoteDevice device(finder, clock);
  std::vector<LedSample> got;
  device.set_sample_sink([&](std::span<const LedSample> s, Nanos) { got.insert(got.end(), s.begin(), s.end()); });
  for (int i = 0; i < 100'000 && got.size() < 45; ++i) device.step();
  EXPECT_EQ(device.state().link, LinkState::running);  // the start-up got its acks
  ASSERT_GE(got.size(), 45u);
  std::vector<LedSample> points;
  for (const LedSample& s : got)
    if (s.has_point) points.push_back(s);
  ASSERT_GE(points.size(), 41u);
  EXPECT_EQ(points[0].point.x, 400.0);
  EXPECT_EQ(points[19].point.x, 419.0);
  EXPECT_EQ(points[20].point.x, 400.0);  // looped
  for (std::size_t i = 1; i < 20; ++i) EXPECT_EQ(points[i].t_ns - points[i - 1].t_ns, 10'000'000) << i;
  EXPECT_EQ(points[20].t_ns - points[19].t_ns, 10'000'000);  // one report period between loops
}

TEST(RemoteKiosk, ARecordingWithoutIrReportsIsRefusedWithItsName) {
  input::wiimote::Recording rec;
  rec.reports.push_back({1, fake::status_report()});
  fake::FakeClock clock;
  try {
    input::wiimote::ReplayFinder finder(rec, "empty.replay", clock);
    FAIL() << "accepted";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("empty.replay"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no data (IR) report"), std::string::npos) << e.what();
  }
}

TEST(RemoteKiosk, TheStateDirFollowsItsOverridesInOrder) {
  ::setenv("MALLET_STATE_DIR", "/tmp/mallet-state-test", 1);
  ::setenv("STATE_DIRECTORY", "/var/lib/mallet:/var/lib/other", 1);
  EXPECT_EQ(state_dir(), "/tmp/mallet-state-test");
  EXPECT_EQ(calibration_path(), "/tmp/mallet-state-test/calibration.toml");
  ::unsetenv("MALLET_STATE_DIR");
  EXPECT_EQ(state_dir(), "/var/lib/mallet");  // systemd's StateDirectory=mallet
  ::unsetenv("STATE_DIRECTORY");
  ::setenv("XDG_STATE_HOME", "/tmp/xdg-state", 1);
  EXPECT_EQ(state_dir(), "/tmp/xdg-state/mallet");  // a binary that is not installed
  ::unsetenv("XDG_STATE_HOME");
}

}  // namespace
}  // namespace mallet::app
