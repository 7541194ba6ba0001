// State files: replaced whole or not at all, and an unusable one kept for the operator as
// FILE.bad while the program goes on from its defaults.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

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

// A version of the file: `size` bytes of one letter, so a torn file (two versions mixed, or
// a short one) is seen at once.
std::string version(int v, std::size_t size) { return std::string(size, static_cast<char>('a' + v % 26)); }

bool is_one_whole_version(const std::string& text, std::size_t size) {
  return text.size() == size && text.find_first_not_of(text.front()) == std::string::npos;
}

// Killed in the middle of replacing the file, again and again, by SIGKILL (which nothing can
// catch) and by SIGTERM's default action: the file is always one whole version.
TEST(AtomicFile, KilledMidWriteTheFileIsNeverTorn) {
  const fs::path dir = test::scratch_dir();
  const fs::path file = dir / "state.toml";
  constexpr std::size_t kSize = 4 << 20;  // 4 MiB: most of a writer's time is spent inside write()
  write_file_atomically(file, version(0, kSize));
  for (int round = 0; round < 12; ++round) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      ::signal(SIGTERM, SIG_DFL);
      for (int v = 1;; ++v) write_file_atomically(file, version(v, kSize));
    }
    // Once it has replaced the file at least once (waited for, never timed), kill it: it
    // is then somewhere in its loop of writes, most likely inside one.
    const std::string before = slurp(file);
    for (int polls = 0; polls < 60000 && slurp(file) == before; ++polls) ::usleep(1000);
    ASSERT_EQ(::kill(child, round % 2 == 0 ? SIGKILL : SIGTERM), 0);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status));
    EXPECT_TRUE(is_one_whole_version(slurp(file), kSize)) << "round " << round;
  }
  // The killed writers' temporary files are gone after the next write.
  write_file_atomically(file, version(0, 16));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
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
