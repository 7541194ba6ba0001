#pragma once
// Recorded or scripted pointer trajectories: a CSV with a header naming the columns
// t, x, y (any order; other columns are ignored), t in seconds, increasing.
// Blank lines and lines starting with '#' are skipped.
#include <filesystem>
#include <string>
#include <vector>

#include "core/pointer_sample.hpp"

namespace mallet::input {

struct Trajectory {
  std::vector<PointerSample> samples;  //!< t on the int64 ns clock; x, y as in the file
};

//! Throws FileError "FILE:LINE: problem" for: an unreadable or empty file, a missing
//! column, a row with too few fields, a t that is not a finite number >= 0, a t smaller
//! than the previous row's. x or y may be nan/inf (the contact solver ignores and counts
//! such samples); anything else that is not a number is an error.
Trajectory read_trajectory_csv(const std::filesystem::path& path);
Trajectory parse_trajectory_csv(std::string_view text, const std::string& name);

}  // namespace mallet::input
