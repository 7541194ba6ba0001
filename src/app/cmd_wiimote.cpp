// `mallet wiimote ...`: the operator's and the tests' window into the Wii Remote protocol.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <memory>
#include <string>
#include <variant>

#include "app/commands.hpp"
#include "core/file_error.hpp"
#include "core/text_lines.hpp"
#include "input/wiimote/reports.hpp"

namespace mallet::app {

namespace wm = mallet::input::wiimote;

namespace {

std::string format_slots(const IrSlots& slots) {
  std::string out;
  for (std::size_t i = 0; i < slots.size(); ++i) {
    if (i) out += ' ';
    if (!slots[i]) {
      out += '-';
      continue;
    }
    const IrDot& d = *slots[i];
    out += std::to_string(d.x);
    out += ',';
    out += std::to_string(d.y);
    out += ',';
    out += d.size < 0 ? std::string("?") : std::to_string(d.size);
  }
  return out;
}

//! The whole `decode` output, or FileError on the first malformed line (nothing printed).
std::string decode_hex_text(std::string_view text, const std::string& name) {
  std::string out;
  text::Lines lines(text);
  while (auto next = lines.next()) {
    const std::uint32_t line_no = lines.number();
    std::string_view line = *next;
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    std::string problem;
    std::size_t column = 0;
    const auto bytes = wm::parse_hex_bytes(line, problem, column);
    if (!bytes) throw FileError(name, line_no, static_cast<std::uint32_t>(column), problem);
    if (bytes->empty()) continue;  // blank or comment only
    const auto report = wm::parse_input(*bytes);
    if (!report) throw FileError(name, line_no, 0, report.error().message());
    if (const auto* ir = std::get_if<wm::IrReport>(&*report)) {
      out += format_slots(ir->slots);
      out += '\n';
    }
  }
  return out;
}

void add_decode(CLI::App& wiimote) {
  auto file = std::make_shared<std::string>();
  CLI::App* cmd = wiimote.add_subcommand(
      "decode", "Decode raw input reports (hex, one per line) into the IR camera's four dots");
  cmd->footer(
      "Input (--hex FILE, or - for stdin): one raw input report per line, in hex, byte 0 =\n"
      "the report id exactly as hidraw delivers it, e.g.  33 00 00 80 80 80 00 00 00 ...\n"
      "Bytes are two hex digits each, optionally separated by spaces; blank lines and\n"
      "everything after '#' are ignored.\n"
      "Output (stdout): one line per report that carries IR (0x33 extended; 0x36, 0x37\n"
      "basic), its four camera slots in order separated by single spaces:\n"
      "  x,y,size   extended mode: raw camera coordinates x 0..1023, y 0..767 (no\n"
      "             mirroring: orientation belongs to calibration), size 0..15\n"
      "  x,y,?      basic mode, which sends no size\n"
      "  -          empty slot (the camera sends y = 1023; any y > 767 is empty)\n"
      "A dot at exactly 0,0 is printed as sent; some remotes report it spuriously.\n"
      "Other valid input reports (status, acks, data without IR) print nothing.\n"
      "A malformed line (bad hex, unknown report id, wrong length for its id) prints\n"
      "nothing to stdout, reports the FIRST such line as FILE:LINE[:COL]: problem on\n"
      "stderr and exits 2.");
  cmd->add_option("--hex", *file, "File of hex reports, one per line (- = stdin)")->required();
  cmd->callback([file] {
    std::string text;
    if (*file == "-") {
      text.assign(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
    } else {
      std::ifstream in(*file, std::ios::binary);
      if (!in) throw FileError(*file, 0, 0, "cannot open (does it exist?)");
      std::ostringstream buffer;
      buffer << in.rdbuf();
      text = buffer.str();
    }
    const std::string out = decode_hex_text(text, *file == "-" ? std::string("<stdin>") : *file);
    std::fwrite(out.data(), 1, out.size(), stdout);
  });
}

}  // namespace

void register_wiimote(CLI::App& app) {
  CLI::App* wiimote = app.add_subcommand("wiimote", "Wii Remote IR camera: decode reports (list, monitor to come)");
  wiimote->require_subcommand(1);
  add_decode(*wiimote);
  // The hidapi transport (src/input/wiimote/hid_transport.*) adds its subcommands here,
  // each from its own static helper like add_decode():
  //   add_list(*wiimote);     `mallet wiimote list`     devices seen, or "none found"
  //   add_monitor(*wiimote);  `mallet wiimote monitor`  live dots, rate, battery;
  //                           with `--record FILE` (wm::ReplayWriter) saving raw reports
}

}  // namespace mallet::app
