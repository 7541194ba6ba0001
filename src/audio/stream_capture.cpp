#include "audio/stream_capture.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mallet::audio {

StreamCapture::StreamCapture(int sample_rate_hz, std::vector<int> input_channels, double seconds)
    : rate_(sample_rate_hz), picks_(std::move(input_channels)) {
  if (picks_.empty()) throw std::invalid_argument("a capture needs an input channel");
  if (!(seconds > 0) || seconds > 600) throw std::invalid_argument("a capture lasts 0 to 600 s");
  frames_ = static_cast<std::size_t>(std::llround(seconds * sample_rate_hz));
  samples_.assign(frames_ * picks_.size(), 0.0f);
  blocks_.resize(frames_ / 16 + 1);
}

void StreamCapture::arm() {
  if (armed() && !complete()) throw std::logic_error("a capture is already under way");
  armed_.store(false, std::memory_order_release);
  block_count_ = 0;
  continuous_ = true;
  xruns_.store(0, std::memory_order_relaxed);
  written_.store(0, std::memory_order_release);
  armed_.store(true, std::memory_order_release);
}

void StreamCapture::write(const float* in, int in_channels, unsigned long frames, std::int64_t position, Nanos now,
                          bool xrun) {
  if (!armed_.load(std::memory_order_acquire)) return;
  const std::size_t at = written_.load(std::memory_order_acquire);
  if (at >= frames_) return;
  if (block_count_ > 0) {
    const CaptureBlock& last = blocks_[block_count_ - 1];
    if (position != last.position + static_cast<std::int64_t>(at - last.index)) continuous_ = false;
  }
  if (block_count_ < blocks_.size()) blocks_[block_count_++] = CaptureBlock{at, position, now, xrun};
  if (xrun) xruns_.fetch_add(1, std::memory_order_relaxed);
  const std::size_t n = std::min<std::size_t>(frames, frames_ - at);
  const std::size_t k = picks_.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < k; ++c) {
      const int pick = picks_[c];
      samples_[(at + i) * k + c] =
          in && pick < in_channels ? in[i * static_cast<std::size_t>(in_channels) + static_cast<std::size_t>(pick)] : 0.0f;
    }
  written_.store(at + n, std::memory_order_release);
}

CaptureRecording StreamCapture::recording() const {
  if (!complete()) throw std::logic_error("the capture is not complete");
  CaptureRecording r;
  r.sample_rate_hz = rate_;
  const std::size_t k = picks_.size();
  r.channels.assign(k, std::vector<float>(frames_));
  for (std::size_t i = 0; i < frames_; ++i)
    for (std::size_t c = 0; c < k; ++c) r.channels[c][i] = samples_[i * k + c];
  r.blocks.assign(blocks_.begin(), blocks_.begin() + static_cast<std::ptrdiff_t>(block_count_));
  r.xruns = xruns_.load(std::memory_order_relaxed);
  r.continuous = continuous_;
  return r;
}

}  // namespace mallet::audio
