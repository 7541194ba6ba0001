// src/core is the pure model: it must not include any device header, so that it can be
// tested (and reasoned about) without a window, a sound card or a remote.
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "test_paths.hpp"

namespace {

TEST(Layering, CoreIncludesNoDeviceHeader) {
  const std::regex device_include(
      R"(#\s*include\s*[<"](vulkan|GLFW|hidapi|portaudio|fluidsynth|alsa|stk|AL/|SDL)[^">]*[">])",
      std::regex::icase);
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(mallet::test::source_dir() / "src" / "core")) {
    if (!entry.is_regular_file()) continue;
    ++files;
    std::ifstream in(entry.path());
    std::string line;
    int line_no = 0;
    while (std::getline(in, line)) {
      ++line_no;
      EXPECT_FALSE(std::regex_search(line, device_include)) << entry.path() << ":" << line_no << ": " << line;
    }
  }
  EXPECT_GT(files, 10);  // the scan really looked at the core
}

}  // namespace
