#include <memory>
#include <string>

#include "app/cli/commands.hpp"
#include "core/data_paths.hpp"
#include "app/kiosk/kiosk.hpp"
#include "app/common/settings_source.hpp"
#include "app/study/study_window.hpp"
#include "app/study/visitor_study.hpp"

namespace mallet::app {

namespace {

//! The kiosk's visitor micro-study, from the study product: its protocol loader, and a
//! session planned for one visitor and run in the kiosk's window.
VisitorSessions visitor_sessions() {
  VisitorSessions v;
  v.load = load_visitor_protocol;
  v.run = [](render::ProductWindow& window, const AppConfig& config, const Scene& scene,
             const study::StudyProtocol& protocol, const std::string& id, const std::string& date,
             std::function<std::vector<PointerSample>()> pointer, std::function<bool()> each_frame) {
    const StudyPlan plan = plan_visitor(config, scene, protocol, visitor_results_dir(config.study), id, date);
    return run_visitor_window(window, plan, std::move(pointer), std::move(each_frame));
  };
  return v;
}

}  // namespace

void register_run(CLI::App& app) {
  auto o = std::make_shared<KioskOptions>();
  o->config = default_settings();  // the operator's mallet.toml (/etc/mallet when installed)
  o->visitor_sessions = visitor_sessions();  // the study's, for [study] visitor_protocol
  CLI::App* cmd = app.add_subcommand("run", "Run the kiosk (fullscreen; headless without a display)");
  cmd->footer(R"(With a display: fullscreen and borderless (--windowed: a window), the mouse is the mallet,
sound and the actuator signal play on the configured audio device, and the attract mode's
ghost player plays whenever nobody has moved for --idle-after seconds. Visitors cannot close
it: Ctrl+Alt+O opens the operator page (Up/Down volume, Left/Right actuator gain, R
recalibrate, S next scene of [scenes] choices, M the wall's next material, L next language,
T latency test, D doctor, Page Down/Up its next/previous screen, Q Q quit, Esc close). Texts are in [kiosk] language (en, de, fr, ja). SIGHUP re-reads the
settings and the scene (a bad file is refused, the old ones stay). Settings refused at start
do not keep the kiosk dark: it runs on its last good settings (kept in the state folder as
last-good-settings.toml at each start or reload that loaded), else on the shipped defaults,
and says so (an error line naming the file and line, the operator page, `mallet doctor`).
A state folder that cannot be written is said once; the kiosk plays on. Each strike and a
heartbeat a minute are logged on stderr (journald priorities);
under systemd: READY=1 after the second frame (the first drawn over the cached background),
WATCHDOG=1 while input, audio and render run.
Without a display (DISPLAY and WAYLAND_DISPLAY unset) or with --headless: the same loop runs
offscreen on a simulated 60 Hz clock for --seconds, the attract loop playing into a WAV file,
and writes DIR/screenshot.png (the last frame), DIR/audio.wav (channels as [audio.routing])
and DIR/log.txt (one line per strike), then exits 0; settings that are refused end it with
exit status 2 and the one line, as for every other command.)");
  cmd->add_option("--scene", o->scene,
                  "Scene file (default: [scenes] start of the settings, a file in the scenes/ folder next to "
                  "them: percussion.toml)")
      ->check(CLI::ExistingFile);
  add_settings_options(*cmd, o->config, o->config_dir);
  cmd->add_flag("--headless", o->headless, "Run offscreen even if there is a display");
  cmd->add_flag("--windowed", o->windowed, "A window instead of fullscreen (its close button quits)");
  cmd->add_option("--seconds", o->seconds, "Headless: seconds of the loop to run")
      ->capture_default_str()
      ->check(positive_at_most(86400.0));
  cmd->add_option("--out", o->out_dir, "Headless: output directory (default: a new mallet-run-DATE folder)");
  cmd->add_option("--size", o->size, "Headless image size, or the window's size with --windowed")
      ->capture_default_str()
      ->check(pixel_size());
  cmd->add_option("--idle-after", o->idle_after_s,
                  "Seconds without input before the attract mode plays (default [attract].idle_after_s, 45)")
      ->check(positive_at_most(86400.0));
  cmd->add_option("--device", o->device, "Vulkan device (substring of its name; default [render].device)");
  cmd->add_flag("--no-frame-cap", o->no_frame_cap,
                "With a display: draw frames as fast as they come, ignoring [render] max_fps (to measure what the "
                "frame budget saves; never on a kiosk)");
  cmd->add_option("--quit-after", o->quit_after_s, "With a display: quit after this many seconds (0 = never)")
      ->capture_default_str();
  cmd->callback([o] { finish_with(run_kiosk(*o)); });
}

}  // namespace mallet::app
