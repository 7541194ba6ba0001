// src/core is the pure model: it must not include any device header, so that it can be
// tested (and reasoned about) without a window, a sound card or a remote.
#include <filesystem>
#include <fstream>
#include <algorithm>
#include <array>
#include <string>

#include <gtest/gtest.h>

#include "test_paths.hpp"

namespace {

TEST(Layering, CoreIncludesNoDeviceHeader) {
  // Lower-cased prefixes of the headers of every device library the project uses or may use.
  const std::array<std::string, 9> devices{"vulkan", "glfw", "hidapi", "portaudio", "fluidsynth",
                                           "alsa",   "stk",  "al/",    "sdl"};
  auto includes_device = [&](std::string line) {
    std::transform(line.begin(), line.end(), line.begin(), [](unsigned char c) { return std::tolower(c); });
    const auto hash = line.find_first_not_of(" \t");
    if (hash == std::string::npos || line[hash] != '#' || line.find("include", hash) == std::string::npos) return false;
    const auto open = line.find_first_of("<\"", hash);
    if (open == std::string::npos) return false;
    const std::string header = line.substr(open + 1);
    return std::any_of(devices.begin(), devices.end(), [&](const std::string& d) { return header.rfind(d, 0) == 0; });
  };
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(mallet::test::source_dir() / "src" / "core")) {
    if (!entry.is_regular_file()) continue;
    ++files;
    std::ifstream in(entry.path());
    std::string line;
    int line_no = 0;
    while (std::getline(in, line)) {
      ++line_no;
      EXPECT_FALSE(includes_device(line)) << entry.path() << ":" << line_no << ": " << line;
    }
  }
  EXPECT_GT(files, 10);  // the scan really looked at the core
}

}  // namespace
