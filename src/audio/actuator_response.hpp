#pragma once
// What a measured impulse response of the actuator chain (amplifier → voice coil → stick
// → sensor) says: its magnitude and phase, group delay, resonance, usable band and pure
// delay. `mallet calibrate actuator` prints it and saves it (core/actuator_eq_file.hpp).
//
// THE USABLE BAND is the stretch of 1/12-octave points around the resonance whose
// magnitude stays within band_db (default 30 dB) of the resonance's, inside the sweep's range
// less a third of an octave at each end (where the sweep's fades leave little energy).
//
// THE PURE DELAY is what the chain adds beyond a minimum-phase system of the same
// magnitude: the slope of the excess phase arg(H / H_min) over the usable band, fitted
// with an intercept (a sensor wired the other way round adds π). H_min comes from the
// magnitude by the real cepstrum, from the magnitude measured up to a sixth of an octave
// below the sweep's top and continued along its slope beyond (extended_magnitude). What the
// chain does beyond the sweep is not known: a zero on the unit circle out there (a digital
// filter's at the Nyquist frequency, an accelerometer's at DC) holds half a sample of delay
// that no magnitude within the sweep shows (the cookbook low-pass's two gave +1.1 samples).
// Against the simulated plants (audio/simulated_plant.hpp; `mallet bench actuator`, measured):
// +0.23 samples for the low-pass (a resonance of poles only), +0.35 for the high-pass.
#include <complex>
#include <span>
#include <vector>

namespace mallet::audio {

struct ResponsePoint {
  double freq_hz = 0;
  double magnitude_db = 0;   //!< 20·log10|H|, the sensor's units per unit of output
  double phase_deg = 0;      //!< unwrapped from the first point
  double group_delay_ms = 0;
};

struct ActuatorResponse {
  int sample_rate_hz = 0;
  std::vector<ResponsePoint> points;  //!< 1/12 octave, f1 to f2
  double resonance_hz = 0;
  double resonance_db = 0;
  double band_low_hz = 0;   //!< the usable band
  double band_high_hz = 0;
  //! Where the magnitude counts as measured: the sweep less a third of an octave at the
  //! bottom (its fade-in) and a sixth at the top. Beyond, extended_magnitude continues it;
  //! the delay here and the inverse (actuator_inverse.hpp) both use this range.
  double measured_low_hz = 0;
  double measured_high_hz = 0;
  double delay_samples = 0; //!< the pure delay
  bool inverted = false;    //!< the excess phase's intercept is nearer π than 0
};

//! H(e^(j2πf/rate)) of the impulse response h, evaluated directly.
std::complex<double> response_at(std::span<const double> h, double freq_hz, int rate);
//! Its group delay in samples at freq_hz: Re(Σ n·h[n]·e^(−jωn) / H).
double group_delay_at(std::span<const double> h, double freq_hz, int rate);

//! `h[pre]` is the response at the sweep's first sample (deconvolve_sweep's `pre`): phases,
//! group delays and the delay are measured from there.
ActuatorResponse analyse_response(std::span<const double> h, int rate, double f1_hz, double f2_hz,
                                  double band_db = 30.0, std::size_t pre = 0);

//! The delay in samples of a flat path (a loopback cable) from its impulse response: the
//! peak, interpolated by a parabola through it and its neighbours, less `pre`.
double flat_path_delay(std::span<const double> h, std::size_t pre = 0);

//! |spectrum| (n/2 + 1 bins) between bins k_lo and k_hi, continued outside them along the
//! log-log slope of the octave inside the low edge and the half octave inside the high one
//! (at most 80 dB below the edge; held flat
//! below k_lo when that octave rises by less than 6 dB): the
//! magnitude a minimum-phase reconstruction needs everywhere, from a measurement that only
//! holds between the sweep's ends.
std::vector<double> extended_magnitude(std::span<const std::complex<double>> spectrum, std::size_t k_lo,
                                       std::size_t k_hi);

//! The minimum-phase spectrum (n/2 + 1 bins of an n-point DFT) of the magnitude `magnitude`
//! (n/2 + 1 bins, all > 0), by folding the real cepstrum.
std::vector<std::complex<double>> minimum_phase(std::span<const double> magnitude, std::size_t n);

}  // namespace mallet::audio
