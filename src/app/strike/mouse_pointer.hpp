#pragma once
// The mouse as the kiosk's mallet when it is read at its source (input/evdev): its reading
// thread hands each sample, stamped by the kernel, straight to the strike route, so a
// mouse strike is heard without waiting for a frame and is timed to the mouse's own
// report (1 ms at 1000 Hz), not to the frame that happened to poll it.
//
//   EvdevMouse's reading thread → on_samples(): normalised screen → scene (world m)
//     → StrikeRoute (Producer::input: the remote, the other user of that ring, is never
//       the input at the same time) → a View the render loop reads
//   The render loop (main thread) take()s the samples since its last frame for the
//   kiosk's states (movement) and the calibration screen.
//
// Strikes happen only while playing (set_playing(true)); switching on starts a new stroke.
#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <span>
#include <vector>

#include "app/strike/strike_route.hpp"
#include "audio/engine.hpp"
#include "core/app_config.hpp"
#include "core/pointer_sample.hpp"
#include "core/present_clock.hpp"
#include "core/scene.hpp"
#include "core/view_aspect.hpp"

namespace mallet::app {

class MousePointer {
 public:
  //! `scene`, `config`, `engine`, `picture` and `aspect` must outlive this object and the
  //! source's thread. `aspect`: the screen's proportions, which frame the scene the pointer
  //! moves in (nullptr: the scene's own).
  MousePointer(const Scene& scene, const AppConfig& config, audio::AudioEngine& engine, const PresentClock* picture,
               const ViewAspect* aspect = nullptr);

  //! The source's sink (its reading thread): each sample is known to the route when it
  //! is handed over.
  void on_samples(std::span<const PointerSample> samples);
  //! Called on the reading thread after each strike was delivered. Set before the source starts.
  std::function<void(const Strike&)> on_strike;

  // --- main thread
  void set_playing(bool playing);
  //! The samples since the last call (at most kMaxPending; older ones are dropped).
  std::vector<PointerSample> take();
  StrikeLoop::View view() const { return route_.view(); }
  void set_wall_material(int material) { route_.request_wall_material(material); }
  std::uint64_t strikes() const { return route_.strikes(); }

  static constexpr std::size_t kMaxPending = 8192;  //!< 8 s at 1000 Hz with no frame

 private:
  const Scene& scene_;
  const ViewAspect* aspect_;
  StrikeRoute route_;  //!< the reading thread's
  bool was_playing_ = false;  //!< reading thread
  std::atomic<bool> playing_{false};
  mutable std::mutex mutex_;
  std::vector<PointerSample> pending_;
};

}  // namespace mallet::app
