// `mallet doctor [--json]`: one line per check of what a kiosk needs.
#include <cstdio>
#include <memory>

#include "app/cli/commands.hpp"
#include "core/data_paths.hpp"
#include "app/kiosk/doctor.hpp"
#include "app/common/settings_source.hpp"

namespace mallet::app {

void register_doctor(CLI::App& app) {
  auto o = std::make_shared<DoctorOptions>();
  auto json = std::make_shared<bool>(false);
  auto print_renderer = std::make_shared<bool>(false);
  o->config = default_settings();
  CLI::App* cmd = app.add_subcommand("doctor", "Check everything a kiosk needs, one line per check, with the fix");
  cmd->footer(R"(Checks, in this order, each printed as `ok`, `warn` or `fail`, what was found and how to fix it:
  vulkan       the device and driver; a 1080p (or the display's size) frame is drawn and timed:
               a software renderer on a large display warns, slower than 60 Hz fails
  compositor   the renderer of the kiosk's compositor (cage): pixman where /dev/dri has no GPU
               render node (wlroots' GLES2 would fall back to kms_swrast and crash), else the
               GPU's (gles2); a WLR_RENDERER set for mallet-session.service wins and is named
  audio        the output the kiosk opens ([audio] device): name, sample rate, output latency,
               the channel routing against the device's channels
  wiimote      paired and connected, its IR camera's start-up answered, the battery
               (no remote: fail with [input] source = "wiimote", warn with "auto")
  camera       the V4L2 camera ([input] source = "camera"): its format, the rate it achieves,
               the LED seen
  settings     mallet.toml and its drop-ins, the start scene and [scenes] choices; refused, it
               fails with the file and line, and says what the kiosk runs on meanwhile (its
               last good settings, else the shipped defaults)
  models       every glTF model the scenes draw
  soundfont    when [audio] acoustic = "midi"
  languages    the visitor catalogues found
  language     the language shown, and what its texts need (fonts, shaping)
  actuator     the actuator's measured equalisation (mallet calibrate actuator), its age
  latency      the sound card's measured output latency (mallet calibrate latency), its age
  display      the display's measured latency (a photodiode), its age
  hidraw       the udev rule, the mallet user's groups, hidraw nodes that cannot be opened
  calibration  present, its age, its largest error, made with the remote connected now
  disk         the state folder (calibration, last good settings, counters, visitor results):
               its free space, and whether it can be written (a full or read-only one fails;
               the kiosk plays on but keeps nothing new)
  service      mallet.service enabled, running, restarts in the last 24 h (the journal)
  watchdog     the last time the systemd watchdog stopped the kiosk, and why
The operator page shows the same checks (Ctrl+Alt+O, then D).
--only NAME[,NAME...] runs and prints only the checks named (e.g. --only wiimote,hidraw while
pairing a remote): a device no named check needs is not opened, so no frame is drawn without
vulkan. An unknown name is refused (exit 2), naming the checks.
Exit status: 0 when no check fails (of those run), 1 otherwise.
--print-renderer prints only the compositor's renderer, `pixman` or `gles2` (or what
WLR_RENDERER names), and exits 0: mallet-session exports it as WLR_RENDERER.)");
  add_settings_options(*cmd, o->config, o->config_dir);
  cmd->add_option("--device", o->device, "Vulkan device (substring of its name; default [render] device)");
  cmd->add_option("--only", o->only, "Only these checks, by name, comma-separated (e.g. wiimote,hidraw); default: all")
      ->delimiter(',')
      ->check(CLI::IsMember(doctor_check_names()));
  cmd->add_flag("--json", *json, "The same checks as JSON: {\"checks\": [{name, status, found, fix}...], ok, warn, fail}");
  cmd->add_flag("--print-renderer", *print_renderer,
                "Print only the renderer the kiosk's compositor should use (pixman or gles2; $WLR_RENDERER if set) "
                "and exit 0, checking nothing else");
  cmd->callback([o, json, print_renderer] {
    if (*print_renderer) {  // for the session's start script: one word, nothing opened
      std::printf("%s\n", kiosk_compositor_renderer(false).renderer.c_str());
      return;
    }
    const std::vector<DoctorCheck> checks = run_doctor(*o);
    if (*json) {
      std::fputs(doctor_json(checks).c_str(), stdout);
    } else {
      for (const DoctorCheck& c : checks) std::printf("%s\n", format_check(c).c_str());
    }
    finish_with(doctor_exit_status(checks));
  });
}

}  // namespace mallet::app
