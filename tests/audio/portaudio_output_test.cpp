// The real output path — PortAudio → ALSA — on a machine without a sound card: each test
// points ALSA at a configuration of its own (before anything touches PortAudio) whose
// default PCM is the file plugin over a null sink, so what the callback delivers lands in
// a WAV file. The file plugin is not paced: the tests count frames, never wall time.
// It labels float data as integer PCM, so the strikes are written as int16.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "audio/audio_setup.hpp"
#include "audio/actuator_track.hpp"
#include "audio/portaudio_output.hpp"
#include "audio/wav_file.hpp"
#include "test_paths.hpp"

namespace mallet::audio {
namespace {

namespace fs = std::filesystem;
using test::percussion;

constexpr int kRate = 48000;
constexpr std::int64_t kFrames = kRate;  // one second of output per strike test

using test::strike;

// Waits until `done()` holds, polling with small sleeps; the cap only keeps a broken
// stream from hanging the test (the file plugin delivers a second in a few ms).
template <class Done>
bool wait_until(Done done) {
  for (int i = 0; i < 20000; ++i) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return done();
}

double energy(const std::vector<double>& x) {
  double e = 0;
  for (double v : x) e += v * v;
  return e;
}

std::int64_t first_above(const std::vector<double>& x, double level) {
  for (std::size_t i = 0; i < x.size(); ++i)
    if (std::fabs(x[i]) > level) return static_cast<std::int64_t>(i);
  return -1;
}

class PortAudioOutputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratch_dir();
    fs::permissions(dir_, fs::perms::owner_all, fs::perm_options::replace);
    // default → out.wav; "mallet_probe" → probe.wav (a second device to select by name).
    std::ofstream conf(dir_ / "asound.conf");
    conf << "pcm.!default { type file slave.pcm \"nullsink\" file \"" << wav().string() << "\" format \"wav\" }\n"
         << "pcm.mallet_probe { type file slave.pcm \"nullsink\" file \"" << probe_wav().string()
         << "\" format \"wav\" }\n"
         << "pcm.nullsink { type null }\n";
    conf.close();
    ASSERT_TRUE(conf);
    const std::string path = "/usr/share/alsa/alsa.conf:" + (dir_ / "asound.conf").string();
    ::setenv("ALSA_CONFIG_PATH", path.c_str(), 1);
    ::setenv("XDG_RUNTIME_DIR", dir_.c_str(), 1);
  }

  fs::path wav() const { return dir_ / "out.wav"; }
  fs::path probe_wav() const { return dir_ / "probe.wav"; }

  static AppConfig config() {
    AppConfig c;
    c.audio.sample_rate_hz = kRate;
    return c;
  }

  static PortAudioOutput::Options int16() {
    PortAudioOutput::Options o;
    o.format = StreamFormat::int16;
    return o;
  }

  // Plays one strike (posted before the start, so it begins on frame 0) for kFrames
  // frames and returns what the device received.
  WavData play(const AppConfig& c, bool acoustic, const fs::path& file) {
    AudioRig rig = make_audio_rig(percussion(), c, kRate, acoustic);
    if (acoustic) rig.engine->set_actuator_gain(0.0);
    EXPECT_TRUE(rig.engine->post(strike(3, 0, 1.0)));
    {
      PortAudioOutput out(*rig.engine, c.audio, int16());
      out.start();
      // counters().frames, not engine.position(): the latter belongs to the audio thread.
      EXPECT_TRUE(wait_until([&] { return out.counters().frames >= static_cast<std::uint64_t>(kFrames); }));
      out.stop();
      EXPECT_EQ(out.counters().device_losses, 0u);
    }  // closed: the file plugin has written the WAV header's sizes
    return read_wav(file);
  }

  fs::path dir_;
};

DeviceInfo device(int index, std::string name, std::string api, bool is_default = false) {
  DeviceInfo d;
  d.index = index;
  d.name = std::move(name);
  d.host_api = std::move(api);
  d.max_output_channels = 2;
  d.is_default = is_default;
  return d;
}

std::vector<std::string> names(const std::vector<DeviceInfo>& devices) {
  std::vector<std::string> out;
  for (const DeviceInfo& d : devices) out.push_back(d.name);
  return out;
}

TEST(DefaultOutputOrder, AlsasDefaultGoesToDmixItselfFirst) {
  // Debian 12 on a card without a sound server: default = plug → softvol → dmix.
  const std::vector<DeviceInfo> outputs = {device(0, "HDA Intel: Generic Analog (hw:0,0)", "ALSA"),
                                           device(1, "default", "ALSA", true), device(2, "dmix", "ALSA")};
  EXPECT_EQ(names(default_output_order(outputs)), (std::vector<std::string>{"dmix", "default"}));
}

TEST(DefaultOutputOrder, AnyOtherDefaultIsTakenAsItIs) {
  // No dmix listed (no card it could open), JACK's default, or a default by another name.
  EXPECT_EQ(names(default_output_order({device(0, "default", "ALSA", true)})), (std::vector<std::string>{"default"}));
  EXPECT_EQ(names(default_output_order({device(0, "system", "JACK Audio Connection Kit", true),
                                        device(1, "dmix", "ALSA")})),
            (std::vector<std::string>{"system"}));
  EXPECT_EQ(names(default_output_order({device(0, "pulse", "ALSA", true), device(1, "dmix", "ALSA")})),
            (std::vector<std::string>{"pulse"}));
  EXPECT_TRUE(default_output_order({device(0, "dmix", "ALSA")}).empty());
}

TEST_F(PortAudioOutputTest, ListsTheDefaultDevice) {
  const std::vector<DeviceInfo> devices = list_output_devices();
  const auto def = std::find_if(devices.begin(), devices.end(), [](const DeviceInfo& d) { return d.is_default; });
  ASSERT_NE(def, devices.end());
  EXPECT_EQ(def->name, "default");
  EXPECT_EQ(def->host_api, "ALSA");
  EXPECT_GE(def->max_output_channels, 2);
  EXPECT_GT(def->default_low_latency_s, 0.0);
  EXPECT_TRUE(std::any_of(devices.begin(), devices.end(), [](const DeviceInfo& d) { return d.name == "mallet_probe"; }));
}

TEST_F(PortAudioOutputTest, ActuatorStrikeReachesChannelOneExactly) {
  AppConfig c = config();
  const WavData wav = play(c, /*acoustic=*/false, this->wav());
  EXPECT_EQ(wav.channels, 2);
  EXPECT_EQ(wav.sample_rate_hz, kRate);
  ASSERT_GE(wav.frames(), static_cast<std::size_t>(kFrames));
  const std::vector<double> acoustic = wav.channel(0), actuator = wav.channel(1);
  EXPECT_EQ(energy(acoustic), 0.0);
  EXPECT_GT(energy(actuator), 1.0);

  // The device received Eq. 1 itself (to int16 resolution), after whatever silence
  // PortAudio primed the buffer with.
  const std::vector<Impact> impacts{strike(3, 0, 1.0)};
  ActuatorTrack reference(percussion(), impacts, c.actuator, kRate);
  std::vector<float> want(static_cast<std::size_t>(kRate / 2));
  reference.render(0, want);
  const std::vector<double> want_d(want.begin(), want.end());
  const std::int64_t lag = first_above(actuator, 0.01) - first_above(want_d, 0.01);
  ASSERT_GE(lag, 0);
  ASSERT_LE(static_cast<std::size_t>(lag) + want.size(), actuator.size());
  double worst = 0;
  for (std::size_t i = 0; i < want.size(); ++i)
    worst = std::max(worst, std::fabs(actuator[static_cast<std::size_t>(lag) + i] - want_d[i]));
  EXPECT_LT(worst, 1e-4);
}

TEST_F(PortAudioOutputTest, AcousticStrikeReachesChannelZeroOnly) {
  const WavData wav = play(config(), /*acoustic=*/true, this->wav());
  EXPECT_EQ(wav.channels, 2);
  EXPECT_EQ(wav.sample_rate_hz, kRate);
  EXPECT_GT(energy(wav.channel(0)), 1.0);
  EXPECT_EQ(energy(wav.channel(1)), 0.0);
}

TEST_F(PortAudioOutputTest, RoutingIsHonouredOnTheDevice) {
  AppConfig c = config();
  c.audio.routing.acoustic = 1;
  c.audio.routing.actuator = 0;
  const WavData wav = play(c, /*acoustic=*/false, this->wav());
  EXPECT_GT(energy(wav.channel(0)), 1.0);
  EXPECT_EQ(energy(wav.channel(1)), 0.0);
}

TEST_F(PortAudioOutputTest, SelectsADeviceByAPartOfItsNameIgnoringCase) {
  AppConfig c = config();
  c.audio.device = "PROBE";
  const WavData wav = play(c, /*acoustic=*/false, probe_wav());
  EXPECT_GT(energy(wav.channel(1)), 1.0);
  EXPECT_FALSE(fs::exists(this->wav()) && fs::file_size(this->wav()) > 44);  // the default got nothing
}

TEST_F(PortAudioOutputTest, SelectsADeviceByIndex) {
  const std::vector<DeviceInfo> devices = list_output_devices();
  const auto probe =
      std::find_if(devices.begin(), devices.end(), [](const DeviceInfo& d) { return d.name == "mallet_probe"; });
  ASSERT_NE(probe, devices.end());
  AppConfig c = config();
  c.audio.device = std::to_string(probe->index);
  AudioRig rig = make_audio_rig(percussion(), c, kRate, false);
  PortAudioOutput out(*rig.engine, c.audio, int16());
  EXPECT_EQ(out.device().name, "mallet_probe");
  EXPECT_EQ(out.device().index, probe->index);
  EXPECT_GT(out.output_latency_s(), 0.0);
  EXPECT_EQ(out.sample_rate_hz(), kRate);
}

TEST_F(PortAudioOutputTest, AnUnknownDeviceIsAClearErrorListingWhatExists) {
  for (const std::string spec : {"no-such-card", "9999"}) {
    AppConfig c = config();
    c.audio.device = spec;
    AudioRig rig = make_audio_rig(percussion(), c, kRate, false);
    try {
      PortAudioOutput out(*rig.engine, c.audio, int16());
      ADD_FAILURE() << spec << " opened " << out.device().name;
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(spec), std::string::npos) << what;
      EXPECT_NE(what.find("\"default\""), std::string::npos) << what;
      EXPECT_NE(what.find("\"mallet_probe\""), std::string::npos) << what;
    }
  }
}

TEST_F(PortAudioOutputTest, APhotodiodesInputThatDoesNotOpenLeavesTheStreamPlaying) {
  // [timing] photodiode_input naming no input: the kiosk's stream plays on, recording nothing.
  AppConfig c = config();
  AudioRig rig = make_audio_rig(percussion(), c, kRate, false);
  PortAudioOutput::Options o = int16();
  o.capture = CaptureSpec{"no-such-input", {0}, 2.0};
  PortAudioOutput out(*rig.engine, c.audio, o);
  EXPECT_EQ(out.capture(), nullptr);
  EXPECT_EQ(out.input_latency_s(), 0.0);
  EXPECT_EQ(out.input_device_name(), "");
  out.start();
  EXPECT_TRUE(wait_until([&] { return out.counters().frames >= static_cast<std::uint64_t>(kRate / 10); }));
  out.stop();
  EXPECT_EQ(out.counters().device_losses, 0u);
}

TEST_F(PortAudioOutputTest, Float32StreamRunsTheEngine) {
  AppConfig c = config();
  AudioRig rig = make_audio_rig(percussion(), c, kRate, true);
  PortAudioOutput out(*rig.engine, c.audio);  // float32: the file's header is wrong, its frame count is not
  out.start();
  EXPECT_TRUE(wait_until([&] { return out.counters().frames >= static_cast<std::uint64_t>(kFrames); }));
  out.stop();
  EXPECT_GT(out.counters().callbacks, 0u);
  EXPECT_EQ(out.counters().device_losses, 0u);
  // Stop and start again: the stream resumes, the engine's timeline continues.
  const std::uint64_t before = out.counters().frames;
  out.start();
  EXPECT_TRUE(wait_until([&] { return out.counters().frames >= before + 4096; }));
  out.stop();
}

TEST_F(PortAudioOutputTest, ALostDeviceIsReopenedAndPlaysAgain) {
  AppConfig c = config();
  AudioRig rig = make_audio_rig(percussion(), c, kRate, false);
  PortAudioOutput::Options options = int16();
  options.first_retry = std::chrono::milliseconds(5);
  options.poll_interval = std::chrono::milliseconds(2);
  {
    PortAudioOutput out(*rig.engine, c.audio, options);
    out.start();
    ASSERT_TRUE(wait_until([&] { return out.counters().frames >= 4096; }));
    out.drop_device();
    ASSERT_TRUE(wait_until([&] { return out.counters().reopens >= 1; }));
    EXPECT_TRUE(out.device_ok());
    EXPECT_EQ(out.counters().device_losses, 1u);
    EXPECT_GE(out.counters().reopen_attempts, 1u);
    // Reopening truncated the file; a strike posted now must be in it.
    ASSERT_TRUE(rig.engine->post(strike(3, 0, 1.0)));
    const std::uint64_t before = out.counters().frames;
    ASSERT_TRUE(wait_until([&] { return out.counters().frames >= before + static_cast<std::uint64_t>(kFrames); }));
    out.stop();
    EXPECT_EQ(out.counters().device_losses, 1u);
  }
  const WavData wav = read_wav(this->wav());
  EXPECT_EQ(wav.channels, 2);
  EXPECT_EQ(energy(wav.channel(0)), 0.0);
  EXPECT_GT(energy(wav.channel(1)), 1.0);
}

// A larger buffer (what repeated underruns ask for) reopens the device; the engine's
// timeline goes on, and a strike after it still reaches the actuator's channel as Eq. 1
// itself, sample for sample.
TEST_F(PortAudioOutputTest, AGrownBufferKeepsStrikesExact) {
  AppConfig c = config();
  AudioRig rig = make_audio_rig(percussion(), c, kRate, false);
  PortAudioOutput::Options options = int16();
  options.poll_interval = std::chrono::milliseconds(2);
  {
    PortAudioOutput out(*rig.engine, c.audio, options);
    const double first = out.requested_latency_s();
    EXPECT_GE(first, c.audio.min_latency_ms / 1000.0);
    out.start();
    ASSERT_TRUE(wait_until([&] { return out.counters().frames >= 4096; }));
    out.grow_buffer();
    ASSERT_TRUE(wait_until([&] { return out.counters().buffer_growths >= 1; }));
    EXPECT_DOUBLE_EQ(out.requested_latency_s(), 2 * first);
    EXPECT_EQ(out.counters().device_losses, 0u);
    // Reopening truncated the file; a strike posted now must be in it.
    ASSERT_TRUE(rig.engine->post(strike(3, 0, 1.0)));
    const std::uint64_t before = out.counters().frames;
    ASSERT_TRUE(wait_until([&] { return out.counters().frames >= before + static_cast<std::uint64_t>(kFrames); }));
    out.stop();
  }
  const WavData wav = read_wav(this->wav());
  const std::vector<double> actuator = wav.channel(1);
  EXPECT_EQ(energy(wav.channel(0)), 0.0);
  const std::vector<Impact> impacts{strike(3, 0, 1.0)};
  ActuatorTrack reference(percussion(), impacts, c.actuator, kRate);
  std::vector<float> want(static_cast<std::size_t>(kRate / 2));
  reference.render(0, want);
  const std::vector<double> want_d(want.begin(), want.end());
  const std::int64_t lag = first_above(actuator, 0.01) - first_above(want_d, 0.01);
  ASSERT_GE(lag, 0);
  ASSERT_LE(static_cast<std::size_t>(lag) + want.size(), actuator.size());
  double worst = 0;
  for (std::size_t i = 0; i < want.size(); ++i)
    worst = std::max(worst, std::fabs(actuator[static_cast<std::size_t>(lag) + i] - want_d[i]));
  EXPECT_LT(worst, 1e-4);
}

}  // namespace
}  // namespace mallet::audio
