// Underruns through the real PortAudio → ALSA path, without a sound card: ALSA's default
// PCM is `plug` (the float → S16 converter, whose status is the snd_pcm_plugin_status of
// the kiosk's abort) over a paced test card (paced_pcm_plugin.cpp) that loses 30 ms every
// 60 ms, as a guest descheduled by its host. A buffer shorter than 30 ms underruns at every
// stall. The tests wait for states (counters), never for a time.
//
// What this machine cannot show: the abort itself needs dmix on a real card (dmix's commit
// moves its pointer before it reports the underrun; see UNDERRUNS in portaudio_output.hpp),
// and there is no /dev/snd here. What it shows: PortAudio's xrun path (status, prepare,
// restart) under the plug converter survives many underruns, the output counts them, and
// repeated underruns reopen the device with a larger buffer while the stream plays on.
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "audio/audio_setup.hpp"
#include "audio/portaudio_output.hpp"
#include "core/config/app_config_loader.hpp"
#include "core/file_error.hpp"
#include "test_paths.hpp"

namespace mallet::audio {
namespace {

namespace fs = std::filesystem;

constexpr int kUnderrunRate = 48000;

// Polls with small sleeps until `done()`; the cap only keeps a broken stream from hanging.
template <class Done>
bool poll_until(Done done) {
  for (int i = 0; i < 30000; ++i) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return done();
}

class UnderrunTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratch_dir();
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::replace);
    std::ofstream conf(dir_ / "asound.conf");
    conf << "pcm_type.mallet_paced { lib \"" << MALLET_TEST_PACED_PCM << "\" }\n"
         << "pcm.paced { type mallet_paced stall_ms 30 every_ms 60 }\n"
         << "pcm.!default { type plug slave { pcm \"paced\" format S16_LE } }\n";
    conf.close();
    ASSERT_TRUE(conf);
    const std::string path = "/usr/share/alsa/alsa.conf:" + (dir_ / "asound.conf").string();
    ::setenv("ALSA_CONFIG_PATH", path.c_str(), 1);
    ::setenv("XDG_RUNTIME_DIR", dir_.c_str(), 1);
  }

  static AppConfig config() {
    AppConfig c;
    c.audio.sample_rate_hz = kUnderrunRate;
    c.audio.min_latency_ms = 10;  // 10 ms + a period: under the card's 30 ms stalls
    return c;
  }

  // Frames go on flowing: `more` frames after the call.
  static bool keeps_playing(const PortAudioOutput& out, std::uint64_t more) {
    const std::uint64_t from = out.counters().frames;
    return poll_until([&] { return out.counters().frames >= from + more; });
  }

  fs::path dir_;
};

TEST_F(UnderrunTest, UnderrunsAreCountedAndTheStreamPlaysOn) {
  AppConfig c = config();
  c.audio.grow_after_underruns = 0;  // never grow: every stall underruns
  AudioRig rig = make_audio_rig(test::percussion(), c, kUnderrunRate, false);
  PortAudioOutput out(*rig.engine, c.audio);
  EXPECT_DOUBLE_EQ(out.requested_latency_s(), 0.010);
  out.start();
  ASSERT_TRUE(poll_until([&] { return out.counters().xruns >= 10; })) << out.counters().xruns << " underruns";
  EXPECT_TRUE(keeps_playing(out, kUnderrunRate / 2));
  // A strike posted between underruns is still consumed and rendered.
  ASSERT_TRUE(rig.engine->post(test::strike(3, 0, 1.0)));
  EXPECT_TRUE(keeps_playing(out, kUnderrunRate / 2));
  out.stop();
  const OutputCounters n = out.counters();
  EXPECT_TRUE(out.counters().xruns >= 10);
  EXPECT_EQ(n.buffer_growths, 0u);
  EXPECT_EQ(n.device_losses, 0u);
  EXPECT_EQ(out.requested_latency_s(), 0.010);
}

TEST_F(UnderrunTest, RepeatedUnderrunsGrowTheBufferUpToItsCeilingWhileThePlayGoesOn) {
  AppConfig c = config();
  c.audio.grow_after_underruns = 3;
  c.audio.underrun_window_ms = 60000;
  c.audio.max_latency_ms = 40;  // 10 → 20 (still under the stalls) → 40 ms, and no further
  AudioRig rig = make_audio_rig(test::percussion(), c, kUnderrunRate, false);
  PortAudioOutput out(*rig.engine, c.audio);
  const double first_latency = out.output_latency_s();
  out.start();
  ASSERT_TRUE(poll_until([&] { return out.counters().buffer_growths >= 2; }))
      << out.counters().xruns << " underruns, " << out.counters().buffer_growths << " growths";
  EXPECT_DOUBLE_EQ(out.requested_latency_s(), 0.040);
  EXPECT_GT(out.output_latency_s(), first_latency);
  EXPECT_TRUE(out.device_ok());
  EXPECT_TRUE(keeps_playing(out, kUnderrunRate));
  // At the ceiling, neither underruns nor an operator's request grow it further.
  out.grow_buffer();
  EXPECT_TRUE(keeps_playing(out, kUnderrunRate / 2));
  out.stop();
  const OutputCounters n = out.counters();
  EXPECT_GE(n.xruns, 6u);  // grow_after_underruns at 10 ms, again at 20 ms
  EXPECT_EQ(n.buffer_growths, 2u);
  EXPECT_EQ(n.device_losses, 0u);
  EXPECT_DOUBLE_EQ(out.requested_latency_s(), 0.040);
}

// A card whose buffer stays 10 ms whatever is asked (as a JACK server keeps its period): the
// first reopen comes back no larger, and the underruns that go on are not answered by another
// (each reopen is a gap in the sound; on JACK, a new client nobody has connected).
TEST_F(UnderrunTest, ADeviceThatKeepsItsBufferIsReopenedOnceNotOverAndOver) {
  {
    std::ofstream conf(dir_ / "asound.conf");
    conf << "pcm_type.mallet_paced { lib \"" << MALLET_TEST_PACED_PCM << "\" }\n"
         << "pcm.paced { type mallet_paced stall_ms 30 every_ms 60 buffer_bytes 1920 }\n"  // 480 stereo S16 frames
         << "pcm.!default { type plug slave { pcm \"paced\" format S16_LE } }\n";
    ASSERT_TRUE(conf);
  }
  AppConfig c = config();
  c.audio.grow_after_underruns = 2;
  c.audio.underrun_window_ms = 60000;
  c.audio.max_latency_ms = 100;  // doubled up to here, were each reopen taken for a growth
  AudioRig rig = make_audio_rig(test::percussion(), c, kUnderrunRate, false);
  PortAudioOutput out(*rig.engine, c.audio);
  const double first_latency = out.output_latency_s(), first_asked = out.requested_latency_s();
  ASSERT_LT(2 * first_asked, c.audio.max_latency_ms / 1000);  // room for more than one doubling
  out.start();
  // Underruns well past what four more reopens would have needed (two each).
  ASSERT_TRUE(poll_until([&] { return out.counters().xruns >= 14; })) << out.counters().xruns << " underruns";
  EXPECT_TRUE(keeps_playing(out, kUnderrunRate / 2));
  out.stop();
  const OutputCounters n = out.counters();
  EXPECT_EQ(n.buffer_growths, 0u);                     // the one reopen grew nothing
  EXPECT_DOUBLE_EQ(out.requested_latency_s(), 2 * first_asked);  // asked for more once, never again
  EXPECT_DOUBLE_EQ(out.output_latency_s(), first_latency);
  EXPECT_EQ(n.device_losses, 0u);
}

TEST_F(UnderrunTest, AGrownBufferSurvivesADeviceReopen) {
  AppConfig c = config();
  c.audio.grow_after_underruns = 2;
  c.audio.underrun_window_ms = 60000;
  AudioRig rig = make_audio_rig(test::percussion(), c, kUnderrunRate, false);
  PortAudioOutput::Options o;
  o.first_retry = std::chrono::milliseconds(5);
  PortAudioOutput out(*rig.engine, c.audio, o);
  out.start();
  ASSERT_TRUE(poll_until([&] { return out.counters().buffer_growths >= 1; }));
  const double grown = out.requested_latency_s();
  EXPECT_GE(grown, 0.020);
  out.drop_device();
  ASSERT_TRUE(poll_until([&] { return out.counters().reopens >= 1; }));
  EXPECT_GE(out.requested_latency_s(), grown);
  EXPECT_TRUE(keeps_playing(out, kUnderrunRate / 2));
  out.stop();
}

// [audio]'s underrun keys: read with their ranges, and a ceiling below the floor refused.
TEST(UnderrunSettings, AreReadAndChecked) {
  const AppConfig d;
  EXPECT_EQ(d.audio.min_latency_ms, 10.0);
  EXPECT_EQ(d.audio.grow_after_underruns, 4);
  const AppConfig shipped = config::load_app_config(test::config_dir() / "mallet.toml");
  EXPECT_EQ(shipped.audio.min_latency_ms, d.audio.min_latency_ms);
  EXPECT_EQ(shipped.audio.grow_after_underruns, d.audio.grow_after_underruns);
  EXPECT_EQ(shipped.audio.underrun_window_ms, d.audio.underrun_window_ms);
  EXPECT_EQ(shipped.audio.max_latency_ms, d.audio.max_latency_ms);
  const AppConfig c = config::parse_app_config(
      "[audio]\nmin_latency_ms = 20.0\ngrow_after_underruns = 0\nunderrun_window_ms = 1000.0\nmax_latency_ms = 60.0\n",
      "c.toml");
  EXPECT_EQ(c.audio.min_latency_ms, 20.0);
  EXPECT_EQ(c.audio.grow_after_underruns, 0);
  EXPECT_EQ(c.audio.underrun_window_ms, 1000.0);
  EXPECT_EQ(c.audio.max_latency_ms, 60.0);
  const FileError e = test::file_error_of(
      [] { config::parse_app_config("[audio]\nmin_latency_ms = 50.0\nmax_latency_ms = 20.0\n", "c.toml"); });
  EXPECT_NE(std::string(e.what()).find("max_latency_ms"), std::string::npos) << e.what();
  EXPECT_EQ(e.line(), 3u) << e.what();
  test::file_error_of([] { config::parse_app_config("[audio]\ngrow_after_underruns = -1\n", "c.toml"); });
}

}  // namespace
}  // namespace mallet::audio
