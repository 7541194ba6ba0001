// `mallet wiimote ...`: the operator's and the tests' window into the Wii Remote protocol.
#include <atomic>
#include <cstdio>
#include <iostream>
#include <iterator>
#include <memory>
#include <string>
#include <variant>

#include "app/cli/commands.hpp"
#include "core/data_paths.hpp"
#include "app/common/settings_source.hpp"
#include "app/kiosk/wiimote_monitor.hpp"
#include "core/config/app_config_loader.hpp"
#include "core/file_error.hpp"
#include "core/text_lines.hpp"
#include "input/clock.hpp"
#include "input/wiimote/hid_transport.hpp"
#include "input/wiimote/reports.hpp"
#include "input/wiimote/wiimote_device.hpp"

namespace mallet::app {

namespace wm = mallet::input::wiimote;

namespace {

//! The whole `decode` output, or FileError on the first malformed line (nothing printed).
std::string decode_hex_text(std::string_view text, const std::string& name) {
  std::string out;
  text::Lines lines(text);
  while (auto next = lines.next()) {
    const std::uint32_t line_no = lines.number();
    std::string_view line = *next;
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    const auto bytes = wm::parse_hex_bytes(line);
    if (!bytes) throw FileError(name, line_no, static_cast<std::uint32_t>(bytes.error().column), bytes.error().problem);
    if (bytes->empty()) continue;  // blank or comment only
    const auto report = wm::parse_input(*bytes);
    if (!report) throw FileError(name, line_no, 0, report.error().message());
    if (const auto* ir = std::get_if<wm::IrReport>(&*report)) {
      out += wm::format_ir_slots(ir->slots);
      out += '\n';
    }
  }
  return out;
}

void add_decode(CLI::App& wiimote) {
  auto file = std::make_shared<std::string>();
  CLI::App* cmd = wiimote.add_subcommand(
      "decode", "Decode raw input reports (hex, one per line) into the IR camera's four dots");
  cmd->footer(R"(Input (--hex FILE, or - for stdin): one raw input report per line, in hex, byte 0 =
the report id exactly as hidraw delivers it, e.g.  33 00 00 80 80 80 00 00 00 ...
Bytes are two hex digits each, optionally separated by spaces; blank lines and
everything after '#' are ignored.
Output (stdout): one line per report that carries IR (0x33 extended; 0x36, 0x37
basic), its four camera slots in order separated by single spaces:
  x,y,size   extended mode: raw camera coordinates x 0..1023, y 0..767 (no
             mirroring: orientation belongs to calibration), size 0..15
  x,y,?      basic mode, which sends no size
  -          empty slot (the camera sends y = 1023; any y > 767 is empty)
A dot at exactly 0,0 is printed as sent; some remotes report it spuriously.
Other valid input reports (status, acks, data without IR) print nothing.
A malformed line (bad hex, unknown report id, wrong length for its id) prints
nothing to stdout, reports the FIRST such line as FILE:LINE[:COL]: problem on
stderr and exits 2.)");
  cmd->add_option("--hex", *file, "File of hex reports, one per line (- = stdin)")->required();
  cmd->callback([file] {
    std::string text;
    if (*file == "-") {
      text.assign(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
    } else {
      text = text::read_file(*file);
    }
    const std::string out = decode_hex_text(text, *file == "-" ? std::string("<stdin>") : *file);
    std::fwrite(out.data(), 1, out.size(), stdout);
  });
}

void add_list(CLI::App& wiimote) {
  CLI::App* cmd = wiimote.add_subcommand("list", "List the Wii Remotes connected now (hidraw path, product, serial)");
  cmd->footer(R"(Lists every HID device of vendor 057e (Nintendo) with product 0306 (RVL-CNT-01) or
0330 (RVL-CNT-01-TR): its /dev/hidraw path, product, serial (on Bluetooth: the
remote's address) and name. A remote must be paired and connected to be listed.
When none is found it says so, with the pairing and udev-rule hints, and still exits 0:
"none found" is an answer, not a failure.)");
  cmd->callback([] {
    const std::string out = format_device_list(wm::HidTransport::enumerate());
    std::fwrite(out.data(), 1, out.size(), stdout);
  });
}

struct MonitorCli {
  MonitorOptions options;
  std::optional<std::filesystem::path> config = default_settings();
  std::optional<std::filesystem::path> config_dir;
  std::optional<std::filesystem::path> replay;
  std::string device;
};

void run_monitor(const MonitorCli& cli) {
  if (!(cli.options.seconds >= 0 && cli.options.seconds <= 1e7))
    throw CLI::ValidationError("--seconds", "must be >= 0 (0 = until Ctrl+C)");
  const AppConfig config = command_settings(cli.config, cli.config_dir, "wiimote monitor");
  if (cli.replay) {
    finish_with(run_replay_monitor(*cli.replay, config.tracking, cli.options, stdout));
    return;
  }
  wm::WiimoteDeviceConfig device_config = wm::device_config(config);
  if (!cli.device.empty()) device_config.device = cli.device;
  device_config.keep_raw_reports = cli.options.record.has_value();
  wm::HidDeviceFinder finder;
  input::SteadyClock clock;
  wm::WiimoteDevice device(finder, clock, device_config);

  finish_with(run_until_interrupted([&](const std::atomic<bool>& interrupted) {
    return run_live_monitor(device, clock, cli.options, interrupted, stdout);
  }));
}

void add_monitor(CLI::App& wiimote) {
  auto cli = std::make_shared<MonitorCli>();
  CLI::App* cmd = wiimote.add_subcommand(
      "monitor", "Watch a live remote: connection, IR report rate, battery, the tracked LED and the four dots");
  cmd->footer(R"(Finds a remote (the first one, or [wiimote].device / --device), runs the IR camera's
start-up and prints one line about every 0.1 s, times since the start:
     1.200 s  running    100.0 Hz  battery 0xc8  tracking  led 512,384  dots 512,384,3 - - -
  link       searching (no remote: why, and when it retries), starting (IR start-up
             step), running
  Hz         IR reports per second over the last second (a remote sends ~100)
  battery    raw level of the last status report (0xc8 ~ fresh cells; LOW when the
             remote flags it); asked once per connection, ? until it answers
  tracking   the stick's LED is tracked (or lost), led = its raw camera position
  dots       the camera's four slots as `wiimote decode` prints them
Tracking changes are printed as they happen ("tracking lost", "tracking regained at
x,y"). A remote that goes silent for [wiimote].silence_timeout_ms (3 s) is dropped and
looked for again, forever, every 0.5 s doubling to 5 s.
Runs until --seconds have passed or Ctrl+C, then prints a summary. Exit 0 if a remote
was connected, 1 if none was (the reason on stderr: none found, no permission (with
the udev rule to install), IR start-up failed).
--record FILE saves every raw report with its reception time (monotonic ns) in the
replay format ("# mallet-wiimote-replay 1", then one `T_NS HEX` line per report);
--replay FILE plays such a file back through the same parser and tracker instead of
a live remote, lines at the recorded times, as fast as it can (a malformed line
exits 2).)");
  cmd->add_option("--seconds", cli->options.seconds, "Stop after this many seconds (0 = until Ctrl+C)");
  cmd->add_option("--record", cli->options.record, "Save every raw report (replay format) to FILE")->type_name("FILE");
  cmd->add_option("--replay", cli->replay, "Play a recording instead of a live remote")
      ->type_name("FILE")
      ->excludes("--record");
  cmd->add_option("--device", cli->device, "A part of the remote's hidraw path or serial (default: [wiimote].device)")
      ->type_name("TEXT");
  add_settings_options(*cmd, cli->config, cli->config_dir);  // [wiimote], [tracking]
  cmd->callback([cli] { run_monitor(*cli); });
}

}  // namespace

void register_wiimote(CLI::App& app) {
  CLI::App* wiimote = app.add_subcommand("wiimote", "Wii Remote IR camera: list remotes, monitor one, decode reports");
  wiimote->require_subcommand(1);
  add_list(*wiimote);
  add_monitor(*wiimote);
  add_decode(*wiimote);
}

}  // namespace mallet::app
