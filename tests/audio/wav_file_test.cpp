#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>

#include "audio/wav_file.hpp"
#include "test_paths.hpp"

namespace mallet::audio {
namespace {

TEST(WavFile, Float32RoundTripIsBitExact) {
  const auto path = test::scratch_dir() / "a.wav";
  std::vector<float> frames;
  for (int i = 0; i < 3000; ++i) {
    frames.push_back(static_cast<float>(i) * 1e-4f);
    frames.push_back(-1.0f + static_cast<float>(i) * 3e-7f);
  }
  WavWriter w(path, 2, 44100);
  w.write(std::span<const float>(frames).first(1000));
  w.write(std::span<const float>(frames).subspan(1000));
  w.close();
  const WavData d = read_wav(path);
  EXPECT_EQ(d.channels, 2);
  EXPECT_EQ(d.sample_rate_hz, 44100);
  EXPECT_EQ(d.frames(), 3000u);
  EXPECT_EQ(d.samples, frames);
  EXPECT_EQ(std::filesystem::file_size(path), 58u + frames.size() * 4);  // RIFF+fmt(18)+fact+data headers
}

TEST(WavFile, Pcm16QuantisesAndClamps) {
  const auto path = test::scratch_dir() / "b.wav";
  WavWriter w(path, 1, 8000, SampleFormat::pcm16);
  const std::vector<float> in{0.0f, 0.5f, -0.5f, 2.0f, -2.0f};
  w.write(in);
  w.close();
  const WavData d = read_wav(path);
  ASSERT_EQ(d.samples.size(), 5u);
  EXPECT_NEAR(d.samples[1], 0.5f, 1.0f / 32768);
  EXPECT_NEAR(d.samples[3], 32767.0f / 32768, 1e-6);
  EXPECT_NEAR(d.samples[4], -32767.0f / 32768, 1e-6);
}

TEST(WavFile, RefusesWhatIsNotAWavWithTheFileName) {
  const auto path = test::scratch_dir() / "c.wav";
  std::ofstream(path) << "hello, not a wav";
  try {
    read_wav(path);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("c.wav: not a RIFF/WAVE file"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace mallet::audio
