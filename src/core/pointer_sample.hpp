#pragma once
// What every pointer source (Wii Remote IR camera, mouse, replayed trajectory) produces.
#include <cstdint>

#include "core/time.hpp"

namespace mallet {

//! A pointer position in normalised screen coordinates: 0..1, origin top-left, y down.
//! Values outside 0..1 are legal (the stick pointed past the screen's edge).
struct PointerSample {
  Nanos t_ns = 0;
  double x = 0;
  double y = 0;
};

//! What a consumer of samples (the contact solver, the 1€ filter) took, and what it ignored.
struct SampleCounters {
  std::uint64_t accepted = 0;
  std::uint64_t ignored_non_finite = 0;
  std::uint64_t ignored_not_after_previous = 0;  //!< dt <= 0 (duplicates, reordering)
};

}  // namespace mallet
