#include "audio/photodiode_timing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

namespace mallet::audio {

namespace {

constexpr Nanos kBaselineBefore = 300'000'000;  // the quiet before a square
constexpr Nanos kBaselineGap = 10'000'000;       // ... ending this long before its present
constexpr Nanos kSearchBefore = 5'000'000;
constexpr Nanos kSearchAfter = 300'000'000;

double frames_of(Nanos dt, int rate) { return static_cast<double>(dt) * rate / 1e9; }

}  // namespace

Nanos capture_time(const CaptureRecording& r, double n) {
  if (r.blocks.empty()) throw std::runtime_error("the recording has no block");
  const CaptureBlock& first = r.blocks.front();
  // The callbacks' schedule: the earliest any block's callback ran, for its place.
  double origin = std::numeric_limits<double>::infinity();
  for (const CaptureBlock& b : r.blocks) {
    const double place = static_cast<double>(b.position - first.position) * 1e9 / r.sample_rate_hz;
    origin = std::min(origin, static_cast<double>(b.callback_ns) - place);
  }
  return static_cast<Nanos>(std::llround(origin + (n - static_cast<double>(first.index)) * 1e9 / r.sample_rate_hz));
}

PhotodiodeTiming time_photodiode(const CaptureRecording& r, std::size_t channel, double input_latency_s,
                                 const std::vector<PhotodiodeSquare>& squares, const std::string& label) {
  if (r.xruns > 0 || !r.continuous)
    throw std::runtime_error(fmt::format("{}: the stream over- or underran while it recorded (measure again on a "
                                         "quieter machine, or with a larger [audio] suggested_latency_ms)",
                                         label));
  if (channel >= r.channels.size()) throw std::invalid_argument("no such channel in the recording");
  const std::vector<float>& x = r.channels[channel];
  const int rate = r.sample_rate_hz;
  const Nanos zero = capture_time(r, 0);
  const auto input_latency = static_cast<Nanos>(std::llround(input_latency_s * 1e9));
  // The recording's (fractional) sample at kiosk time t, and back.
  const auto index_at = [&](Nanos t) { return frames_of(t - zero + input_latency, rate); };
  const auto time_at = [&](double n) {
    return zero - input_latency + static_cast<Nanos>(std::llround(n * 1e9 / rate));
  };
  const auto clamp_index = [&](double n) {
    return static_cast<std::size_t>(std::clamp(n, 0.0, static_cast<double>(x.size())));
  };

  PhotodiodeTiming out;
  std::vector<double> seen_ms;
  for (const PhotodiodeSquare& sq : squares) {
    PhotodiodePulse p;
    p.present = sq.present;
    out.pulses.push_back(p);
    if (sq.present == 0) continue;
    const std::size_t b0 = clamp_index(index_at(sq.present - kBaselineBefore));
    const std::size_t b1 = clamp_index(index_at(sq.present - kBaselineGap));
    const std::size_t s0 = clamp_index(index_at(sq.present - kSearchBefore));
    const std::size_t s1 = clamp_index(index_at(sq.present + kSearchAfter));
    if (b1 <= b0 + 16 || s1 <= s0 + 1) continue;  // outside the recording
    double mean = 0;
    for (std::size_t i = b0; i < b1; ++i) mean += x[i];
    mean /= static_cast<double>(b1 - b0);
    double noise = 0;
    for (std::size_t i = b0; i < b1; ++i) noise += (x[i] - mean) * (x[i] - mean);
    noise = std::sqrt(noise / static_cast<double>(b1 - b0));
    double swing = 0;
    for (std::size_t i = s0; i < s1; ++i) swing = std::max(swing, std::abs(x[i] - mean));
    if (!(swing > 10 * noise) || swing < 1e-4) continue;
    const double half = swing / 2;
    for (std::size_t i = std::max<std::size_t>(s0, 1); i < s1; ++i) {
      const double a = std::abs(x[i - 1] - mean), b = std::abs(x[i] - mean);
      if (b < half) continue;
      const double frac = b > a ? (half - a) / (b - a) : 0.0;  // where the swing crossed half
      const double n = static_cast<double>(i - 1) + std::clamp(frac, 0.0, 1.0);
      PhotodiodePulse& q = out.pulses.back();
      q.light = time_at(n);
      q.latency_ms = static_cast<double>(*q.light - sq.present) / 1e6;
      seen_ms.push_back(*q.latency_ms);
      out.noise_to_swing = std::max(out.noise_to_swing, noise / swing);
      break;
    }
  }
  out.seen = static_cast<int>(seen_ms.size());
  if (out.seen * 2 < static_cast<int>(squares.size()) || out.seen == 0)
    throw std::runtime_error(fmt::format(
        "{}: the light was seen at {} of {} squares: check that the photodiode faces the screen's top-left "
        "corner, that its circuit is powered, and the input's level",
        label, out.seen, squares.size()));
  std::vector<double> sorted = seen_ms;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t m = sorted.size();
  out.display_latency_ms = m % 2 ? sorted[m / 2] : (sorted[m / 2 - 1] + sorted[m / 2]) / 2;
  out.min_ms = sorted.front();
  out.max_ms = sorted.back();
  return out;
}

}  // namespace mallet::audio
