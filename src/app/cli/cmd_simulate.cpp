#include <cstdio>
#include <string>

#include "app/cli/commands.hpp"
#include "core/data_paths.hpp"
#include "app/common/settings_source.hpp"
#include "app/offline/simulate.hpp"

namespace mallet::app {

void register_simulate(CLI::App& app) {
  auto options = std::make_shared<SimulateOptions>();
  auto rate = std::make_shared<int>(0);
  options->scene = default_scene();
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Replay a trajectory through the contact solver; write events, cursor trace and audio");
  cmd->footer(R"(Writes the exact stimuli of a session:
  DIR/events.csv  t,target,instrument,material,note,velocity
                  one row per impact; t = exact contact time (s), velocity = normal
                  impact speed (m/s)
  DIR/cursor.csv  t,hand_x,hand_y,cursor_x,cursor_y,offset  at --trace-rate, world metres;
                  cursor = the displayed mallet head (held on the surface while the hand
                  is below it, plus the visual vibration); offset = Eq. 1 visual displacement
                  texture scenes add gain,stripe_phase: cursor = the cursor after the Speed
                  technique, gain = its gain, stripe_phase = the stripes' phase (rad)
  DIR/audio.wav   32-bit float, channels as [audio.routing] says (default 0 = acoustic,
                  1 = actuator); sample 0 is t = 0; each impact starts on its own sample
                  on both channels: the note ([audio].acoustic: modal or midi) and Eq. 1.
With --causal the strikes are decided as the live kiosk decides them: each sample is
known only from its own time plus --input-delay-ms, contact prediction and [timing]
align follow the settings, and the frames are paced by --display-hz and --present-mode.
events.csv then adds after its columns  contact_t,sound_t,shown_t,predicted:
  contact_t  the contact as the kiosk estimated it (seen, or predicted) (s)
  sound_t    when both channels start in audio.wav (s)
  shown_t    the present time of the first frame that shows the bounce (s)
  predicted  1 when the strike was scheduled from a prediction, else 0
With --causal --camera the strikes are decided as the kiosk's camera route decides them
([input] source = "camera"): contact prediction tuned for the camera the settings'
[camera] describe (rate_hz, exposure_us, width: its noise, a fit window of at most 4.5
frames, and at 240 Hz prediction up to the next frame's arrival), and --input-delay-ms,
unless given, the camera's read-out (exposure_us / 2 + one frame: 4.42 ms at 240 Hz).
The trajectory's samples are then the camera's frames at their mid-exposure times.
Without --causal every output is the exact stimulus, as before.
TRAJ.csv has a header naming t,x,y; t in seconds (not decreasing); x,y normalised screen
(0..1, origin top-left) or, with --input-space world, the mallet centre in metres.
A t past one hour is refused (FILE:LINE, exit 2) unless --allow-long: the outputs grow
with it (1.4 GB of audio.wav per hour at 48 kHz), and a t in milliseconds looks like that.
Bad input prints FILE:LINE: problem and exits 2 with nothing written.
SIGINT or SIGTERM while writing removes the partial files (DIR/*.partial) and exits
130 or 143.)");
  cmd->add_option("--scene", options->scene, "Scene file")->capture_default_str()->check(CLI::ExistingFile);
  cmd->add_option("--input", options->input, "Trajectory CSV (t,x,y)")->required();
  cmd->add_option("--out", options->out_dir, "Output directory (created if needed)")->required();
  options->config = default_settings();  // the operator's, as the kiosk reads them
  add_settings_options(*cmd, options->config, options->config_dir);
  auto space = std::make_shared<std::string>("screen");
  cmd->add_option("--input-space", *space, "screen: x,y normalised 0..1; world: sphere centre in metres")
      ->check(CLI::IsMember({"screen", "world"}))
      ->capture_default_str();
  cmd->add_option("--sample-rate", *rate, "Audio sample rate in Hz (default: [audio].sample_rate_hz, 48000)")
      ->check(CLI::Range(1000, 384000));
  cmd->add_option("--trace-rate", options->trace_rate_hz, "Rows per second in cursor.csv")
      ->capture_default_str()
      ->check(positive_at_most(1e6));
  cmd->add_option("--tail", options->tail_s, "Seconds rendered after the last trajectory sample")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 3600.0));
  cmd->add_flag("--allow-long", options->allow_long,
                "Simulate a trajectory whose t goes past 3600 s (one hour) instead of refusing it");
  cmd->add_flag("--causal", options->causal, "Decide strikes as the live kiosk does (see below)");
  CLI::Option* delay = cmd->add_option("--input-delay-ms", options->input_delay_ms,
                                       "With --causal: from a sample's time to the kiosk knowing it (ms)")
                           ->check(CLI::Range(0.0, 1000.0))
                           ->capture_default_str();
  cmd->add_flag("--camera", options->camera,
                "With --causal: strikes as the kiosk's camera route decides them (see below)")
      ->needs("--causal");
  cmd->add_option("--display-hz", options->display_hz, "With --causal: the display's refresh rate (Hz)")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  add_choice(*cmd, "--present-mode", options->present_mode, kPresentPacingNames,
             "With --causal: fifo, mailbox or immediate");
  add_choice(*cmd, "--layout", options->layout, kSceneLayoutNames,
             "The scene as a landscape or a portrait screen lays it out (portrait: instruments stacked)");
  cmd->callback([options, rate, space, delay] {
    if (*rate != 0) options->sample_rate_hz = *rate;
    options->input_delay_given = delay->count() > 0;
    options->input_space = *space == "world" ? InputSpace::world : InputSpace::screen;
    SimulateResult r;
    try {
      r = run_simulate(*options);
    } catch (const SimulateInterrupted& e) {
      // Stopped on request, nothing left behind: the shell's convention, 128 + the signal.
      std::fprintf(stderr, "mallet: %s\n", e.what());
      finish_with(128 + e.signal());
      return;
    }
    const auto& c = r.counters;
    std::printf("%zu impact%s from %llu samples", r.impacts.size(), r.impacts.size() == 1 ? "" : "s",
                static_cast<unsigned long long>(c.accepted));
    if (c.ignored_non_finite || c.ignored_not_after_previous)
      std::printf(" (ignored: %llu non-finite, %llu not after the previous sample)",
                  static_cast<unsigned long long>(c.ignored_non_finite),
                  static_cast<unsigned long long>(c.ignored_not_after_previous));
    std::printf("\n");
    if (c.clamped_speed)
      std::printf("note: %llu strike(s) faster than max_impact_speed_m_per_s were clamped\n",
                  static_cast<unsigned long long>(c.clamped_speed));
    if (c.touches_below_min_speed)
      std::printf("note: %llu touch(es) slower than min_impact_speed_m_per_s made no impact\n",
                  static_cast<unsigned long long>(c.touches_below_min_speed));
    if (r.clipped_samples)
      std::printf("note: %llu samples were turned down by the output limiter "
                  "(lower [actuator].gain or [audio].volume)\n",
                  static_cast<unsigned long long>(r.clipped_samples));
    for (const auto& p : r.written) std::printf("wrote %s\n", p.string().c_str());
  });
}

}  // namespace mallet::app
