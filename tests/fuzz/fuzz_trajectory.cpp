// A pointer trajectory CSV (config/trajectories/*.csv) on arbitrary text: samples on a
// clock that starts at or after 0 and never goes back, or one FileError line naming the file.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_support.hpp"
#include "input/trajectory_csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string name = "fuzz.csv";
  mallet::input::Trajectory trajectory;
  try {
    trajectory = mallet::input::parse_trajectory_csv(mallet::fuzz::text_of(data, size), name);
  } catch (const mallet::FileError& e) {
    mallet::fuzz::check_refusal(e, name);
    return 0;
  }
  if (trajectory.samples.empty()) std::abort();
  mallet::Nanos previous = 0;
  for (const mallet::PointerSample& s : trajectory.samples) {
    if (s.t_ns < previous) std::abort();
    previous = s.t_ns;
  }
  return 0;
}
