#pragma once
#include <filesystem>
#include <string>

#include "core/app_config.hpp"

namespace mallet::config {

//! Loads config/mallet.toml. Absent sections and keys keep their defaults; unknown keys
//! and out-of-range values are ConfigErrors.
AppConfig load_app_config(const std::filesystem::path& path);
AppConfig parse_app_config(std::string_view text, const std::string& name);

}  // namespace mallet::config
