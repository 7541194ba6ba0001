#pragma once
#include <filesystem>
#include <string>

#include "core/material.hpp"

namespace mallet::config {

//! Loads config/materials.toml: one [material.NAME] table per material, each with a
//! `visual` and an `actuator` triple {amplitude, decay_per_s, freq_hz}.
MaterialLibrary load_materials(const std::filesystem::path& path);
MaterialLibrary parse_materials(std::string_view text, const std::string& name);

}  // namespace mallet::config
