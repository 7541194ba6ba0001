#include "input/camera/camera_tracker.hpp"

#include <cmath>

#include "input/camera/frame_decode.hpp"

namespace mallet::input::camera {

CameraTracker::CameraTracker(LedFinderConfig finder, double lost_after_ms)
    : finder_(finder), lost_after_ns_(static_cast<Nanos>(std::llround(lost_after_ms * 1e6))) {}

void CameraTracker::restart() {
  finder_.reset();
  last_sequence_.reset();
  last_frame_ns_.reset();
}

std::optional<wiimote::LedSample> CameraTracker::on_frame(const CameraFrame& frame) {
  if (last_frame_ns_ && frame.t_ns <= *last_frame_ns_) {
    ++counters_.out_of_order;
    return std::nullopt;
  }
  ++counters_.frames;
  if (last_sequence_ && frame.sequence > *last_sequence_ + 1) counters_.dropped += frame.sequence - *last_sequence_ - 1;
  last_sequence_ = frame.sequence;
  last_frame_ns_ = frame.t_ns;
  const Result<LumaView, std::string> luma = luma_view(frame, scratch_);
  if (!luma) {
    ++counters_.bad_frames;
    bad_frame_ = luma.error();
    return poll(frame.t_ns);  // unreadable frames are frames without the LED: it may be lost
  }
  const auto found = finder_.find(*luma);
  wiimote::LedSample s;
  s.t_ns = frame.t_ns;
  if (found.led) {
    ++counters_.led_frames;
    s.has_point = true;
    s.point = IrPoint{frame.t_ns, found.led->x, found.led->y, found.led->area_px, -1};
    last_point_ = s.point;
    last_blob_ = found.led;
    last_seen_ns_ = frame.t_ns;
    if (!tracking_) {
      tracking_ = true;
      ++counters_.regained;
      s.event = IrTrackerEvent::regained;
    }
    return s;
  }
  if (std::optional<wiimote::LedSample> lost = poll(frame.t_ns)) return lost;
  return s;  // a frame without the LED: its time, no point
}

std::optional<wiimote::LedSample> CameraTracker::poll(Nanos now_ns) {
  if (!tracking_ || !last_seen_ns_ || now_ns - *last_seen_ns_ < lost_after_ns_) return std::nullopt;
  return lose(now_ns);
}

std::optional<wiimote::LedSample> CameraTracker::lose(Nanos now_ns) {
  if (!tracking_) return std::nullopt;
  tracking_ = false;
  ++counters_.lost;
  finder_.reset();
  wiimote::LedSample s;
  s.t_ns = now_ns;
  s.event = IrTrackerEvent::lost;
  return s;
}

}  // namespace mallet::input::camera
