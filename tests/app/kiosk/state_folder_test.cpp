// The kiosk's state folder when it cannot be written (full, read-only, not a folder): every
// write fails without throwing, the previous file stays whole, and it is said once — not
// once a write — until a write succeeds again. Failures are provoked the ways a test can as
// root: a state "folder" that is a regular file, and a file-size limit (RLIMIT_FSIZE: the
// kernel refuses the write part-way, as a full disk does).
#include <sys/resource.h>

#include <csignal>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "app/kiosk/metrics_file.hpp"
#include "app/kiosk/state_folder.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

namespace fs = std::filesystem;

std::string read_state_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Said {
  std::vector<std::string> warnings, notes;
  StateFolder folder(const fs::path& dir) {
    return StateFolder(
        dir, [this](const std::string& l) { warnings.push_back(l); },
        [this](const std::string& l) { notes.push_back(l); });
  }
};

TEST(StateFolder, AFolderThatCannotBeWrittenIsSaidOnceNamingItAndTheKioskGoesOn) {
  const fs::path dir = test::scratch_dir();
  const fs::path state = dir / "state";
  { std::ofstream(state) << "a file where the folder should be\n"; }  // ENOTDIR / EEXIST, as root too
  Said said;
  StateFolder folder = said.folder(state);
  for (int i = 0; i < 3; ++i) {  // e.g. the count of starts, the last good settings, a calibration
    const Check wrote = folder.write("kiosk-starts", "1\n");
    EXPECT_FALSE(wrote);
  }
  folder.wrote("calibration.toml", refused(state.string() + "/calibration.toml: No space left on device"));
  ASSERT_EQ(said.warnings.size(), 1u) << "once a failing spell, not once a write";
  const std::string& line = said.warnings[0];
  EXPECT_EQ(line.find('\n'), std::string::npos) << "one line";
  EXPECT_EQ(line.rfind("state folder " + state.string() + " cannot be written (", 0), 0u) << line;
  EXPECT_NE(line.find(" free): "), std::string::npos) << line;
  EXPECT_NE(line.find("kiosk-starts"), std::string::npos) << line;
  EXPECT_NE(line.find("the kiosk plays on"), std::string::npos) << line;
  EXPECT_TRUE(folder.failing());
  // The page shows the latest failure.
  EXPECT_NE(folder.problem().find("calibration.toml: No space left on device"), std::string::npos) << folder.problem();
  EXPECT_EQ(read_state_file(state), "a file where the folder should be\n");

  // The folder comes back (the operator freed it): the next write succeeds and says so once.
  fs::remove(state);
  EXPECT_TRUE(folder.write("kiosk-starts", "2\n"));
  EXPECT_FALSE(folder.failing());
  EXPECT_TRUE(folder.problem().empty());
  ASSERT_EQ(said.notes.size(), 1u);
  EXPECT_NE(said.notes[0].find("writing again"), std::string::npos) << said.notes[0];
  EXPECT_TRUE(folder.write("kiosk-starts", "3\n"));
  EXPECT_EQ(said.notes.size(), 1u);
  EXPECT_EQ(read_state_file(state / "kiosk-starts"), "3\n");
}

TEST(StateFolder, AWriteRefusedPartWayLeavesThePreviousFileWholeAndNoTemporaryFile) {
  const fs::path state = test::scratch_dir() / "state";
  Said said;
  StateFolder folder = said.folder(state);
  const std::string before = "# the last good settings\n[audio]\nvolume = 0.5\n";
  ASSERT_TRUE(folder.write("last-good-settings.toml", before));
  // A file may grow to 16 bytes no more: the write of a longer one fails with EFBIG part-way
  // (SIGXFSZ ignored, as a full disk's ENOSPC fails it).
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit old_limit{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old_limit), 0);
  rlimit small = old_limit;
  small.rlim_cur = 16;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const Check wrote = folder.write("last-good-settings.toml", std::string(4096, '#'));
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &old_limit), 0);
  std::signal(SIGXFSZ, old_handler);
  ASSERT_FALSE(wrote);
  EXPECT_NE(wrote.error().find("(the old file, if any, is unchanged)"), std::string::npos) << wrote.error();
  EXPECT_EQ(read_state_file(state / "last-good-settings.toml"), before);
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(state)) files.push_back(e.path().filename());
  EXPECT_EQ(files, std::vector<fs::path>{"last-good-settings.toml"}) << "no temporary file left";
  EXPECT_EQ(said.warnings.size(), 1u);
}

TEST(StateFolder, AStartThatCannotBeCountedCountsAsTheFirstAndSaysSoThroughTheFolder) {
  const fs::path state = test::scratch_dir() / "state";
  { std::ofstream(state) << "not a folder\n"; }
  Said said;
  StateFolder folder = said.folder(state);
  std::vector<std::string> bad_content;
  EXPECT_EQ(count_kiosk_start(folder, [&](const std::string& l) { bad_content.push_back(l); }), 0u);
  EXPECT_TRUE(bad_content.empty());
  ASSERT_EQ(said.warnings.size(), 1u);
  EXPECT_NE(said.warnings[0].find("kiosk-starts"), std::string::npos) << said.warnings[0];
  EXPECT_TRUE(folder.failing());
}

}  // namespace
}  // namespace mallet::app
