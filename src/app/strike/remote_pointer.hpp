#pragma once
// The Wii Remote as the kiosk's mallet: the path from the remote's reading thread to the
// audio engine, which never waits for a frame.
//
//   WiimoteDevice's reading thread (its sample sink, see wiimote_device.hpp)
//     → on_samples(): the tracked LED (raw camera px; the tracker runs in the device)
//       → calibration (camera → normalised screen homography) → scene (screen → world m)
//       → the strike route (strike_route.hpp: contact solver on the unfiltered samples,
//         AudioEngine::post(Producer::input), the log line; the 1€ filter on the drawn head
//         only) → a View the render loop reads
//   The render loop (main thread) takes() the samples since its last frame, for the kiosk's
//   states (movement, tracking lost/regained) and the calibration screen (camera points).
//
// Threads: on_samples() runs on the reading thread only; everything else on the main
// thread. They share a mutex held for a copy or a swap. The reading thread is the only one
// posting to the engine's input ring; the main thread keeps the main ring (mouse, ghost).
//
// Strikes happen only while playing (set_playing(true): the kiosk is in Play) and with a
// calibration; without one the samples still come (the calibration screen needs them) but
// have no screen position.
#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <span>
#include <vector>

#include "app/strike/strike_route.hpp"
#include "audio/engine.hpp"
#include "core/app_config.hpp"
#include "core/calibration_file.hpp"
#include "core/present_clock.hpp"
#include "core/scene.hpp"
#include "core/view_aspect.hpp"
#include "input/wiimote/wiimote_device.hpp"

namespace mallet::app {

//! The IR camera sensitivity the kiosk starts with: the one its calibration screen chose
//! and saved with the calibration, else the settings file's [wiimote] sensitivity.
std::string kiosk_sensitivity(const AppConfig& config, const std::optional<Calibration>& calibration);

//! The kiosk's remote: the settings' device config, with kiosk_sensitivity().
input::wiimote::WiimoteDeviceConfig kiosk_device_config(const AppConfig& config,
                                                        const std::optional<Calibration>& calibration);

//! One LED sample as the main thread sees it.
struct RemoteSample {
  Nanos t_ns = 0;
  IrTrackerEvent event = IrTrackerEvent::none;
  std::optional<Vec2> camera_px;  //!< the LED, raw camera pixels
  std::optional<Vec2> screen;     //!< through the calibration, normalised; none without one
  std::optional<IrFrame> frame;   //!< all the camera's slots (the device's every_frame)
};

class RemotePointer {
 public:
  //! `scene`, `config`, `engine`, `picture` and `aspect` must outlive this object (and the
  //! device's thread). `aspect`: the screen's proportions, which frame the scene the pointer
  //! moves in (nullptr: the scene's own).
  RemotePointer(const Scene& scene, const AppConfig& config, audio::AudioEngine& engine,
                const PresentClock* picture = nullptr, const ViewAspect* aspect = nullptr);

  //! The device's sample sink (reading thread); `now` is when the samples arrived, the
  //! time the route knows a strike they make.
  void on_samples(std::span<const input::wiimote::LedSample> samples, Nanos now);
  //! Called on the reading thread after each strike was delivered (rumble). Set before the
  //! device starts.
  std::function<void(const Impact&)> on_strike;

  // --- main thread ---
  //! The camera → screen map to use from the next sample on (nothing: no strikes).
  void set_calibration(std::optional<Calibration> calibration);
  //! Whether the visitor's strikes count (Play). Switching on starts a new stroke.
  void set_playing(bool playing);
  //! The samples since the last call (at most kMaxPending; older ones are dropped, counted).
  std::vector<RemoteSample> take();
  //! The head as the visitor's strokes place it (only meaningful while playing).
  StrikeLoop::View view() const;
  bool tracking() const;
  //! The wall scene's material for the strikes from the next sample on.
  void set_wall_material(int material) { route_.request_wall_material(material); }
  std::uint64_t strikes() const { return route_.strikes(); }
  std::uint64_t dropped() const;

  static constexpr std::size_t kMaxPending = 4096;

 private:
  void feed_point(Nanos t, Nanos now, Vec2 camera, RemoteSample& out);

  const Scene& scene_;
  const ViewAspect* aspect_;
  // Reading thread only.
  StrikeRoute route_;
  std::uint64_t seen_generation_ = 0;
  // Shared.
  mutable std::mutex mutex_;
  std::optional<Homography> camera_to_screen_;
  std::vector<RemoteSample> pending_;
  bool tracking_ = false;
  std::uint64_t dropped_ = 0;
  std::atomic<bool> playing_{false};
  std::atomic<std::uint64_t> generation_{0};
};

}  // namespace mallet::app
