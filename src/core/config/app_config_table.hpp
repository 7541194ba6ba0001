#pragma once
// The settings read from a TOML table already parsed (and perhaps merged from drop-ins,
// settings_files.hpp). Only the config loaders include this (toml++ is heavy to compile).
#include <string>

#include <toml++/toml.h>

#include "core/app_config.hpp"

namespace mallet::config {

//! Absent sections and keys keep their defaults; unknown keys and out-of-range values are
//! ConfigErrors located in the file each value came from.
AppConfig read_app_config(const toml::table& root, const std::string& file);

}  // namespace mallet::config
