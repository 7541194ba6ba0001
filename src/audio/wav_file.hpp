#pragma once
// WAV files: the offline audio sink (mallet simulate, tests) and a reader for analysis.
// Written as 32-bit IEEE float by default, so a stimulus file holds Eq. 1 to 24 bits
// of mantissa; 16-bit PCM on request.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace mallet::audio {

enum class SampleFormat { float32, pcm16 };

class WavWriter {
 public:
  //! Creates (truncates) the file. Throws std::runtime_error naming the file on failure.
  WavWriter(const std::filesystem::path& path, int channels, int sample_rate_hz,
            SampleFormat format = SampleFormat::float32);
  ~WavWriter();
  WavWriter(const WavWriter&) = delete;
  WavWriter& operator=(const WavWriter&) = delete;

  //! Appends interleaved frames (samples.size() must be a multiple of channels).
  void write(std::span<const float> interleaved);
  //! Patches the header sizes and closes; throws if anything failed on the way.
  void close();

  std::uint64_t frames_written() const { return frames_; }

 private:
  void write_header();

  std::filesystem::path path_;
  std::FILE* file_ = nullptr;
  int channels_;
  int sample_rate_;
  SampleFormat format_;
  std::uint64_t frames_ = 0;
  std::vector<std::uint8_t> scratch_;
};

struct WavData {
  int channels = 0;
  int sample_rate_hz = 0;
  std::vector<float> samples;  //!< interleaved

  std::size_t frames() const { return channels ? samples.size() / channels : 0; }
  std::vector<double> channel(int c) const;
};

//! Reads a PCM16 or float32 WAV (plain or WAVE_FORMAT_EXTENSIBLE). Throws
//! std::runtime_error "FILE: problem" on anything else.
WavData read_wav(const std::filesystem::path& path);

}  // namespace mallet::audio
