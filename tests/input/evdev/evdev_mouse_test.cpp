// The evdev reader where no mouse is (this machine has none, and no /dev/uinput to make
// one): the search finds nothing without crashing, and opening anything that is not a
// pointer's event node gives one line naming the path and the reason.
#include "input/evdev/evdev_mouse.hpp"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

namespace mallet::input::evdev {
namespace {

namespace fs = std::filesystem;

//! An empty scratch directory of this test's own.
fs::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(::testing::TempDir()) / ("mallet_evdev_" + std::string(info->name()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(EvdevMouse, FindMiceInADirectoryWithoutDevicesFindsNone) {
  const fs::path dir = scratch_dir();
  EXPECT_TRUE(find_mice(dir).empty());
  // Look-alikes: a regular file and a directory named like event nodes, and other names.
  std::ofstream(dir / "event0") << "not a device";
  fs::create_directories(dir / "event1");
  std::ofstream(dir / "mouse0") << "";
  std::ofstream(dir / "eventX") << "";
  const MouseScan scan = scan_mice(dir);
  EXPECT_TRUE(scan.mice.empty());
  EXPECT_EQ(scan.unreadable, 0);
  EXPECT_TRUE(find_mice(dir / "missing").empty());
}

TEST(EvdevMouse, OpeningARegularFileSaysItIsNotAnEventNode) {
  const fs::path file = scratch_dir() / "event3";
  std::ofstream(file) << "not a device";
  const EvdevOpenResult r = EvdevMouse::open(file.string());
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error(), file.string() +
                         ": not an input event device (a regular file); give a /dev/input/event* node or \"auto\"");
}

TEST(EvdevMouse, OpeningADirectoryOrAMissingPathSaysWhy) {
  const fs::path dir = scratch_dir();
  EvdevOpenResult r = EvdevMouse::open(dir.string());
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().find(dir.string() + ": not an input event device (a directory)"), std::string::npos) << r.error();
  r = EvdevMouse::open((dir / "event99").string());
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error(), (dir / "event99").string() + ": No such file or directory");
}

TEST(EvdevMouse, OpeningACharacterDeviceThatIsNotEvdevSaysSo) {
  if (!fs::is_character_file("/dev/null")) GTEST_SKIP() << "no /dev/null";
  const EvdevOpenResult r = EvdevMouse::open("/dev/null");
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().rfind("/dev/null: not an input event device (", 0), 0u) << r.error();
}

TEST(EvdevMouse, AutoWithNoMouseSaysWhereItLooked) {
  const fs::path dir = scratch_dir();
  EvdevMouseConfig config;
  config.search_dir = dir;
  const EvdevOpenResult r = EvdevMouse::open(kAutoDevice, config);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error(), "no mouse among " + (dir / "event*").string());
  EXPECT_EQ(why_not(EvdevMouse::open("", config)), r.error());  // empty means auto
}

TEST(EvdevMouse, ABadConfigIsRefusedBeforeAnyDevice) {
  EvdevMouseConfig config;
  config.speed_px_per_count = 0;
  EXPECT_EQ(why_not(EvdevMouse::open(kAutoDevice, config)), "speed_px_per_count must be > 0, got 0.000000");
  config = {};
  config.screen_width_px = 0;
  EXPECT_EQ(why_not(EvdevMouse::open(kAutoDevice, config)), "the screen size must be > 0 pixels, got 0x1080");
}

}  // namespace
}  // namespace mallet::input::evdev
