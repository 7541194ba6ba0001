#pragma once
// A known actuator chain, for the tests and for `mallet-bench actuator`'s JACK plant: a
// resonance (the audio EQ cookbook's poles; its zeros for the high-pass), the stick's roll-off (a
// one-pole low-pass: the second pole), and a pure delay of whole samples. Its exact response
// is known, so what a measurement recovers can be compared with the truth.
//   low_pass:  the voice coil's excursion as a sensor on the stick reads it (a piezo disc):
//              flat below the resonance, a peak of about Q at it, falling above;
//   high_pass: an inertial actuator seen by an accelerometer: flat above the resonance,
//              falling 12 dB an octave below it, nothing at DC.
#include <cmath>
#include <complex>
#include <cstddef>
#include <numbers>
#include <vector>

namespace mallet::audio {

enum class PlantKind { low_pass, high_pass };

struct PlantSpec {
  PlantKind kind = PlantKind::low_pass;
  double resonance_hz = 180.0;
  double q = 4.0;
  double rolloff_hz = 1000.0;  //!< the second pole
  int delay_samples = 37;
  double gain = 0.5;
  int sample_rate_hz = 48000;
};

class SimulatedPlant {
 public:
  explicit SimulatedPlant(const PlantSpec& spec) : spec_(spec), delay_line_(static_cast<std::size_t>(spec.delay_samples) + 1, 0.0) {
    const double w0 = 2 * std::numbers::pi * spec.resonance_hz / spec.sample_rate_hz;
    const double alpha = std::sin(w0) / (2 * spec.q);
    const double a0 = 1 + alpha;
    a1_ = -2 * std::cos(w0) / a0;
    a2_ = (1 - alpha) / a0;
    if (spec.kind == PlantKind::high_pass) {
      b0_ = (1 + std::cos(w0)) / 2 / a0;
      b1_ = -(1 + std::cos(w0)) / a0;
      b2_ = b0_;
    } else {
      // The cookbook's poles without its two zeros at the Nyquist frequency: a mass and a
      // spring have none, and those zeros would add a sample of delay above any sweep
      // (b0 sets the gain at DC to 1).
      b0_ = 1 + a1_ + a2_;
    }
    pole_ = std::exp(-2 * std::numbers::pi * spec.rolloff_hz / spec.sample_rate_hz);
  }

  double tick(double x) {
    // Resonance (direct form I), then the roll-off, then the delay.
    const double y = b0_ * x + b1_ * x1_ + b2_ * x2_ - a1_ * y1_ - a2_ * y2_;
    x2_ = x1_;
    x1_ = x;
    y2_ = y1_;
    y1_ = y;
    lp_ = (1 - pole_) * y + pole_ * lp_;
    delay_line_[write_] = spec_.gain * lp_;
    write_ = (write_ + 1) % delay_line_.size();
    return delay_line_[write_];
  }

  //! The exact response at freq_hz.
  std::complex<double> response(double freq_hz) const {
    const double w = 2 * std::numbers::pi * freq_hz / spec_.sample_rate_hz;
    const std::complex<double> z1 = std::polar(1.0, -w), z2 = z1 * z1;
    const std::complex<double> resonance = (b0_ + b1_ * z1 + b2_ * z2) / (1.0 + a1_ * z1 + a2_ * z2);
    const std::complex<double> rolloff = (1 - pole_) / (1.0 - pole_ * z1);
    return spec_.gain * resonance * rolloff * std::polar(1.0, -w * spec_.delay_samples);
  }

  const PlantSpec& spec() const { return spec_; }

 private:
  PlantSpec spec_;
  double b0_ = 0, b1_ = 0, b2_ = 0, a1_ = 0, a2_ = 0, pole_ = 0;
  double x1_ = 0, x2_ = 0, y1_ = 0, y2_ = 0, lp_ = 0;
  std::vector<double> delay_line_;
  std::size_t write_ = 0;
};

}  // namespace mallet::audio
