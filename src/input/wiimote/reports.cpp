#include "input/wiimote/reports.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cstdio>
#include <cstring>
#include <ostream>

#include "core/file_error.hpp"
#include "core/text_lines.hpp"

namespace mallet::input::wiimote {

namespace {

// Wire layouts, byte 0 = report id. Only single bytes, so no endianness or alignment
// question: multi-byte fields are assembled explicitly (the remote is big-endian).
#pragma pack(push, 1)
struct WireFlagOnly {  // 0x11, 0x13, 0x15, 0x1a
  std::uint8_t id;
  std::uint8_t flags;
};
struct WireReportingMode {  // 0x12
  std::uint8_t id;
  std::uint8_t flags;
  std::uint8_t mode;
};
struct WireWriteMemory {  // 0x16
  std::uint8_t id;
  std::uint8_t flags;  // space | rumble
  std::uint8_t address[3];
  std::uint8_t size;
  std::uint8_t data[16];
};
struct WireReadMemory {  // 0x17
  std::uint8_t id;
  std::uint8_t flags;
  std::uint8_t address[3];
  std::uint8_t size[2];
};
struct WireStatus {  // 0x20
  std::uint8_t id;
  std::uint8_t buttons[2];
  std::uint8_t flags;
  std::uint8_t reserved[2];
  std::uint8_t battery;
};
struct WireReadData {  // 0x21
  std::uint8_t id;
  std::uint8_t buttons[2];
  std::uint8_t size_error;  // high nibble: size - 1; low nibble: error
  std::uint8_t address[2];
  std::uint8_t data[16];
};
struct WireAck {  // 0x22
  std::uint8_t id;
  std::uint8_t buttons[2];
  std::uint8_t report;
  std::uint8_t error;
};
struct WireButtonsAccelIr12 {  // 0x33
  std::uint8_t id;
  std::uint8_t buttons[2];
  std::uint8_t accel[3];
  std::uint8_t ir[12];
};
struct WireButtonsIr10Ext9 {  // 0x36
  std::uint8_t id;
  std::uint8_t buttons[2];
  std::uint8_t ir[10];
  std::uint8_t ext[9];
};
struct WireButtonsAccelIr10Ext6 {  // 0x37
  std::uint8_t id;
  std::uint8_t buttons[2];
  std::uint8_t accel[3];
  std::uint8_t ir[10];
  std::uint8_t ext[6];
};
#pragma pack(pop)

static_assert(sizeof(WireFlagOnly) == 2);
static_assert(sizeof(WireReportingMode) == 3);
static_assert(sizeof(WireWriteMemory) == 22);
static_assert(sizeof(WireReadMemory) == 7);
static_assert(sizeof(WireStatus) == 7);
static_assert(sizeof(WireReadData) == 22);
static_assert(sizeof(WireAck) == 5);
static_assert(sizeof(WireButtonsAccelIr12) == 18);
static_assert(sizeof(WireButtonsIr10Ext9) == 22);
static_assert(sizeof(WireButtonsAccelIr10Ext6) == 22);
static_assert(sizeof(WireWriteMemory) <= kMaxOutputReportSize);

constexpr std::uint8_t u8(unsigned v) { return static_cast<std::uint8_t>(v & 0xffu); }

std::uint8_t flags_byte(Rumble rumble, Ack ack, std::uint8_t extra = 0) {
  return u8(extra | (rumble == Rumble::on ? kRumbleBit : 0u) | (ack == Ack::request ? kAckRequestBit : 0u));
}

template <class Wire>
OutputReport to_report(const Wire& wire) {
  OutputReport out;
  std::memcpy(out.bytes.data(), &wire, sizeof(Wire));
  out.size = sizeof(Wire);
  return out;
}

std::uint16_t be16(const std::uint8_t (&b)[2]) { return static_cast<std::uint16_t>((b[0] << 8) | b[1]); }

// Checks id and exact length, then copies the bytes into the wire struct.
template <class Wire>
std::optional<ReportError> load(std::span<const std::uint8_t> report, InputReportId id, Wire& wire) {
  static_assert(sizeof(Wire) <= kMaxInputReportSize);
  ReportError e;
  e.got_size = report.size();
  if (report.empty()) return e;
  e.id = report[0];
  if (input_report_size(report[0]) == 0) {
    e.kind = ReportError::Kind::unknown_id;
    return e;
  }
  if (report[0] != static_cast<std::uint8_t>(id)) {
    e.kind = ReportError::Kind::wrong_id;
    return e;
  }
  if (report.size() != sizeof(Wire)) {
    e.kind = ReportError::Kind::wrong_length;
    e.expected_size = sizeof(Wire);
    return e;
  }
  std::memcpy(&wire, report.data(), sizeof(Wire));
  return std::nullopt;
}

std::optional<IrDot> visible(int x, int y, int size) {
  if (y > kIrMaxY) return std::nullopt;
  return IrDot{x, y, size};
}

bool is_hex_digit(char c) {
  return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

unsigned hex_value(char c) {
  if (c >= '0' && c <= '9') return static_cast<unsigned>(c - '0');
  if (c >= 'a' && c <= 'f') return static_cast<unsigned>(c - 'a' + 10);
  return static_cast<unsigned>(c - 'A' + 10);
}

bool is_blank(char c) { return c == ' ' || c == '\t'; }

}  // namespace

std::size_t input_report_size(std::uint8_t id) {
  switch (id) {
    case 0x20: return sizeof(WireStatus);
    case 0x21: return sizeof(WireReadData);
    case 0x22: return sizeof(WireAck);
    case 0x30: return 3;
    case 0x31: return 6;
    case 0x32: return 11;
    case 0x33: return sizeof(WireButtonsAccelIr12);
    case 0x34:
    case 0x35:
    case 0x36:
    case 0x37:
    case 0x3d:
    case 0x3e:
    case 0x3f: return 22;
    default: return 0;
  }
}

// ---------------------------------------------------------------------------------------
// Builders

OutputReport set_leds(std::uint8_t led_mask, Rumble rumble, Ack ack) {
  return to_report(WireFlagOnly{static_cast<std::uint8_t>(OutputReportId::leds),
                                flags_byte(rumble, ack, u8((led_mask & 0x0fu) << 4))});
}

OutputReport set_reporting_mode(DataMode mode, bool continuous, Rumble rumble, Ack ack) {
  return to_report(WireReportingMode{static_cast<std::uint8_t>(OutputReportId::reporting_mode),
                                     flags_byte(rumble, ack, continuous ? kContinuousBit : 0),
                                     static_cast<std::uint8_t>(mode)});
}

OutputReport set_ir_pixel_clock(bool enable, Rumble rumble, Ack ack) {
  return to_report(WireFlagOnly{static_cast<std::uint8_t>(OutputReportId::ir_pixel_clock),
                                flags_byte(rumble, ack, enable ? kEnableBit : 0)});
}

OutputReport set_ir_logic(bool enable, Rumble rumble, Ack ack) {
  return to_report(WireFlagOnly{static_cast<std::uint8_t>(OutputReportId::ir_logic),
                                flags_byte(rumble, ack, enable ? kEnableBit : 0)});
}

OutputReport request_status(Rumble rumble) {
  return to_report(
      WireFlagOnly{static_cast<std::uint8_t>(OutputReportId::status_request), flags_byte(rumble, Ack::no)});
}

std::optional<OutputReport> write_memory(AddressSpace space, std::uint32_t address,
                                         std::span<const std::uint8_t> data, Rumble rumble) {
  if (data.empty() || data.size() > kMaxWriteBytes || address > 0xffffffu) return std::nullopt;
  WireWriteMemory w{};
  w.id = static_cast<std::uint8_t>(OutputReportId::write_memory);
  w.flags = flags_byte(rumble, Ack::no, static_cast<std::uint8_t>(space));
  w.address[0] = u8(address >> 16);
  w.address[1] = u8(address >> 8);
  w.address[2] = u8(address);
  w.size = u8(static_cast<unsigned>(data.size()));
  std::memcpy(w.data, data.data(), data.size());
  return to_report(w);
}

std::optional<OutputReport> read_memory(AddressSpace space, std::uint32_t address, std::uint16_t size,
                                        Rumble rumble) {
  if (size == 0 || address > 0xffffffu) return std::nullopt;
  WireReadMemory w{};
  w.id = static_cast<std::uint8_t>(OutputReportId::read_memory);
  w.flags = flags_byte(rumble, Ack::no, static_cast<std::uint8_t>(space));
  w.address[0] = u8(address >> 16);
  w.address[1] = u8(address >> 8);
  w.address[2] = u8(address);
  w.size[0] = u8(size >> 8u);
  w.size[1] = u8(size);
  return to_report(w);
}

// ---------------------------------------------------------------------------------------
// Parsers

std::string ReportError::message() const {
  const std::string id_text = fmt::format("0x{:02x}", id);
  switch (kind) {
    case Kind::empty: return "empty report (no bytes)";
    case Kind::unknown_id:
      return std::string("report id ") + id_text + " is not a Wii Remote input report";
    case Kind::wrong_id: return std::string("report id ") + id_text + " is not the report expected here";
    case Kind::wrong_length:
      return std::string("report ") + id_text + " must be " + std::to_string(expected_size) +
             " bytes (id included), got " + std::to_string(got_size);
  }
  return "bad report";
}

Parsed<StatusReport> parse_status(std::span<const std::uint8_t> report) {
  WireStatus w{};
  if (auto e = load(report, InputReportId::status, w)) return tl::unexpected(*e);
  StatusReport s;
  s.buttons = be16(w.buttons);
  s.battery_low = (w.flags & 0x01) != 0;
  s.extension = (w.flags & 0x02) != 0;
  s.speaker = (w.flags & 0x04) != 0;
  s.ir_enabled = (w.flags & 0x08) != 0;
  s.leds = u8(w.flags >> 4);
  s.battery = w.battery;
  return s;
}

Parsed<ReadDataReport> parse_read_data(std::span<const std::uint8_t> report) {
  WireReadData w{};
  if (auto e = load(report, InputReportId::read_data, w)) return tl::unexpected(*e);
  ReadDataReport r;
  r.buttons = be16(w.buttons);
  r.size = u8((w.size_error >> 4) + 1u);
  r.error = u8(w.size_error & 0x0fu);
  r.address_low = be16(w.address);
  std::memcpy(r.data.data(), w.data, sizeof w.data);
  return r;
}

Parsed<AckReport> parse_ack(std::span<const std::uint8_t> report) {
  WireAck w{};
  if (auto e = load(report, InputReportId::ack, w)) return tl::unexpected(*e);
  return AckReport{be16(w.buttons), w.report, w.error};
}

IrSlots decode_extended_ir(std::span<const std::uint8_t, 12> ir) {
  // Per dot: X low 8 bits, Y low 8 bits, then [Y9 Y8 X9 X8 S3 S2 S1 S0].
  IrSlots slots{};
  for (std::size_t i = 0; i < 4; ++i) {
    const std::uint8_t* b = ir.data() + 3 * i;
    const int x = b[0] | ((b[2] >> 4) & 0x03) << 8;
    const int y = b[1] | ((b[2] >> 6) & 0x03) << 8;
    slots[i] = visible(x, y, b[2] & 0x0f);
  }
  return slots;
}

IrSlots decode_basic_ir(std::span<const std::uint8_t, 10> ir) {
  // Per pair of dots: X1 low, Y1 low, [Y1_98 X1_98 Y2_98 X2_98], X2 low, Y2 low.
  IrSlots slots{};
  for (std::size_t p = 0; p < 2; ++p) {
    const std::uint8_t* b = ir.data() + 5 * p;
    const int x1 = b[0] | ((b[2] >> 4) & 0x03) << 8;
    const int y1 = b[1] | ((b[2] >> 6) & 0x03) << 8;
    const int x2 = b[3] | (b[2] & 0x03) << 8;
    const int y2 = b[4] | ((b[2] >> 2) & 0x03) << 8;
    slots[2 * p] = visible(x1, y1, -1);
    slots[2 * p + 1] = visible(x2, y2, -1);
  }
  return slots;
}

namespace {

//! A report that carries the camera's dots: read as its wire layout, the dots decoded in the
//! format its IR field's size says (12 bytes: extended, 10: basic).
template <typename Wire>
Parsed<IrReport> parse_ir_as(std::span<const std::uint8_t> report, InputReportId id) {
  Wire w{};
  if (auto err = load(report, id, w)) return tl::unexpected(*err);
  IrReport r;
  r.id = id;
  r.buttons = be16(w.buttons);
  if constexpr (sizeof w.ir == 12) {
    r.format = IrFormat::extended;
    r.slots = decode_extended_ir(std::span<const std::uint8_t, 12>(w.ir));
  } else {
    r.format = IrFormat::basic;
    r.slots = decode_basic_ir(std::span<const std::uint8_t, 10>(w.ir));
  }
  return r;
}

//! Any report parsed, as the variant of all of them.
template <typename Report>
Parsed<InputReport> as_input(Parsed<Report> parsed) {
  return parsed.map([](Report& r) { return InputReport{std::move(r)}; });
}

}  // namespace

Parsed<IrReport> parse_ir(std::span<const std::uint8_t> report) {
  ReportError e;
  e.got_size = report.size();
  if (report.empty()) return tl::unexpected(e);
  e.id = report[0];
  switch (report[0]) {
    case 0x33: return parse_ir_as<WireButtonsAccelIr12>(report, InputReportId::buttons_accel_ir12);
    case 0x36: return parse_ir_as<WireButtonsIr10Ext9>(report, InputReportId::buttons_ir10_ext9);
    case 0x37: return parse_ir_as<WireButtonsAccelIr10Ext6>(report, InputReportId::buttons_accel_ir10_ext6);
    default:
      e.kind = input_report_size(report[0]) == 0 ? ReportError::Kind::unknown_id : ReportError::Kind::wrong_id;
      return tl::unexpected(e);
  }
}

Parsed<InputReport> parse_input(std::span<const std::uint8_t> report) {
  ReportError e;
  e.got_size = report.size();
  if (report.empty()) return tl::unexpected(e);
  e.id = report[0];
  const std::size_t size = input_report_size(report[0]);
  if (size == 0) {
    e.kind = ReportError::Kind::unknown_id;
    return tl::unexpected(e);
  }
  switch (report[0]) {
    case 0x20: return as_input(parse_status(report));
    case 0x21: return as_input(parse_read_data(report));
    case 0x22: return as_input(parse_ack(report));
    case 0x33:
    case 0x36:
    case 0x37: return as_input(parse_ir(report));
    default:
      if (report.size() != size) {
        e.kind = ReportError::Kind::wrong_length;
        e.expected_size = size;
        return tl::unexpected(e);
      }
      return InputReport{OtherDataReport{static_cast<InputReportId>(report[0])}};
  }
}

// ---------------------------------------------------------------------------------------
// Hex

Result<std::vector<std::uint8_t>, HexError> parse_hex_bytes(std::string_view text) {
  std::vector<std::uint8_t> out;
  std::size_t i = 0;
  while (i < text.size()) {
    if (is_blank(text[i])) {
      ++i;
      continue;
    }
    const std::size_t start = i;
    while (i < text.size() && !is_blank(text[i])) {
      if (!is_hex_digit(text[i])) {
        const auto c = static_cast<unsigned char>(text[i]);
        const std::string shown =
            c >= 0x20 && c < 0x7f ? fmt::format("'{}'", text[i]) : fmt::format("byte 0x{:02x}", c);
        return tl::unexpected(HexError{shown + " is not a hex digit", i + 1});
      }
      ++i;
    }
    if ((i - start) % 2 != 0) {
      return tl::unexpected(HexError{"\"" + std::string(text.substr(start, i - start)) +
                                         "\" has an odd number of hex digits (write each byte as two digits)",
                                     start + 1});
    }
    for (std::size_t k = start; k < i; k += 2)
      out.push_back(u8(hex_value(text[k]) << 4 | hex_value(text[k + 1])));
  }
  return out;
}

std::string to_hex(std::span<const std::uint8_t> bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out;
  out.reserve(bytes.size() * 3);
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    if (i) out += ' ';
    out += kDigits[bytes[i] >> 4];
    out += kDigits[bytes[i] & 0x0f];
  }
  return out;
}

std::string format_ir_slots(const IrSlots& slots) {
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

// ---------------------------------------------------------------------------------------
// Replay files

Recording parse_replay(std::string_view text, const std::string& name) {
  Recording out;
  text::Lines lines(text);
  while (auto next = lines.next()) {
    const std::uint32_t line_no = lines.number();
    std::string_view line = *next;
    std::size_t lead = 0;
    while (lead < line.size() && is_blank(line[lead])) ++lead;
    const std::string_view body = line.substr(lead);
    if (body.empty()) continue;
    if (body.front() == '#') {
      if (body.starts_with(kReplayMagic)) {
        std::string_view rest = body.substr(kReplayMagic.size());
        while (!rest.empty() && is_blank(rest.front())) rest.remove_prefix(1);
        while (!rest.empty() && is_blank(rest.back())) rest.remove_suffix(1);
        if (rest != "1")
          throw FileError(name, line_no, 0,
                          "replay format version \"" + std::string(rest) + "\" is not supported (expected " +
                              std::to_string(kReplayVersion) + ")");
      }
      continue;
    }
    std::size_t t_end = 0;
    while (t_end < body.size() && !is_blank(body[t_end])) ++t_end;
    const std::string_view t_text = body.substr(0, t_end);
    const auto t_column = static_cast<std::uint32_t>(lead + 1);
    Nanos t_ns = 0;
    const auto [end, ec] = std::from_chars(t_text.data(), t_text.data() + t_text.size(), t_ns);
    if (ec == std::errc::result_out_of_range)
      throw FileError(name, line_no, t_column, "time \"" + std::string(t_text) + "\" is out of range");
    if (ec != std::errc() || end != t_text.data() + t_text.size() || t_ns < 0)
      throw FileError(name, line_no, t_column,
                      "time \"" + std::string(t_text) + "\" is not a whole number of nanoseconds >= 0");
    if (!out.reports.empty() && t_ns < out.reports.back().t_ns)
      throw FileError(name, line_no, t_column,
                      "time " + std::to_string(t_ns) + " is before the previous line's " +
                          std::to_string(out.reports.back().t_ns) + " (times must not decrease)");
    const std::string_view hex = body.substr(t_end);
    auto bytes = parse_hex_bytes(hex);
    if (!bytes)
      throw FileError(name, line_no, static_cast<std::uint32_t>(lead + t_end + bytes.error().column),
                      bytes.error().problem);
    if (bytes->empty()) throw FileError(name, line_no, 0, "missing the report (hex bytes) after the time");
    if (bytes->size() > kMaxRecordedReportSize)
      throw FileError(name, line_no, 0,
                      "report of " + std::to_string(bytes->size()) + " bytes is longer than " +
                          std::to_string(kMaxRecordedReportSize));
    out.reports.push_back({t_ns, std::move(*bytes)});
  }
  return out;
}

Recording read_replay(const std::filesystem::path& path) {
  return parse_replay(text::read_file(path), path.string());
}

std::string format_replay_line(Nanos t_ns, std::span<const std::uint8_t> report) {
  return std::to_string(t_ns) + ' ' + to_hex(report);
}

ReplayWriter::ReplayWriter(std::ostream& out) : out_(&out) {
  *out_ << kReplayMagic << ' ' << kReplayVersion << '\n'
        << "# t_ns (monotonic clock) then the raw input report in hex, byte 0 = report id\n";
}

void ReplayWriter::write(Nanos t_ns, std::span<const std::uint8_t> report) {
  *out_ << format_replay_line(t_ns, report) << '\n';
}

std::vector<std::uint8_t> extended_ir_report(int x, int y) {
  std::vector<std::uint8_t> b = {0x33, 0x00, 0x00, 0x80, 0x80, 0x80};
  b.push_back(static_cast<std::uint8_t>(x & 0xff));
  b.push_back(static_cast<std::uint8_t>(y & 0xff));
  b.push_back(static_cast<std::uint8_t>(((y >> 8) & 0x03) << 6 | ((x >> 8) & 0x03) << 4 | 4));
  for (int i = 0; i < 3; ++i) b.insert(b.end(), {0xff, 0xff, 0xff});
  return b;
}

}  // namespace mallet::input::wiimote
