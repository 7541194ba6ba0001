#include "app/kiosk/calibration_screen.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <system_error>

#include <fmt/printf.h>

#include "core/journal.hpp"
#include "core/visitor_language.hpp"
#include "render/overlay_text.hpp"
#include "render/text_wrap.hpp"

namespace mallet::app {

CalibrationScreen::CalibrationScreen(CalibrationSessionConfig config, std::optional<std::filesystem::path> save_to,
                                     std::string remote)
    : session_(config), save_to_(std::move(save_to)), remote_(std::move(remote)) {}

void CalibrationScreen::tune_sensitivity(SensitivityTunerConfig config, std::string configured) {
  tuner_.emplace(config);
  configured_ = std::move(configured);
  request_ = std::string(tuner_->preset());
}

std::optional<std::string> CalibrationScreen::sensitivity_request() {
  std::optional<std::string> r;
  r.swap(request_);
  return r;
}

void CalibrationScreen::frame(const IrFrame& f) {
  // Until the kiosk takes the preset asked for (once per pass of its loop, after that pass's
  // frames), the camera runs the previous one. A pass lasts as long as the frame it draws:
  // seconds under a CPU rasteriser in a slow guest, more than a preset's 110 reports. Counted,
  // those frames judged a preset the camera never ran, and a tuner that chose in one pass
  // merged its first preset's request with the chosen one's: one switch, not two (the VM
  // test's emulated remote waited for its second, and the calibration never began).
  if (!tuning() || request_) return;
  switch (tuner_->observe(f)) {
    case TunerStep::observing: return;
    case TunerStep::next_preset: request_ = std::string(tuner_->preset()); return;
    case TunerStep::chosen:
      sensitivity_ = std::string(*tuner_->chosen());
      sensitivity_chosen_ = true;
      tuner_note_ = "IR sensitivity: " + sensitivity_;
      break;
    case TunerStep::failed: {
      sensitivity_ = configured_;
      const auto& v = tuner_->verdicts();
      tuner_note_ = "IR sensitivity: none gave one clean dot (" +
                    (v.empty() ? std::string("?") : std::string(v.back().preset) + ": " + v.back().verdict.reason) +
                    "); kept " + configured_;
      break;
    }
  }
  request_ = sensitivity_;
  journal::info("calibration: {}", tuner_note_.c_str());
}

namespace {

//! The current target's ring's radius on a width×height screen, pixels (draw() draws it).
float ring_radius(float w, float h) { return std::max(10.0f, std::min(w, h) * 0.035f); }

}  // namespace

CalibrationStep CalibrationScreen::feed_pointer(Nanos t_ns, Vec2 screen) {
  const ScreenSize size = session_.config().screen;
  const std::optional<int> current = session_.current_target();
  pointer_on_ring_ = false;
  if (current) {
    const Vec2 target = session_.targets().at(static_cast<std::size_t>(*current));
    const double dx = (screen.x - target.x) * size.width_px, dy = (screen.y - target.y) * size.height_px;
    // On the ring: within it and its progress band around it, as drawn.
    const float ring = ring_radius(static_cast<float>(size.width_px), static_cast<float>(size.height_px));
    pointer_on_ring_ = std::hypot(dx, dy) <= ring + 9.0;
  }
  return feed(t_ns, mouse_as_camera_px(screen), pointer_on_ring_);
}

CalibrationStep CalibrationScreen::feed(Nanos t_ns, Vec2 camera_px, bool may_measure) {
  dot_seen_ = true;
  if (outcome_ != Outcome::measuring || tuning()) return CalibrationStep::ignored;
  const CalibrationStep step = session_.feed(t_ns, camera_px, may_measure);
  if (step == CalibrationStep::target_measured || step == CalibrationStep::unstable ||
      step == CalibrationStep::round_rejected)
    journal::info("calibration: {} at camera {:.0f},{:.0f}", to_string(step), camera_px.x, camera_px.y);
  if (step == CalibrationStep::round_rejected || step == CalibrationStep::failed) {
    if (const auto& fit = session_.last_fit())
      last_round_ = fmt::sprintf(tr("Round %d: largest error %.1f px (limit %.1f px): measuring again"),
                                 session_.round(), fit->max_px, session_.config().max_error_screen_px);
    else
      last_round_ = fmt::sprintf(tr("Round %d: the rings could not be matched to the screen: measuring again"),
                                 session_.round());
  }
  if (step == CalibrationStep::accepted) accept();
  if (step == CalibrationStep::failed) {
    // Plain words on the screen, what to do next included; the fit's own reason
    // (session().failure()) goes to the journal beside them.
    outcome_ = Outcome::failed;
    if (const auto& fit = session_.last_fit())
      message_ = fmt::sprintf(tr("Calibration failed: the light did not hold still on the rings (largest error "
                                 "%.0f px, limit %.0f px). Hold it still and try again; the previous "
                                 "calibration stays."),
                              fit->max_px, session_.config().max_error_screen_px);
    else
      message_ = tr("Calibration failed: the rings could not be matched to the screen. Check that the camera "
                    "sees the whole screen and try again; the previous calibration stays.");
  }
  return step;
}

void CalibrationScreen::accept() {
  result_ = session_.calibration(remote_, utc_timestamp_now());
  if (sensitivity_chosen_) result_->ir_sensitivity = sensitivity_;  // kept with it: restored at start-up
  const auto& fit = session_.last_fit();
  message_ = fmt::sprintf(tr("Calibrated: reprojection error %.1f px rms, %.1f px max"), fit ? fit->rms_px : 0.0,
                          fit ? fit->max_px : 0.0);
  if (!save_to_) {
    outcome_ = Outcome::accepted;
    message_ += remote_ == "mouse" ? tr(" (mouse: not saved)") : tr(" (not saved)");
    return;
  }
  try {
    std::error_code ec;
    std::filesystem::create_directories(save_to_->parent_path(), ec);  // a failure shows in the write
    write_calibration_file(*save_to_, *result_);
    outcome_ = Outcome::accepted;
    message_ += tr(", saved");
    saved_ = Check{};
  } catch (const std::exception& e) {
    // Not written: the kiosk keeps its previous calibration, and the operator sees why.
    outcome_ = Outcome::failed;
    result_.reset();
    message_ = std::string(tr("Calibration not saved: ")) + e.what();
    saved_ = Check(refused(e.what()));
  }
}

std::string CalibrationScreen::status_line() const {
  if (outcome_ != Outcome::measuring) return message_;
  // The target on the screen now, by its place in reading order: a round that asks one
  // target again (the fifth, say) must not read as the ninth, as a count of the measured
  // ones would.
  const std::size_t count = session_.targets().size();
  const int target = session_.current_target().value_or(static_cast<int>(count) - 1);
  const char* seen = remote_ == "mouse" ? (pointer_on_ring_ ? tr("pointer on the ring") : tr("move the pointer onto the ring"))
                     : dot_seen_         ? tr("light seen")
                                         : tr("no light seen");
  return fmt::sprintf(tr("Target %d of %zu, round %d   %s"), target + 1, count, session_.round() + 1, seen);
}

void CalibrationScreen::draw(render::Overlay& o, float w, float h) const {
  const float px = o.atlas().pixel_height();
  const std::array<float, 4> white{1.0f, 1.0f, 1.0f, 1.0f}, dim{1.0f, 1.0f, 1.0f, 0.35f},
      done{0.35f, 0.85f, 0.45f, 1.0f}, ring{1.0f, 0.78f, 0.2f, 1.0f};
  o.fill_rect(0, 0, w, h, {0.02f, 0.02f, 0.04f, 0.86f});
  // The words sit between the target rows (0.1, 0.5, 0.9 of the height by default).
  // Each instruction on as many centred lines as the screen's width needs (a long language,
  // a portrait screen); the next one below it.
  float pen = h * 0.27f;
  auto say = [&](std::string_view text, std::array<float, 4> colour) {
    for (const std::string& line : render::wrap_text(o.atlas(), text, w - 4 * px)) {
      o.text(w / 2, pen, line, colour, render::TextAlign::center);
      pen += px * 1.3f;
    }
    pen += px * 0.2f;
  };
  say(tr("Calibration"), white);
  // The way out, a small note in the bottom-left corner: below the bottom row of targets,
  // whose rings (the current one's is the largest) it would otherwise touch. A mouse's
  // calibration is never saved: there is no previous one to keep.
  render::draw_corner_note(o, remote_ == "mouse" ? tr("Esc stops the calibration")
                                                 : tr("Esc stops the calibration; the previous one stays"),
                           render::Corner::bottom_left, w, h);
  if (remote_ != "mouse" && !link_up_ && outcome_ == Outcome::measuring) {
    // Nothing can come until it is back: say what is wrong and what to do, not "no light".
    say(camera_ ? tr("The camera is not connected: check its cable")
                : tr("The Wii Remote is not connected: press its 1 and 2 buttons together"),
        {1, 0.75f, 0.4f, 1});
    return;
  }

  if (tuning()) {
    // One step at a time: this one's instruction alone, its ring below the words.
    const auto& verdicts = tuner_->verdicts();
    say(tr("First, hold the mallet's light up towards the camera"), {1, 1, 1, 0.8f});
    const float r = std::max(16.0f, std::min(w, h) * 0.06f);
    const float cy = std::max(h * 0.5f, pen + px * 0.5f + r);
    o.progress_ring(w / 2, cy, r, 8.0f,
                    static_cast<float>(verdicts.size() + 1) / static_cast<float>(kSensitivityPresets.size()), ring);
    pen = std::max(h * 0.70f, cy + r + px * 1.5f);
    say(fmt::sprintf(tr("Choosing the camera's sensitivity: setting %d of %zu"), static_cast<int>(verdicts.size()) + 1,
                     kSensitivityPresets.size()) +
            "   " + (dot_seen_ ? tr("light seen") : tr("no light seen")),
        white);
    return;
  }
  say(remote_ == "mouse" ? tr("Hold the pointer still on the ring until it fills")
                        : tr("Hold the mallet's light still on the ring until it fills"),
      {1, 1, 1, 0.8f});
  const std::vector<Vec2>& targets = session_.targets();
  const std::optional<int> current = session_.current_target();
  const float r = ring_radius(w, h);
  for (int i = 0; i < static_cast<int>(targets.size()); ++i) {
    const float x = static_cast<float>(targets[static_cast<std::size_t>(i)].x) * w;
    const float y = static_cast<float>(targets[static_cast<std::size_t>(i)].y) * h;
    if (current && *current == i) {
      o.stroke_circle(x, y, r, 2.0f, white);
      o.fill_circle(x, y, r * 0.18f, white);
      o.progress_ring(x, y, r + 6.0f, 6.0f, static_cast<float>(session_.progress()), ring);
    } else if (session_.measured(i)) {
      o.fill_circle(x, y, r * 0.3f, done);
    } else {
      o.stroke_circle(x, y, r * 0.5f, 1.5f, dim);
    }
  }

  // Below the middle row of targets, each line wrapped to the screen: never cut at its edges.
  pen = h * 0.70f;
  say(status_line(), outcome_ == Outcome::failed ? std::array<float, 4>{1, 0.5f, 0.4f, 1} : white);
  // (The sensitivity chosen is the journal's and the operator page's: a preset's name means
  // nothing on this screen.)
  if (outcome_ == Outcome::measuring && !last_round_.empty()) say(last_round_, {1, 0.75f, 0.4f, 1});
}

}  // namespace mallet::app
