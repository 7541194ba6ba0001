#include "core/ir_tracker.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace mallet {

namespace {

constexpr double kCentreX = 511.5;
constexpr double kCentreY = 383.5;

double distance(const IrPoint& a, const IrPoint& b) { return std::hypot(a.x - b.x, a.y - b.y); }

//! The acquiring rule: largest, then nearest the centre, then lowest slot (the loop order).
bool better_to_acquire(const IrPoint& a, const IrPoint& b) {
  if (a.size != b.size) return a.size > b.size;
  return std::hypot(a.x - kCentreX, a.y - kCentreY) < std::hypot(b.x - kCentreX, b.y - kCentreY);
}

}  // namespace

Check validate(const IrTrackerConfig& c) {
  if (!std::isfinite(c.max_speed_px_per_s) || !(c.max_speed_px_per_s > 0))
    return refused("max_speed_px_per_s must be a finite number > 0");
  if (!std::isfinite(c.jump_slack_px) || c.jump_slack_px < 0)
    return refused("jump_slack_px must be a finite number >= 0");
  if (c.reacquire_after_frames < 1) return refused("reacquire_after_frames must be >= 1");
  if (!std::isfinite(c.lost_after_ms) || !(c.lost_after_ms > 0))
    return refused("lost_after_ms must be a finite number > 0");
  return {};
}

const char* to_string(IrTrackerEvent event) { return name_in(kIrTrackerEventNames, event); }

IrTracker::IrTracker(IrTrackerConfig config) : config_(config) {
  if (const Check why = validate(config_); !why) throw std::invalid_argument("IR tracker: " + why.error());
}

void IrTracker::reset() {
  last_.reset();
  jump_.reset();
  jump_frames_ = 0;
}

IrTrackerEvent IrTracker::poll(Nanos now_ns) {
  if (!last_) return IrTrackerEvent::none;
  // Nanosecond difference → ms: exact enough at any uptime.
  if (to_seconds(now_ns - last_->t_ns) * 1e3 < config_.lost_after_ms) return IrTrackerEvent::none;
  reset();
  ++counters_.lost;
  return IrTrackerEvent::lost;
}

IrTrackerUpdate IrTracker::update(const IrFrame& frame) {
  IrTrackerUpdate out;
  if (last_frame_ns_ && frame.t_ns <= *last_frame_ns_) {
    ++counters_.ignored_not_after_previous;
    return out;
  }
  last_frame_ns_ = frame.t_ns;
  ++counters_.frames;

  IrPoint dots[4];
  int n = 0;
  for (int slot = 0; slot < 4; ++slot) {
    const std::optional<IrDot>& d = frame.slots[static_cast<std::size_t>(slot)];
    if (!d) continue;
    if (d->x < 0 || d->x > 1023 || d->y < 0 || d->y > 767) {
      ++counters_.ignored_off_sensor;
      continue;
    }
    if (d->x == 0 && d->y == 0) {
      ++counters_.ignored_zero_dots;
      continue;
    }
    // A size outside the camera's 0..15 is garbage: keep the position, forget the size.
    const int size = (d->size >= 0 && d->size <= 15) ? d->size : -1;
    dots[n++] = {frame.t_ns, double(d->x), double(d->y), size, slot};
  }
  if (n == 0) ++counters_.frames_without_dot;

  if (!last_) {  // acquiring
    if (n == 0) return out;
    int best = 0;
    for (int i = 1; i < n; ++i)
      if (better_to_acquire(dots[i], dots[best])) best = i;
    last_ = last_accepted_ = out.point = dots[best];
    ++counters_.accepted;
    ++counters_.regained;
    out.event = IrTrackerEvent::regained;
    return out;
  }

  // Tracking: the nearest dot, if it could have got there since the last accepted one.
  int nearest = -1;
  for (int i = 0; i < n; ++i)
    if (nearest < 0 || distance(dots[i], *last_) < distance(dots[nearest], *last_)) nearest = i;
  const double since_s = to_seconds(frame.t_ns - last_->t_ns);
  if (nearest >= 0 && distance(dots[nearest], *last_) <= config_.max_speed_px_per_s * since_s + config_.jump_slack_px) {
    last_ = last_accepted_ = out.point = dots[nearest];
    jump_.reset();
    jump_frames_ = 0;
    ++counters_.accepted;
    return out;
  }

  if (n > 0) {
    ++counters_.rejected_jumps;
    // Does an implausible dot persist? Follow the jump candidate if it moved plausibly,
    // otherwise start a new candidate by the acquiring rule.
    int pick = -1;
    if (jump_) {
      const double since_jump_s = to_seconds(frame.t_ns - jump_->t_ns);
      for (int i = 0; i < n; ++i)
        if (distance(dots[i], *jump_) <= config_.max_speed_px_per_s * since_jump_s + config_.jump_slack_px &&
            (pick < 0 || distance(dots[i], *jump_) < distance(dots[pick], *jump_)))
          pick = i;
    }
    if (pick >= 0) {
      ++jump_frames_;
    } else {
      pick = 0;
      for (int i = 1; i < n; ++i)
        if (better_to_acquire(dots[i], dots[pick])) pick = i;
      jump_frames_ = 1;
    }
    jump_ = dots[pick];
    if (jump_frames_ >= config_.reacquire_after_frames) {
      last_ = last_accepted_ = out.point = *jump_;
      jump_.reset();
      jump_frames_ = 0;
      ++counters_.accepted;
      ++counters_.jumps_followed;
      out.event = IrTrackerEvent::jumped;
      return out;
    }
  } else {
    // A frame with no dot breaks a persisting jump: it must be seen in consecutive frames.
    jump_.reset();
    jump_frames_ = 0;
  }
  if (poll(frame.t_ns) == IrTrackerEvent::lost) out.event = IrTrackerEvent::lost;
  return out;
}

}  // namespace mallet
