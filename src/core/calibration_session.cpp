#include "core/calibration_session.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <stdexcept>

#include <fmt/format.h>

namespace mallet {

namespace {

bool finite(Vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }
double distance(Vec2 a, Vec2 b) { return std::hypot(a.x - b.x, a.y - b.y); }

std::string px_text(double v) {
  return fmt::format("{:.1f}", v);
}

// |H(camera) − target| in screen px; nothing where H sends the point to infinity.
std::optional<double> screen_error_px(const Homography& h, Vec2 camera, Vec2 target, ScreenSize screen) {
  const auto p = h.try_map(camera);
  if (!p) return std::nullopt;
  return std::hypot((p->x - target.x) * screen.width_px, (p->y - target.y) * screen.height_px);
}

}  // namespace

Check validate(const CalibrationSessionConfig& c) {
  auto seconds_ok = [](double s) { return std::isfinite(s) && s > 0 && from_seconds(s).has_value(); };
  auto px_ok = [](double v) { return std::isfinite(v) && v > 0; };
  if (c.columns < 2) return refused("columns must be >= 2");
  if (c.rows < 2) return refused("rows must be >= 2");
  if (!(c.margin_x >= 0 && c.margin_x < 0.5)) return refused("margin_x must be >= 0 and < 0.5");
  if (!(c.margin_y >= 0 && c.margin_y < 0.5)) return refused("margin_y must be >= 0 and < 0.5");
  if (!seconds_ok(c.dwell_s)) return refused("dwell_s must be a finite number of seconds > 0");
  if (!px_ok(c.dwell_radius_camera_px)) return refused("dwell_radius_camera_px must be a finite number > 0");
  if (!px_ok(c.max_std_dev_camera_px)) return refused("max_std_dev_camera_px must be a finite number > 0");
  if (!seconds_ok(c.max_gap_s)) return refused("max_gap_s must be a finite number of seconds > 0");
  if (c.min_dwell_samples < 1) return refused("min_dwell_samples must be >= 1");
  if (!(std::isfinite(c.settle_s) && c.settle_s >= 0 && from_seconds(c.settle_s).has_value()))
    return refused("settle_s must be a finite number of seconds >= 0");
  if (!(std::isfinite(c.min_separation_camera_px) && c.min_separation_camera_px >= 0))
    return refused("min_separation_camera_px must be a finite number >= 0");
  if (!px_ok(c.max_error_screen_px)) return refused("max_error_screen_px must be a finite number > 0");
  if (c.repeat_worst < 1) return refused("repeat_worst must be >= 1");
  if (c.max_repeat_rounds < 0) return refused("max_repeat_rounds must be >= 0");
  if (!px_ok(c.screen.width_px) || !px_ok(c.screen.height_px)) return refused("screen size must be > 0");
  return {};
}

std::vector<Vec2> calibration_grid(const CalibrationSessionConfig& c) {
  std::vector<Vec2> out;
  for (int r = 0; r < c.rows; ++r)
    for (int k = 0; k < c.columns; ++k)
      out.push_back({c.margin_x + (1 - 2 * c.margin_x) * k / (c.columns - 1),
                     c.margin_y + (1 - 2 * c.margin_y) * r / (c.rows - 1)});
  return out;
}

const char* to_string(CalibrationStep step) { return name_in(kCalibrationStepNames, step); }

CalibrationSession::CalibrationSession(CalibrationSessionConfig config)
    : CalibrationSession(config, calibration_grid(config)) {}

CalibrationSession::CalibrationSession(CalibrationSessionConfig config, std::vector<Vec2> targets)
    : config_(config), targets_(std::move(targets)) {
  if (const Check problem = validate(config_); !problem) throw std::invalid_argument(problem.error());
  if (targets_.size() < 4) throw std::invalid_argument("a calibration needs at least 4 targets");
  if (!std::all_of(targets_.begin(), targets_.end(), finite))
    throw std::invalid_argument("calibration targets must be finite");
  dwell_ns_ = *from_seconds(config_.dwell_s);
  max_gap_ns_ = *from_seconds(config_.max_gap_s);
  settle_ns_ = *from_seconds(config_.settle_s);
  measured_.assign(targets_.size(), std::nullopt);
  queue_.resize(targets_.size());
  std::iota(queue_.begin(), queue_.end(), 0);
}

std::optional<int> CalibrationSession::current_target() const {
  if (status_ != CalibrationStatus::measuring || queue_.empty()) return std::nullopt;
  return queue_.front();
}

double CalibrationSession::progress() const {
  if (window_.empty()) return 0.0;
  return std::min(1.0, to_seconds(window_last_ns_ - window_first_ns_) / to_seconds(dwell_ns_));
}

std::optional<Vec2> CalibrationSession::measured(int target) const {
  if (target < 0 || static_cast<std::size_t>(target) >= measured_.size()) return std::nullopt;
  return measured_[static_cast<std::size_t>(target)];
}

void CalibrationSession::clear_window() {
  window_.clear();
  sum_x_ = sum_y_ = 0;
}

CalibrationStep CalibrationSession::feed(Nanos t_ns, Vec2 p, bool may_measure) {
  if (status_ != CalibrationStatus::measuring || !finite(p) || (last_sample_ns_ && t_ns <= *last_sample_ns_)) {
    ++counters_.ignored;
    return CalibrationStep::ignored;
  }
  ++counters_.samples;
  last_sample_ns_ = t_ns;
  // The grace before each target: where the dot rested when the target was shown is never
  // measured, nor is the way from there to the target.
  if (rest_unknown_) {
    rest_unknown_ = false;
    must_leave_ = p;
  }
  if (must_leave_) {
    if (distance(p, *must_leave_) <= config_.min_separation_camera_px) return CalibrationStep::still_on_last;
    must_leave_.reset();
    settle_end_ns_ = t_ns + settle_ns_;
  }
  if (settle_end_ns_) {
    if (t_ns < *settle_end_ns_) return CalibrationStep::settling;
    settle_end_ns_.reset();
  }
  if (!may_measure) {  // off the target: no dwell here, one starts afresh on it
    if (!window_.empty()) {
      clear_window();
      ++counters_.dwell_resets;
    }
    return CalibrationStep::dwell_reset;
  }
  CalibrationStep step = CalibrationStep::dwelling;
  if (!window_.empty()) {
    const double n = static_cast<double>(window_.size());
    const Vec2 mean{sum_x_ / n, sum_y_ / n};
    if (t_ns - window_last_ns_ > max_gap_ns_ || distance(p, mean) > config_.dwell_radius_camera_px) {
      clear_window();
      ++counters_.dwell_resets;
      step = CalibrationStep::dwell_reset;
    }
  }
  if (window_.empty()) window_first_ns_ = t_ns;
  window_.push_back(p);
  window_last_ns_ = t_ns;
  sum_x_ += p.x;
  sum_y_ += p.y;
  if (static_cast<int>(window_.size()) < config_.min_dwell_samples || t_ns - window_first_ns_ < dwell_ns_) return step;

  const double n = static_cast<double>(window_.size());
  const Vec2 mean{sum_x_ / n, sum_y_ / n};
  double sq = 0;
  for (Vec2 q : window_) sq += (q.x - mean.x) * (q.x - mean.x) + (q.y - mean.y) * (q.y - mean.y);
  clear_window();
  if (std::sqrt(sq / n) > config_.max_std_dev_camera_px) {
    ++counters_.unstable_windows;
    return CalibrationStep::unstable;
  }
  measured_[static_cast<std::size_t>(queue_.front())] = mean;
  queue_.erase(queue_.begin());
  must_leave_ = mean;
  return queue_.empty() ? finish_round() : CalibrationStep::target_measured;
}

void CalibrationSession::repeat(std::vector<int> which) {
  ++round_;
  ++counters_.rounds_rejected;
  for (int i : which) measured_[static_cast<std::size_t>(i)].reset();
  queue_ = std::move(which);
}

CalibrationStep CalibrationSession::finish_round() {
  std::vector<Vec2> from;
  for (const auto& m : measured_) from.push_back(*m);
  const auto result = fit_homography(from, targets_, config_.screen);
  last_fit_.reset();
  leave_one_out_px_.clear();
  without_px_.clear();
  const bool rounds_left = round_ < config_.max_repeat_rounds;
  if (!result) {
    failure_ = "the fit was refused: " + result.error();
    if (!rounds_left) {
      status_ = CalibrationStatus::failed;
      return CalibrationStep::failed;
    }
    std::vector<int> all(targets_.size());
    std::iota(all.begin(), all.end(), 0);
    repeat(std::move(all));
    return CalibrationStep::round_rejected;
  }
  last_fit_ = *result;
  const HomographyFit& fit = *last_fit_;

  // Each point against the fit of all the others; where those cannot be fitted, its
  // full-fit error stands in and the others' error is +inf.
  for (std::size_t i = 0; i < from.size(); ++i) {
    std::vector<Vec2> f, t;
    for (std::size_t j = 0; j < from.size(); ++j)
      if (j != i) {
        f.push_back(from[j]);
        t.push_back(targets_[j]);
      }
    double err = fit.reprojection_error_px[i];
    double without = std::numeric_limits<double>::infinity();
    if (f.size() >= 4) {
      const auto others = fit_homography(f, t, config_.screen);
      if (others) {
        if (auto e = screen_error_px(others->h, from[i], targets_[i], config_.screen)) err = *e;
        without = others->max_px;
      }
    }
    leave_one_out_px_.push_back(err);
    without_px_.push_back(without);
  }
  if (fit.max_px <= config_.max_error_screen_px) {
    failure_.clear();
    status_ = CalibrationStatus::accepted;
    return CalibrationStep::accepted;
  }
  failure_ = "the largest reprojection error is " + px_text(fit.max_px) + " px, above " +
             px_text(config_.max_error_screen_px) + " px";
  if (!rounds_left) {
    failure_ += " after " + std::to_string(round_ + 1) + " round(s)";
    status_ = CalibrationStatus::failed;
    return CalibrationStep::failed;
  }
  std::vector<int> order(targets_.size());
  std::iota(order.begin(), order.end(), 0);
  // With 5 targets every fit of the other 4 is exact: only the prediction error tells.
  const bool others_overdetermined = targets_.size() >= 6;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
    if (others_overdetermined && without_px_[ua] != without_px_[ub]) return without_px_[ua] < without_px_[ub];
    return leave_one_out_px_[ua] > leave_one_out_px_[ub];
  });
  order.resize(std::min(order.size(), static_cast<std::size_t>(config_.repeat_worst)));
  repeat(std::move(order));
  return CalibrationStep::round_rejected;
}

std::optional<Calibration> CalibrationSession::calibration(std::string remote, std::string created_utc) const {
  if (status_ != CalibrationStatus::accepted || !last_fit_) return std::nullopt;
  Calibration c = calibration_from_fit(*last_fit_, "mallet run (calibration screen)", std::move(remote));
  c.created_utc = std::move(created_utc);  // the caller's clock, so that tests are exact
  return c;
}

}  // namespace mallet
