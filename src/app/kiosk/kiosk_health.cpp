#include "app/kiosk/kiosk_health.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>

#include "core/journal.hpp"
#include "render/vk_handle.hpp"

namespace mallet::app {

KioskHealth::KioskHealth(Nanos started)
    : started_(started), next_log_(started + 60 * kNanosPerSecond), metrics_frame_at_(started) {}

void KioskHealth::feed_watchdog(Nanos now) {
  const Nanos interval = notifier_.watchdog_interval().value_or(0);
  if (interval > 0 && now >= next_watchdog_) {
    notifier_.watchdog();
    next_watchdog_ = now + interval;
  }
}

void KioskHealth::output_closed(const KioskStage& stage) {
  if (stage.output) xruns_retired_ += stage.output->counters().xruns;
  callbacks_at_beat_ = 0;  // the next output's callbacks count from 0
}

void KioskHealth::beat(Nanos now, const KioskStage& stage, const KioskStates& states,
                       const render::ProductWindow& win) {
  heartbeat(now, stage, states);
  feed_metrics(now, stage, states, win);
}

void KioskHealth::stop(Nanos now, const KioskStage& stage, const render::ProductWindow& win) {
  // No STOPPING=1 here: see run_window_kiosk.
  journal::info("mallet run: stopping after {} frames and {} strikes", frames_, strikes(stage));
  if (metrics_file_.enabled()) write_metrics(now, stage, win);  // the final counts, as the line above
}

std::uint64_t KioskHealth::strikes(const KioskStage& stage) const {
  return strikes_before_ + stage.route->strikes() + (stage.remote ? stage.remote->strikes() : 0) +
         (stage.mouse ? stage.mouse->strikes() : 0);
}

void KioskHealth::heartbeat(Nanos now, const KioskStage& stage, const KioskStates& states) {
  const Nanos interval = notifier_.watchdog_interval().value_or(0);
  const bool beat_due = ready_ && interval > 0 && now >= next_watchdog_;
  const bool log_due = now >= next_log_;
  if (!beat_due && !log_due) return;
  const audio::OutputCounters a = stage.output ? stage.output->counters() : audio::OutputCounters{};
  // Audio is alive when its callbacks advance, or when its supervisor is retrying a lost
  // device (that is survived, silently), or when the kiosk runs without a device at all.
  const bool audio_alive =
      !stage.output || a.callbacks > callbacks_at_beat_ || !stage.output->device_ok();
  // A still scene draws no frames; its loop still decides each one.
  const bool render_alive = frames_ + still_frames_ > frames_at_beat_;
  // A remote that is gone is survived (attract, hint, reconnect): the main loop's polls
  // stand for input; the reading thread never blocks for long by design.
  const bool input_alive = polls_ > polls_at_beat_;
  if (beat_due) {
    const bool alive = audio_alive && render_alive && input_alive;
    if (alive) notifier_.watchdog();
    // Why the watchdog goes hungry, said once per stall: systemd's own line only says that it
    // fired (`mallet doctor` shows this line as the watchdog's last reason).
    if (!alive && !starving_)
      journal::warning("watchdog not fed: {}{}{} stalled", render_alive ? "" : "render ", audio_alive ? "" : "audio ",
                       input_alive ? "" : "input");
    starving_ = !alive;
    next_watchdog_ = now + interval;
  }
  if (log_due) {
    journal::info("heartbeat: {}, frames {}, strikes {}, audio callbacks {}, xruns {}{}", to_string(states.state()),
                  frames_, strikes(stage), a.callbacks, a.xruns,
                  stage.output && !stage.output->device_ok() ? ", audio device lost (retrying)" : "");
    next_log_ = now + 60 * kNanosPerSecond;
  }
  frames_at_beat_ = frames_ + still_frames_;
  polls_at_beat_ = polls_;
  callbacks_at_beat_ = a.callbacks;
}

void KioskHealth::feed_metrics(Nanos now, const KioskStage& stage, const KioskStates& states,
                               const render::ProductWindow& win) {
  if (frames_ > metrics_.frames()) {  // this iteration drew a frame (at most one)
    metrics_.count_frame(now - metrics_frame_at_);
    metrics_frame_at_ = now;
  } else if (win.window->still()) {
    metrics_frame_at_ = now;  // a still scene's gap between drawn frames is not a slow frame
  }
  metrics_.observe_state(states.state(), states.since(), states.last_movement());
  // Lost only where it matters: a visitor plays, the remote runs, its camera sees no LED.
  metrics_.observe_tracking((stage.device || stage.camera) && stage.link.up() && states.visitor_plays() && !states.tracking(), now);
  if (metrics_file_.due(now)) write_metrics(now, stage, win);
}

void KioskHealth::write_metrics(Nanos now, const KioskStage& stage, const render::ProductWindow& win) {
  constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
  metrics_.strikes = strikes_retired_;
  stage.tally->add_to(metrics_.strikes);
  metrics_.audio_xruns = xruns_retired_ + (stage.output ? stage.output->counters().xruns : 0);
  metrics_.audio_output_latency_s = stage.output ? stage.output->output_latency_s() : kUnknown;
  metrics_.vulkan_device_memory_bytes = static_cast<double>(render::device_memory_bytes());
  metrics_.render_devices_lost = win.devices_lost();
  metrics_.remote_connected = (stage.device || stage.camera) && stage.link.up();
  metrics_.remote_battery_ratio = kUnknown;
  if (stage.device)
    if (const std::optional<std::uint8_t> b = stage.device->state().remote.battery)
      metrics_.remote_battery_ratio = std::min(1.0, *b / 200.0);  // 0xC8 on fresh cells (reports.hpp)
  metrics_.settings_refused = !stage.refused.empty();
  metrics_.state_folder_writable = !state_.failing();
  metrics_.uptime_ns = now - started_;
  metrics_.version = mallet_version();
  metrics_file_.write(metrics_, now);
}

void KioskHealth::retire(const KioskStage& old) {
  strikes_before_ = strikes(old);
  old.tally->add_to(strikes_retired_);  // its input threads have stopped: the counts are final
  if (old.output) xruns_retired_ += old.output->counters().xruns;
}

}  // namespace mallet::app
