#include "core/stripe_signal.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mallet {

namespace {
constexpr double kStripeTwoPi = 2 * std::numbers::pi;
}

void StripePhase::update(double dt_s, double speed_m_per_s) {
  // Neumaier: base_ + comp_ is the distance with the rounding of every addition kept.
  const double add = speed_ * std::max(0.0, dt_s);
  const double t = base_ + add;
  comp_ += std::fabs(base_) >= std::fabs(add) ? (base_ - t) + add : (add - t) + base_;
  base_ = t;
  const double cap = p_.max_freq_hz * p_.wavelength_m;
  speed_ = std::isfinite(speed_m_per_s) ? std::clamp(speed_m_per_s, 0.0, cap) : 0.0;
}

void StripePhase::end_gesture() {
  base_ = comp_ = 0;
  speed_ = 0;
}

double StripePhase::distance_at(double dt_s) const { return base_ + comp_ + speed_ * std::max(0.0, dt_s); }

double StripePhase::phase_at(double dt_s) const {
  // Reduce the distance modulo λ first so the phase keeps its precision after hours.
  const double cycles = std::fmod(base_, p_.wavelength_m) + comp_ + speed_ * std::max(0.0, dt_s);
  double phase = std::fmod(kStripeTwoPi * (cycles / p_.wavelength_m) + p_.phase_rad, kStripeTwoPi);
  if (phase < 0) phase += kStripeTwoPi;
  return phase;
}

StripeSignal::StripeSignal(const StripeParams& p, int sample_rate_hz)
    : p_(p),
      fs_(static_cast<double>(sample_rate_hz)),
      env_step_(p.fade_s > 0 ? 1.0 / (p.fade_s * sample_rate_hz) : 1.0),
      timeout_samples_(std::max<std::int64_t>(1, std::llround(p.motion_timeout_s * sample_rate_hz))),
      phase_(p) {}

void StripeSignal::motion(double speed_m_per_s, bool on_texture) {
  phase_.update(static_cast<double>(since_update_) / fs_, speed_m_per_s);
  since_update_ = 0;
  on_texture_ = on_texture;
  // A gesture that starts from silence starts at distance 0 (phase φ).
  if (env_ == 0.0 && !phase_.moving()) phase_.end_gesture();
}

void StripeSignal::add_to(double* out, int frames, double gain) {
  const double amp = p_.amplitude * gain;
  for (int i = 0; i < frames; ++i) {
    if (since_update_ == timeout_samples_ && phase_.moving()) {  // no news: the cursor has stopped
      phase_.update(static_cast<double>(since_update_) / fs_, 0.0);
      since_update_ = 0;
    }
    const bool sounding = on_texture_ && phase_.moving();
    env_ = sounding ? std::min(1.0, env_ + env_step_) : std::max(0.0, env_ - env_step_);
    if (env_ > 0.0) out[i] += amp * env_ * std::sin(phase_.phase_at(static_cast<double>(since_update_) / fs_));
    ++since_update_;
  }
  if (env_ == 0.0 && !phase_.moving()) {  // silent at rest: the gesture is over
    phase_.update(static_cast<double>(since_update_) / fs_, 0.0);
    phase_.end_gesture();
    since_update_ = 0;
  }
}

}  // namespace mallet
