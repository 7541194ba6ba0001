#include "app/calibration/actuator_calibration.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "app/calibration/recording_checks.hpp"
#include "core/calibration_file.hpp"

namespace mallet::app {

namespace {

constexpr double kLeadS = 0.25;  // silence before the sweep: the noise floor

}  // namespace

ActuatorMeasurement measure_actuator(const ActuatorRig& rig, const audio::SweepSpec& spec,
                                     const audio::InverseSpec& inverse_spec) {
  const std::vector<double> sweep = audio::exp_sweep(spec);
  const auto lead = static_cast<std::size_t>(kLeadS * spec.sample_rate_hz);
  audio::DuplexRequest io = rig.io;
  io.sample_rate_hz = spec.sample_rate_hz;
  io.input_channels = {rig.sensor_channel};
  if (rig.loopback_channel) io.input_channels.push_back(*rig.loopback_channel);
  io.tail_s = 0.5;
  const audio::DuplexRecording rec = record_whole(io, after_silence(sweep, lead));

  ActuatorMeasurement m;
  m.xruns = rec.xruns;
  const ChannelLevels sensor =
      check_channel(rec.channels[0], lead, sweep.size(), fmt::format("sensor (input channel {})", rig.sensor_channel + 1));
  m.sensor_peak_dbfs = sensor.peak_dbfs;
  m.snr_db = sensor.snr_db;
  const std::size_t length = audio::kDeconvolutionPre + 16384;
  const auto after_lead = [&](const std::vector<double>& x) { return std::span<const double>(x).subspan(lead); };
  const std::vector<double> h = audio::deconvolve_sweep(after_lead(rec.channels[0]), sweep, spec, length);
  m.response = audio::analyse_response(h, spec.sample_rate_hz, spec.f1_hz, spec.f2_hz, 30.0, audio::kDeconvolutionPre);
  if (rig.loopback_channel) {
    check_channel(rec.channels[1], lead, sweep.size(), fmt::format("loopback (input channel {})", *rig.loopback_channel + 1));
    const std::vector<double> loop = audio::deconvolve_sweep(after_lead(rec.channels[1]), sweep, spec, length);
    m.round_trip_samples = audio::flat_path_delay(loop, audio::kDeconvolutionPre);
  }
  try {
    m.inverse = audio::design_inverse(h, m.response, inverse_spec);
  } catch (const std::invalid_argument& e) {
    throw MeasurementRefused(std::string("no inverse can be made from this recording: ") + e.what());
  }

  ActuatorEq& e = m.eq;
  e.created_utc = utc_timestamp_now();
  e.created_by = "mallet calibrate actuator";
  e.sensor = rig.sensor;
  e.sample_rate_hz = spec.sample_rate_hz;
  e.sweep_low_hz = spec.f1_hz;
  e.sweep_high_hz = spec.f2_hz;
  e.level_db = spec.level_db;
  e.resonance_hz = m.response.resonance_hz;
  e.resonance_db = m.response.resonance_db;
  e.band_low_hz = m.response.band_low_hz;
  e.band_high_hz = m.response.band_high_hz;
  e.delay_ms = 1000.0 * m.response.delay_samples / spec.sample_rate_hz;
  if (m.round_trip_samples) e.round_trip_ms = 1000.0 * *m.round_trip_samples / spec.sample_rate_hz;
  e.gain_limit_db = inverse_spec.gain_limit_db;
  e.target_db = m.inverse.target_db;
  e.latency_samples = m.inverse.latency_samples;
  for (const audio::ResponsePoint& p : m.response.points) {
    e.frequency_hz.push_back(p.freq_hz);
    e.magnitude_db.push_back(p.magnitude_db);
    e.phase_deg.push_back(p.phase_deg);
  }
  e.taps = m.inverse.taps;
  return m;
}

std::vector<FeltRow> verify_felt(const ActuatorRig& rig, const std::vector<Material>& materials, double gain,
                                 const std::optional<ActuatorEq>& eq) {
  const int rate = eq ? eq->sample_rate_hz : rig.io.sample_rate_hz;
  const std::vector<audio::FeltStrike> strikes = audio::felt_strikes(materials, rate);
  const std::size_t total = static_cast<std::size_t>(strikes.back().start) + static_cast<std::size_t>(rate) / 2;
  const double delay = eq ? eq->delay_ms * rate / 1000.0 : 0.0;
  audio::DuplexRequest io = rig.io;
  io.sample_rate_hz = rate;
  io.input_channels = {rig.sensor_channel};
  io.tail_s = 0.25;
  const auto record = [&](std::span<const double> taps) {
    const std::vector<float> signal = audio::render_felt(strikes, gain, taps, total, rate);
    audio::DuplexRecording rec = record_whole(io, signal);
    double peak = 0;
    for (double v : rec.channels[0]) peak = std::max(peak, std::abs(v));
    if (peak >= kClipLevel)
      throw MeasurementRefused(fmt::format("the sensor clips (peak {:.1f} dBFS) on Table 1's strikes: lower [actuator] gain or the input's gain", 20 * std::log10(peak)));
    if (peak <= 0) throw MeasurementRefused("the sensor records silence on Table 1's strikes: check its wiring and --channel");
    return audio::fit_felt(strikes, rec.channels[0], delay, rate);
  };
  const std::vector<audio::FeltFit> before = record({});
  std::vector<audio::FeltFit> after;
  if (eq) after = record(eq->taps);
  std::vector<FeltRow> rows;
  for (std::size_t k = 0; k < strikes.size(); ++k) {
    FeltRow row{strikes[k], before[k], std::nullopt};
    if (eq) row.after = after[k];
    rows.push_back(row);
  }
  return rows;
}

std::string felt_table(const std::vector<FeltRow>& rows) {
  std::string out = fmt::format("{:<10} {:>6} {:>8} {:>8} | {:>9} {:>7} {:>9} {:>7} | {:>9} {:>7} {:>9} {:>7}\n",
                                "material", "v m/s", "B 1/s", "f Hz", "B before", "err", "f before", "err", "B after",
                                "err", "f after", "err");
  double worst_before = 0, worst_after = 0;
  bool any_after = false;
  const auto cell = [](const audio::FeltFit& f, double value, double error) {
    return f.fit.ok ? fmt::format("{:>9.1f} {:>+6.1f}%", value, 100 * error) : fmt::format("{:>9} {:>7}", "no fit", "");
  };
  for (const FeltRow& r : rows) {
    out += fmt::format("{:<10} {:>6.2f} {:>8.1f} {:>8.1f} | {} {} |", r.strike.material, r.strike.speed_m_per_s,
                       r.strike.table.decay_per_s, r.strike.table.freq_hz,
                       cell(r.before, r.before.fit.decay_per_s, r.before.decay_error),
                       cell(r.before, r.before.fit.freq_hz, r.before.freq_error));
    worst_before = std::max({worst_before, std::abs(r.before.decay_error), std::abs(r.before.freq_error)});
    if (r.after) {
      any_after = true;
      out += fmt::format(" {} {}", cell(*r.after, r.after->fit.decay_per_s, r.after->decay_error),
                         cell(*r.after, r.after->fit.freq_hz, r.after->freq_error));
      worst_after = std::max({worst_after, std::abs(r.after->decay_error), std::abs(r.after->freq_error)});
    } else {
      out += fmt::format(" {:>9} {:>7} {:>9} {:>7}", "-", "", "-", "");
    }
    out += "\n";
  }
  out += fmt::format("worst |error| of B and f: {:.1f}% without the inverse", 100 * worst_before);
  out += any_after ? fmt::format(", {:.1f}% with it\n", 100 * worst_after) : std::string(" (no calibration: nothing to compare)\n");
  return out;
}

std::string response_report(const ActuatorMeasurement& m) {
  const audio::ActuatorResponse& r = m.response;
  const double rate = r.sample_rate_hz;
  std::string out;
  out += fmt::format("sensor: peak {:.1f} dBFS, {:.1f} dB over the noise{}\n", m.sensor_peak_dbfs, m.snr_db,
                     m.xruns ? fmt::format(" ({} over/underrun(s) during the sweep: measure again)", m.xruns) : "");
  out += fmt::format("resonance: {:.1f} Hz at {:.1f} dB\n", r.resonance_hz, r.resonance_db);
  out += fmt::format("usable band: {:.1f} to {:.1f} Hz (within 30 dB of the resonance)\n", r.band_low_hz, r.band_high_hz);
  out += fmt::format("delay: {:.2f} samples ({:.3f} ms){}\n", r.delay_samples, 1000 * r.delay_samples / rate,
                     r.inverted ? "; the sensor's polarity is inverted" : "");
  if (m.round_trip_samples)
    out += fmt::format("round trip (loopback): {:.2f} samples ({:.3f} ms); the chain's own delay: {:.2f} samples ({:.3f} ms)\n",
                       *m.round_trip_samples, 1000 * *m.round_trip_samples / rate, r.delay_samples - *m.round_trip_samples,
                       1000 * (r.delay_samples - *m.round_trip_samples) / rate);
  out += fmt::format("{:>10} {:>10} {:>10} {:>14}\n", "f (Hz)", "|H| (dB)", "phase (°)", "group delay (ms)");
  for (std::size_t i = 0; i < r.points.size(); i += 2) {
    const audio::ResponsePoint& p = r.points[i];
    out += fmt::format("{:>10.1f} {:>10.2f} {:>10.1f} {:>14.3f}{}\n", p.freq_hz, p.magnitude_db, p.phase_deg,
                       p.group_delay_ms, p.freq_hz >= r.band_low_hz && p.freq_hz <= r.band_high_hz ? "" : "  (outside the band)");
  }
  out += fmt::format("inverse: {} taps, minimum phase; level {:.1f} dB; lifts at most {:+.1f} dB, cuts at most {:+.1f} dB "
                     "(limit {:+.1f} dB); latency {:.1f} samples ({:.3f} ms){}\n",
                     m.inverse.taps.size(), m.inverse.target_db, m.inverse.max_gain_db, m.inverse.min_gain_db,
                     m.eq.gain_limit_db, m.inverse.latency_samples, 1000 * m.inverse.latency_samples / rate,
                     m.inverse.latency_samples < 0 ? " (it takes the resonance's own delay away)" : "");
  return out;
}

}  // namespace mallet::app
