#include "input/evdev/evdev_decoder.hpp"

#include <algorithm>
#include <cmath>

namespace mallet::input::evdev {

bool EvdevDecoder::set_screen(int width_px, int height_px) {
  if (width_px <= 0 || height_px <= 0) return false;
  const PointerSample at = position();
  width_px_ = width_px;
  height_px_ = height_px;
  warp(at.x, at.y);
  return true;
}

bool EvdevDecoder::set_speed(double px_per_count) {
  if (!std::isfinite(px_per_count) || px_per_count <= 0) return false;
  speed_px_per_count_ = px_per_count;
  return true;
}

void EvdevDecoder::set_abs_range(std::uint16_t code, AbsAxisRange range) {
  const std::optional<AbsAxisRange> value =
      range.max > range.min ? std::optional<AbsAxisRange>(range) : std::nullopt;
  if (code == ABS_X) abs_x_ = value;
  if (code == ABS_Y) abs_y_ = value;
}

void EvdevDecoder::warp(double x, double y) {
  // A NaN would stick forever (every later sum is NaN): keep the old coordinate instead.
  if (std::isfinite(x)) x_px_ = x * width_px_;
  if (std::isfinite(y)) y_px_ = y * height_px_;
  clamp_position();
}

PointerSample EvdevDecoder::position() const {
  return {last_t_ns_, x_px_ / width_px_, y_px_ / height_px_};
}

void EvdevDecoder::clear_frame() {
  rel_x_counts_ = 0;
  rel_y_counts_ = 0;
  abs_x_value_.reset();
  abs_y_value_.reset();
  left_button_value_.reset();
  frame_events_ = 0;
}

void EvdevDecoder::clamp_position() {
  x_px_ = std::clamp(x_px_, 0.0, static_cast<double>(width_px_));
  y_px_ = std::clamp(y_px_, 0.0, static_cast<double>(height_px_));
}

namespace {

double abs_fraction(int value, AbsAxisRange range) {
  return (static_cast<double>(value) - range.min) / (static_cast<double>(range.max) - range.min);
}

}  // namespace

std::optional<PointerSample> EvdevDecoder::feed(const input_event& event) {
  if (event.type == EV_SYN && event.code == SYN_DROPPED) {
    ++counters_.dropped_syncs;
    counters_.discarded_events += frame_events_;
    clear_frame();
    discarding_ = true;
    return std::nullopt;
  }
  if (discarding_) {
    ++counters_.discarded_events;
    if (event.type == EV_SYN && event.code == SYN_REPORT) discarding_ = false;
    return std::nullopt;
  }
  if (event.type != EV_SYN) ++frame_events_;
  switch (event.type) {
    case EV_REL:
      if (event.code == REL_X) rel_x_counts_ += event.value;
      if (event.code == REL_Y) rel_y_counts_ += event.value;
      return std::nullopt;
    case EV_ABS:
      if (event.code == ABS_X && abs_x_) abs_x_value_ = event.value;
      if (event.code == ABS_Y && abs_y_) abs_y_value_ = event.value;
      return std::nullopt;
    case EV_KEY:
      if (event.code == BTN_LEFT) left_button_value_ = event.value != 0;
      return std::nullopt;
    case EV_SYN:
      break;
    default:
      return std::nullopt;
  }
  if (event.code != SYN_REPORT) return std::nullopt;  // SYN_CONFIG, SYN_MT_REPORT: not ours

  ++counters_.reports;
  if (left_button_value_) left_button_ = *left_button_value_;
  const bool moved = rel_x_counts_ != 0 || rel_y_counts_ != 0 || abs_x_value_ || abs_y_value_;
  if (moved) {
    x_px_ += static_cast<double>(rel_x_counts_) * speed_px_per_count_;
    y_px_ += static_cast<double>(rel_y_counts_) * speed_px_per_count_;
    if (abs_x_value_) x_px_ = abs_fraction(*abs_x_value_, *abs_x_) * width_px_;
    if (abs_y_value_) y_px_ = abs_fraction(*abs_y_value_, *abs_y_) * height_px_;
    clamp_position();
    last_t_ns_ = event_time_ns(event) + clock_offset_ns_;
  }
  clear_frame();
  if (!moved) return std::nullopt;
  ++counters_.samples;
  return position();
}

}  // namespace mallet::input::evdev
