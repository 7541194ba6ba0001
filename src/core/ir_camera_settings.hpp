#pragma once
// The Wii Remote IR camera's settings as data: its report format and the published
// sensitivity blocks. Here, in the core, because the settings file names them
// ([wiimote].ir_mode and .sensitivity) and the config loader must refuse an unknown name
// with its line; the start-up sequence that writes them to the camera is
// input/wiimote/ir_startup.hpp.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace mallet {

//! The camera's two sensitivity blocks (registers 0xB00000.. and 0xB0001A..).
struct SensitivityPreset {
  std::string_view name;
  std::array<std::uint8_t, 9> block1;
  std::array<std::uint8_t, 2> block2;
  std::string_view note;
};

//! The commonly published blocks (wiibrew "IR Camera"): the Wii's levels 1..5 (what the
//! console's sensor-bar sensitivity setting writes), the "marcan" and "max" sets. "wii3"
//! is what the Linux driver writes.
inline constexpr std::array<SensitivityPreset, 7> kSensitivityPresets{{
    {"wii1", {0x02, 0x00, 0x00, 0x71, 0x01, 0x00, 0x64, 0x00, 0xfe}, {0xfd, 0x05}, "Wii level 1 (least sensitive)"},
    {"wii2", {0x02, 0x00, 0x00, 0x71, 0x01, 0x00, 0x96, 0x00, 0xb4}, {0xb3, 0x04}, "Wii level 2"},
    {"wii3", {0x02, 0x00, 0x00, 0x71, 0x01, 0x00, 0xaa, 0x00, 0x64}, {0x63, 0x03}, "Wii level 3 (Linux default)"},
    {"wii4", {0x02, 0x00, 0x00, 0x71, 0x01, 0x00, 0xc8, 0x00, 0x36}, {0x35, 0x03}, "Wii level 4"},
    {"wii5", {0x07, 0x00, 0x00, 0x71, 0x01, 0x00, 0x72, 0x00, 0x20}, {0x1f, 0x03}, "Wii level 5"},
    {"marcan", {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x90, 0x00, 0xc0}, {0x40, 0x00}, "suggested by marcan"},
    {"max", {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x90, 0x00, 0x41}, {0x40, 0x00}, "maximum sensitivity"},
}};

inline constexpr std::string_view kDefaultSensitivity = "wii3";

//! The preset named `name` (exact, lower case), or nothing.
inline std::optional<SensitivityPreset> find_sensitivity(std::string_view name) {
  for (const auto& p : kSensitivityPresets)
    if (p.name == name) return p;
  return std::nullopt;
}

//! "wii1, wii2, ..., max" for error messages and --help.
inline std::string sensitivity_names() {
  std::string out;
  for (const auto& p : kSensitivityPresets) {
    if (!out.empty()) out += ", ";
    out += p.name;
  }
  return out;
}

//! Register 0xB00033: the camera's report format. Basic has no dot size (the tracker
//! then acquires the dot nearest the centre); extended carries a size 0..15.
enum class IrMode : std::uint8_t { basic = 1, extended = 3 };

}  // namespace mallet
