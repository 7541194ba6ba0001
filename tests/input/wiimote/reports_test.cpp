// The Wii Remote's reports against byte-exact vectors written by hand from the public
// protocol description (wiibrew "Wiimote/Protocol"): report layouts, the 3-byte extended
// and 5-byte-per-pair basic IR formats, the output reports' flag bits.
#include "input/wiimote/reports.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "run_cli.hpp"
#include "core/file_error.hpp"

namespace mallet::input::wiimote {
namespace {

using Bytes = std::vector<std::uint8_t>;

IrDot dot(int x, int y, int size = -1) { return IrDot{x, y, size}; }

// ---------------------------------------------------------------------------------------
// IR data reports

// 0x33: buttons 12 34, accelerometer 3 bytes, then 4 dots × 3 bytes [X, Y, Y98 X98 S].
const Bytes kExtended = {
    0x33, 0x12, 0x34, 0x80, 0x80, 0x80,
    0x00, 0x00, 0x00,  // (0,0) size 0: the spurious origin some remotes send
    0xff, 0xff, 0xbf,  // (1023,767) size 15: y hi 2 → 0x80, x hi 3 → 0x30, size 0x0f
    0x00, 0x80, 0x65,  // (512,384) size 5: y hi 1 → 0x40, x hi 2 → 0x20
    0xff, 0xff, 0xff,  // empty
};

TEST(WiimoteReports, ExtendedIrDecodesAllFourSlots) {
  const auto r = parse_ir(kExtended);
  ASSERT_TRUE(r.has_value()) << r.error().message();
  EXPECT_EQ(r->id, InputReportId::buttons_accel_ir12);
  EXPECT_EQ(r->format, IrFormat::extended);
  EXPECT_EQ(r->buttons, 0x1234);
  EXPECT_EQ(r->slots[0], dot(0, 0, 0));
  EXPECT_EQ(r->slots[1], dot(1023, 767, 15));
  EXPECT_EQ(r->slots[2], dot(512, 384, 5));
  EXPECT_FALSE(r->slots[3].has_value());
}

TEST(WiimoteReports, SpuriousOriginIsKeptAndMarked) {
  const auto r = parse_ir(kExtended);
  ASSERT_TRUE(r.has_value());
  ASSERT_TRUE(r->slots[0].has_value());
  EXPECT_TRUE(is_spurious_origin(*r->slots[0]));
  EXPECT_FALSE(is_spurious_origin(*r->slots[1]));
  EXPECT_FALSE(is_spurious_origin(dot(0, 1, 3)));
  EXPECT_FALSE(is_spurious_origin(dot(1, 0, 3)));
}

TEST(WiimoteReports, ExtendedIrAllEmpty) {
  Bytes b = {0x33, 0, 0, 0, 0, 0};
  b.resize(18, 0xff);
  const auto r = parse_ir(b);
  ASSERT_TRUE(r.has_value());
  for (const auto& s : r->slots) EXPECT_FALSE(s.has_value());
}

TEST(WiimoteReports, YAbove767IsEmptyEvenWhenNotAllOnes) {
  // (5,768) size 1: y hi 3 → 0xc0. 768 is outside the 1024×768 picture.
  Bytes b = {0x33, 0, 0, 0, 0, 0, 0x05, 0x00, 0xc1, 0x05, 0xff, 0x81};  // then (5,767) size 1
  b.resize(18, 0xff);
  const auto r = parse_ir(b);
  ASSERT_TRUE(r.has_value());
  EXPECT_FALSE(r->slots[0].has_value());
  EXPECT_EQ(r->slots[1], dot(5, 767, 1));
}

// Basic IR, per pair: X1, Y1, [Y1_98 X1_98 Y2_98 X2_98], X2, Y2.
const Bytes kBasicIr = {
    0xff, 0xff, 0xb9, 0x2c, 0xbc,  // (1023,767) and (300,700): 0x80|0x30|0x08|0x01
    0xff, 0xff, 0xf0, 0x01, 0x02,  // empty (1023,1023) and (1,2)
};

TEST(WiimoteReports, BasicIrIn0x36) {
  Bytes b = {0x36, 0x00, 0x08};
  b.insert(b.end(), kBasicIr.begin(), kBasicIr.end());
  b.resize(22, 0x00);  // 9 extension bytes
  const auto r = parse_ir(b);
  ASSERT_TRUE(r.has_value()) << r.error().message();
  EXPECT_EQ(r->id, InputReportId::buttons_ir10_ext9);
  EXPECT_EQ(r->format, IrFormat::basic);
  EXPECT_EQ(r->buttons, 0x0008);
  EXPECT_EQ(r->slots[0], dot(1023, 767));
  EXPECT_EQ(r->slots[1], dot(300, 700));
  EXPECT_FALSE(r->slots[2].has_value());
  EXPECT_EQ(r->slots[3], dot(1, 2));
  EXPECT_EQ(r->slots[3]->size, -1);  // basic mode has no size
}

TEST(WiimoteReports, BasicIrIn0x37AfterTheAccelerometer) {
  Bytes b = {0x37, 0x00, 0x00, 0x11, 0x22, 0x33};
  b.insert(b.end(), kBasicIr.begin(), kBasicIr.end());
  b.resize(22, 0xee);  // 6 extension bytes
  const auto r = parse_ir(b);
  ASSERT_TRUE(r.has_value()) << r.error().message();
  EXPECT_EQ(r->id, InputReportId::buttons_accel_ir10_ext6);
  EXPECT_EQ(r->slots[0], dot(1023, 767));
  EXPECT_EQ(r->slots[1], dot(300, 700));
  EXPECT_FALSE(r->slots[2].has_value());
  EXPECT_EQ(r->slots[3], dot(1, 2));
}

TEST(WiimoteReports, BasicIrOriginAndAllEmpty) {
  Bytes zero(10, 0x00), ones(10, 0xff);
  const IrSlots z = decode_basic_ir(std::span<const std::uint8_t, 10>(zero));
  for (const auto& s : z) EXPECT_EQ(s, dot(0, 0));
  const IrSlots e = decode_basic_ir(std::span<const std::uint8_t, 10>(ones));
  for (const auto& s : e) EXPECT_FALSE(s.has_value());
}

TEST(WiimoteReports, WrongLengthsAreErrorsNotCrashes) {
  for (const Bytes& good : {kExtended}) {
    for (std::size_t n = 0; n < good.size() + 4; ++n) {
      Bytes b(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(std::min(n, good.size())));
      b.resize(n, 0xff);
      const auto r = parse_ir(b);
      EXPECT_EQ(r.has_value(), n == good.size()) << n;
    }
  }
  const auto short33 = parse_ir(Bytes(17, 0x33));
  ASSERT_FALSE(short33.has_value());
  EXPECT_EQ(short33.error().kind, ReportError::Kind::wrong_length);
  EXPECT_EQ(short33.error().expected_size, 18u);
  EXPECT_EQ(short33.error().got_size, 17u);
  EXPECT_EQ(short33.error().message(), "report 0x33 must be 18 bytes (id included), got 17");

  Bytes long36(23, 0x00);
  long36[0] = 0x36;
  EXPECT_EQ(parse_ir(long36).error().kind, ReportError::Kind::wrong_length);
  EXPECT_EQ(parse_input(long36).error().kind, ReportError::Kind::wrong_length);
}

TEST(WiimoteReports, WrongAndUnknownIds) {
  EXPECT_EQ(parse_ir(Bytes{}).error().kind, ReportError::Kind::empty);
  EXPECT_EQ(parse_input(Bytes{}).error().kind, ReportError::Kind::empty);
  EXPECT_EQ(parse_ir(Bytes{0x99, 0, 0}).error().kind, ReportError::Kind::unknown_id);
  EXPECT_EQ(parse_input(Bytes{0x99}).error().message(), "report id 0x99 is not a Wii Remote input report");
  EXPECT_EQ(parse_ir(Bytes{0x30, 0, 0}).error().kind, ReportError::Kind::wrong_id);
  EXPECT_EQ(parse_status(kExtended).error().kind, ReportError::Kind::wrong_id);
  EXPECT_EQ(parse_ack(kExtended).error().kind, ReportError::Kind::wrong_id);
  // Output report ids are not input reports.
  EXPECT_EQ(parse_input(Bytes{0x12, 0x04, 0x33}).error().kind, ReportError::Kind::unknown_id);
}

// ---------------------------------------------------------------------------------------
// Status, read data, acknowledge

TEST(WiimoteReports, Status) {
  // flags 0x1b: battery low, extension, IR on, LED 1.
  const auto r = parse_status(Bytes{0x20, 0x00, 0x08, 0x1b, 0x00, 0x00, 0xc8});
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->buttons, 0x0008);
  EXPECT_TRUE(r->battery_low);
  EXPECT_TRUE(r->extension);
  EXPECT_FALSE(r->speaker);
  EXPECT_TRUE(r->ir_enabled);
  EXPECT_EQ(r->leds, 0x1);
  EXPECT_EQ(r->battery, 200);
  const auto s = parse_status(Bytes{0x20, 0x00, 0x00, 0xf4, 0x00, 0x00, 0x00});
  ASSERT_TRUE(s.has_value());
  EXPECT_TRUE(s->speaker);
  EXPECT_FALSE(s->battery_low);
  EXPECT_EQ(s->leds, 0xf);
  EXPECT_EQ(parse_status(Bytes{0x20, 0, 0, 0, 0, 0}).error().kind, ReportError::Kind::wrong_length);
}

TEST(WiimoteReports, ReadData) {
  Bytes b = {0x21, 0x00, 0x00, 0xf0, 0x00, 0x20};
  for (std::uint8_t i = 0; i < 16; ++i) b.push_back(i);
  const auto r = parse_read_data(b);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->size, 16);
  EXPECT_EQ(r->error, 0);
  EXPECT_EQ(r->address_low, 0x0020);
  EXPECT_EQ(r->data[15], 15);
  b[3] = 0x18;  // 2 bytes, error 8 (no such memory)
  const auto e = parse_read_data(b);
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->size, 2);
  EXPECT_EQ(e->error, 8);
}

TEST(WiimoteReports, Acknowledge) {
  const auto ok = parse_ack(Bytes{0x22, 0x00, 0x00, 0x16, 0x00});
  ASSERT_TRUE(ok.has_value());
  EXPECT_EQ(ok->report, 0x16);
  EXPECT_TRUE(ok->success());
  const auto bad = parse_ack(Bytes{0x22, 0x00, 0x00, 0x13, 0x03});
  ASSERT_TRUE(bad.has_value());
  EXPECT_EQ(bad->report, 0x13);
  EXPECT_EQ(bad->error, 3);
  EXPECT_FALSE(bad->success());
  EXPECT_EQ(parse_ack(Bytes{0x22, 0x00, 0x00, 0x16}).error().kind, ReportError::Kind::wrong_length);
}

TEST(WiimoteReports, ParseInputDispatchesById) {
  EXPECT_TRUE(std::holds_alternative<IrReport>(*parse_input(kExtended)));
  EXPECT_TRUE(std::holds_alternative<AckReport>(*parse_input(Bytes{0x22, 0, 0, 0x12, 0})));
  EXPECT_TRUE(std::holds_alternative<StatusReport>(*parse_input(Bytes{0x20, 0, 0, 0, 0, 0, 0})));
  const auto buttons = parse_input(Bytes{0x30, 0x00, 0x00});
  ASSERT_TRUE(buttons.has_value());
  EXPECT_EQ(std::get<OtherDataReport>(*buttons).id, InputReportId::buttons);
  EXPECT_EQ(parse_input(Bytes{0x31, 0, 0}).error().kind, ReportError::Kind::wrong_length);
  for (unsigned id = 0; id < 256; ++id) {  // every id, every length up to 24: no crash
    for (std::size_t n = 1; n <= 24; ++n) {
      Bytes b(n, 0xff);
      b[0] = static_cast<std::uint8_t>(id);
      const auto r = parse_input(b);
      EXPECT_EQ(r.has_value(), input_report_size(b[0]) == n) << id << " " << n;
    }
  }
}

// ---------------------------------------------------------------------------------------
// Output reports

Bytes v(const OutputReport& r) { return r.vector(); }

TEST(WiimoteReports, LedsAndRumbleBit) {
  EXPECT_EQ(v(set_leds(0b0001, Rumble::off)), (Bytes{0x11, 0x10}));
  EXPECT_EQ(v(set_leds(0b1111, Rumble::on)), (Bytes{0x11, 0xf1}));
  EXPECT_EQ(v(set_leds(0b1001, Rumble::off, Ack::request)), (Bytes{0x11, 0x92}));
  EXPECT_EQ(v(set_leds(0xff, Rumble::off)), (Bytes{0x11, 0xf0}));  // only 4 LEDs
  EXPECT_EQ(set_leds(0, Rumble::off).id(), OutputReportId::leds);
}

TEST(WiimoteReports, ReportingMode) {
  EXPECT_EQ(v(set_reporting_mode(DataMode::buttons_accel_ir12, true, Rumble::off)), (Bytes{0x12, 0x04, 0x33}));
  EXPECT_EQ(v(set_reporting_mode(DataMode::buttons_ir10_ext9, false, Rumble::on)), (Bytes{0x12, 0x01, 0x36}));
  EXPECT_EQ(v(set_reporting_mode(DataMode::buttons_accel_ir12, true, Rumble::on, Ack::request)),
            (Bytes{0x12, 0x07, 0x33}));
  EXPECT_TRUE(set_reporting_mode(DataMode::buttons, false, Rumble::off, Ack::request).requests_ack());
}

TEST(WiimoteReports, IrEnables) {
  EXPECT_EQ(v(set_ir_pixel_clock(true, Rumble::off, Ack::request)), (Bytes{0x13, 0x06}));
  EXPECT_EQ(v(set_ir_pixel_clock(true, Rumble::on)), (Bytes{0x13, 0x05}));
  EXPECT_EQ(v(set_ir_pixel_clock(false, Rumble::off)), (Bytes{0x13, 0x00}));
  EXPECT_EQ(v(set_ir_logic(true, Rumble::off, Ack::request)), (Bytes{0x1a, 0x06}));
  EXPECT_EQ(v(set_ir_logic(false, Rumble::on)), (Bytes{0x1a, 0x01}));
}

TEST(WiimoteReports, StatusRequest) {
  EXPECT_EQ(v(request_status(Rumble::off)), (Bytes{0x15, 0x00}));
  EXPECT_EQ(v(request_status(Rumble::on)), (Bytes{0x15, 0x01}));
}

TEST(WiimoteReports, WriteMemory) {
  const std::uint8_t eight = 0x08;
  const auto w = write_memory(AddressSpace::registers, 0xb00030, std::span(&eight, 1), Rumble::off);
  ASSERT_TRUE(w);
  Bytes expected = {0x16, 0x04, 0xb0, 0x00, 0x30, 0x01, 0x08};
  expected.resize(22, 0x00);
  EXPECT_EQ(v(*w), expected);

  Bytes sixteen(16);
  for (std::size_t i = 0; i < 16; ++i) sixteen[i] = static_cast<std::uint8_t>(0xa0 + i);
  const auto e = write_memory(AddressSpace::eeprom, 0x000016, sixteen, Rumble::on);
  ASSERT_TRUE(e);
  Bytes expected_e = {0x16, 0x01, 0x00, 0x00, 0x16, 0x10};
  expected_e.insert(expected_e.end(), sixteen.begin(), sixteen.end());
  EXPECT_EQ(v(*e), expected_e);

  EXPECT_FALSE(write_memory(AddressSpace::registers, 0xb00000, Bytes(17), Rumble::off));
  EXPECT_FALSE(write_memory(AddressSpace::registers, 0xb00000, Bytes{}, Rumble::off));
  EXPECT_FALSE(write_memory(AddressSpace::registers, 0x1000000, Bytes(1), Rumble::off));
}

TEST(WiimoteReports, ReadMemory) {
  const auto r = read_memory(AddressSpace::registers, 0xa400fa, 6, Rumble::on);
  ASSERT_TRUE(r);
  EXPECT_EQ(v(*r), (Bytes{0x17, 0x05, 0xa4, 0x00, 0xfa, 0x00, 0x06}));
  const auto e = read_memory(AddressSpace::eeprom, 0x000000, 0x1234, Rumble::off);
  ASSERT_TRUE(e);
  EXPECT_EQ(v(*e), (Bytes{0x17, 0x00, 0x00, 0x00, 0x00, 0x12, 0x34}));
  EXPECT_FALSE(read_memory(AddressSpace::eeprom, 0, 0, Rumble::off));
  EXPECT_FALSE(read_memory(AddressSpace::eeprom, 0x1000000, 1, Rumble::off));
}

// ---------------------------------------------------------------------------------------
// Hex text

TEST(WiimoteHex, ParsesPairsWithOptionalSpaces) {
  EXPECT_EQ(*parse_hex_bytes("33 00 fF"), (Bytes{0x33, 0x00, 0xff}));
  EXPECT_EQ(*parse_hex_bytes("\t3300FF  "), (Bytes{0x33, 0x00, 0xff}));
  EXPECT_EQ(*parse_hex_bytes(""), Bytes{});
  const auto odd = parse_hex_bytes("33 3 00");
  ASSERT_FALSE(odd);
  EXPECT_EQ(odd.error().column, 4u);
  EXPECT_NE(odd.error().problem.find("odd number"), std::string::npos);
  const auto not_hex = parse_hex_bytes("33 0g");
  ASSERT_FALSE(not_hex);
  EXPECT_EQ(not_hex.error().column, 5u);
  EXPECT_EQ(not_hex.error().problem, "'g' is not a hex digit");
  EXPECT_EQ(to_hex(Bytes{0x33, 0x0a, 0xff}), "33 0a ff");
}

// ---------------------------------------------------------------------------------------
// Replay files

TEST(WiimoteReplay, ReadsAGoodFile) {
  const std::string text =
      "# mallet-wiimote-replay 1\n"
      "100 33 12 34 80 80 80 000000 ffffbf 008065 ffffff\n"
      "\n"
      "  # a comment\r\n"
      "100\t22 00 00 16 00\r\n"
      "250 20 00 08 1b 00 00 c8";
  const Recording rec = parse_replay(text, "r.txt");
  ASSERT_EQ(rec.reports.size(), 3u);
  EXPECT_EQ(rec.reports[0], (RecordedReport{100, kExtended}));
  EXPECT_EQ(rec.reports[1], (RecordedReport{100, Bytes{0x22, 0x00, 0x00, 0x16, 0x00}}));
  EXPECT_EQ(rec.reports[2].t_ns, 250);
  EXPECT_TRUE(parse_status(rec.reports[2].bytes).has_value());
  // Bytes are stored as recorded, even when they are no valid report.
  EXPECT_EQ(parse_replay("5 99", "x").reports[0].bytes, Bytes{0x99});
}

TEST(WiimoteReplay, WriterRoundTrips) {
  std::ostringstream out;
  ReplayWriter writer(out);
  writer.write(1'000'000'007, kExtended);
  writer.write(1'010'000'000, Bytes{0x20, 0, 0, 0, 0, 0, 0xc8});
  EXPECT_TRUE(out.str().starts_with("# mallet-wiimote-replay 1\n"));
  const Recording rec = parse_replay(out.str(), "mem");
  ASSERT_EQ(rec.reports.size(), 2u);
  EXPECT_EQ(rec.reports[0], (RecordedReport{1'000'000'007, kExtended}));
  EXPECT_EQ(rec.reports[1].t_ns, 1'010'000'000);
  EXPECT_EQ(format_replay_line(7, Bytes{0x22, 0x00}), "7 22 00");
}

void expect_replay_error(const std::string& text, std::uint32_t line, const std::string& fragment) {
  try {
    parse_replay(text, "rec.txt");
    ADD_FAILURE() << "no error for: " << text;
  } catch (const FileError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.file(), "rec.txt");
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    EXPECT_TRUE(std::string(e.what()).starts_with("rec.txt:" + std::to_string(line) + ":")) << e.what();
  }
}

TEST(WiimoteReplay, MalformedLinesNameTheirNumber) {
  expect_replay_error("1 20\n2 20\nabc 33 00\n", 3, "not a whole number of nanoseconds");
  expect_replay_error("-5 20\n", 1, "not a whole number");
  expect_replay_error("99999999999999999999 20\n", 1, "out of range");
  expect_replay_error("10 20\n# c\n9 20\n", 3, "times must not decrease");
  expect_replay_error("10\n", 1, "missing the report");
  expect_replay_error("10 2\n", 1, "odd number of hex digits");
  expect_replay_error("\n\n10 20 zz\n", 3, "'z' is not a hex digit");
  expect_replay_error("# mallet-wiimote-replay 2\n", 1, "version \"2\"");
  expect_replay_error("1 " + std::string(130, 'a') + "\n", 1, "longer than 64");
}

TEST(WiimoteReplay, ColumnPointsAtTheBadCharacter) {
  try {
    parse_replay("10 33 0x\n", "f");
    FAIL();
  } catch (const FileError& e) {
    EXPECT_EQ(e.column(), 8u) << e.what();  // the x of "0x"
  }
}

TEST(WiimoteReplay, ReadsFromDisk) {
  const auto path = std::filesystem::path(testing::TempDir()) / "wiimote_replay_test.txt";
  {
    std::ofstream out(path);
    ReplayWriter w(out);
    w.write(42, kExtended);
  }
  const Recording rec = read_replay(path);
  ASSERT_EQ(rec.reports.size(), 1u);
  EXPECT_EQ(rec.reports[0].t_ns, 42);
  std::filesystem::remove(path);
  EXPECT_THROW(read_replay(path), FileError);
}

// ---------------------------------------------------------------------------------------
// `mallet wiimote decode`, run as the operator runs it

std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::path(testing::TempDir()) / name;
  std::ofstream(path) << text;
  return path;
}

TEST(WiimoteDecodeCli, PrintsFourSlotsPerIrReport) {
  const auto path = write_temp("wiimote_decode_good.hex",
                               "# extended: origin, far corner, centre, empty\n"
                               "33 12 34 80 80 80  00 00 00  ff ff bf  00 80 65  ff ff ff\n"
                               "\n"
                               "20 00 08 1b 00 00 c8   # status: no line\n"
                               "22 00 00 16 00\n"
                               "30 00 00\n"
                               "36 00 00 ff ff b9 2c bc ff ff f0 01 02 00 00 00 00 00 00 00 00 00\n"
                               "37000011223300000000000000000000eeeeeeeeeeee\n"
                               "33 00 00 00 00 00 ffffffffffffffffffffffff\n");
  const auto r = test::run_mallet("wiimote decode --hex " + path.string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output,
            "0,0,0 1023,767,15 512,384,5 -\n"
            "1023,767,? 300,700,? - 1,2,?\n"
            "0,0,? 0,0,? 0,0,? 0,0,?\n"
            "- - - -\n");
  std::filesystem::remove(path);
}

TEST(WiimoteDecodeCli, MalformedLineExits2WithItsNumberAndPrintsNothing) {
  const auto path = write_temp("wiimote_decode_bad.hex",
                               "33 12 34 80 80 80  00 00 00  ff ff bf  00 80 65  ff ff ff\n"
                               "# fine so far\n"
                               "33 00 00 00\n"
                               "99\n");
  const auto r = test::run_mallet("wiimote decode --hex " + path.string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find(path.string() + ":3: report 0x33 must be 18 bytes"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("0,0,0"), std::string::npos) << "stdout must stay empty: " << r.output;
  EXPECT_EQ(r.output.find(":4:"), std::string::npos) << "only the first malformed line: " << r.output;
  std::filesystem::remove(path);
}

TEST(WiimoteDecodeCli, BadHexAndUnknownIdAndMissingFile) {
  const auto hex = write_temp("wiimote_decode_hex.hex", "\n\n33 0q\n");
  auto r = test::run_mallet("wiimote decode --hex " + hex.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find(hex.string() + ":3:5: 'q' is not a hex digit"), std::string::npos) << r.output;
  const auto unknown = write_temp("wiimote_decode_id.hex", "a1 00\n");
  r = test::run_mallet("wiimote decode --hex " + unknown.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find(":1: report id 0xa1 is not a Wii Remote input report"), std::string::npos) << r.output;
  r = test::run_mallet("wiimote decode --hex /nonexistent/x.hex");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("cannot open"), std::string::npos) << r.output;
  std::filesystem::remove(hex);
  std::filesystem::remove(unknown);
}

TEST(WiimoteDecodeCli, HelpDocumentsTheContract) {
  const auto r = test::run_mallet("wiimote decode --help");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.output.find("x,y,size"), std::string::npos);
  EXPECT_NE(r.output.find("x,y,?"), std::string::npos);
  EXPECT_NE(r.output.find("exits 2"), std::string::npos);
}

}  // namespace
}  // namespace mallet::input::wiimote
