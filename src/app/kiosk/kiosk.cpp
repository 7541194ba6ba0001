#include "app/kiosk/kiosk.hpp"

#include "app/kiosk/visitor_words.hpp"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <memory>
#include <span>

#include <fmt/format.h>

#include "core/scene_layout.hpp"
#include "core/strike_line.hpp"
#include "core/data_paths.hpp"
#include "render/render_setup.hpp"
#include "app/strike/headless_loop.hpp"
#include "app/kiosk/kiosk_setup.hpp"
#include "render/overlay_text.hpp"
#include "app/kiosk/metrics_file.hpp"
#include "app/kiosk/window_kiosk.hpp"
#include "audio/wav_file.hpp"
#include "core/bar_lights.hpp"
#include "core/config/app_config_loader.hpp"
#include "core/config/scene_config.hpp"
#include "core/file_error.hpp"
#include "core/journal.hpp"
#include "core/kiosk_states.hpp"
#include "core/sample_clock.hpp"
#include "core/visitor_language.hpp"
#include "render/font_atlas.hpp"
#include "render/overlay.hpp"
#include "render/window_target.hpp"

namespace mallet::app {
namespace fs = std::filesystem;
namespace {

fs::path new_out_dir() {
  const std::time_t now = std::time(nullptr);
  char name[64];
  std::strftime(name, sizeof name, "mallet-run-%Y%m%d-%H%M%S", std::localtime(&now));
  return fs::current_path() / name;
}

int run_headless(const KioskOptions& o, const KioskSetup& setup, const std::string& why) {
  const AppConfig& config = setup.config;
  const render::HeadlessOptions ho =
      render::kiosk_headless_options(config.render, render::parse_size(o.size, "--size"), o.device);
  // Laid out for the image's shape as the kiosk lays it out for its screen's.
  const Scene scene = laid_out(
      setup.scene, layout_for(setup.scene, static_cast<double>(ho.size.width) / static_cast<double>(ho.size.height)));
  const fs::path out = o.out_dir.empty() ? new_out_dir() : o.out_dir;
  fs::create_directories(out);
  std::ofstream log(out / "log.txt");
  auto say = [&](const std::string& line) { log << line << '\n'; };
  say("mallet run (headless: " + why + ")");
  say(setup.settings_line);
  for (const std::string& p : setup.problems) say("warning: " + p);
  say("scene: " + scene.file + (scene.layout == SceneLayout::landscape ? "" : std::string(", laid out ") + to_string(scene.layout)));
  say("language: " + visitor_language() + " (the invitation: \"" +
      std::string(hint_text(KioskHint::invitation, scene.kind)) + "\")");

  // Nobody is there: the attract loop plays from the start, on a simulated 60 Hz clock.
  HeadlessLoop loop(scene, config, 0);
  const int rate = loop.sample_rate_hz();
  audio::WavWriter wav(out / "audio.wav", loop.channels(), rate);
  loop.on_audio = [&](std::span<const float> block) { wav.write(block); };
  // [metrics]: counted from what the log says (a strike line each, the frames below), on the
  // simulated clock; the headless run is not a start of the kiosk (no restart count).
  KioskMetrics metrics;
  metrics.version = mallet_version();
  seed_strike_labels(scene, metrics.strikes);
  auto warn = [&](const std::string& line) {
    say("warning: " + line);
    std::fprintf(stderr, "mallet run: warning: %s\n", line.c_str());
  };
  MetricsFile metrics_file(nullptr, warn, [&](const std::string& line) { say(line); });
  metrics_file.configure(config.metrics);
  loop.on_strike = [&](const Strike& s, bool) {
    say(strike_line(scene, s.impact));
    count_strike(scene, s.impact, metrics.strikes);
  };

  render::HeadlessRenderer renderer(scene, ho);
  say("render: " + renderer.context().device_name() + ", " + o.size);
  const std::unique_ptr<render::FontAtlas> font = render::overlay_font(ho.size);
  render::Overlay overlay(*font);

  const Nanos frame = kNanosPerSecond / 60;
  const Nanos end = static_cast<Nanos>(std::llround(o.seconds * 1e9));
  std::uint64_t frames = 0;
  for (Nanos t = 0; t <= end; t += frame) {
    loop.advance(t);
    overlay.clear();
    const float width = static_cast<float>(ho.size.width), height = static_cast<float>(ho.size.height);
    VisitorWords words;
    words.note_names = config.note_names;
    words.banner = hint_text(KioskHint::invitation, scene.kind);
    draw_visitor_words(overlay, scene, words, width, height);
    render::FrameState state;
    const StrikeLoop::View view = loop.strike_loop().view();
    state.mallet_centre = view.displayed(t);
    state.bar_lights = bar_lights(scene, view.shown, view.vibration, t);
    state.overlay = &overlay;
    renderer.draw(state);
    ++frames;
    metrics.count_frame(frame);
    metrics.uptime_ns = t;
    if (metrics_file.due(t)) metrics_file.write(metrics, t);
  }
  const std::uint64_t strikes = loop.counters().ghost_strikes + loop.counters().visitor_strikes;
  const std::int64_t audio_pos = static_cast<std::int64_t>(loop.counters().audio_frames);
  wav.close();
  render::write_png(renderer.read_back(), out / "screenshot.png");
  const std::uint64_t vk_messages = renderer.context().validation_messages();
  const std::string summary = fmt::format("ran {:.3f} s: {} frames, {} strikes, {} audio frames at {} Hz", o.seconds,
                                          frames, strikes, static_cast<long long>(audio_pos), rate);
  say(summary);
  if (vk_messages) say("error: " + std::to_string(vk_messages) + " Vulkan validation message(s)");
  metrics.uptime_ns = end;  // the run's simulated span, as its "ran" line says
  if (metrics_file.enabled() && metrics_file.write(metrics, end)) say("metrics: " + metrics_file.path().string());
  log.close();
  std::printf("mallet run: headless (%s)\n%s\n", why.c_str(), summary.c_str());
  for (const char* f : {"screenshot.png", "audio.wav", "log.txt"}) std::printf("wrote %s\n", (out / f).c_str());
  return vk_messages ? 1 : 0;
}

}  // namespace

int run_kiosk(const KioskOptions& options) {
  const bool window = !options.headless && render::WindowSystem::display_available();
  // A kiosk on a display never goes dark over its settings: refused, it starts on its last
  // good settings or the shipped defaults and says so (start_setup). Headless (a
  // researcher's run) refuses bad input as every other command does: exit 2, one line.
  Result<KioskSetup, std::string> started = window ? start_setup(options, state_dir() / kLastGoodSettings)
                                                   : Result<KioskSetup, std::string>(load_kiosk_setup(options));
  if (!started) {  // nothing to fall back on: the operator's own error, one line and exit 2, as before
    load_kiosk_setup(options);
    throw std::runtime_error(started.error());
  }
  KioskSetup setup = std::move(*started);
  KioskOptions o = options;
  // A reload re-reads the scene it runs; on a fallback, what the operator's settings name.
  if (setup.refused.empty()) o.scene = setup.scene.file;
  // The kiosk's stderr goes to the journal: its priorities; a headless run's to a person.
  const std::string info = window ? "<6>" : "mallet run: ", warning = window ? "<4>" : "mallet run: warning: ";
  std::fprintf(stderr, "%s%s\n", info.c_str(), setup.settings_line.c_str());
  for (const std::string& p : setup.problems) {
    if (p == setup.refused) journal::error("{}", p);
    else std::fprintf(stderr, "%s%s\n", warning.c_str(), p.c_str());
  }
  if (o.headless) return run_headless(o, setup, "--headless");
  if (!window) return run_headless(o, setup, "no display: DISPLAY and WAYLAND_DISPLAY are unset");
  return run_window_kiosk(o, std::move(setup));
}

}  // namespace mallet::app
