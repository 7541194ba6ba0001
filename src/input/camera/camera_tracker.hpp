#pragma once
// A camera frame → the stick's LED as the strike route takes it: the same LedSample the
// Wii Remote's tracker hands over (raw camera pixels, the frame's time, and the events
// regained / lost), so that calibration, the strike route and the kiosk's states treat
// both cameras alike. Device-free: the reading thread (camera_device) calls it, the tests
// hand it generated streams.
//
//  * Each frame's luma is read in place (frame_decode) and searched (led_finder).
//  * The sample's time is the frame's (mid-exposure, on the program's clock). A frame that
//    is not after the previous one is ignored and counted, as the Wii tracker does.
//  * Lost: no LED for lost_after_ms; poll(now) says so when frames stop coming too.
//  * A gap in the driver's sequence numbers counts the frames the driver dropped.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/ir_tracker.hpp"
#include "input/camera/camera_frame.hpp"
#include "input/camera/led_finder.hpp"
#include "input/wiimote/wiimote_device.hpp"

namespace mallet::input::camera {

struct CameraTrackerCounters {
  std::uint64_t frames = 0;
  std::uint64_t led_frames = 0;       //!< frames in which the LED was found
  std::uint64_t dropped = 0;          //!< frames the driver's sequence skipped
  std::uint64_t bad_frames = 0;       //!< frames that could not be read (a corrupt JPEG, a short buffer)
  std::uint64_t out_of_order = 0;     //!< frames not after the previous one
  std::uint64_t lost = 0;
  std::uint64_t regained = 0;
};

class CameraTracker {
 public:
  explicit CameraTracker(LedFinderConfig finder = {}, double lost_after_ms = 150.0);

  //! The frame's sample: a point when the LED was found, an event when tracking changed;
  //! for a frame that could not be read (bad_frame() then says why) nothing, or `lost`
  //! when the LED has not been seen for lost_after_ms.
  std::optional<wiimote::LedSample> on_frame(const CameraFrame& frame);
  //! Frames stopped (a camera gone): `lost` once the time-out has run out, at that time.
  std::optional<wiimote::LedSample> poll(Nanos now_ns);
  //! The camera went away: `lost` now, if the LED was being tracked.
  std::optional<wiimote::LedSample> lose(Nanos now_ns);
  //! A new connection: the LED is looked for afresh and the sequence starts again.
  void restart();

  bool tracking() const { return tracking_; }
  //! The last LED found (kept after `lost`, for display).
  std::optional<IrPoint> last_point() const { return last_point_; }
  const LedBlob* last_blob() const { return last_blob_ ? &*last_blob_ : nullptr; }
  const std::string& bad_frame() const { return bad_frame_; }
  const CameraTrackerCounters& counters() const { return counters_; }
  const LedFinder& finder() const { return finder_; }

 private:
  LedFinder finder_;
  Nanos lost_after_ns_;
  std::vector<std::uint8_t> scratch_;
  bool tracking_ = false;
  std::optional<Nanos> last_frame_ns_;
  std::optional<Nanos> last_seen_ns_;
  std::optional<std::uint32_t> last_sequence_;
  std::optional<IrPoint> last_point_;
  std::optional<LedBlob> last_blob_;
  std::string bad_frame_;
  CameraTrackerCounters counters_;
};

}  // namespace mallet::input::camera
