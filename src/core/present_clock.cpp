#include "core/present_clock.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

namespace mallet {

const char* to_string(PresentPacing p) { return name_in(kPresentPacingNames, p, "fifo"); }

std::optional<PresentPacing> parse_present_pacing(std::string_view text) {
  return value_named(kPresentPacingNames, text);
}

namespace {
Nanos period_of(double hz) { return static_cast<Nanos>(std::llround(1e9 / std::clamp(hz, 1.0, 1000.0))); }
}  // namespace

PresentClock::PresentClock(double refresh_hz, PresentPacing pacing, Nanos frame_cost_ns)
    : pacing_(static_cast<int>(pacing)),
      period_ns_(period_of(refresh_hz)),
      refresh_ns_(period_of(refresh_hz)),
      unheld_ns_(period_of(refresh_hz)),
      cost_ns_(frame_cost_ns) {}

void PresentClock::set_pacing(PresentPacing pacing) {
  if (pacing_.exchange(static_cast<int>(pacing), std::memory_order_relaxed) == static_cast<int>(pacing)) return;
  judged_.store(0, std::memory_order_relaxed);
  fast_.store(0, std::memory_order_relaxed);
  unvoted_.store(0, std::memory_order_relaxed);
}

void PresentClock::set_refresh_hz(double hz) {
  if (refresh_ns_.load(std::memory_order_relaxed) != period_of(hz)) {
    judged_.store(0, std::memory_order_relaxed);
    fast_.store(0, std::memory_order_relaxed);
    unvoted_.store(0, std::memory_order_relaxed);
  }
  period_ns_.store(period_of(hz), std::memory_order_relaxed);
  refresh_ns_.store(period_of(hz), std::memory_order_relaxed);
  unheld_ns_.store(period_of(hz), std::memory_order_relaxed);
}

namespace {
//! Sooner than 85 % of the refresh period: more than a display that paces FIFO ever shows.
bool faster_than_refresh(Nanos interval, Nanos refresh) { return interval * 20 < refresh * 17; }
}  // namespace

bool PresentClock::judged() const {
  return pacing() != PresentPacing::fifo || judged_.load(std::memory_order_relaxed) >= kJudgedFrames;
}

bool PresentClock::unpaced() const {
  if (pacing() != PresentPacing::fifo) return false;
  if (judged()) return fast_.load(std::memory_order_relaxed) > kFastAllowed;
  // Before the verdict: the votes so far; with none, frames slow by their own work that no
  // display held are shown when done, as an unpaced display shows them; else the pace.
  const int votes = judged_.load(std::memory_order_relaxed), fast = fast_.load(std::memory_order_relaxed);
  if (votes > 0) return fast * 2 > votes;
  if (unvoted_.load(std::memory_order_relaxed) > 0) return true;
  return faster_than_refresh(unheld_ns_.load(std::memory_order_relaxed), refresh_ns_.load(std::memory_order_relaxed));
}

void PresentClock::frame_started(Nanos t, Nanos held_ns, bool learn, Nanos display_wait_ns) {
  const Nanos last = last_start_.exchange(t, std::memory_order_relaxed);
  if (!learn || last < 0 || t <= last) return;
  // The period follows the measured frame interval slowly (a display that does not pace
  // FIFO, such as a virtual X server, shows frames as fast as they come), and so does the
  // frames' own pace, the interval less the frame budget's wait. A frame that took several
  // times the frames' own pace (a hiccup, a minimised window) tells neither; a wait the
  // budget added does not make one.
  const Nanos period = period_ns_.load(std::memory_order_relaxed);
  const Nanos unheld = unheld_ns_.load(std::memory_order_relaxed);
  const Nanos interval = t - last;
  const Nanos own = std::max<Nanos>(0, interval - held_ns);
  if (own > 3 * unheld) return;
  if (pacing() == PresentPacing::fifo && judged_.load(std::memory_order_relaxed) < kJudgedFrames) {
    const Nanos refresh = refresh_ns_.load(std::memory_order_relaxed);
    if (faster_than_refresh(own, refresh)) {
      fast_.fetch_add(1, std::memory_order_relaxed);
      judged_.fetch_add(1, std::memory_order_relaxed);
    } else if (display_wait_ns < 0 || faster_than_refresh(own - display_wait_ns, refresh)) {
      judged_.fetch_add(1, std::memory_order_relaxed);  // the display held it to its refresh
    } else {
      unvoted_.fetch_add(1, std::memory_order_relaxed);  // slow by its own work: says nothing
    }
  }
  period_ns_.store(std::max<Nanos>(500'000, period + (interval - period) / 16), std::memory_order_relaxed);
  unheld_ns_.store(std::max<Nanos>(500'000, unheld + (own - unheld) / 16), std::memory_order_relaxed);
}

Nanos PresentClock::next_start(Nanos t) const {
  const Nanos period = period_ns_.load(std::memory_order_relaxed);
  const Nanos anchor = std::max<Nanos>(0, last_start_.load(std::memory_order_relaxed));
  if (t <= anchor) return anchor;
  const Nanos k = (t - anchor + period - 1) / period;  // whole periods: exact on the int64 clock
  return anchor + k * period;
}

Nanos PresentClock::present_of_frame_started(Nanos start) const {
  const Nanos period = period_ns_.load(std::memory_order_relaxed);
  const Nanos cost = cost_ns_;
  switch (pacing()) {
    // Not paced: shown when done, one frame's work after its start (at most one period).
    case PresentPacing::fifo: return unpaced() ? start + std::min(period, cost) : start + 2 * period;
    case PresentPacing::mailbox: return next_start(start + cost);
    case PresentPacing::immediate: return start + cost;
  }
  return start + 2 * period;
}

Nanos PresentClock::first_shown(Nanos t, Nanos not_before) const {
  const Nanos period = period_ns_.load(std::memory_order_relaxed);
  // FIFO frames start on the grid; the others start as soon as the previous one is done.
  Nanos start = pacing() == PresentPacing::fifo ? next_start(t) : t;
  Nanos shown = present_of_frame_started(start);
  if (shown < not_before) {
    const Nanos frames = (not_before - shown + period - 1) / period;
    shown += frames * period;
  }
  return shown;
}

std::string PresentClock::describe() const {
  const double ms = static_cast<double>(period_ns()) * 1e-6;
  return fmt::format("{}{}, frame period {:.1f} ms ({:.1f} Hz)", to_string(pacing()),
                     unpaced() ? " (not paced by the display)" : "", ms, 1e3 / ms);
}

}  // namespace mallet
