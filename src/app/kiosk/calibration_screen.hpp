#pragma once
// The kiosk's auto-calibration screen: core's CalibrationSession (targets one by one, dwell,
// unstable windows rejected, homography fit, accept under the error threshold or repeat the
// worst targets) with its pictures — the current target with its progress ring, the targets
// done, the reprojection error of the last round — and, once accepted, the atomic save.
//
// Fed on the main thread with the IR dot's raw camera position (the Wii Remote) or with a
// stand-in for it (the mouse: the operator's test of the screen; then nothing is saved and
// the remote's calibration is left alone). The previous calibration file stays until a new
// one is accepted and written.
//
// With the remote, the screen first picks the IR camera's sensitivity (core's
// SensitivityTuner: the least sensitive preset that shows the LED as one clean dot of a
// sane size): the visitor holds the light up while presets are tried; the kiosk sets each
// on the camera when sensitivity_request() says so. If none is clean, the configured one
// is put back and the targets come anyway (the reason is shown).
#include <filesystem>
#include <optional>
#include <string>

#include "core/result.hpp"
#include "core/calibration_session.hpp"
#include "core/sensitivity_tuner.hpp"
#include "render/overlay.hpp"

namespace mallet::app {

//! The mouse as a stand-in IR dot: normalised screen → the camera's 1024×768 pixels.
inline Vec2 mouse_as_camera_px(Vec2 screen) { return {screen.x * 1023.0, screen.y * 767.0}; }

class CalibrationScreen {
 public:
  enum class Outcome { measuring, accepted, failed };

  //! `save_to`: where an accepted calibration is written (nothing: not saved, the mouse).
  //! `remote`: the remote's identity stored in the file. Throws std::invalid_argument on a
  //! bad session config.
  CalibrationScreen(CalibrationSessionConfig config, std::optional<std::filesystem::path> save_to,
                    std::string remote);

  //! Starts with the sensitivity phase; `configured` is the preset to put back on failure.
  void tune_sensitivity(SensitivityTunerConfig config, std::string configured);
  bool tuning() const { return tuner_.has_value() && !tuner_->done(); }
  //! One IR frame (every report) during the sensitivity phase; ignored while a preset asked
  //! for waits to be taken by sensitivity_request(): the camera still runs the previous one.
  void frame(const IrFrame& frame);
  //! A preset the camera must switch to now (once per change), then nothing.
  std::optional<std::string> sensitivity_request();
  //! The preset the phase chose (or put back), once it is over.
  const std::string& sensitivity() const { return sensitivity_; }

  //! One position of the dot (raw camera pixels) at t; ignored while tuning. `may_measure`:
  //! as CalibrationSession::feed.
  CalibrationStep feed(Nanos t_ns, Vec2 camera_px, bool may_measure = true);
  //! The mouse standing in for the dot, at `screen` (normalised): a target is measured only
  //! while the pointer holds still on its ring, never wherever the mouse happens to rest.
  CalibrationStep feed_pointer(Nanos t_ns, Vec2 screen);
  //! Whether the remote (or the camera: `camera`) is connected: without it the screen says
  //! so and what to do, instead of waiting for a light that cannot come.
  void link(bool up, bool camera) {
    link_up_ = up;
    camera_ = camera;
  }
  //! The dot is lost (or the remote is): only shown.
  void dot_seen(bool seen) { dot_seen_ = seen; }

  Outcome outcome() const { return outcome_; }
  //! The new calibration once accepted (and, with save_to, written).
  const std::optional<Calibration>& result() const { return result_; }
  //! One line for the screen after the end: the accepted error and where it went, or why it
  //! failed (the previous calibration stays).
  const std::string& message() const { return message_; }
  //! Whether an accepted calibration was to be written to save_to and how that went: none
  //! when nothing was to be written (not accepted, or no save_to); else the write's outcome
  //! (its refusal: why, one line), for the state folder's report.
  const std::optional<Check>& saved() const { return saved_; }
  const CalibrationSession& session() const { return session_; }

  //! The line under the targets: which target is being measured and in which round, and
  //! whether the dot is seen; once over, message().
  std::string status_line() const;

  //! The screen's pictures over a width×height window.
  void draw(render::Overlay& overlay, float width, float height) const;

 private:
  void accept();

  CalibrationSession session_;
  std::optional<std::filesystem::path> save_to_;
  std::string remote_;
  Outcome outcome_ = Outcome::measuring;
  std::optional<Calibration> result_;
  std::string message_;
  std::optional<Check> saved_;
  std::string last_round_;  //!< the last rejected round's errors, shown while repeating
  std::optional<SensitivityTuner> tuner_;
  std::string configured_, sensitivity_, tuner_note_;
  bool sensitivity_chosen_ = false;  //!< the tuner found one (not: kept the configured one)
  std::optional<std::string> request_;
  bool dot_seen_ = false;
  bool link_up_ = true, camera_ = false;
  bool pointer_on_ring_ = false;  //!< the mouse: its pointer on the current target's ring
};

}  // namespace mallet::app
