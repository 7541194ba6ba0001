// actuator_felt.csv (core/felt_table_file.hpp): written and read back, no fit as an empty
// field, and a malformed file refused with its line.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/felt_table_file.hpp"
#include "core/file_error.hpp"

namespace mallet {
namespace {

TEST(FeltTableFile, RowsReadBackWithNoFitAsNaNAndABadFieldIsRefusedWithItsLine) {
  const auto dir = std::filesystem::temp_directory_path() / ("mallet-felt-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::vector<FeltRecord> rows = {
      {"wood", 0.3, 80, 100, 108.9, 102.0, 80.0, 100.0, "19c52f955d6bb599", "2026-12-06T09:00:00Z"},
      {"metal", 1.0, 90, 300, 352.1, 169.1, std::nan(""), std::nan(""), "", "2026-12-06T09:00:00Z"}};
  std::ofstream(dir / "f.csv") << format_felt_table(rows);
  const std::vector<FeltRecord> back = read_felt_table(dir / "f.csv");
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].material, "wood");
  EXPECT_EQ(back[0].decay_before, 108.9);
  EXPECT_EQ(back[0].calibration, "19c52f955d6bb599");
  EXPECT_TRUE(std::isnan(back[1].decay_after));
  EXPECT_EQ(back[1].freq_before, 169.1);
  std::ofstream(dir / "bad.csv") << kFeltHeader << "\nwood,fast,80,100,,,,,,\n";
  try {
    read_felt_table(dir / "bad.csv");
    ADD_FAILURE() << "accepted";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("speed_m_per_s"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace mallet
