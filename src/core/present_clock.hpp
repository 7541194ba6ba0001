#pragma once
// When a picture reaches the screen. The bounce is evaluated at the present time of the
// frame that shows it (Eq. 1 on the time since the impact), and with [timing] align =
// "picture" the actuator and the note are scheduled to be heard together with the first
// frame that shows a strike. Both ask this clock, so the two can never disagree.
//
// The model, per present mode (frames are recorded right after the previous one's acquire):
//  * fifo: frame starts follow the display's refresh grid; a frame started at s is on
//    screen at s + 2 periods (it waits behind the frame already queued, then for vblank);
//  * mailbox: the next frame starts within one frame's cost and is shown at the first
//    refresh after it is done;
//  * immediate: shown as soon as it is done (tearing).
// The grid's period and phase are learnt from the frame starts the window reports
// (frame_started); without a window (simulate --causal) they come from --display-hz. A
// FIFO swapchain whose frames come much faster than the display's refresh is not paced by
// it (a virtual X server: no vblank at all): its frames are shown as soon as they are done,
// one frame's work after they start (measured with bench latency: 2–7 ms, not two
// refreshes). Whether the display paces is judged once, from the first kJudgedFrames frames
// drawn back to back that tell, by their own pace: the interval between frame starts less the
// time the window's frame budget (core/frame_pacer.hpp) held the frame back (the window holds
// none back until the verdict). A display that paces FIFO shows no frame sooner than its
// refresh, but for the few a new swapchain's free images take at once; a display that does
// not shows most of them sooner. A frame as long as the refresh votes "paced" only when
// waiting on the display (the swapchain's acquire and present) made it so: one that was slow
// by its own work (a CPU rasteriser's first frames, a full redraw at 1080p) says nothing of
// the display and does not vote, so a slow start can no longer make a virtual display look
// paced one run and not the next. The verdict then stands until the pacing or the refresh
// changes, so that the frame budget it engages can never make the display look paced (nor
// the frames it holds back make it look unpaced), and one display gets one verdict, run
// after run. Before it, a running estimate of the frames' own pace stands in.
// Written by the render thread, read by the input threads: every field is one atomic.
#include <atomic>
#include <string>
#include <string_view>

#include "core/enum_names.hpp"
#include "core/time.hpp"

namespace mallet {

enum class PresentPacing { fifo, mailbox, immediate };
inline constexpr EnumNames<PresentPacing, 3> kPresentPacingNames{
    {{PresentPacing::fifo, "fifo"}, {PresentPacing::mailbox, "mailbox"}, {PresentPacing::immediate, "immediate"}}};

const char* to_string(PresentPacing p);
//! "fifo", "mailbox" or "immediate"; nothing for any other text.
std::optional<PresentPacing> parse_present_pacing(std::string_view text);

class PresentClock {
 public:
  explicit PresentClock(double refresh_hz = 60.0, PresentPacing pacing = PresentPacing::fifo,
                        Nanos frame_cost_ns = 3'000'000);

  //! The render thread: a frame began recording at `t` (after its acquire), `held_ns` of
  //! the interval since the previous start spent waiting for the frame budget's slot.
  //! Refines the grid's phase and, from that interval, its period; and from the interval
  //! less the wait, whether the display paces the frames.
  //! `learn` false: the previous start drew nothing (a still scene: no acquire, no present
  //! held it back), so the interval says nothing of the display; the grid is only anchored.
  //! `display_wait_ns`: how long the previous frame waited in the swapchain's acquire and
  //! present (WindowTarget::display_wait_ns); a frame as long as the refresh votes "paced"
  //! only if that wait made it so. Negative: not known, and such a frame votes "paced".
  void frame_started(Nanos t, Nanos held_ns = 0, bool learn = true, Nanos display_wait_ns = -1);
  //! Another pacing or refresh than before: the display is judged again.
  void set_pacing(PresentPacing pacing);
  void set_refresh_hz(double hz);

  //! When the frame that begins recording at `start` reaches the screen.
  Nanos present_of_frame_started(Nanos start) const;
  //! The present time of the first frame that can show something decided at `t` and is
  //! on screen no earlier than `not_before` (a predicted strike's contact time).
  Nanos first_shown(Nanos t, Nanos not_before) const;

  Nanos period_ns() const { return period_ns_.load(std::memory_order_relaxed); }
  //! The first frame start on the grid at or after `t`: where a loop that drew nothing
  //! waits for its next frame, in step with the display.
  Nanos next_start(Nanos t) const;
  //! FIFO frames that would come at under 85 % of the refresh period, were the frame
  //! budget not holding them back (a display that paces FIFO never shows them faster than
  //! its refresh): nothing paces them.
  bool unpaced() const;
  //! Frames drawn back to back that the verdict on a FIFO display is drawn from; of them,
  //! more than kFastAllowed coming sooner than 85 % of the refresh period: not paced.
  static constexpr int kJudgedFrames = 48;
  static constexpr int kFastAllowed = kJudgedFrames / 4;
  //! Whether the display has been judged (always, but for FIFO before kJudgedFrames votes).
  bool judged() const;
  //! Of the FIFO frames seen before the verdict, those slow by their own work: no vote.
  int unvoted_frames() const { return unvoted_.load(std::memory_order_relaxed); }
  //! Of the judged frames, how many came sooner than 85 % of the refresh period (for the log).
  int fast_frames() const { return fast_.load(std::memory_order_relaxed); }
  PresentPacing pacing() const { return static_cast<PresentPacing>(pacing_.load(std::memory_order_relaxed)); }
  //! "fifo, 60.0 Hz (measured 16.7 ms)": for the operator page.
  std::string describe() const;

 private:

  std::atomic<int> pacing_;
  std::atomic<Nanos> period_ns_;
  std::atomic<Nanos> refresh_ns_;      //!< the display's nominal refresh period
  std::atomic<Nanos> last_start_{-1};  //!< the latest frame start: the grid's anchor (0 before any)
  std::atomic<Nanos> unheld_ns_;  //!< the frame interval without the frame budget's wait, smoothed
  std::atomic<int> judged_{0};    //!< frames judged so far (kJudgedFrames: the verdict is in)
  std::atomic<int> fast_{0};      //!< of them, those sooner than 85 % of the refresh period
  std::atomic<int> unvoted_{0};   //!< frames slow by their own work before the verdict
  const Nanos cost_ns_;  //!< one frame's work (mailbox, immediate)
  static_assert(std::atomic<Nanos>::is_always_lock_free);
};

}  // namespace mallet
