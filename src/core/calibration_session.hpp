#pragma once
// The auto-calibration screen's logic (issue 6): targets shown one by one, each measured by
// holding the stick's IR dot still on it; then the camera → screen homography is fitted
// (fit_homography, normalised DLT) and accepted only if it reprojects well.
//
// Rules:
//  * Targets: a columns × rows grid (default 3 × 3) in normalised screen coordinates, inset by
//    the margins, in reading order; or any ≥ 4 given points.
//  * Grace before each target: when a target is shown (the session's first sample, or the
//    sample that measured the previous target) the dot is where it rested, not on the new
//    target. Its samples count for nothing (still_on_last) until the dot has left that point
//    by more than min_separation_camera_px, and then for settle_s more (settling): the stick
//    travels to the target and steadies there before the dwell starts. So a stick lying
//    still when calibration starts never measures target 1 where it lies, and the travel
//    to a target is never part of its window.
//  * Dwell: the samples of the current target since the last reset form the dwell window.
//    A sample farther than dwell_radius_camera_px from the window's mean (the dot moved or
//    jumped) starts a new window at that sample; so does a gap longer than max_gap_s (the
//    dot was lost). progress() = (last − first sample time) / dwell_s, capped at 1.
//  * When the window spans dwell_s with at least min_dwell_samples, it is judged: if the RMS
//    distance of its samples from their mean (the 2-D standard deviation) is above
//    max_std_dev_camera_px, the window is rejected as unstable and dwelling starts again;
//    otherwise the target's measured point is the window's mean and the next target comes.
//  * After a target is measured, its point is where the dot rests for the next target (the
//    grace above): a visitor still resting on the old target does not measure the new one.
//  * Samples that are not finite, or not after the previous sample, are ignored and counted.
//  * End of a round: fit all measured points. Accepted when the largest per-point
//    reprojection error (screen px, full fit) is ≤ max_error_screen_px. Otherwise the
//    repeat_worst most suspect targets are measured again, up to max_repeat_rounds more
//    rounds; then the session fails with the errors. A refused fit (e.g. points collinear)
//    repeats every target.
//  * Most suspect: the target whose removal leaves the best fit, i.e. the smallest largest
//    error of the fit of all the other targets (without_px()). The full fit spreads one
//    missed target's error over its neighbours, and so does a neighbour's leave-one-out
//    prediction, which is why neither ranks the culprit reliably; the others' fit without
//    the culprit is clean. Ties (with 5 targets every fit of the other 4 is exact) go to the
//    largest leave-one-out error (the target's error under the others' fit). With exactly 4
//    targets the fit is exact and a missed target cannot be seen: use ≥ 5 (default 9).
//  * The session returns a Calibration only once accepted; until then the kiosk keeps the
//    previous one, and saves the new one with write_calibration_file (atomic).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/calibration_file.hpp"
#include "core/enum_names.hpp"
#include "core/geometry.hpp"
#include "core/homography.hpp"
#include "core/result.hpp"
#include "core/time.hpp"

namespace mallet {

struct CalibrationSessionConfig {
  int columns = 3;          //!< target grid, ≥ 2 each way
  int rows = 3;
  double margin_x = 0.1;    //!< normalised screen units from the left and right edges
  double margin_y = 0.1;    //!< from the top and bottom edges
  double dwell_s = 1.2;     //!< how long the dot must stay still on a target
  double dwell_radius_camera_px = 8.0;   //!< farther from the window's mean = moved
  double max_std_dev_camera_px = 2.5;    //!< a steadier window than this is required
  double max_gap_s = 0.15;               //!< a longer silence restarts the dwell (as IrTracker's lost_after_ms)
  int min_dwell_samples = 10;
  //! The dot must leave where it rested when the target was shown (at first: its first
  //! sample; then: the last measured point) by this much before the target can be measured.
  double min_separation_camera_px = 30.0;
  //! The grace period after the dot has left that point, before the dwell starts: the time to
  //! carry the stick to the target and steady it. A choice, not a measurement; with dwell_s
  //! a target takes ≥ 1.7 s from leaving the previous one, and ≥ 0 is allowed (0 = only the
  //! leaving is required).
  double settle_s = 0.5;
  //! Accept when the max reprojection error is ≤ this: ≈ 0.5 % of a 1920 px screen, well under
  //! the mallet head; ±1 camera px on each point gives 2–4 px (tests/core/homography_test).
  double max_error_screen_px = 10.0;
  int repeat_worst = 1;                    //!< targets measured again after a rejected round
  int max_repeat_rounds = 3;               //!< rounds after the first before giving up
  ScreenSize screen;                       //!< the screen the errors are measured on
};

//! Passes when `config` is usable; otherwise fails with one line naming the bad key and why.
Check validate(const CalibrationSessionConfig& config);

//! The config's target grid, reading order, normalised screen coordinates.
std::vector<Vec2> calibration_grid(const CalibrationSessionConfig& config);

enum class CalibrationStatus { measuring, accepted, failed };

//! What one sample did.
enum class CalibrationStep {
  dwelling,        //!< counted towards the current target's dwell
  dwell_reset,     //!< the dot moved, jumped or was lost for a while: a new dwell starts
  unstable,        //!< a full window was too unsteady: rejected, a new dwell starts
  still_on_last,   //!< not counted: the dot has not left where it rested when the target was shown
  settling,        //!< not counted: the dot left less than settle_s ago (travelling, steadying)
  ignored,         //!< not finite, not after the previous sample, or the session is over
  target_measured, //!< the current target got its point; the next one is current
  round_rejected,  //!< the fit was not good enough (or refused): some targets come again
  accepted,        //!< calibration() now returns the new calibration
  failed,          //!< out of rounds: failure() says why, last_fit() holds the errors
};
inline constexpr EnumNames<CalibrationStep, 10> kCalibrationStepNames{{
    {CalibrationStep::dwelling, "dwelling"}, {CalibrationStep::dwell_reset, "dwell_reset"},
    {CalibrationStep::unstable, "unstable"}, {CalibrationStep::still_on_last, "still_on_last"},
    {CalibrationStep::settling, "settling"}, {CalibrationStep::ignored, "ignored"},
    {CalibrationStep::target_measured, "target_measured"}, {CalibrationStep::round_rejected, "round_rejected"},
    {CalibrationStep::accepted, "accepted"}, {CalibrationStep::failed, "failed"}}};

const char* to_string(CalibrationStep step);

class CalibrationSession {
 public:
  struct Counters {
    std::uint64_t samples = 0;
    std::uint64_t ignored = 0;
    std::uint64_t dwell_resets = 0;
    std::uint64_t unstable_windows = 0;
    std::uint64_t rounds_rejected = 0;
  };

  //! Throws std::invalid_argument when validate(config) fails, or (second form) when
  //! fewer than 4 targets are given or one is not finite.
  explicit CalibrationSession(CalibrationSessionConfig config = {});
  CalibrationSession(CalibrationSessionConfig config, std::vector<Vec2> targets);

  //! One position of the tracked IR dot, raw camera pixels. `may_measure` false: a position
  //! known to be off the target shown (the mouse standing in for the dot, away from its
  //! ring): it counts for leaving the resting point, and restarts the dwell (dwell_reset)
  //! instead of measuring the target there.
  CalibrationStep feed(Nanos t_ns, Vec2 camera_px, bool may_measure = true);

  const std::vector<Vec2>& targets() const { return targets_; }
  //! The target to show now (index into targets()), or nothing once accepted or failed.
  std::optional<int> current_target() const;
  double progress() const;  //!< 0..1, for the progress ring
  int round() const { return round_; }  //!< 0 for the first pass over all targets
  CalibrationStatus status() const { return status_; }
  //! A target's measured camera point in the current round, if it has one.
  std::optional<Vec2> measured(int target) const;

  //! The last round's fit (errors per target, in target order), if its fit succeeded.
  const std::optional<HomographyFit>& last_fit() const { return last_fit_; }
  //! Per target, from the last round (empty if its fit was refused), screen px: the target's
  //! error under the fit of all the others, and the largest error of that fit over the
  //! others (+inf where the others cannot be fitted).
  const std::vector<double>& leave_one_out_px() const { return leave_one_out_px_; }
  const std::vector<double>& without_px() const { return without_px_; }
  //! Why the last round was rejected, or why the session failed; empty otherwise.
  const std::string& failure() const { return failure_; }
  //! The new calibration, only once accepted.
  std::optional<Calibration> calibration(std::string remote = {}, std::string created_utc = {}) const;

  const Counters& counters() const { return counters_; }
  const CalibrationSessionConfig& config() const { return config_; }

 private:
  void clear_window();
  CalibrationStep finish_round();
  void repeat(std::vector<int> which);

  CalibrationSessionConfig config_;
  std::vector<Vec2> targets_;
  Nanos dwell_ns_ = 0;
  Nanos max_gap_ns_ = 0;
  std::vector<std::optional<Vec2>> measured_;
  std::vector<int> queue_;  //!< targets still to measure this round, front first
  int round_ = 0;
  CalibrationStatus status_ = CalibrationStatus::measuring;
  std::vector<Vec2> window_;
  double sum_x_ = 0, sum_y_ = 0;
  Nanos window_first_ns_ = 0, window_last_ns_ = 0;
  std::optional<Nanos> last_sample_ns_;
  bool rest_unknown_ = true;         //!< no sample yet: the first one is where the dot rests
  std::optional<Vec2> must_leave_;   //!< where the dot rested when the current target was shown
  std::optional<Nanos> settle_end_ns_;  //!< the dwell may start from here (the dot has left)
  Nanos settle_ns_ = 0;
  std::optional<HomographyFit> last_fit_;
  std::vector<double> leave_one_out_px_;
  std::vector<double> without_px_;
  std::string failure_;
  Counters counters_;
};

}  // namespace mallet
