#pragma once
// The one interface every live pointer source implements (mouse via evdev, and the others
// as they move behind it), so the strike route takes samples without knowing which device
// made them. A source reads on its own thread and stamps each sample where it is read: the
// time is the device's (or the kernel's) time of the observation, never a frame's, because
// the contact solver's impact time and speed are only as good as these stamps.
#include <functional>
#include <span>
#include <string>

#include "core/pointer_sample.hpp"

namespace mallet::input {

//! Receives samples in reading order, t_ns on the program's monotonic clock
//! (CLOCK_MONOTONIC), x and y normalised screen coordinates (0..1, origin top-left, y down).
//! Called on the source's own thread, once per batch the source read together (often one
//! sample): it must not block for long (it delays the next read) and must not throw. The
//! span is valid only during the call.
using PointerSink = std::function<void(std::span<const PointerSample>)>;

class PointerSource {
 public:
  virtual ~PointerSource() = default;
  //! Starts the reading thread, which hands every sample to `sink` until stop(). A source
  //! that lost its device keeps trying to get it back; it never gives up on its own.
  virtual void start(PointerSink sink) = 0;
  //! Stops the reading thread promptly (within one bounded wait) and returns once it has
  //! ended: after stop() the sink is not called again. Safe to call twice or unstarted;
  //! never from within the sink (the thread would wait for itself).
  virtual void stop() = 0;
  //! One line for logs and the operator page, e.g.
  //! "mouse via evdev /dev/input/event3 (Logitech USB Optical Mouse)".
  virtual std::string describe() const = 0;
};

}  // namespace mallet::input
