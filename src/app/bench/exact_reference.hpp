#pragma once
// The exact references that `mallet bench report` and the extremes test measure the audio
// against: Eq. 1 and a modal note in long double, written from the formulas in
// core/vibration.hpp and core/modal_preset.hpp — not from the double code they check.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/modal_preset.hpp"

namespace mallet::app {

//! Eq. 1, a·e^(−b·t)·sin(2π·f·t), in long double.
inline long double eq1_ld(long double a, long double b, long double f, long double t) {
  return a * std::exp(-b * t) * std::sin(2.0L * std::numbers::pi_v<long double> * f * t);
}

//! A struck bar's note by the strike law of modal_preset.hpp over all its modes, in long
//! double; like the voice, it leaves out modes at or above 0.45 × the sample rate.
class NoteReference {
 public:
  NoteReference(const ModalPreset& p, long double f0, long double v, int sample_rate_hz) {
    const long double loud = p.loudness;
    const long double s = v / p.reference_speed_m_per_s;
    const long double e = s <= 1 ? loud * s : 1 - (1 - loud) * (1 - loud) / (1 - 2 * loud + loud * s);
    const long double sigma = e / loud;
    std::vector<long double> w;
    long double total = 0;
    for (const Mode& m : p.modes) {
      const long double ex = p.brightness * (m.ratio - 1) / m.ratio;
      w.push_back(m.gain * (ex == 0 ? 1.0L : std::min(4.0L, std::pow(sigma, ex))));
      total += w.back();
    }
    for (std::size_t k = 0; k < p.modes.size(); ++k) {
      const long double f = p.modes[k].ratio * f0;
      if (f < 0.45L * sample_rate_hz) modes_.push_back({e * w[k] / total, p.modes[k].decay_per_s, f});
    }
  }

  //! The note t seconds after the strike.
  long double operator()(long double t) const {
    long double y = 0;
    for (const Partial& m : modes_) y += eq1_ld(m.a, m.b, m.f, t);
    return y;
  }

 private:
  struct Partial {
    long double a, b, f;
  };
  std::vector<Partial> modes_;
};

}  // namespace mallet::app
