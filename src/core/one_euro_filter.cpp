#include "core/one_euro_filter.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace mallet {

Check validate(const OneEuroConfig& c) {
  if (!std::isfinite(c.min_cutoff_hz) || !(c.min_cutoff_hz > 0))
    return refused("min_cutoff_hz must be a finite number > 0");
  if (!std::isfinite(c.beta_per_m) || c.beta_per_m < 0) return refused("beta_per_m must be a finite number >= 0");
  if (!std::isfinite(c.d_cutoff_hz) || !(c.d_cutoff_hz > 0)) return refused("d_cutoff_hz must be a finite number > 0");
  return {};
}

double one_euro_alpha(double cutoff_hz, double dt_s) {
  const double tau = 1.0 / (2.0 * std::numbers::pi * cutoff_hz);
  return 1.0 / (1.0 + tau / dt_s);
}

OneEuroFilter::OneEuroFilter(OneEuroConfig config) : config_(config) {
  if (const Check why = validate(config_); !why) throw std::invalid_argument("1€ filter: " + why.error());
}

void OneEuroFilter::reset() {
  primed_ = false;
  dx_ = {};
  last_cutoff_hz_ = 0;
}

std::optional<Vec2> OneEuroFilter::value() const {
  if (!primed_) return std::nullopt;
  return x_;
}

std::optional<Vec2> OneEuroFilter::update(Nanos t_ns, Vec2 raw) {
  if (!std::isfinite(raw.x) || !std::isfinite(raw.y)) {
    ++counters_.ignored_non_finite;
    return value();
  }
  if (!primed_) {
    primed_ = true;
    t_ns_ = t_ns;
    x_ = raw_ = raw;
    dx_ = {};
    last_cutoff_hz_ = config_.min_cutoff_hz;
    ++counters_.accepted;
    return x_;
  }
  if (t_ns <= t_ns_) {
    ++counters_.ignored_not_after_previous;
    return x_;
  }
  // Only the difference of two timestamps becomes a double: exact at any uptime.
  const double dt = to_seconds(t_ns - t_ns_);
  const Vec2 prev = config_.derivative_from_raw ? raw_ : x_;
  const Vec2 d{(raw.x - prev.x) / dt, (raw.y - prev.y) / dt};
  if (!std::isfinite(d.x) || !std::isfinite(d.y)) {  // a finite but absurd jump over a tiny dt
    ++counters_.ignored_non_finite;
    return x_;
  }
  const double ad = one_euro_alpha(config_.d_cutoff_hz, dt);
  dx_ = {dx_.x + ad * (d.x - dx_.x), dx_.y + ad * (d.y - dx_.y)};
  const double cutoff = config_.min_cutoff_hz + config_.beta_per_m * std::hypot(dx_.x, dx_.y);
  const double a = one_euro_alpha(cutoff, dt);
  x_ = {x_.x + a * (raw.x - x_.x), x_.y + a * (raw.y - x_.y)};
  raw_ = raw;
  t_ns_ = t_ns;
  last_cutoff_hz_ = cutoff;
  ++counters_.accepted;
  return x_;
}

}  // namespace mallet
