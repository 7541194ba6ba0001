#pragma once
// A finite impulse response filter for the audio callback (the actuator's inverse,
// audio/actuator_inverse.hpp): y[n] = Σ taps[j] · x[n − j].
//
// Real-time safe after construction: no allocation, no locks, no exceptions in tick() and
// process(). The history is kept twice over (a "doubled" ring), so each output is one
// straight dot product with no wrap-around test. A default-constructed filter is inactive
// and passes its input through unchanged.
#include <cstddef>
#include <utility>
#include <vector>

namespace mallet::audio {

class FirFilter {
 public:
  FirFilter() = default;
  explicit FirFilter(std::vector<double> taps) : taps_(std::move(taps)), history_(2 * taps_.size(), 0.0) {}

  bool active() const { return !taps_.empty(); }
  std::size_t size() const { return taps_.size(); }
  const std::vector<double>& taps() const { return taps_; }

  double tick(double x) {
    const std::size_t n = taps_.size();
    if (n == 0) return x;
    // Silence in, and silence for as long as the filter is: the output is exactly 0 and the
    // history all zeros, so nothing needs computing (an idle kiosk's actuator costs nothing).
    if (x == 0.0) {
      if (zeros_ >= n) return 0.0;
      ++zeros_;
    } else {
      zeros_ = 0;
    }
    pos_ = pos_ == 0 ? n - 1 : pos_ - 1;
    history_[pos_] = x;
    history_[pos_ + n] = x;
    // Four running sums (the compiler may not reorder one sum): independent multiply-adds a
    // vector unit can do side by side. The order of the additions is fixed, so the output
    // is the same on every run.
    const double* h = history_.data() + pos_;
    const double* t = taps_.data();
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
    std::size_t j = 0;
    for (; j + 4 <= n; j += 4) {
      s0 += t[j] * h[j];
      s1 += t[j + 1] * h[j + 1];
      s2 += t[j + 2] * h[j + 2];
      s3 += t[j + 3] * h[j + 3];
    }
    for (; j < n; ++j) s0 += t[j] * h[j];
    return (s0 + s1) + (s2 + s3);
  }

  //! In place, `frames` samples.
  void process(double* samples, int frames) {
    if (taps_.empty()) return;
    for (int i = 0; i < frames; ++i) samples[i] = tick(samples[i]);
  }

  void reset() {
    for (double& v : history_) v = 0.0;
    pos_ = 0;
    zeros_ = taps_.size();
  }

 private:
  std::vector<double> taps_;
  std::vector<double> history_;
  std::size_t pos_ = 0;
  std::size_t zeros_ = 0;  //!< the zero inputs in a row (the history is all zeros from size() on)
};

}  // namespace mallet::audio
