#pragma once
// One kernel input event, as a recording or a fake device hands it over.
#include <cstdint>

#include <linux/input.h>

namespace mallet::input::evdev::test {

//! One event at `t_us` microseconds of the kernel's clock.
inline input_event ev(std::int64_t t_us, std::uint16_t type, std::uint16_t code, std::int32_t value) {
  input_event e{};
  e.input_event_sec = static_cast<decltype(e.input_event_sec)>(t_us / 1'000'000);
  e.input_event_usec = static_cast<decltype(e.input_event_usec)>(t_us % 1'000'000);
  e.type = type;
  e.code = code;
  e.value = value;
  return e;
}

}  // namespace mallet::input::evdev::test
