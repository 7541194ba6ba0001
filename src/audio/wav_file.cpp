#include "audio/wav_file.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>

namespace mallet::audio {

static_assert(std::endian::native == std::endian::little, "WAV I/O assumes a little-endian host");

namespace {

constexpr std::uint16_t kFormatPcm = 1;
constexpr std::uint16_t kFormatFloat = 3;
constexpr std::uint16_t kFormatExtensible = 0xFFFE;

void put16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v & 0xFF));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>((v >> (8 * i)) & 0xFF));
}
void put_tag(std::vector<std::uint8_t>& out, const char* tag) { out.insert(out.end(), tag, tag + 4); }

std::uint16_t get16(const std::uint8_t* p) { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }
std::uint32_t get32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

}  // namespace

WavWriter::WavWriter(const std::filesystem::path& path, int channels, int sample_rate_hz,
                     SampleFormat format)
    : path_(path), channels_(channels), sample_rate_(sample_rate_hz), format_(format) {
  if (channels < 1 || sample_rate_hz < 1) throw std::invalid_argument("WavWriter: bad channels or rate");
  file_ = std::fopen(path.c_str(), "wb");
  if (!file_) throw std::runtime_error(path.string() + ": cannot create: " + std::strerror(errno));
  write_header();
}

WavWriter::~WavWriter() {
  if (file_) std::fclose(file_);
}

void WavWriter::write_header() {
  const bool is_float = format_ == SampleFormat::float32;
  const std::uint16_t bytes = is_float ? 4 : 2;
  const std::uint64_t data_bytes = frames_ * channels_ * bytes;
  if (data_bytes > 0xFFFFFFFFull - 64)
    throw std::runtime_error(path_.string() + ": longer than a WAV file can hold (4 GiB)");
  std::vector<std::uint8_t> h;
  const std::uint32_t fmt_size = is_float ? 18 : 16;
  const std::uint32_t fact_size = is_float ? 12 : 0;
  put_tag(h, "RIFF");
  put32(h, static_cast<std::uint32_t>(4 + (8 + fmt_size) + fact_size + 8 + data_bytes));
  put_tag(h, "WAVE");
  put_tag(h, "fmt ");
  put32(h, fmt_size);
  put16(h, is_float ? kFormatFloat : kFormatPcm);
  put16(h, static_cast<std::uint16_t>(channels_));
  put32(h, static_cast<std::uint32_t>(sample_rate_));
  put32(h, static_cast<std::uint32_t>(sample_rate_ * channels_ * bytes));
  put16(h, static_cast<std::uint16_t>(channels_ * bytes));
  put16(h, static_cast<std::uint16_t>(bytes * 8));
  if (is_float) {
    put16(h, 0);  // cbSize
    put_tag(h, "fact");  // required for non-PCM formats
    put32(h, 4);
    put32(h, static_cast<std::uint32_t>(frames_));
  }
  put_tag(h, "data");
  put32(h, static_cast<std::uint32_t>(data_bytes));
  if (std::fwrite(h.data(), 1, h.size(), file_) != h.size())
    throw std::runtime_error(path_.string() + ": write failed: " + std::strerror(errno));
}

void WavWriter::write(std::span<const float> interleaved) {
  if (!file_) throw std::logic_error("WavWriter: write after close");
  if (interleaved.size() % channels_ != 0) throw std::invalid_argument("WavWriter: partial frame");
  std::size_t n = 0;
  if (format_ == SampleFormat::float32) {
    n = std::fwrite(interleaved.data(), sizeof(float), interleaved.size(), file_);
  } else {
    scratch_.resize(interleaved.size() * 2);
    for (std::size_t i = 0; i < interleaved.size(); ++i) {
      const float s = std::clamp(interleaved[i], -1.0f, 1.0f);
      const auto v = static_cast<std::int16_t>(std::lrint(s * 32767.0f));
      std::memcpy(&scratch_[2 * i], &v, 2);
    }
    n = std::fwrite(scratch_.data(), 2, interleaved.size(), file_);
  }
  if (n != interleaved.size())
    throw std::runtime_error(path_.string() + ": write failed: " + std::strerror(errno));
  frames_ += interleaved.size() / channels_;
}

void WavWriter::close() {
  if (!file_) return;
  if (std::fseek(file_, 0, SEEK_SET) != 0)
    throw std::runtime_error(path_.string() + ": seek failed: " + std::strerror(errno));
  write_header();
  const bool ok = std::fflush(file_) == 0;
  std::fclose(file_);
  file_ = nullptr;
  if (!ok) throw std::runtime_error(path_.string() + ": write failed: " + std::strerror(errno));
}

std::vector<double> WavData::channel(int c) const {
  std::vector<double> out;
  out.reserve(frames());
  for (std::size_t i = static_cast<std::size_t>(c); i < samples.size(); i += channels) out.push_back(samples[i]);
  return out;
}

WavData read_wav(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot open");
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto fail = [&](const std::string& why) { throw std::runtime_error(path.string() + ": " + why); };
  if (bytes.size() < 12 || std::memcmp(bytes.data(), "RIFF", 4) || std::memcmp(bytes.data() + 8, "WAVE", 4))
    fail("not a RIFF/WAVE file");
  WavData out;
  std::uint16_t format = 0, bits = 0;
  bool have_fmt = false;
  std::size_t pos = 12;
  while (pos + 8 <= bytes.size()) {
    const std::uint8_t* chunk = bytes.data() + pos;
    const std::uint32_t size = get32(chunk + 4);
    const std::size_t body = pos + 8;
    const std::size_t available = bytes.size() - body;
    if (!std::memcmp(chunk, "fmt ", 4)) {
      if (size < 16 || available < 16) fail("truncated fmt chunk");
      format = get16(chunk + 8);
      out.channels = get16(chunk + 10);
      out.sample_rate_hz = static_cast<int>(get32(chunk + 12));
      bits = get16(chunk + 22);
      if (format == kFormatExtensible) {
        if (size < 40 || available < 40) fail("truncated extensible fmt chunk");
        format = get16(chunk + 8 + 24);  // first two bytes of the sub-format GUID
      }
      have_fmt = true;
    } else if (!std::memcmp(chunk, "data", 4)) {
      if (!have_fmt) fail("data chunk before fmt chunk");
      if (out.channels < 1) fail("no channels");
      // A streaming writer that was killed leaves 0 or 0xFFFFFFFF here: read what exists.
      const std::size_t n_bytes = (size == 0 || size > available) ? available : size;
      if (format == kFormatFloat && bits == 32) {
        out.samples.resize(n_bytes / 4);
        std::memcpy(out.samples.data(), chunk + 8, out.samples.size() * 4);
      } else if (format == kFormatPcm && bits == 16) {
        out.samples.resize(n_bytes / 2);
        for (std::size_t i = 0; i < out.samples.size(); ++i)
          out.samples[i] = static_cast<float>(static_cast<std::int16_t>(get16(chunk + 8 + 2 * i))) / 32768.0f;
      } else {
        fail("unsupported sample format " + std::to_string(format) + " with " + std::to_string(bits) +
             " bits (expected 16-bit PCM or 32-bit float)");
      }
      out.samples.resize(out.samples.size() - out.samples.size() % out.channels);
      return out;
    }
    pos = body + size + (size & 1);
  }
  fail("no data chunk");
  return out;
}

}  // namespace mallet::audio
