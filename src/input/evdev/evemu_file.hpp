#pragma once
// Recorded evdev event streams in evemu's text format (Debian: evemu-tools), so a stream
// recorded from a real mouse on a kiosk with `evemu-record /dev/input/eventN > mouse.evemu`
// is a test input as it is, and what the tests use can be played into a real system with
// `evemu-play`. Only the event lines matter here:
//   E: 93784.000500 0002 0000 -001	# EV_REL / REL_X  -1
// seconds.microseconds, type and code in hex, value in decimal; the rest of the line after
// the value (evemu's comment) is ignored, as are the device description lines (N:, I:, P:,
// B:, A:, L:, S:) and '#' comment lines.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <linux/input.h>

namespace mallet::input::evdev {

//! The E: lines of an evemu recording, in file order. Throws FileError "NAME:LINE: problem"
//! for a malformed E: line (fields missing or not numbers, microseconds not six digits, a
//! type or code over 0xffff). Times are taken as written (evemu-record writes them relative
//! to the first event; the kernel's absolute stamps are kept when a tool writes those).
std::vector<input_event> parse_evemu_events(std::string_view text, const std::string& name);
//! parse_evemu_events of a file (FileError when it cannot be read).
std::vector<input_event> read_evemu_events(const std::filesystem::path& path);

//! One event as evemu writes it, without the comment and the newline:
//! "E: 93784.000500 0002 0000 -001".
std::string format_evemu_event(const input_event& event);

}  // namespace mallet::input::evdev
