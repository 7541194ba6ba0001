#include "audio/photodiode_timing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

namespace mallet::audio {

namespace {

constexpr Nanos kBaselineBefore = 300'000'000;  // the quiet before a square
constexpr Nanos kBaselineGap = 10'000'000;       // ... ending this long before its present
constexpr Nanos kSearchBefore = 5'000'000;
constexpr Nanos kSearchAfter = 300'000'000;
constexpr double kScheduleWindow = 0.5;  // s: the host buffers after a sample that time it

// The blocks that begin a host buffer. PortAudio may hand a host buffer (a JACK period, an
// ALSA period) to the callback in several blocks, called one after the other at once: only
// the first of them is called when its frames are due, the others early for theirs. A new
// host buffer shows as a pause before its first block. A callback held up inside a buffer
// shows as one too: on the bench (a JACK period of 1024 frames in blocks of 64, the sanitizer
// build) one block in seven paused, so the commonest distance between pauses was one block
// and every block was taken for a buffer's first, timing the light most of a period early.
// What only the buffers' first blocks do is pause every time: so the spacing (in frames,
// tried among the distances between pauses) and the place modulo it are those where the
// largest share of the blocks paused, the shortest such spacing (twice the period pauses as
// often).
std::vector<std::size_t> host_buffer_starts(const CaptureRecording& r) {
  const double rate = r.sample_rate_hz;
  std::vector<bool> paused(r.blocks.size(), false);
  std::vector<std::size_t> pauses;
  for (std::size_t i = 0; i < r.blocks.size(); ++i) {
    if (i > 0) {
      const CaptureBlock& a = r.blocks[i - 1];
      const CaptureBlock& b = r.blocks[i];
      if (static_cast<double>(b.callback_ns - a.callback_ns) < 0.5 * static_cast<double>(b.index - a.index) * 1e9 / rate)
        continue;
    }
    paused[i] = true;
    pauses.push_back(i);
  }
  std::set<std::size_t> spacings;
  for (std::size_t k = 1; k < pauses.size(); ++k)
    spacings.insert(r.blocks[pauses[k]].index - r.blocks[pauses[k - 1]].index);
  constexpr int kFewest = 4;         // blocks at a place for its share to count
  constexpr double kAsOften = 0.05;  // shares this close are as good: the shortest spacing wins
  struct Lattice {
    std::size_t period = 0, phase = 0;
    double share = -1;
  };
  std::vector<Lattice> tried;
  for (std::size_t period : spacings) {
    if (period == 0) continue;
    std::map<std::size_t, std::pair<int, int>> at;  // place → (blocks, pauses)
    for (std::size_t i = 0; i < r.blocks.size(); ++i) {
      auto& [blocks, paused_here] = at[r.blocks[i].index % period];
      ++blocks;
      paused_here += paused[i] ? 1 : 0;
    }
    Lattice best{period, 0, -1};
    for (const auto& [phase, counts] : at)
      if (counts.first >= kFewest && static_cast<double>(counts.second) / counts.first > best.share)
        best.phase = phase, best.share = static_cast<double>(counts.second) / counts.first;
    if (best.share >= 0) tried.push_back(best);
  }
  if (tried.empty()) return pauses;
  double top = 0;
  for (const Lattice& l : tried) top = std::max(top, l.share);
  const Lattice* pick = nullptr;  // spacings are tried shortest first
  for (const Lattice& l : tried)
    if (l.share >= top - kAsOften) {
      pick = &l;
      break;
    }
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i < r.blocks.size(); ++i)
    if (r.blocks[i].index % pick->period == pick->phase) starts.push_back(i);
  return starts.empty() ? pauses : starts;
}

// The callbacks' schedule at sample n: the monotonic time of the recording's first frame, as
// the earliest any host buffer's first callback ran for its place, among the host buffer
// holding n and those that follow it within kScheduleWindow. Never earlier ones: a host that
// skipped time without skipping frames (JACK's dummy driver on a loaded machine does) runs
// later for its place from then on, and a late callback is only ever late.
double schedule_origin(const CaptureRecording& r, const std::vector<std::size_t>& starts, double n) {
  if (starts.empty()) throw std::runtime_error("the recording has no block");
  const CaptureBlock& first = r.blocks.front();
  const double rate = r.sample_rate_hz;
  double best = std::numeric_limits<double>::infinity();
  double held = best;  // the offset of the host buffer holding n (the latest to start at or before it)
  for (std::size_t i : starts) {
    const CaptureBlock& b = r.blocks[i];
    const double offset =
        static_cast<double>(b.callback_ns) - static_cast<double>(b.position - first.position) * 1e9 / rate;
    const double at = static_cast<double>(b.index);
    if (at <= n) held = offset;
    else if (at <= n + kScheduleWindow * rate) best = std::min(best, offset);
    else break;
  }
  best = std::min(best, held);
  return best - static_cast<double>(first.index) * 1e9 / rate;
}

}  // namespace

Nanos capture_time(const CaptureRecording& r, double n) {
  if (r.blocks.empty()) throw std::runtime_error("the recording has no block");
  return static_cast<Nanos>(std::llround(schedule_origin(r, host_buffer_starts(r), n) + n * 1e9 / r.sample_rate_hz));
}

PhotodiodeTiming time_photodiode(const CaptureRecording& r, std::size_t channel, double input_latency_s,
                                 const std::vector<PhotodiodeSquare>& squares, const std::string& label) {
  if (!r.continuous)
    throw std::runtime_error(fmt::format("{}: the stream skipped frames while it recorded: press T again", label));
  if (channel >= r.channels.size()) throw std::invalid_argument("no such channel in the recording");
  const std::vector<float>& x = r.channels[channel];
  const int rate = r.sample_rate_hz;
  const auto input_latency = static_cast<Nanos>(std::llround(input_latency_s * 1e9));
  if (r.blocks.empty()) throw std::runtime_error(label + ": nothing was recorded");
  const std::vector<std::size_t> starts = host_buffer_starts(r);
  // The recording's (fractional) sample at kiosk time t, and back, each on the schedule at that
  // sample (index_at: guessed on the recording's first schedule, then taken on the one there).
  const auto index_at = [&](Nanos t) {
    const double guess = (static_cast<double>(t + input_latency) - schedule_origin(r, starts, 0)) * rate / 1e9;
    return (static_cast<double>(t + input_latency) - schedule_origin(r, starts, guess)) * rate / 1e9;
  };
  const auto time_at = [&](double n) {
    return static_cast<Nanos>(std::llround(schedule_origin(r, starts, n) + n * 1e9 / rate)) - input_latency;
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
    // A square near an over- or underrun is left out: samples were lost or repeated there, and
    // the schedule that times it comes from the half second after it.
    const double last = static_cast<double>(s1) + kScheduleWindow * rate;
    if (std::any_of(r.blocks.begin(), r.blocks.end(), [&](const CaptureBlock& b) {
          return b.xrun && b.index >= b0 && static_cast<double>(b.index) <= last;
        })) {
      ++out.near_xruns;
      continue;
    }
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
        "{}: the light was seen at {} of {} squares{}: check that the photodiode faces the screen's top-left "
        "corner, that its circuit is powered, and the input's level",
        label, out.seen, squares.size(),
        out.near_xruns ? fmt::format(" ({} left out: the stream over- or underran near them; a busy kiosk may need a "
                                     "larger [audio] suggested_latency_ms)",
                                     out.near_xruns)
                       : std::string()));
  std::sort(seen_ms.begin(), seen_ms.end());
  const std::size_t m = seen_ms.size();
  out.display_latency_ms = m % 2 ? seen_ms[m / 2] : (seen_ms[m / 2 - 1] + seen_ms[m / 2]) / 2;
  out.min_ms = seen_ms.front();
  out.max_ms = seen_ms.back();
  return out;
}

}  // namespace mallet::audio
