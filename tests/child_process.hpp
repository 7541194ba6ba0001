#pragma once
// For tests that run the real `mallet` binary as a child with a window: its environment,
// and reading what it wrote while it runs.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace mallet::test {

//! The whole file (empty when it does not exist yet).
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

//! Polls `file` every 0.1 s, `polls` times (60 s by default), until it contains `text`.
inline bool wait_for(const std::filesystem::path& file, const std::string& text, int polls = 600) {
  for (int i = 0; i < polls; ++i) {
    if (slurp(file).find(text) != std::string::npos) return true;
    std::system("sleep 0.1");
  }
  return false;
}

//! The sanitizer build preloads the Vulkan driver and the validation layer (see
//! tests/CMakeLists.txt). GLFW looks vkGetInstanceProcAddr up by name, and a preloaded
//! layer would answer instead of the loader: a child that opens a window keeps only the
//! driver. A prefix for the child's shell command.
inline std::string child_preload() {
  const char* preload = std::getenv("LD_PRELOAD");
  std::string kept, entry;
  std::stringstream in(preload ? preload : "");
  while (std::getline(in, entry, ':'))
    if (!entry.empty() && entry.find("VkLayer") == std::string::npos) kept += (kept.empty() ? "" : ":") + entry;
  return "LD_PRELOAD='" + kept + "' ";
}

}  // namespace mallet::test
