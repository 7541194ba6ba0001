#pragma once
// gnuplot (Debian's gnuplot-nox), the one way the project draws its PNG plots: the bench
// report's and the study summary's. Each plot is a .dat and a .gp script written beside the
// PNG, so that without gnuplot the data is still there and the plot can be drawn elsewhere.
#include <filesystem>
#include <string>

namespace mallet {

//! Whether `gnuplot` is on the PATH.
bool have_gnuplot();
//! Runs `gnuplot SCRIPT` in `dir` (the script names its files relative to it); false when it failed.
bool run_gnuplot(const std::filesystem::path& dir, const std::string& script);

}  // namespace mallet
