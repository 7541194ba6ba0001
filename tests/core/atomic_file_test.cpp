// State files: replaced whole or not at all, and an unusable one kept for the operator as
// FILE.bad while the program goes on from its defaults.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "core/atomic_file.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(AtomicFile, ReplacesTheWholeFileAndLeavesNoTemporary) {
  const fs::path dir = test::scratch_dir();
  write_file_atomically(dir / "state.toml", "old\n");
  write_file_atomically(dir / "state.toml", "new\n");
  EXPECT_EQ(slurp(dir / "state.toml"), "new\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(AtomicFile, AFailedWriteLeavesTheOldFile) {
  const fs::path dir = test::scratch_dir();
  write_file_atomically(dir / "state.toml", "old\n");
  EXPECT_THROW(write_file_atomically(dir / "absent-folder" / "state.toml", "new\n"), std::runtime_error);
  EXPECT_EQ(slurp(dir / "state.toml"), "old\n");
}

TEST(AtomicFile, AnUnusableFileIsKeptBesideItAsBad) {
  const fs::path dir = test::scratch_dir();
  write_file_atomically(dir / "calibration.toml", "garbage\n");
  const std::optional<fs::path> bad = set_aside_as_bad(dir / "calibration.toml");
  ASSERT_TRUE(bad);
  EXPECT_EQ(*bad, dir / "calibration.toml.bad");
  EXPECT_FALSE(fs::exists(dir / "calibration.toml"));
  EXPECT_EQ(slurp(*bad), "garbage\n");
  // A second bad file replaces the first one's copy.
  write_file_atomically(dir / "calibration.toml", "worse\n");
  ASSERT_TRUE(set_aside_as_bad(dir / "calibration.toml"));
  EXPECT_EQ(slurp(dir / "calibration.toml.bad"), "worse\n");
}

TEST(AtomicFile, AFileThatCannotBeMovedStaysAndSaysSo) {
  EXPECT_FALSE(set_aside_as_bad(test::scratch_dir() / "absent.toml"));
}

}  // namespace
}  // namespace mallet
