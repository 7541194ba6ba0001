// evemu's text format: the E: lines become input_events with their times, types, codes and
// values; everything else (the device description, comments) is skipped; a malformed E: line
// is an error naming its line; format_evemu_event writes what evemu writes.
#include "input/evdev/evemu_file.hpp"

#include <gtest/gtest.h>

#include "core/file_error.hpp"

namespace mallet::input::evdev {
namespace {

TEST(EvemuFile, ReadsTheEventLinesAndSkipsTheRest) {
  const std::string text =
      "# EVEMU 1.3\n"
      "N: Logitech USB Optical Mouse\n"
      "I: 0003 046d c077 0111\n"
      "B: 00 0b 00 00 00 00 00 00 00\n"
      "E: 0.000000 0002 0000 -001\t# EV_REL / REL_X                -1\n"
      "E: 0.000000 0002 0001 0002\t# EV_REL / REL_Y                2\r\n"
      "E: 12.000999 0001 0110 0001\n"
      "E: 12.000999 0000 0000 0000\t# ------------ SYN_REPORT (0) ---------- +0ms\n";
  const std::vector<input_event> events = parse_evemu_events(text, "mouse.evemu");
  ASSERT_EQ(events.size(), 4u);
  EXPECT_EQ(events[0].type, EV_REL);
  EXPECT_EQ(events[0].code, REL_X);
  EXPECT_EQ(events[0].value, -1);
  EXPECT_EQ(events[1].code, REL_Y);
  EXPECT_EQ(events[1].value, 2);
  EXPECT_EQ(events[2].input_event_sec, 12);
  EXPECT_EQ(events[2].input_event_usec, 999);
  EXPECT_EQ(events[2].type, EV_KEY);
  EXPECT_EQ(events[2].code, BTN_LEFT);
  EXPECT_EQ(events[3].type, EV_SYN);
  EXPECT_EQ(events[3].code, SYN_REPORT);
}

TEST(EvemuFile, AMalformedEventLineNamesItsLine) {
  const auto error_of = [](const std::string& text) {
    try {
      parse_evemu_events(text, "bad.evemu");
    } catch (const FileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of("N: x\nE: 1.5 0002 0000 1\n").rfind("bad.evemu:2: bad time \"1.5\"", 0), 0u);
  EXPECT_EQ(error_of("E: 1.000000 0002 0000\n").rfind("bad.evemu:1: bad value \"\"", 0), 0u);
  EXPECT_EQ(error_of("E: 1.000000 zz 0000 1\n").rfind("bad.evemu:1: bad type \"zz\"", 0), 0u);
  EXPECT_EQ(error_of("E: 1.000000 0002 10000 1\n").rfind("bad.evemu:1: bad code \"10000\"", 0), 0u);
  EXPECT_EQ(error_of("E: -1.000000 0002 0000 1\n").rfind("bad.evemu:1: bad time", 0), 0u);
  EXPECT_TRUE(parse_evemu_events("", "empty.evemu").empty());
}

TEST(EvemuFile, WritesWhatItReads) {
  input_event e{};
  e.input_event_sec = 93784;
  e.input_event_usec = 500;
  e.type = EV_REL;
  e.code = REL_WHEEL_HI_RES;
  e.value = -120;
  const std::string line = format_evemu_event(e);
  EXPECT_EQ(line, "E: 93784.000500 0002 000b -120");
  const std::vector<input_event> back = parse_evemu_events(line, "line");
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].input_event_sec, e.input_event_sec);
  EXPECT_EQ(back[0].input_event_usec, e.input_event_usec);
  EXPECT_EQ(back[0].type, e.type);
  EXPECT_EQ(back[0].code, e.code);
  EXPECT_EQ(back[0].value, e.value);
}

}  // namespace
}  // namespace mallet::input::evdev
