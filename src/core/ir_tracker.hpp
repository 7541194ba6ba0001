#pragma once
// Picks the stick's IR LED among the up-to-four dots the Wii Remote's camera reports, and
// says when the LED is lost and found again.
//
// Rules (in the order they are applied to each IrFrame):
//  * A slot is a candidate only if it lies on the sensor (x 0..1023, y 0..767) and is not
//    the spurious (0,0) dot some remotes report. Anything else is ignored and counted.
//  * Acquiring (nothing tracked yet, or tracking was lost): the largest dot wins; equal
//    sizes (and basic mode, which has no size) go to the dot nearest the camera's centre,
//    then to the lowest slot. The LED on the stick is the nearest, strongest source; a
//    reflection is smaller and, in the kiosk's setup, off to the side.
//  * Tracking: the dot nearest the last accepted position wins, if it could have got there:
//    distance ≤ max_speed_px_per_s · (time since the last accepted dot) + jump_slack_px.
//    A farther dot is an implausible jump (a reflection, another IR source) and is
//    rejected — unless such a jump persists: when `reacquire_after_frames` consecutive
//    frames show no plausible dot but a dot that moves plausibly from frame to frame, the
//    tracker follows it (the LED really is there; what it followed was not the LED).
//  * Lost: no accepted dot for `lost_after_ms`. Frames keep arriving while the camera sees
//    nothing, but a silent remote sends none: `poll(now)` checks the time-out without a frame.
//  * Frames whose time is not after the previous frame's are ignored and counted.
//
// Output: raw camera coordinates and the frame's time; calibration maps them to the screen.
#include <cstdint>
#include <optional>
#include <string>

#include "core/enum_names.hpp"
#include "core/ir_dot.hpp"
#include "core/result.hpp"
#include "core/time.hpp"

namespace mallet {

struct IrTrackerConfig {
  //! Fastest plausible LED motion on the sensor. 10000 px/s ≈ 8 m/s at 0.82 mm per pixel
  //! (the default scene's 0.84 m wide view over 1024 px); a hard strike is 1–4 m/s.
  double max_speed_px_per_s = 10000.0;
  double jump_slack_px = 8.0;      //!< allowed on top of the speed bound (noise, blob centroid)
  int reacquire_after_frames = 3;  //!< consecutive frames an implausible jump must persist
  double lost_after_ms = 150.0;    //!< no accepted dot for this long = tracking lost
};

//! Passes when `config` is usable; otherwise fails with one line naming the bad key and why.
Check validate(const IrTrackerConfig& config);

//! The tracked LED in raw camera coordinates.
struct IrPoint {
  Nanos t_ns = 0;
  double x = 0;  //!< 0..1023, as the camera reports it (no mirroring)
  double y = 0;  //!< 0..767
  int size = -1;
  int slot = -1;  //!< which of the four slots it came from
};

enum class IrTrackerEvent {
  none,
  regained,  //!< tracking started: the first dot ever, or the first after `lost`
  lost,      //!< no accepted dot for lost_after_ms
  jumped,    //!< an implausible jump persisted; the tracker now follows the new dot
};
inline constexpr EnumNames<IrTrackerEvent, 4> kIrTrackerEventNames{{
    {IrTrackerEvent::none, "none"}, {IrTrackerEvent::regained, "regained"}, {IrTrackerEvent::lost, "lost"},
    {IrTrackerEvent::jumped, "jumped"}}};

const char* to_string(IrTrackerEvent event);

struct IrTrackerUpdate {
  std::optional<IrPoint> point;  //!< the LED in this frame, if one was accepted
  IrTrackerEvent event = IrTrackerEvent::none;
};

class IrTracker {
 public:
  struct Counters {
    std::uint64_t frames = 0;
    std::uint64_t accepted = 0;
    std::uint64_t frames_without_dot = 0;    //!< no candidate slot at all
    std::uint64_t ignored_zero_dots = 0;     //!< the spurious (0,0) dot
    std::uint64_t ignored_off_sensor = 0;    //!< a slot outside 0..1023 × 0..767 (garbage)
    std::uint64_t ignored_not_after_previous = 0;
    std::uint64_t rejected_jumps = 0;        //!< frames whose only dots were implausibly far
    std::uint64_t jumps_followed = 0;
    std::uint64_t lost = 0;
    std::uint64_t regained = 0;
  };

  //! Throws std::invalid_argument when validate(config) fails.
  explicit IrTracker(IrTrackerConfig config = {});

  IrTrackerUpdate update(const IrFrame& frame);

  //! Time passes without frames (a silent remote): reports `lost` once the time-out ran out.
  IrTrackerEvent poll(Nanos now_ns);

  bool tracking() const { return last_.has_value(); }
  //! The last accepted LED position (kept after `lost`, for display), if any.
  std::optional<IrPoint> last_point() const { return last_accepted_; }
  const IrTrackerConfig& config() const { return config_; }
  const Counters& counters() const { return counters_; }
  void reset();  //!< back to acquiring; counters are kept

 private:
  IrTrackerConfig config_;
  std::optional<IrPoint> last_;           //!< set while tracking
  std::optional<IrPoint> last_accepted_;  //!< survives `lost`
  std::optional<IrPoint> jump_;           //!< the persisting implausible dot, if any
  int jump_frames_ = 0;
  std::optional<Nanos> last_frame_ns_;
  Counters counters_;
};

}  // namespace mallet
