#pragma once
// What the Wii Remote's IR camera reports: up to four dots in raw camera coordinates
// (x 0..1023, y 0..767, no mirroring: orientation belongs to calibration).
#include <array>
#include <optional>

#include "core/time.hpp"

namespace mallet {

struct IrDot {
  int x = 0;      //!< 0..1023
  int y = 0;      //!< 0..767
  int size = -1;  //!< 0..15 in extended mode; -1 when the report has no size (basic mode)
  friend bool operator==(const IrDot&, const IrDot&) = default;
};

//! The camera's four slots; an empty slot is nullopt.
using IrSlots = std::array<std::optional<IrDot>, 4>;

//! One IR report, stamped on the monotonic clock when it was received.
struct IrFrame {
  Nanos t_ns = 0;
  IrSlots slots{};
};

}  // namespace mallet
