#pragma once
// Paths the tests need: the source tree's shipped data and a scratch directory per test.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/config/scene_config.hpp"
#include "core/file_error.hpp"
#include "core/impact.hpp"

namespace mallet::test {

inline std::filesystem::path source_dir() { return MALLET_TEST_SOURCE_DIR; }

//! Writes `text` to `file`, making its folders first.
inline void write_text(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text;
}
inline std::filesystem::path config_dir() { return source_dir() / "config"; }
inline std::filesystem::path percussion_scene() { return config_dir() / "scenes" / "percussion.toml"; }

//! The shipped percussion scene, loaded once per test binary.
inline const Scene& percussion() {
  static const Scene scene = config::load_scene(percussion_scene());
  return scene;
}

inline std::filesystem::path texture_scene() { return config_dir() / "scenes" / "texture.toml"; }
inline std::filesystem::path wall_scene() { return config_dir() / "scenes" / "wall.toml"; }

//! The shipped texture and wall scenes of the second paper, loaded once per test binary.
inline const Scene& texture() {
  static const Scene scene = config::load_scene(texture_scene());
  return scene;
}
inline const Scene& wall() {
  static const Scene scene = config::load_scene(wall_scene());
  return scene;
}

//! A strike on a bar of the shipped scene at t with impact speed v, as the solver emits it.
inline Impact strike(int target, Nanos t, double v) {
  const Target& bar = percussion().targets[static_cast<std::size_t>(target)];
  Impact i;
  i.t_ns = t;
  i.target = target;
  i.material = bar.material;
  i.note = bar.note;
  i.speed_m_per_s = v;
  return i;
}

inline constexpr Nanos kDay = 86'400 * kNanosPerSecond;
inline constexpr Nanos kMicrosecond = 1'000;

//! Runs `load` and returns the FileError it throws (the test fails if none is thrown).
template <typename F>
FileError file_error_of(F&& load) {
  try {
    load();
  } catch (const FileError& e) {
    return e;
  }
  ADD_FAILURE() << "no FileError thrown";
  return FileError("", 0, 0, "");
}

//! This build tree's scratch folder, <temp>/mallet-<6 hex digits of the build tree's path>
//! (tests/CMakeLists.txt): two build trees running the same tests at once never share a folder,
//! and the name stays short (a test's Unix socket path must fit in 108 bytes).
inline std::filesystem::path scratch_root() {
  return std::filesystem::temp_directory_path() / MALLET_TEST_SCRATCH_NAME;
}

//! A fresh, empty directory named after the running test (in this build tree's scratch_root).
inline std::filesystem::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = scratch_root() / (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace mallet::test
