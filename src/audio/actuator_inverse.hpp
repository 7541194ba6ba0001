#pragma once
// The actuator's bounded inverse: a minimum-phase FIR filter that, placed before the
// amplifier, makes the chain's magnitude flat over the usable band, so that what the stick
// carries follows Eq. 1 instead of the voice coil's resonance.
//
// DESIGN (Kirkeby's regularised inversion toward a target, then minimum phase):
//   level T    = the chain's median magnitude over the usable band (1/12-octave points),
//                but no more than its weakest point there + G_dB − 3 dB, so that the whole
//                band can be reached within the gain limit (the resonance is cut instead);
//   target D   = T · a 2nd-order Butterworth high-pass at the band's low edge and low-pass
//                at its high edge: flat inside, gentle outside, so the equalised chain rings
//                at no new frequency (a brick-wall target leaves a slowly decaying mode at
//                the band's edge, which a fit of Eq. 1 then reads as a wrong B);
//   |C(k)|     = D(k)·|H(k)| / (|H(k)|² + β),  β = (T / (2·G))²,  G = 10^(gain_limit_db/20):
//                |C| never exceeds G (the regulariser's maximum); outside the usable band
//                |H| is continued along its slope (extended_magnitude);
//   C          = the minimum-phase spectrum of |C| (real cepstrum), cut to `taps` samples
//                with a half-Hann fade over the last eighth.
// A minimum-phase filter has the least delay any filter of that magnitude can have: its
// latency (its group delay, averaged over the band weighted by the chain's magnitude) is
// stated with it. Against a resonance it is negative (the inverse takes the resonance's own
// delay away); where it is positive the engine delays the speaker's note by its whole
// samples so that both channels of a strike are still heard together (audio/engine.hpp).
#include <span>
#include <vector>

#include "audio/actuator_response.hpp"

namespace mallet::audio {

struct InverseSpec {
  double gain_limit_db = 12.0;
  int taps = 2048;  //!< 43 ms at 48 kHz: 1024 cannot hold an inertial actuator's inverse (its low shelf)
};

struct InverseFilter {
  std::vector<double> taps;
  double target_db = 0;        //!< the level the chain is equalised to (sensor units, dB)
  double max_gain_db = 0;      //!< the most the filter lifts anything (≤ gain_limit_db)
  double min_gain_db = 0;      //!< the most it cuts (negative)
  double latency_samples = 0;  //!< its group delay over the band
};

//! The target's shape: Butterworth 2nd-order high-pass at low_hz times low-pass at high_hz.
double target_shape(double f, double low_hz, double high_hz);

//! Throws std::invalid_argument for a response without a usable band, or a spec out of
//! range (0 < gain_limit_db ≤ 40, 16 ≤ taps ≤ 8192).
InverseFilter design_inverse(std::span<const double> h, const ActuatorResponse& response, const InverseSpec& spec);

}  // namespace mallet::audio
