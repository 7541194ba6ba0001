#pragma once
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/modal_preset.hpp"

namespace mallet::config {

//! Loads config/instruments.toml: one [instrument.NAME] table per acoustic preset, with
//! loudness, reference_speed_m_per_s, brightness and an array of 1..kMaxModalModes modes
//! {ratio, gain, decay_per_s}; the first mode's ratio is 1. Presets come in file order.
std::vector<ModalPreset> load_instruments(const std::filesystem::path& path);
std::vector<ModalPreset> parse_instruments(std::string_view text, const std::string& name);

}  // namespace mallet::config
