#pragma once
// `mallet calibrate actuator`'s work, device to file: the sweep played on the actuator's
// channel and recorded from the sensor on the stick (and, with a loopback cable, from the
// actuator's own output), the chain's response deconvolved and analysed, its bounded inverse
// designed, and the result as actuator_eq.toml; and --verify's felt-signal table, Table 1's
// strikes played without and with the inverse and fitted back out of the recording.
//
// A recording that cannot be used is refused with one line (recording_checks.hpp): a sensor
// that clips, one that records nothing but noise, a loopback that carries nothing.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "audio/actuator_inverse.hpp"
#include "audio/actuator_response.hpp"
#include "audio/duplex_measurement.hpp"
#include "app/calibration/recording_checks.hpp"
#include "audio/exp_sweep.hpp"
#include "audio/felt_signal.hpp"
#include "core/actuator_eq_file.hpp"
#include "core/material.hpp"

namespace mallet::app {

struct ActuatorRig {
  audio::DuplexRequest io;        //!< output device and channels; io.input_channels set here
  int sensor_channel = 0;         //!< 0-based
  std::optional<int> loopback_channel;  //!< 0-based: a cable from the actuator's output
  std::string sensor;             //!< the operator's words for it (saved in the file)
};

struct ActuatorMeasurement {
  audio::ActuatorResponse response;
  audio::InverseFilter inverse;
  std::optional<double> round_trip_samples;  //!< the loopback's delay: the sound card's round trip
  double sensor_peak_dbfs = 0;
  double snr_db = 0;                         //!< the sweep's level over the noise before it
  unsigned long xruns = 0;
  ActuatorEq eq;                             //!< what is saved
};

//! Plays the sweep (0.25 s of silence first: the noise floor), records, analyses, designs.
ActuatorMeasurement measure_actuator(const ActuatorRig& rig, const audio::SweepSpec& sweep,
                                     const audio::InverseSpec& inverse);

struct FeltRow {
  audio::FeltStrike strike;
  audio::FeltFit before;
  std::optional<audio::FeltFit> after;  //!< with the calibration's inverse
};

//! Table 1's strikes of `materials` (each at kFeltSpeeds) at `gain`, played without and (with
//! `eq`) with its inverse, each recorded and fitted. The fit starts at eq's delay (or the
//! sound card's round trip measured with the loopback, or 0).
std::vector<FeltRow> verify_felt(const ActuatorRig& rig, const std::vector<Material>& materials, double gain,
                                 const std::optional<ActuatorEq>& eq);

//! The felt-signal table as text: one row per strike, B and f fitted before and after, and
//! their errors against Table 1; then the worst error of each column.
std::string felt_table(const std::vector<FeltRow>& rows);

//! The response as text: the resonance, the band, the delay, then magnitude, phase and group
//! delay every sixth of an octave; the inverse's gains and latency.
std::string response_report(const ActuatorMeasurement& m);

}  // namespace mallet::app
