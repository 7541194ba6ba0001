// `mallet calibrate actuator`: the actuator chain (amplifier → voice coil → stick → sensor)
// measured through the sound card's input, its bounded inverse saved as actuator_eq.toml, and
// with --verify Table 1's strikes checked as the sensor feels them
// (app/calibration/actuator_calibration.hpp).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "app/calibration/actuator_calibration.hpp"
#include "app/cli/commands.hpp"
#include "app/common/settings_source.hpp"
#include "core/atomic_file.hpp"
#include "core/calibration_file.hpp"
#include "core/config/materials_config.hpp"
#include "core/felt_table_file.hpp"
#include "core/data_paths.hpp"

namespace mallet::app {

namespace {

struct ActuatorOptions {
  std::optional<std::filesystem::path> config = default_settings();
  std::optional<std::filesystem::path> config_dir;
  std::string input;
  int channel = 1;
  std::optional<int> loopback;
  double level_db = -20.0;
  double seconds = 4.0;
  double gain_limit_db = 12.0;
  int taps = 2048;
  std::string sensor = "unnamed sensor";
  bool verify = false;
  std::filesystem::path out;
};

ActuatorRig rig_for(const ActuatorOptions& o, const AppConfig& config) {
  ActuatorRig rig;
  rig.io.output_device = config.audio.device;
  rig.io.input_device = o.input;
  rig.io.sample_rate_hz = config.audio.sample_rate_hz;
  rig.io.output_channels = config.audio.routing.channels;
  rig.io.output_channel = config.audio.routing.actuator;
  rig.sensor_channel = o.channel - 1;
  if (o.loopback) rig.loopback_channel = *o.loopback - 1;
  rig.sensor = o.sensor;
  return rig;
}

void run_measure(const ActuatorOptions& o, const AppConfig& config) {
  const ActuatorRig rig = rig_for(o, config);
  audio::SweepSpec sweep;
  sweep.level_db = o.level_db;
  sweep.duration_s = o.seconds;
  sweep.sample_rate_hz = config.audio.sample_rate_hz;
  std::printf("playing a %.1f s sweep, %.0f Hz to %.0f Hz at %.1f dBFS, on output channel %d; recording input "
              "channel %d%s\n",
              sweep.duration_s, sweep.f1_hz, sweep.f2_hz, sweep.level_db, rig.io.output_channel + 1, o.channel,
              o.loopback ? fmt::format(" (sensor) and {} (loopback)", *o.loopback).c_str() : " (sensor)");
  std::fflush(stdout);
  ActuatorMeasurement m;
  try {
    m = measure_actuator(rig, sweep, {.gain_limit_db = o.gain_limit_db, .taps = o.taps});
  } catch (const MeasurementRefused& e) {
    refuse_measurement(e);
  }
  std::fputs(response_report(m).c_str(), stdout);
  write_actuator_eq_file(o.out, m.eq);
  std::printf("wrote %s (calibration %s, %s); the kiosk applies it at its next start while [actuator] equalize = %s\n",
              o.out.string().c_str(), m.eq.hash().c_str(), m.eq.created_utc.c_str(),
              config.actuator.equalize ? "true" : "false (it is off: nothing changes)");
}

void run_verify(const ActuatorOptions& o, const AppConfig& config) {
  std::optional<ActuatorEq> eq;
  std::error_code ec;
  if (std::filesystem::exists(o.out, ec)) eq = load_actuator_eq(o.out);  // a bad file: FileError, exit 2
  const MaterialLibrary library = config::load_materials(config_dir() / "materials.toml");
  std::vector<Material> table1;
  for (const char* name : {"wood", "metal"})
    if (const Material* m = library.find(name)) table1.push_back(*m);
  if (table1.empty()) throw FileError((config_dir() / "materials.toml").string(), 0, 0, "has neither wood nor metal (Table 1)");
  const ActuatorRig rig = rig_for(o, config);
  std::printf("playing Table 1's strikes (%zu materials at 0.3, 0.6 and 1.0 m/s, [actuator] gain %.2f) on output "
              "channel %d, %s; recording input channel %d\n",
              table1.size(), config.actuator.gain, rig.io.output_channel + 1,
              eq ? fmt::format("without and with the inverse of {} ({})", eq->hash(), eq->created_utc).c_str()
                 : "without an inverse (no calibration yet)",
              o.channel);
  std::fflush(stdout);
  std::vector<FeltRow> rows;
  try {
    rows = verify_felt(rig, table1, config.actuator.gain, eq);
  } catch (const MeasurementRefused& e) {
    refuse_measurement(e);
  }
  std::fputs(felt_table(rows).c_str(), stdout);
  const std::filesystem::path kept = o.out.parent_path() / "actuator_felt.csv";
  std::vector<FeltRecord> records;
  const std::string now = utc_timestamp_now();
  for (const FeltRow& r : rows) {
    const auto fitted = [](const audio::FeltFit& f, double v) { return f.fit.ok ? v : std::nan(""); };
    FeltRecord k{r.strike.material, r.strike.speed_m_per_s, r.strike.table.decay_per_s, r.strike.table.freq_hz,
                 fitted(r.before, r.before.fit.decay_per_s), fitted(r.before, r.before.fit.freq_hz),
                 r.after ? fitted(*r.after, r.after->fit.decay_per_s) : std::nan(""),
                 r.after ? fitted(*r.after, r.after->fit.freq_hz) : std::nan(""), eq ? eq->hash() : std::string(), now};
    records.push_back(k);
  }
  write_file_atomically(kept, format_felt_table(records));
  std::printf("kept in %s (mallet bench report shows it)\n", kept.string().c_str());
  if (!eq) std::printf("no calibration at %s: run `mallet calibrate actuator` for the after columns\n", o.out.string().c_str());
}

}  // namespace

void add_calibrate_actuator(CLI::App& calibrate) {
  auto o = std::make_shared<ActuatorOptions>();
  o->out = actuator_eq_path();
  CLI::App* cmd = calibrate.add_subcommand(
      "actuator", "Measure the actuator and stick through the sound card's input; save its bounded inverse");
  cmd->footer(R"(Plays an exponential sine sweep (Farina's method, 20 Hz to 2 kHz, --level dBFS peak,
after 0.25 s of silence for the noise floor) on the actuator's output channel ([audio] device,
[audio.routing] actuator) and records a sensor on the stick (a piezo disc or an analogue
accelerometer, docs/operators.md) on input channel --channel of --input. Prints the chain's
magnitude and phase response, group delay, resonance, usable band (within 30 dB of the
resonance) and pure delay; designs a bounded inverse (Kirkeby-regularised, at most
--gain-limit dB of lift, minimum phase, --taps taps) and states its latency; writes
actuator_eq.toml (--out, default the state folder's) atomically with its date, the sensor's
description (--sensor) and its identity (a hash of its taps). The kiosk applies the inverse to
the actuator channel at its next start while [actuator] equalize = true.
--loopback CH: a cable from the actuator's output to input channel CH; the sound card's round
trip is then measured too and the chain's own delay given without it.
--verify: no sweep; plays Table 1's wood and metal strikes at 0.3, 0.6 and 1.0 m/s without and
with the saved inverse, fits Eq. 1's B and f back out of the recording and prints the
felt-signal table (columns: material, v m/s, B 1/s, f Hz, then B, error, f, error before and
after); keeps it beside the calibration as actuator_felt.csv (`mallet bench report` shows it).
Exit status: 0 done; 2 with one line: no input ("this sound card has no input: ..."), a sensor
that records silence or clips, bad settings or a bad file; 1 a device that fails.)");
  add_settings_options(*cmd, o->config, o->config_dir);
  cmd->add_option("--input", o->input, "Input device: a part of its name or its index (default: the default input)");
  cmd->add_option("--channel", o->channel, "Input channel of the sensor, from 1")->capture_default_str()->check(CLI::Range(1, 64));
  cmd->add_option("--loopback", o->loopback, "Input channel of a loopback cable from the actuator's output, from 1")
      ->check(CLI::Range(1, 64));
  cmd->add_option("--level", o->level_db, "The sweep's peak in dBFS")->capture_default_str()->check(CLI::Range(-60.0, -3.0));
  cmd->add_option("--seconds", o->seconds, "The sweep's length")->capture_default_str()->check(CLI::Range(1.0, 30.0));
  cmd->add_option("--gain-limit", o->gain_limit_db, "The most the inverse lifts any frequency, dB")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 30.0));
  cmd->add_option("--taps", o->taps, "The inverse's length in samples")->capture_default_str()->check(CLI::Range(64, 8192));
  cmd->add_option("--sensor", o->sensor, "What records (saved with the calibration), e.g. \"piezo disc, stick tip\"")
      ->capture_default_str();
  cmd->add_flag("--verify", o->verify, "Play Table 1's strikes without and with the inverse; print the felt-signal table");
  cmd->add_option("--out", o->out, "The calibration file")->capture_default_str();
  cmd->callback([o] {
    if (o->loopback && *o->loopback == o->channel)
      throw CLI::ValidationError("--loopback", "the loopback and the sensor need their own input channels");
    const AppConfig config = command_settings(o->config, o->config_dir, "calibrate actuator");
    if (o->verify)
      run_verify(*o, config);
    else
      run_measure(*o, config);
  });
}

}  // namespace mallet::app
