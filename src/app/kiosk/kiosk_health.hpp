#pragma once
// The kiosk's health: whether it lives, said to systemd and the journal, and what it counts
// for the operators' dashboards.
//
// Liveness: systemd's watchdog is fed only while input, audio and render all make progress
// (the main loop's polls, the audio callbacks or a supervised lost device, frames drawn or
// decided still); why it goes hungry is said once per stall. A heartbeat line a minute
// (state, frames, strikes, audio callbacks, xruns). [metrics]: the frames, states, tracking,
// strikes, xruns, device memory and the remote's battery into the Prometheus file
// (metrics_file.hpp) when due, counts kept across reloads. The state folder
// (state_folder.hpp): its writes, and whether they fail, said once.
#include <cstdint>

#include "app/kiosk/kiosk_stage.hpp"
#include "app/kiosk/metrics_file.hpp"
#include "app/kiosk/state_folder.hpp"
#include "app/kiosk/systemd_notify.hpp"
#include "core/data_paths.hpp"
#include "core/journal.hpp"
#include "core/kiosk_metrics.hpp"
#include "core/kiosk_states.hpp"
#include "core/time.hpp"
#include "render/render_setup.hpp"

namespace mallet::app {

class KioskHealth {
 public:
  explicit KioskHealth(Nanos started);

  SystemdNotifier& notifier() { return notifier_; }
  KioskMetrics& metrics() { return metrics_; }
  MetricsFile& metrics_file() { return metrics_file_; }
  //! The state folder: every write of the kiosk into it (calibration, last good settings,
  //! counters, visitor results) goes through it or reports to it.
  StateFolder& state() { return state_; }
  const StateFolder& state() const { return state_; }
  Nanos started() const { return started_; }

  //! The main loop went round (input polled); a frame was drawn; one was decided still.
  void polled() { ++polls_; }
  void frame_drawn() { ++frames_; }
  void frame_still() { ++still_frames_; }
  std::uint64_t frames() const { return frames_; }
  //! READY=1: at start-up once the frames cost what they will (WindowKiosk::run), and after
  //! each reload. systemd arms the watchdog only at the first, so none is fed before it:
  //! READY=1 is the first word it hears.
  void ready() {
    notifier_.ready();
    ready_ = true;
  }
  bool said_ready() const { return ready_; }

  //! Once a loop: the watchdog and the heartbeat when due, the frame, the state and the
  //! tracking into the metrics, and the file when due.
  void beat(Nanos now, const KioskStage& stage, const KioskStates& states, const render::ProductWindow& win);
  //! The watchdog fed when due, unconditionally: the study's frames are the kiosk's life
  //! while a visitor's session holds the window.
  void feed_watchdog(Nanos now);
  //! The stage's audio output is closed (a visitor's session, a reload): its xruns kept,
  //! and the next output's callbacks counted from 0.
  void output_closed(const KioskStage& stage);
  //! A stage was built: its scene's strike labels counted from 0, [metrics] as it says.
  void stage_built(const KioskStage& stage) {
    seed_strike_labels(stage.scene, strikes_retired_);
    metrics_file_.configure(stage.config.metrics);
  }
  //! A reload replaces `old`: its strikes and xruns are kept (its input threads have stopped).
  void retire(const KioskStage& old);
  //! Strikes delivered since start, over every route and every reload.
  std::uint64_t strikes(const KioskStage& stage) const;
  void write_metrics(Nanos now, const KioskStage& stage, const render::ProductWindow& win);
  //! The end: STOPPING=1, the closing line, the final metrics.
  void stop(Nanos now, const KioskStage& stage, const render::ProductWindow& win);

 private:
  void heartbeat(Nanos now, const KioskStage& stage, const KioskStates& states);
  void feed_metrics(Nanos now, const KioskStage& stage, const KioskStates& states, const render::ProductWindow& win);

  Nanos started_;
  SystemdNotifier notifier_ = SystemdNotifier::from_environment();
  Nanos next_watchdog_ = 0, next_log_;
  bool starving_ = false;  //!< the watchdog was not fed at the last beat
  bool ready_ = false;     //!< READY=1 said
  std::uint64_t frames_ = 0, frames_at_beat_ = 0, polls_ = 0, polls_at_beat_ = 0;
  std::uint64_t still_frames_ = 0;  //!< frames not drawn: nothing on the screen would have changed
  std::uint64_t callbacks_at_beat_ = 0;
  std::uint64_t strikes_before_ = 0;  //!< by the stages a reload replaced
  KioskMetrics metrics_;
  StateFolder state_{state_dir(), [](const std::string& line) { journal::warning("{}", line.c_str()); },
                     [](const std::string& line) { journal::notice("{}", line.c_str()); }};
  MetricsFile metrics_file_{&state_, [](const std::string& line) { journal::warning("{}", line.c_str()); },
                            [](const std::string& line) { journal::notice("{}", line.c_str()); }};
  StrikeCounts strikes_retired_;      //!< by the stages a reload replaced (and a zero per scene's label)
  std::uint64_t xruns_retired_ = 0;   //!< by the audio outputs a reload replaced
  Nanos metrics_frame_at_;            //!< the last drawn frame's time
};

}  // namespace mallet::app
