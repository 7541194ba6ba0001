#pragma once
// What every pointer source (Wii Remote IR camera, mouse, replayed trajectory) produces.
#include "core/time.hpp"

namespace mallet {

//! A pointer position in normalised screen coordinates: 0..1, origin top-left, y down.
//! Values outside 0..1 are legal (the stick pointed past the screen's edge).
struct PointerSample {
  Nanos t_ns = 0;
  double x = 0;
  double y = 0;
};

}  // namespace mallet
