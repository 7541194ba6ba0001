// `mallet calibrate latency --loopback CH`: the sound card's round trip on a loopback cable,
// the output latency it gives, kept in the state folder (latency.toml) and, with --save,
// written as [timing] audio_output_latency_ms in a settings drop-in
// (app/calibration/latency_calibration.hpp).
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "app/calibration/latency_calibration.hpp"
#include "app/calibration/recording_checks.hpp"
#include "app/cli/commands.hpp"
#include "app/common/settings_source.hpp"
#include "core/atomic_file.hpp"
#include "core/data_paths.hpp"
#include "core/toml_text.hpp"

namespace mallet::app {

namespace {

struct LatencyOptions {
  std::optional<std::filesystem::path> config = default_settings();
  std::optional<std::filesystem::path> config_dir;
  std::string input;
  std::optional<int> loopback;
  bool save = false;
};

constexpr const char* kDropIn = "60-measured-latency.toml";

void run_latency(const LatencyOptions& o) {
  if (!o.loopback)
    refuse_measurement(MeasurementRefused(
        "nothing to measure with: give --loopback CH (a cable from the actuator's output to input channel CH)"));
  const AppConfig config = command_settings(o.config, o.config_dir, "calibrate latency");
  audio::DuplexRequest io;
  io.output_device = config.audio.device;
  io.input_device = o.input;
  io.sample_rate_hz = config.audio.sample_rate_hz;
  io.output_channels = config.audio.routing.channels;
  io.output_channel = config.audio.routing.actuator;
  std::printf("playing a 1 s sweep on output channel %d; recording the loopback on input channel %d\n",
              io.output_channel + 1, *o.loopback);
  std::fflush(stdout);
  LatencyMeasurement m;
  try {
    m = measure_round_trip(io, *o.loopback - 1);
  } catch (const MeasurementRefused& e) {
    refuse_measurement(e);
  }
  std::printf("devices: \"%s\" out, \"%s\" in, %d Hz%s\n", m.output_device.c_str(), m.input_device.c_str(),
              m.sample_rate_hz, m.xruns ? " (the stream over/underran: measure again)" : "");
  std::printf("round trip: %.2f samples (%.3f ms)\n", m.round_trip_samples, m.round_trip_ms());
  std::printf("PortAudio's figures for this stream: input %.3f ms, output %.3f ms\n", m.portaudio_input_latency_ms,
              m.portaudio_output_latency_ms);
  std::printf("output latency: %.3f ms (the round trip less the input's); PortAudio says %.3f ms, [timing] "
              "audio_output_latency_ms is %s\n",
              m.output_latency_ms(), m.portaudio_output_latency_ms,
              config.audio.output_latency_ms < 0 ? std::string("-1 (PortAudio's figure)").c_str()
                                                        : fmt::format("{:.3f}", config.audio.output_latency_ms).c_str());
  const std::filesystem::path record = latency_record_path();
  std::filesystem::create_directories(record.parent_path());
  write_file_atomically(record, format_latency_record(m));
  std::printf("kept in %s\n", record.string().c_str());
  if (o.save) {
    const std::filesystem::path dir = drop_in_dir_for(o.config, o.config_dir);
    std::filesystem::create_directories(dir);
    const std::string text = "# Written by mallet calibrate latency --loopback --save at " + m.measured_utc +
                             ": the sound card's\n# output latency, measured on a loopback cable (round trip " +
                             toml_text::exact_number(m.round_trip_ms()) + " ms less PortAudio's input latency).\n" +
                             "[timing]\naudio_output_latency_ms = " + toml_text::exact_number(m.output_latency_ms()) + "\n";
    write_file_atomically(dir / kDropIn, text);
    std::printf("wrote %s: the kiosk uses it from its next reload (systemctl reload mallet)\n", (dir / kDropIn).string().c_str());
  } else {
    std::printf("to use it: run again with --save, or set [timing] audio_output_latency_ms = %.3f\n", m.output_latency_ms());
  }
}

}  // namespace

void add_calibrate_latency(CLI::App& calibrate) {
  auto o = std::make_shared<LatencyOptions>();
  CLI::App* cmd = calibrate.add_subcommand("latency", "Measure the sound card's output latency on a loopback cable");
  cmd->footer(R"(--loopback CH: a cable from the actuator's output channel ([audio.routing] actuator of
[audio] device) to input channel CH (from 1) of --input. Plays a 1 s sweep (50 Hz to 15 kHz)
after 0.25 s of silence and finds the round trip on the cable to a fraction of a sample;
prints it, PortAudio's own input and output latency for the stream, and the output latency
measured (the round trip less the input latency), which is what [timing]
audio_output_latency_ms stands for. Keeps what it measured in the state folder (latency.toml:
`mallet doctor` says when it was last measured). --save writes the value as a settings drop-in,
60-measured-latency.toml in the settings' drop-in folder (--config-dir), which the kiosk reads
at its next reload.
Exit status: 0 done; 2 with one line: no --loopback, no input ("this sound card has no input:
..."), a loopback that records silence or clips, bad settings; 1 a device or a file that fails.)");
  add_settings_options(*cmd, o->config, o->config_dir);
  cmd->add_option("--input", o->input, "Input device: a part of its name or its index (default: the default input)");
  cmd->add_option("--loopback", o->loopback, "Input channel of the loopback cable, from 1")->check(CLI::Range(1, 64));
  cmd->add_flag("--save", o->save, "Write the output latency as [timing] audio_output_latency_ms (a drop-in)");
  cmd->callback([o] { run_latency(*o); });
}

}  // namespace mallet::app
