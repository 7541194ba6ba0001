// Trajectory files: every kind of bad input is one clear line with file and line.
#include <cmath>

#include <gtest/gtest.h>

#include "core/file_error.hpp"
#include "input/trajectory_csv.hpp"

namespace mallet::input {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_trajectory_csv(text, "traj.csv");
  } catch (const FileError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(TrajectoryCsv, ReadsColumnsByNameToTheNanosecond) {
  const Trajectory t = parse_trajectory_csv("# a comment\ny,t,x,note\n0.5,0.000000001,0.25,a\n\n0.4,1.5,0.3,b\n", "f");
  ASSERT_EQ(t.samples.size(), 2u);
  EXPECT_EQ(t.samples[0].t_ns, 1);
  EXPECT_EQ(t.samples[0].x, 0.25);
  EXPECT_EQ(t.samples[0].y, 0.5);
  EXPECT_EQ(t.samples[1].t_ns, 1'500'000'000);
}

TEST(TrajectoryCsv, NonFinitePositionsPassToTheSolver) {
  const Trajectory t = parse_trajectory_csv("t,x,y\n0,nan,0.5\n0.1,0.2,inf\n", "f");
  ASSERT_EQ(t.samples.size(), 2u);
  EXPECT_TRUE(std::isnan(t.samples[0].x));
  EXPECT_TRUE(std::isinf(t.samples[1].y));
}

TEST(TrajectoryCsv, EqualTimesAreAllowedDecreasingAreNot) {
  EXPECT_EQ(parse_trajectory_csv("t,x,y\n0.1,0,0\n0.1,0,0\n", "f").samples.size(), 2u);
  EXPECT_EQ(error_of("t,x,y\n0.2,0,0\n0.1,0,0\n"),
            "traj.csv:3: t = 0.1 is before the previous row's t = 0.2 (times must not decrease)");
}

TEST(TrajectoryCsv, EveryProblemNamesFileAndLine) {
  EXPECT_EQ(error_of(""), "traj.csv: empty file (expected a header t,x,y and rows)");
  EXPECT_EQ(error_of("t,x,y\n"), "traj.csv: no data rows after the header");
  EXPECT_EQ(error_of("t,x\n0,0\n"), "traj.csv:1: missing column \"y\" (the header must name the columns t,x,y)");
  EXPECT_EQ(error_of("t,x,y\n0,0\n"), "traj.csv:2: expected 3 fields, got 2");
  EXPECT_EQ(error_of("t,x,y\n0,0,abc\n"), "traj.csv:2: y: \"abc\" is not a number");
  EXPECT_EQ(error_of("t,x,y\nnan,0,0\n"), "traj.csv:2: t is not a finite number");
  EXPECT_EQ(error_of("t,x,y\n-1,0,0\n"), "traj.csv:2: t must be >= 0 seconds");
  EXPECT_EQ(error_of("t,x,y\n0,0,0\n1e300,0,0\n"), "traj.csv:3: t is out of range");
}

TEST(TrajectoryCsv, MissingFileIsAFileError) {
  EXPECT_THROW(read_trajectory_csv("/nonexistent/traj.csv"), FileError);
}

}  // namespace
}  // namespace mallet::input
