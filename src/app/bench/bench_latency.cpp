// `mallet bench latency`: true contact → actuator, note and picture, measured on the real
// windowed kiosk (a child process) with a virtual X server and a JACK server of the
// bench's own. See bench_latency.hpp for what each time means and --help for the output.
// This file runs every configuration in turn and prints the table, the CSVs and the notes.
#include "app/bench/bench_latency.hpp"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "app/bench/bench_commands.hpp"
#include "app/bench/bench_kiosk_child.hpp"
#include "app/bench/bench_latency_rig.hpp"
#include "app/bench/bench_latency_run.hpp"
#include "core/config/scene_config.hpp"

namespace mallet::app::latency {

namespace {

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five;
  in >> one >> five;
  return in ? one + " / " + five : std::string("unknown");
}

std::string cell(const std::optional<double>& v) {
  if (!v) return "nan";
  return fmt::format("{:.3f}", *v);
}


}  // namespace

void run_bench_latency(const LatencyOptions& options) {
  // The servers, named by their Debian packages when they are missing.
  require_x_and_jack("bench latency");
  StopSignals signals;
  const int strokes = options.strokes > 0 ? options.strokes : options.quick ? 6 : 20;
  const std::vector<std::string> presets =
      options.quick ? std::vector<std::string>{"balanced"} : std::vector<std::string>{"balanced", "exact"};
  const std::vector<std::string> aligns = {"asap", "picture"};
  const std::vector<std::string> sources = {"mouse", "remote"};
  const std::size_t configs = presets.size() * aligns.size() * sources.size();
  // Start-up ≈ 15 s, a configuration ≈ 10 s + 0.6 s a stroke: the bound is well above that.
  Deadline deadline{monotonic_now() + (40 + static_cast<Nanos>(configs) * (60 + strokes)) * kNanosPerSecond};
  std::filesystem::create_directories(options.out);

  Rig rig;
  rig.scene_file = still_scene(rig.folders.temp.path());
  rig.scene = config::load_scene(rig.scene_file);
  for (const Material& m : rig.scene.materials)
    if (m.visual.amplitude != 0.0) throw std::runtime_error("bench latency: the still scene still has a bounce");
  rig.map.scene = &rig.scene;
  rig.bars = choose_bars(rig.scene, rig.map);

  rig.x = std::make_unique<VirtualDisplay>(kWidth, kHeight);
  deadline.check();
  rig.jack = std::make_unique<JackServer>("mallet-bench-" + std::to_string(getpid()), kRate, kPeriod);
  deadline.check();
  rig.recorder = std::make_unique<JackRecorder>(rig.jack->name(), 2);
  rig.hand = std::make_unique<FakePointer>(rig.x->name());
  rig.eye = std::make_unique<ScreenReader>(rig.x->name());
  std::vector<PixelBox> strips;
  for (const Bar& b : rig.bars) strips.push_back(b.strip);
  rig.watch = std::make_unique<PictureWatch>(rig.x->name(), strips, kPictureTolerancePx);

  std::printf("mallet bench latency: true contact → each cue, measured on `mallet run --windowed` "
              "(a child process)\n");
  std::printf(
      "  X: Xvfb %s, %dx%d; JACK: dummy driver, %d Hz, %d-frame cycles (%.2f ms), playback latency %.2f ms, "
      "JACK clock − monotonic %+.3f ms\n",
      rig.x->name().c_str(), kWidth, kHeight, rig.recorder->rate(), rig.recorder->period(),
      1e3 * rig.recorder->period() / rig.recorder->rate(), to_seconds(rig.recorder->playback_latency_ns()) * 1e3,
      to_seconds(rig.recorder->clock_offset_ns()) * 1e3);
  std::printf("  strokes: %d per configuration on %s and %s, 1.0–2.0 m/s, one every 600 ms\n", strokes,
              rig.bars[0].name.c_str(), rig.bars[1].name.c_str());
  std::fflush(stdout);

  std::vector<ConfigResult> results;
  for (const std::string& preset : presets)
    for (const std::string& align : aligns)
      for (const std::string& source : sources) {  // the mouse first: its warm-up finds where the head rests
        deadline.check();
        std::printf("  running: %s, quality %s, align %s ...\n", source.c_str(), preset.c_str(), align.c_str());
        std::fflush(stdout);
        results.push_back(run_config(rig, {preset, align, source, {}}, strokes, options.device, deadline));
        for (const std::string& line : results.back().kiosk_status) std::printf("    kiosk: %s\n", line.c_str());
        std::fflush(stdout);
      }
  const double poll_ms = rig.watch->mean_poll_ms();
  const std::uint64_t xruns = rig.recorder->xruns(), dropped = rig.recorder->dropped();

  // The table and the CSV. The table has two columns the CSV has not: n, the strikes the
  // cue was measured for, and the JACK xruns during the configuration's strokes.
  std::printf("\n| source | preset   | align   | cue              | median ms | p99 ms   | max ms   "
              "| strikes | false | missed |  n | xruns |\n");
  std::printf("|--------|----------|---------|------------------|-----------|----------|----------"
              "|---------|-------|--------|----|-------|\n");
  const std::filesystem::path csv_path = options.out / "latency.csv";
  std::ofstream csv(csv_path);
  csv << "source,preset,align,cue,median_ms,p99_ms,max_ms,strikes,false_strikes,missed_strikes\n";
  for (const ConfigResult& r : results)
    for (const CueSamples& c : r.matched.cues) {
      const Summary s = summarise(c.ms);
      std::printf("| %-6s | %-8s | %-7s | %-16s | %9s | %8s | %8s | %7d | %5d | %6d | %2zu | %5llu |\n",
                  r.config.source.c_str(), r.config.preset.c_str(), r.config.align.c_str(), c.cue.c_str(), cell(s.median).c_str(),
                  cell(s.p99).c_str(), cell(s.max).c_str(), r.matched.strikes, r.matched.false_strikes,
                  r.matched.missed_strikes, s.n, static_cast<unsigned long long>(r.xruns));
      csv << r.config.source << ',' << r.config.preset << ',' << r.config.align << ',' << c.cue << ',' << cell(s.median) << ','
          << cell(s.p99) << ',' << cell(s.max) << ',' << r.matched.strikes << ',' << r.matched.false_strikes << ','
          << r.matched.missed_strikes << '\n';
    }
  csv.close();
  if (!csv) throw std::runtime_error("cannot write " + csv_path.string());
  // Every strike, for a closer look (not part of the summary's contract).
  const std::filesystem::path strikes_path = options.out / "latency_strikes.csv";
  std::ofstream per(strikes_path);
  per << "source,preset,align,stroke,bar,speed_m_per_s,contact_s,strike_ms,actuator_ms,note_ms,picture_ms\n";
  for (const ConfigResult& r : results)
    for (std::size_t i = 0; i < r.matched.rows.size(); ++i) {
      const StrikeRow& row = r.matched.rows[i];
      const std::string t = fmt::format("{:.6f}", to_seconds(row.contact.t));
      per << r.config.source << ',' << r.config.preset << ',' << r.config.align << ',' << i << ','
          << rig.bars[static_cast<std::size_t>(row.contact.bar)].target << ',' << row.contact.speed << ',' << t << ','
          << cell(row.strike_ms) << ',' << cell(row.actuator_ms) << ',' << cell(row.note_ms) << ','
          << cell(row.picture_ms) << '\n';
    }
  per.close();
  if (!per) throw std::runtime_error("cannot write " + strikes_path.string());

  std::printf(
      "\nCue − true contact, ms. actuator-picture and note-actuator: signed differences per strike (positive: the\n"
      "first named cue comes later); max = the sample of largest magnitude, sign kept. Cues are counted for the\n"
      "strikes the kiosk logged within ±50 ms of a true contact.\n");
  std::printf(
      "  true contact: the injected pointer path (XTest motion every 1 ms, stamped on CLOCK_MONOTONIC when flushed)\n"
      "    crossing the contact plane (bar top + mallet radius), interpolated between the two events around it.\n");
  std::printf(
      "  actuator, note: the strike's first sample on its channel as the JACK recorder heard it, at its cycle's time\n"
      "    plus the playback latency (%.2f ms); over a bar still ringing, the first sample a linear predictor of\n"
      "    the ring does not explain.\n",
      to_seconds(rig.recorder->playback_latency_ns()) * 1e3);
  std::printf(
      "  picture: the first frame in the X server's framebuffer that shows the mallet at the bar (where the bounce\n"
      "    starts; the bench's scene has its visual amplitude set to 0): the head's lowest white pixel within %d px\n"
      "    of where it rests on the bar (rows %d, %d). Framebuffer polled every %.2f ms on average; detection\n"
      "    resolution ±1 px / v = ±%.2f ms at 1.0 m/s. Xvfb has no display: a panel's scan-out comes on top.\n",
      kPictureTolerancePx, results.empty() ? 0 : results[0].rest_row[0], results.empty() ? 0 : results[0].rest_row[1],
      poll_ms, results.empty() ? 0.0 : results[0].resolution_ms);
  std::error_code ec;
  std::printf(
      "  source remote = a recording played as a live Wii Remote ([input] source = \"replay\": the real device\n"
      "    start-up, reading thread, IR tracker and strike route; 100 Hz reports, contacts anywhere between two);\n"
      "    its true contact = the recorded path's crossing, placed on the kiosk's clock by the replay's start line.\n");
  std::printf(
      "  source mouse = the window system's pointer ([input] mouse = \"window\"). The evdev mouse is not measured:\n"
      "    injecting it needs /dev/uinput%s.\n",
      std::filesystem::exists("/dev/uinput", ec) ? " (present here, but the bench does not use it yet)"
                                                 : ", which this machine lacks");
  std::string disturbed;
  for (const ConfigResult& r : results)
    if (r.xruns > 0)
      disturbed += (disturbed.empty() ? "" : ", ") + r.config.source + "/" + r.config.preset + "/" + r.config.align;
  std::printf(
      "  JACK: %llu xruns in all (start-ups included), %llu cycles the recorder had no room for; the kiosk\n"
      "    reopened its stream %llu times (underruns: a larger buffer asked), its new ports connected each time.\n"
      "    This machine: %ld CPUs online, load average %s.\n",
      static_cast<unsigned long long>(xruns), static_cast<unsigned long long>(dropped),
      static_cast<unsigned long long>(rig.recorder->reopens_followed()), sysconf(_SC_NPROCESSORS_ONLN),
      load_average().c_str());
  if (!disturbed.empty())
    std::printf(
        "  ! Audio rows of these ran with xruns (the machine could not keep JACK's cycles): %s.\n"
        "    A late cycle costs the dummy driver that time; the kiosk's audio stream re-anchors its clock\n"
        "    when its callback finds itself behind (OutputCounters::resyncs), so the loss does not add up,\n"
        "    but a strike near a late cycle is heard late. Strikes whose onset lies on such a seam are left\n"
        "    out (n). Rerun on an idle machine for the kiosk's own figures.\n",
        disturbed.c_str());
  std::printf("wrote %s and %s\n", csv_path.c_str(), strikes_path.c_str());
}

}  // namespace mallet::app::latency

namespace mallet::app {

void add_bench_latency(CLI::App& bench) {
  auto o = std::make_shared<latency::LatencyOptions>();
  CLI::App* cmd = bench.add_subcommand(
      "latency", "Measured: true contact → actuator, note and picture on the real windowed kiosk (Xvfb + JACK)");
  cmd->footer(R"(Starts its own X server (Xvfb, Debian package xvfb) and JACK server (jackd2, dummy driver), runs
`mallet run --windowed` under them once per source (mouse, remote), quality preset (balanced, exact;
--quick: balanced) and [timing] align (asap, picture), strikes a metal and a wood bar with the X pointer (XTest; a straight
downswing at 1.0-2.0 m/s, 20 strokes per run, 6 with --quick) and measures, per strike, from the true
contact (the injected path crossing the bar's contact plane) to:
  actuator, note  the strike's first sample on each channel, recorded by a JACK client of the bench's
                  own. JACK's dummy driver is paced by a real-time timer, so its sample clock is wall
                  time; ALSA's file plugin (the other card-free path) is not paced: PortAudio writes into
                  it as fast as it can, so sample indices there carry no wall time.
  picture         the first frame in the X server's framebuffer showing the mallet at the bar (where the
                  bounce starts; the bench's scene copy has no visual vibration so nothing lifts it).
Output: a table on stdout and OUT/latency.csv (OUT defaults to the current directory), one row per
source x preset x align x cue (OUT/latency_strikes.csv has every stroke):
  source,preset,align,cue,median_ms,p99_ms,max_ms,strikes,false_strikes,missed_strikes
cue: actuator, note, picture (cue time - true contact), and the signed asynchronies actuator-picture
and note-actuator (per strike, first named minus second named; their max_ms is the value of largest
magnitude, sign kept). strikes: true contacts the kiosk logged a strike for within +-50 ms;
false_strikes: logged strikes with no true contact within +-50 ms; missed_strikes: true contacts with
none. A value that could not be measured is nan. source: "mouse" (the window system's pointer) or
"remote" (a recording of 100 Hz IR reports the bench writes, played by the kiosk as a live Wii Remote:
[input] source = "replay"); the evdev mouse cannot be injected without /dev/uinput.
Everything it starts is stopped on exit, on errors and on Ctrl+C. Exit status 1 when a server or the
kiosk cannot run here (the message names what is missing).)");
  cmd->add_option("--out", o->out, "Output directory for latency.csv (default: the current directory)")
      ->capture_default_str();
  cmd->add_flag("--quick", o->quick, "The balanced preset only, 6 strokes per run (a check that it works; ~1 min)");
  cmd->add_option("--strokes", o->strokes, "Strokes per configuration (default 20, 6 with --quick)")
      ->check(CLI::Range(2, 500));
  cmd->add_option("--device", o->device, "The kiosk's Vulkan device (substring of its name; default: its own choice)");
  cmd->callback([o] { latency::run_bench_latency(*o); });
}

}  // namespace mallet::app
