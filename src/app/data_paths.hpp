#pragma once
// Where the shipped data (config/, models/, shaders/) is found: $MALLET_DATA_DIR, else
// the source tree this binary was built from, else /usr/share/mallet (the package).
#include <cstdlib>
#include <filesystem>

#ifndef MALLET_SOURCE_DATA_DIR
#define MALLET_SOURCE_DATA_DIR ""
#endif

namespace mallet::app {

inline std::filesystem::path data_dir() {
  if (const char* env = std::getenv("MALLET_DATA_DIR"); env && *env) return env;
  std::error_code ec;
  const std::filesystem::path source = MALLET_SOURCE_DATA_DIR;
  if (!source.empty() && std::filesystem::exists(source / "config" / "materials.toml", ec)) return source;
  return "/usr/share/mallet";
}

inline std::filesystem::path default_scene() { return data_dir() / "config" / "scenes" / "percussion.toml"; }

}  // namespace mallet::app
