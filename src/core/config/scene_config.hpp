#pragma once
#include <filesystem>

#include "core/scene.hpp"

namespace mallet::config {

//! Loads a scene file (config/scenes/*.toml). `materials_file` in it is resolved
//! relative to the scene file. Every problem is a ConfigError with file:line:column.
Scene load_scene(const std::filesystem::path& path);

//! Same, from text; `materials` is used instead of the scene's `materials_file`.
Scene parse_scene(std::string_view text, const std::string& name, const MaterialLibrary& materials);

}  // namespace mallet::config
