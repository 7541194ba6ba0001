#pragma once
// The frame budget: frames begin on a grid of 1 / max_fps seconds, so a kiosk whose display
// does not hold it back (a virtual X server; a mailbox or immediate swapchain) does not draw
// hundreds of frames a second on a fanless PC. The grid is kept on the int64 clock (no
// drift over weeks); a frame that began late is not made up for by a burst of frames after
// it, and one late by more than a whole period starts the grid anew.
//
// The window engages it only where frames would otherwise come faster than max_fps: a FIFO
// display that paces itself at its refresh is left alone (two clocks at one rate would beat
// against each other and drop frames), unless max_fps is below the refresh.
#include "core/time.hpp"

namespace mallet {

class FramePacer {
 public:
  //! `max_fps` ≤ 0: no cap (begin() returns `now`).
  explicit FramePacer(double max_fps = 0);
  void set_max_fps(double max_fps);
  double max_fps() const { return max_fps_; }
  Nanos period_ns() const { return period_ns_; }

  //! A frame is about to begin at `now`: when it may begin (≥ now). The caller waits until
  //! then; the next frame's slot is one period after this one's.
  Nanos begin(Nanos now);

 private:
  double max_fps_ = 0;
  Nanos period_ns_ = 0;
  Nanos next_ = -1;  //!< this frame's slot on the grid; < 0 before the first
};

//! Sleeps until `t` on the program's clock (CLOCK_MONOTONIC); returns at once when it has passed.
void sleep_until_monotonic(Nanos t);

}  // namespace mallet
