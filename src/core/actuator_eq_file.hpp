#pragma once
// The actuator's calibration: what `mallet calibrate actuator` measured of the chain
// (amplifier → voice coil → stick → sensor) and the bounded inverse the engine applies to
// the actuator channel when [actuator] equalize allows it. A TOML file in the state folder,
// actuator_eq.toml, written atomically, e.g.
//
//   # Mallet actuator calibration.
//   format_version = 1
//   created_utc = "2026-12-06T09:30:00Z"
//   created_by = "mallet calibrate actuator"
//   sensor = "piezo disc, stick tip"        # what recorded it (the operator's words)
//   sample_rate_hz = 48000                  # the taps are for this rate only
//   sweep_hz = [20.0, 2000.0]
//   level_db = -20.0                        # the sweep's peak, dB of full scale
//   resonance_hz = 179.6
//   resonance_db = 5.9                      # sensor units per unit of output
//   usable_band_hz = [63.5, 1522.2]
//   delay_ms = 0.77                         # the chain's pure delay (round trip included)
//   round_trip_ms = 10.7                    # optional: the sound card's, by a loopback cable
//   gain_limit_db = 12.0
//   target_db = -6.8                        # the level the chain is equalised to
//   latency_samples = -66.1                 # the inverse's group delay over the band
//   [response]                              # 1/12 octave: what the report plots
//   frequency_hz = [...]
//   magnitude_db = [...]
//   phase_deg = [...]
//   [inverse]
//   taps = [...]                            # the minimum-phase FIR filter
//
// Its identity (hash()) is FNV-1a 64 of the rate and the taps' bits: a study's results
// name the calibration in force by its date and this hash.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mallet {

struct ActuatorEq {
  std::string created_utc;
  std::string created_by;
  std::string sensor;
  int sample_rate_hz = 0;
  double sweep_low_hz = 0, sweep_high_hz = 0;
  double level_db = 0;
  double resonance_hz = 0, resonance_db = 0;
  double band_low_hz = 0, band_high_hz = 0;
  double delay_ms = 0;
  std::optional<double> round_trip_ms;  //!< the sound card's, when a loopback measured it
  double gain_limit_db = 0;
  double target_db = 0;
  double latency_samples = 0;
  std::vector<double> frequency_hz, magnitude_db, phase_deg;
  std::vector<double> taps;

  //! 16 hex digits, FNV-1a 64 over the rate and the taps' IEEE bits.
  std::string hash() const;
  //! The whole samples the engine delays the speaker's note by (max(0, round(latency))).
  int alignment_samples() const;
};

//! Every problem is a FileError naming file:line:column and key (unknown keys refused; the
//! taps 16..8192 finite numbers, the response's three lists as long as each other).
ActuatorEq load_actuator_eq(const std::filesystem::path& path);
ActuatorEq parse_actuator_eq(std::string_view text, const std::string& name);
std::string format_actuator_eq(const ActuatorEq& eq);
//! Atomically (core/atomic_file.hpp); refuses (std::invalid_argument) what would not load.
void write_actuator_eq_file(const std::filesystem::path& path, const ActuatorEq& eq);

}  // namespace mallet
