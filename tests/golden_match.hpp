#pragma once
// A rendered frame against its golden image, tests/golden/NAME.png: ≤ 3/255 per channel, and
// fewer than 0.1 % of the pixels beyond that. A failing test writes the actual and a
// difference image to golden-output/ in the build's test directory.
//
// Updating the goldens after an intended change of the picture (look at them first):
//   MALLET_UPDATE_GOLDENS=1 build/debug/strike_tests --gtest_filter='Golden*'
//   (and kiosk_tests --gtest_filter='OperatorPageGolden*')
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "render/image.hpp"
#include "render/render_setup.hpp"
#include "test_paths.hpp"

namespace mallet::test {

inline constexpr int kGoldenTolerance = 3;  // per channel, of 255
inline constexpr double kGoldenMaxDifferingFraction = 0.001;

inline void expect_matches_golden(const render::Image& actual, const std::string& name,
                                  render::HeadlessRenderer& used) {
  const std::filesystem::path golden = source_dir() / "tests" / "golden" / (name + ".png");
  if (const char* update = std::getenv("MALLET_UPDATE_GOLDENS"); update && std::string(update) == "1") {
    render::write_png(actual, golden);
    GTEST_SKIP() << "updated " << golden;
  }
  ASSERT_TRUE(std::filesystem::exists(golden)) << golden << " is missing (see tests/golden_match.hpp)";
  const render::ImageDiff diff = render::compare_images(actual, render::read_png(golden), kGoldenTolerance);
  if (!diff.same_size || diff.differing_fraction > kGoldenMaxDifferingFraction) {
    const std::filesystem::path dir = std::filesystem::current_path() / "golden-output";
    std::filesystem::create_directories(dir);
    render::write_png(actual, dir / (name + ".actual.png"));
    render::write_png(diff.difference, dir / (name + ".diff.png"));
    ADD_FAILURE() << name << ": " << diff.differing_pixels << " pixels (" << diff.differing_fraction * 100
                  << "%) differ by more than " << kGoldenTolerance << "/255, max " << diff.max_channel_delta
                  << "; wrote " << (dir / (name + ".actual.png")) << " and .diff.png";
  }
  EXPECT_EQ(used.context().validation_messages(), 0u) << used.context().first_validation_message();
}

}  // namespace mallet::test
