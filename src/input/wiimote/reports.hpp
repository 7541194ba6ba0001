#pragma once
// The Wii Remote's HID reports as pure bytes: builders for the output reports we send,
// parsers for the input reports it sends, and the text format of recorded reports.
// No hidapi here: byte 0 of every buffer is the report id, exactly as `hid_write` takes
// it and `hid_read` (hidraw) returns it. Written from the public protocol description
// (wiibrew "Wiimote/Protocol"), cross-checked against the Linux driver and Dolphin.
//
// Nothing in this file throws or has undefined behaviour on device input: every parser
// checks the id and the exact length first and returns a ReportError otherwise. Only the
// replay-file reader throws, FileError "FILE:LINE:COL: problem", like every file reader.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/ir_dot.hpp"
#include "core/result.hpp"
#include "core/time.hpp"

namespace mallet::input::wiimote {

// ---------------------------------------------------------------------------------------
// Report ids

//! Host → remote.
enum class OutputReportId : std::uint8_t {
  leds = 0x11,            //!< player LEDs (and rumble)
  reporting_mode = 0x12,  //!< which data report, continuous or on change
  ir_pixel_clock = 0x13,  //!< "IR camera enable" 1
  speaker_enable = 0x14,
  status_request = 0x15,
  write_memory = 0x16,
  read_memory = 0x17,
  speaker_data = 0x18,
  speaker_mute = 0x19,
  ir_logic = 0x1a,        //!< "IR camera enable" 2
};

//! Remote → host.
enum class InputReportId : std::uint8_t {
  status = 0x20,
  read_data = 0x21,
  ack = 0x22,
  buttons = 0x30,
  buttons_accel = 0x31,
  buttons_ext8 = 0x32,
  buttons_accel_ir12 = 0x33,  //!< extended IR (with dot size)
  buttons_ext19 = 0x34,
  buttons_accel_ext16 = 0x35,
  buttons_ir10_ext9 = 0x36,   //!< basic IR (no size)
  buttons_accel_ir10_ext6 = 0x37,  //!< basic IR (no size)
  ext21 = 0x3d,
  interleaved_a = 0x3e,  //!< full IR mode, first half (not decoded: we never ask for it)
  interleaved_b = 0x3f,  //!< full IR mode, second half (not decoded)
};

//! The data report a 0x12 request selects is named by its input report id.
using DataMode = InputReportId;

//! Bits of byte 1 of output reports. Rumble (0x01) is in *every* output report: the
//! motor follows the last value sent, so each builder takes it explicitly.
inline constexpr std::uint8_t kRumbleBit = 0x01;
inline constexpr std::uint8_t kAckRequestBit = 0x02;  //!< ask for a 0x22 acknowledgement
inline constexpr std::uint8_t kEnableBit = 0x04;      //!< 0x13/0x1a: on; 0x12: continuous
inline constexpr std::uint8_t kContinuousBit = 0x04;

enum class Rumble : bool { off = false, on = true };
enum class Ack : bool { no = false, request = true };

//! Where 0x16/0x17 read and write: the EEPROM or the peripherals' control registers
//! (the IR camera lives at 0xB00000 in register space).
enum class AddressSpace : std::uint8_t { eeprom = 0x00, registers = 0x04 };

//! Lengths including the id byte (the HID descriptor's payload + 1).
inline constexpr std::size_t kMaxOutputReportSize = 22;
inline constexpr std::size_t kMaxInputReportSize = 22;
inline constexpr std::size_t kMaxWriteBytes = 16;

//! Exact length (id byte included) of a known input report, or 0 for an unknown id.
std::size_t input_report_size(std::uint8_t id);

// ---------------------------------------------------------------------------------------
// Output reports (builders)

//! The bytes to hand to hid_write: byte 0 = report id. Fixed capacity, no allocation, so
//! it can be built on any thread and queued.
struct OutputReport {
  std::array<std::uint8_t, kMaxOutputReportSize> bytes{};
  std::size_t size = 0;

  const std::uint8_t* data() const { return bytes.data(); }
  std::span<const std::uint8_t> span() const { return {bytes.data(), size}; }
  std::vector<std::uint8_t> vector() const { return {span().begin(), span().end()}; }
  OutputReportId id() const { return static_cast<OutputReportId>(bytes[0]); }
  bool requests_ack() const { return size > 1 && (bytes[1] & kAckRequestBit) != 0; }
  friend bool operator==(const OutputReport& a, const OutputReport& b) {
    return std::ranges::equal(a.span(), b.span());
  }
};

//! 0x11: LEDs 1..4 = bits 0..3 of `led_mask` (sent as bits 4..7).      [11 LR]
OutputReport set_leds(std::uint8_t led_mask, Rumble rumble, Ack ack = Ack::no);
//! 0x12: data reporting mode; `continuous` = send at ≈100 Hz, not only on change. [12 CR MM]
OutputReport set_reporting_mode(DataMode mode, bool continuous, Rumble rumble, Ack ack = Ack::no);
//! 0x13: IR pixel clock on/off.                                          [13 ER]
OutputReport set_ir_pixel_clock(bool enable, Rumble rumble, Ack ack = Ack::no);
//! 0x1a: IR logic on/off.                                                [1A ER]
OutputReport set_ir_logic(bool enable, Rumble rumble, Ack ack = Ack::no);
//! 0x15: ask for a 0x20 status report.                                   [15 0R]
OutputReport request_status(Rumble rumble);
//! 0x16: write 1..16 bytes at a 24-bit address. [16 SR A2 A1 A0 NN D0..D15] (22 bytes,
//! data zero-padded). The remote always answers with a 0x22 ack. Nothing when `data` is
//! empty or longer than 16 bytes, or the address does not fit in 24 bits.
std::optional<OutputReport> write_memory(AddressSpace space, std::uint32_t address,
                                         std::span<const std::uint8_t> data, Rumble rumble);
//! 0x17: read `size` (≥ 1) bytes at a 24-bit address; answered by 0x21 reports of up to
//! 16 bytes each. [17 SR A2 A1 A0 N1 N0] (size big-endian). Nothing on a bad argument.
std::optional<OutputReport> read_memory(AddressSpace space, std::uint32_t address, std::uint16_t size,
                                        Rumble rumble);

// ---------------------------------------------------------------------------------------
// Input reports (parsers)

//! Why bytes are not the report asked for. `message()` is one line for a person.
struct ReportError {
  enum class Kind : std::uint8_t {
    empty,         //!< no bytes at all
    unknown_id,    //!< byte 0 is not a Wii Remote input report id
    wrong_id,      //!< a known id, but not the report this parser reads
    wrong_length,  //!< the id's exact length differs
  };
  Kind kind = Kind::empty;
  std::uint8_t id = 0;
  std::size_t expected_size = 0;  //!< wrong_length: the id's length
  std::size_t got_size = 0;
  std::string message() const;
  friend bool operator==(const ReportError&, const ReportError&) = default;
};

//! A parsed report or why not.
template <class T>
using Parsed = Result<T, ReportError>;

//! 0x20 status. Arrives after a 0x15 request *and* unsolicited (extension plugged or
//! unplugged, battery low); either way the remote then stops sending data reports until
//! the reporting mode is set again.
struct StatusReport {
  std::uint16_t buttons = 0;  //!< core buttons, bytes 1..2 big-endian
  bool battery_low = false;   //!< flag 0x01
  bool extension = false;     //!< flag 0x02
  bool speaker = false;       //!< flag 0x04
  bool ir_enabled = false;    //!< flag 0x08
  std::uint8_t leds = 0;      //!< LEDs 1..4 as bits 0..3 (flags 0x10..0x80)
  std::uint8_t battery = 0;   //!< raw level 0..255 (≈0xC8 on fresh cells)
  friend bool operator==(const StatusReport&, const StatusReport&) = default;
};

//! 0x21: one chunk (1..16 bytes) answering a 0x17 read.
struct ReadDataReport {
  std::uint16_t buttons = 0;
  std::uint8_t error = 0;           //!< 0 ok; 7 write-only register; 8 no such memory
  std::uint16_t address_low = 0;    //!< low 16 bits of the chunk's first address
  std::uint8_t size = 0;            //!< 1..16 valid bytes in `data`
  std::array<std::uint8_t, 16> data{};
  friend bool operator==(const ReadDataReport&, const ReadDataReport&) = default;
};

//! 0x22: the remote's answer to an output report (always for 0x16; for the others when
//! they carried the ack-request bit).
struct AckReport {
  std::uint16_t buttons = 0;
  std::uint8_t report = 0;  //!< the output report id it acknowledges
  std::uint8_t error = 0;   //!< 0 success; anything else failed (3 is the usual error)
  bool success() const { return error == 0; }
  friend bool operator==(const AckReport&, const AckReport&) = default;
};

//! Which IR layout a data report carries.
enum class IrFormat : std::uint8_t {
  basic,     //!< 10 bytes: two pairs of dots in 5 bytes each, no size (0x36, 0x37)
  extended,  //!< 12 bytes: four dots in 3 bytes each, with size (0x33)
};

//! The IR part of a data report.
struct IrReport {
  InputReportId id = InputReportId::buttons_accel_ir12;
  IrFormat format = IrFormat::extended;
  std::uint16_t buttons = 0;
  //! Raw camera coordinates, exactly as sent (no mirroring). A slot is empty when the
  //! camera sent y > 767 (it sends all ones, y = 1023). A dot at exactly (0,0) is kept:
  //! it is data, but some remotes report it spuriously — see is_spurious_origin().
  IrSlots slots{};
  friend bool operator==(const IrReport&, const IrReport&) = default;
};

//! Some remotes report a phantom dot at exactly (0,0) (a corner no real LED sits on in
//! practice). The decoder keeps it; the tracker should ignore dots for which this is true.
constexpr bool is_spurious_origin(const IrDot& dot) { return dot.x == 0 && dot.y == 0; }

//! The largest y of a visible dot; the camera sends y = 1023 for an empty slot.
inline constexpr int kIrMaxY = 767;
inline constexpr int kIrMaxX = 1023;

//! A data report without IR (0x30..0x32, 0x34, 0x35, 0x3d) or a full-mode half (0x3e,
//! 0x3f): recognised, right length, nothing decoded beyond the id.
struct OtherDataReport {
  InputReportId id = InputReportId::buttons;
  friend bool operator==(const OtherDataReport&, const OtherDataReport&) = default;
};

using InputReport = std::variant<StatusReport, ReadDataReport, AckReport, IrReport, OtherDataReport>;

Parsed<StatusReport> parse_status(std::span<const std::uint8_t> report);
Parsed<ReadDataReport> parse_read_data(std::span<const std::uint8_t> report);
Parsed<AckReport> parse_ack(std::span<const std::uint8_t> report);
//! 0x33 (extended), 0x36 and 0x37 (basic). Other ids → wrong_id (or unknown_id).
Parsed<IrReport> parse_ir(std::span<const std::uint8_t> report);
//! Any input report, by its id.
Parsed<InputReport> parse_input(std::span<const std::uint8_t> report);

//! The IR bytes alone (no report header), for callers that already located them.
IrSlots decode_extended_ir(std::span<const std::uint8_t, 12> ir);
IrSlots decode_basic_ir(std::span<const std::uint8_t, 10> ir);

// ---------------------------------------------------------------------------------------
// Hex text (the `decode` command's input and the replay file's payload)

//! Why hex text is not bytes: the problem, at the 1-based `column` of the offending character.
struct HexError {
  std::string problem;
  std::size_t column = 0;
};

//! Bytes written as hex: pairs of hex digits, upper or lower case, with optional spaces or
//! tabs between bytes ("33 00 00 ff", "330000ff").
Result<std::vector<std::uint8_t>, HexError> parse_hex_bytes(std::string_view text);
//! Lower-case hex, one space between bytes: "33 00 00 ff".
std::string to_hex(std::span<const std::uint8_t> bytes);

//! The four camera slots as `mallet wiimote decode` prints them: separated by single
//! spaces, each `x,y,size` (`x,y,?` without a size, basic mode) or `-` when empty.
std::string format_ir_slots(const IrSlots& slots);

// ---------------------------------------------------------------------------------------
// Recorded reports (`--record FILE`, the replay source)
//
// Text, one report per line:   T_NS HEX
//   T_NS  reception time on the monotonic clock, integer nanoseconds, >= 0, not decreasing
//   HEX   the raw input report as hid_read returned it, byte 0 = report id, 1..64 bytes,
//         hex pairs with optional spaces between bytes
// Blank lines and lines starting with '#' are ignored. The writer starts with the line
// "# mallet-wiimote-replay 1"; a file that starts with "# mallet-wiimote-replay" must
// name version 1. The reader stores the bytes as recorded (a device may send junk: the
// replay source runs them through parse_input like live reports).

inline constexpr std::string_view kReplayMagic = "# mallet-wiimote-replay";
inline constexpr int kReplayVersion = 1;
inline constexpr std::size_t kMaxRecordedReportSize = 64;

struct RecordedReport {
  Nanos t_ns = 0;
  std::vector<std::uint8_t> bytes;
  friend bool operator==(const RecordedReport&, const RecordedReport&) = default;
};

struct Recording {
  std::vector<RecordedReport> reports;
};

//! Throws FileError "NAME:LINE:COL: problem" on the first malformed line.
Recording parse_replay(std::string_view text, const std::string& name);
Recording read_replay(const std::filesystem::path& path);

//! A 0x33 report (buttons + accelerometer + extended IR) with one dot of size 4 at camera
//! pixel (x, y) and the other three slots empty: what benchmarks synthesise as a remote.
std::vector<std::uint8_t> extended_ir_report(int x, int y);

//! "T_NS HEX" without a newline.
std::string format_replay_line(Nanos t_ns, std::span<const std::uint8_t> report);

//! Writes a recording line by line (the header on construction). The caller owns the
//! stream and flushes it; write() formats into the stream and never throws by itself.
class ReplayWriter {
 public:
  explicit ReplayWriter(std::ostream& out);
  void write(Nanos t_ns, std::span<const std::uint8_t> report);

 private:
  std::ostream* out_;
};

}  // namespace mallet::input::wiimote
