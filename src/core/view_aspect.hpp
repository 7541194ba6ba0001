#pragma once
// The proportions of the screen the scene is shown on, shared by the render loop, which
// sets them from its window's size every frame, and the input threads, which map the
// pointer with them: the picture and the pointer frame the scene the same way
// (framed() in screen_to_world.hpp), even while a window is being resized.
#include <atomic>

#include "core/screen_to_world.hpp"

namespace mallet {

class ViewAspect {
 public:
  //! 0: not known yet; the content's own proportions are used.
  explicit ViewAspect(double aspect = 0) : aspect_(aspect) {}

  //! A window of no area (minimised) keeps the last proportions.
  void set(int width_px, int height_px) {
    if (width_px > 0 && height_px > 0)
      aspect_.store(static_cast<double>(width_px) / height_px, std::memory_order_relaxed);
  }
  double get() const { return aspect_.load(std::memory_order_relaxed); }

 private:
  std::atomic<double> aspect_;
};

//! The rectangle of the world `aspect`'s screen shows: `content` framed for it; nullptr (or
//! proportions not known yet): `content` as it is.
inline ScreenToWorld framed(const ScreenToWorld& content, const ViewAspect* aspect) {
  return aspect ? framed(content, aspect->get()) : content;
}

}  // namespace mallet
