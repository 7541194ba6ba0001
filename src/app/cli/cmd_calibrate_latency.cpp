// `mallet calibrate latency --loopback CH`: the sound card's round trip on a loopback cable,
// the output latency it gives, kept in the state folder (latency.toml) and, with --save,
// written as [timing] audio_output_latency_ms in a settings drop-in
// (app/calibration/latency_calibration.hpp). `--photodiode CH`: the kiosk itself on the
// screen, its operator page's latency test timed by a photodiode on the screen's corner
// (app/kiosk/photodiode_latency.hpp); the operator's Enter on the page saves it.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "app/calibration/latency_calibration.hpp"
#include "app/calibration/recording_checks.hpp"
#include "app/cli/commands.hpp"
#include "app/kiosk/kiosk.hpp"
#include "app/common/settings_source.hpp"
#include "app/common/timing_drop_in.hpp"
#include "core/atomic_file.hpp"
#include "core/calibration_file.hpp"
#include "core/data_paths.hpp"
#include "core/toml_text.hpp"
#include "render/window_target.hpp"

namespace mallet::app {

namespace {

struct LatencyOptions {
  std::optional<std::filesystem::path> config = default_settings();
  std::optional<std::filesystem::path> config_dir;
  std::string input;
  std::optional<int> loopback;
  std::optional<int> photodiode;
  bool save = false;
};

// The display's latency: the kiosk on this screen, its page's latency test timed by the
// photodiode; the operator answers on the page. Returns the kiosk's exit status (0: answered;
// 2: nothing usable measured, said on stderr) and whether the operator saved it.
int run_photodiode(const LatencyOptions& o, bool& saved) {
  KioskOptions ko;
  ko.config = o.config;
  ko.config_dir = o.config_dir;
  ko.measure_display_latency = KioskOptions::DisplayLatencyRun{*o.photodiode, o.input};
  std::printf("the kiosk on this screen: its operator page's latency test, ten white squares in the top-left "
              "corner, timed by the photodiode on input channel %d; Enter on the page saves what it finds, Esc "
              "keeps the setting\n",
              *o.photodiode);
  std::fflush(stdout);
  const std::string started = utc_timestamp_now();
  const int status = run_kiosk(ko);
  std::optional<DisplayLatencyMeasurement> m;
  try {
    m = load_display_latency(display_latency_path());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mallet: %s\n", e.what());
  }
  saved = status == 0 && m && m->saved && m->measured_utc >= started;
  if (status == 0 && m && m->measured_utc >= started)
    std::printf("display latency: %.3f ms (%.3f to %.3f over %d of %d squares), %s\n", m->display_latency_ms, m->min_ms,
                m->max_ms, m->squares_seen, m->squares,
                m->saved ? "saved as [timing] display_latency_ms" : "not saved (Esc)");
  return status;
}

void run_latency(const LatencyOptions& o) {
  if (!o.loopback && !o.photodiode)
    refuse_measurement(MeasurementRefused(
        "nothing to measure with: give --loopback CH (a cable from the actuator's output to input channel CH) or "
        "--photodiode CH (a photodiode on the screen's top-left corner, on input channel CH)"));
  if (o.loopback && o.photodiode && *o.loopback == *o.photodiode)
    refuse_measurement(MeasurementRefused(fmt::format(
        "--loopback and --photodiode are both input channel {}: each needs an input of its own", *o.loopback)));
  if (o.photodiode && !render::WindowSystem::display_available())
    refuse_measurement(MeasurementRefused(
        "--photodiode needs the kiosk's screen, the one the photodiode is on: DISPLAY and WAYLAND_DISPLAY are "
        "unset (on a kiosk, the operator page's T measures it with [timing] photodiode_channel: docs/operators.md)"));
  const AppConfig config = command_settings(o.config, o.config_dir, "calibrate latency");
  if (!o.loopback) {
    bool saved = false;
    if (const int status = run_photodiode(o, saved); status != 0) finish_with(status);
    return;
  }
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
  bool save = o.save;
  if (o.photodiode) {  // the page's Enter saves both
    bool saved = false;
    if (const int status = run_photodiode(o, saved); status != 0) finish_with(status);
    save = save || saved;
  }
  if (save) {
    const std::filesystem::path written = write_timing_drop_in(
        drop_in_dir_for(o.config, o.config_dir), kOutputLatencyDropIn,
        "Written by mallet calibrate latency --loopback --save at " + m.measured_utc +
            ": the sound card's\noutput latency, measured on a loopback cable (round trip " +
            toml_text::exact_number(m.round_trip_ms()) + " ms less PortAudio's input latency).",
        "audio_output_latency_ms", m.output_latency_ms());
    std::printf("wrote %s: the kiosk uses it from its next reload (systemctl reload mallet)\n", written.string().c_str());
  } else {
    std::printf("to use it: run again with --save, or set [timing] audio_output_latency_ms = %.3f\n", m.output_latency_ms());
  }
}

}  // namespace

void add_calibrate_latency(CLI::App& calibrate) {
  auto o = std::make_shared<LatencyOptions>();
  CLI::App* cmd = calibrate.add_subcommand(
      "latency", "Measure the sound card's output latency (a loopback cable) and the display's (a photodiode)");
  cmd->footer(R"(--loopback CH: a cable from the actuator's output channel ([audio.routing] actuator of
[audio] device) to input channel CH (from 1) of --input. Plays a 1 s sweep (50 Hz to 15 kHz)
after 0.25 s of silence and finds the round trip on the cable to a fraction of a sample;
prints it, PortAudio's own input and output latency for the stream, and the output latency
measured (the round trip less the input latency), which is what [timing]
audio_output_latency_ms stands for. Keeps what it measured in the state folder (latency.toml:
`mallet doctor` says when it was last measured). --save writes the value as a settings drop-in,
60-measured-latency.toml in the settings' drop-in folder (--config-dir), which the kiosk reads
at its next reload.
--photodiode CH: a photodiode on the screen's top-left corner (docs/operators.md has the
circuit) on input channel CH of --input. Runs the kiosk on this screen with its operator page
open and its latency test (T): ten white squares in the corner, one a second. The kiosk's own
stream records the photodiode, and each square's light is timed against the present of the
frame that showed it; the page shows the median and its spread and asks: Enter saves it as
[timing] display_latency_ms (the drop-in 61-measured-display-latency.toml in the state
folder's measured.d, which the settings merge with their own drop-ins in the order of the
files' names; with --loopback, the output latency too, as --save would), Esc keeps the
setting. Either way it is kept in the state folder (display_latency.toml: `mallet doctor`
shows it). Needs the screen the photodiode is on (DISPLAY or WAYLAND_DISPLAY). On a packaged
kiosk the operator page's T measures the same, with [timing] photodiode_channel set.
Exit status: 0 done; 2 with one line: neither --loopback nor --photodiode, no input ("this sound
card has no input: ..."), a loopback that records silence or clips, a photodiode that sees no
light, no screen, bad settings; 1 a device or a file that fails.)");
  add_settings_options(*cmd, o->config, o->config_dir);
  cmd->add_option("--input", o->input, "Input device: a part of its name or its index (default: the default input)");
  cmd->add_option("--loopback", o->loopback, "Input channel of the loopback cable, from 1")->check(CLI::Range(1, 64));
  cmd->add_option("--photodiode", o->photodiode, "Input channel of the photodiode on the screen's corner, from 1")
      ->check(CLI::Range(1, 64));
  cmd->add_flag("--save", o->save, "Write the output latency as [timing] audio_output_latency_ms (a drop-in)");
  cmd->callback([o] { run_latency(*o); });
}

}  // namespace mallet::app
