#include "core/contact_predictor.hpp"

#include <algorithm>
#include <cmath>

namespace mallet {

PredictionConfig prediction_off() { return {}; }

PredictionConfig prediction_balanced() {
  PredictionConfig c;
  c.horizon_ms = 10;
  return c;
}

PredictionConfig prediction_exact() {
  PredictionConfig c = prediction_balanced();
  c.min_predicted_speed_m_per_s = 0.3;
  c.max_speedup_m_per_s2 = 0;
  c.braking_m_per_s2 = 120;
  c.max_timing_sigma_ms = 2.0;
  c.max_speed_sigma_pct = 40;
  return c;
}

PredictionConfig prediction_eager() {
  PredictionConfig c = prediction_balanced();
  c.max_fit_residual_m = 0.002;
  c.max_speedup_m_per_s2 = 1e9;
  c.max_timing_sigma_ms = 1e9;
  c.max_speed_sigma_pct = 1e9;
  return c;
}

std::optional<PredictionConfig> prediction_confidence(std::string_view name) {
  if (name == "eager") return prediction_eager();
  if (name == "balanced") return prediction_balanced();
  if (name == "exact") return prediction_exact();
  return std::nullopt;
}

ContactPredictor::ContactPredictor(PredictionConfig config) : config_(config) {}

void ContactPredictor::add(Nanos t_ns, Vec2 hand) {
  history_[head_] = {t_ns, hand};
  head_ = (head_ + 1) % kHistory;
  count_ = std::min(count_ + 1, kHistory);
}

std::optional<Nanos> ContactPredictor::expected_interval_ns() const {
  constexpr std::size_t kIntervals = 8;
  std::array<Nanos, kIntervals> dt{};
  std::size_t n = 0;
  for (; n < kIntervals && n + 1 < count_; ++n) dt[n] = back(n).t_ns - back(n + 1).t_ns;
  if (n == 0) return std::nullopt;
  // The median: one dropped sample (a double interval) does not move it.
  std::nth_element(dt.begin(), dt.begin() + static_cast<long>(n / 2), dt.begin() + static_cast<long>(n));
  return dt[n / 2];
}

std::optional<ContactPredictor::Fit> ContactPredictor::fit() const {
  constexpr int kMax = Fit::kMaxTerms;
  const int terms = std::clamp(config_.fit_degree, 1, kMax - 1) + 1;
  const double window_s = config_.fit_window_ms * 1e-3;
  if (count_ == 0 || !(window_s > 0)) return std::nullopt;
  const Sample& last = back(0);
  // Times as fractions of the window (s in [-1, 0]) and positions relative to the last
  // sample keep the normal equations well conditioned.
  std::array<std::array<double, kMax>, kMax> m{};
  std::array<double, kMax> rhs{};
  double x0 = 0, x1 = 0, l0 = 0, l1 = 0, l2 = 0;
  int n = 0;
  for (; static_cast<std::size_t>(n) < count_; ++n) {
    const Sample& p = back(static_cast<std::size_t>(n));
    const double s = to_seconds(p.t_ns - last.t_ns) / window_s;
    if (s < -1.0) break;
    std::array<double, kMax> pow{1, s, s * s, s * s * s};
    for (int r = 0; r < terms; ++r) {
      rhs[r] += pow[r] * (p.hand.y - last.hand.y);
      for (int c = 0; c < terms; ++c) m[r][c] += pow[r] * pow[c];
    }
    l0 += 1;
    l1 += s;
    l2 += s * s;
    x0 += p.hand.x - last.hand.x;
    x1 += s * (p.hand.x - last.hand.x);
  }
  if (n < std::max(config_.min_samples, terms)) return std::nullopt;

  // (XᵀX)⁻¹ by Gauss–Jordan with partial pivoting: it gives the coefficients and, times
  // σ², their covariance.
  Fit f;
  f.terms_ = terms;
  f.window_s_ = window_s;
  f.y_last_ = last.hand.y;
  auto& inv = f.inverse_;
  for (int r = 0; r < terms; ++r) inv[r][r] = 1;
  for (int c = 0; c < terms; ++c) {
    int pivot = c;
    for (int r = c + 1; r < terms; ++r)
      if (std::fabs(m[r][c]) > std::fabs(m[pivot][c])) pivot = r;
    if (!(std::fabs(m[pivot][c]) > 1e-12)) return std::nullopt;
    std::swap(m[c], m[pivot]);
    std::swap(inv[c], inv[pivot]);
    const double d = m[c][c];
    for (int k = 0; k < terms; ++k) {
      m[c][k] /= d;
      inv[c][k] /= d;
    }
    for (int r = 0; r < terms; ++r) {
      if (r == c) continue;
      const double g = m[r][c];
      for (int k = 0; k < terms; ++k) {
        m[r][k] -= g * m[c][k];
        inv[r][k] -= g * inv[c][k];
      }
    }
  }
  for (int r = 0; r < terms; ++r)
    for (int c = 0; c < terms; ++c) f.c_[r] += inv[r][c] * rhs[c];

  double ssr = 0;
  for (int i = 0; i < n; ++i) {
    const Sample& p = back(static_cast<std::size_t>(i));
    const double r = p.hand.y - f.y_m(to_seconds(p.t_ns - last.t_ns));
    ssr += r * r;
  }
  const double dlin = l0 * l2 - l1 * l1;
  f.samples = n;
  f.span_s = to_seconds(last.t_ns - back(static_cast<std::size_t>(n - 1)).t_ns);
  f.rms_residual_m = n > terms ? std::sqrt(ssr / (n - terms)) : 0.0;
  f.x_m = last.hand.x + (std::fabs(dlin) > 1e-12 ? (l2 * x0 - l1 * x1) / dlin : x0 / l0);
  f.vx_m_per_s = std::fabs(dlin) > 1e-12 ? (l0 * x1 - l1 * x0) / dlin / window_s : 0.0;
  return f;
}

double ContactPredictor::Fit::y_m(double tau_s) const {
  const double s = tau_s / window_s_;
  double y = 0;
  for (int k = terms_ - 1; k >= 0; --k) y = y * s + c_[k];
  return y_last_ + y;
}

double ContactPredictor::Fit::vy_m_per_s(double tau_s) const {
  const double s = tau_s / window_s_;
  double v = 0;
  for (int k = terms_ - 1; k >= 1; --k) v = v * s + k * c_[k];
  return v / window_s_;
}

double ContactPredictor::Fit::ay_m_per_s2(double tau_s) const {
  const double s = tau_s / window_s_;
  double a = 0;
  for (int k = terms_ - 1; k >= 2; --k) a = a * s + k * (k - 1) * c_[k];
  return a / (window_s_ * window_s_);
}

namespace {
//! gᵀ·A·g for the first `terms` entries.
template <typename M, typename V>
double quadratic_form(const M& a, const V& g, int terms) {
  double q = 0;
  for (int r = 0; r < terms; ++r)
    for (int c = 0; c < terms; ++c) q += g[r] * a[r][c] * g[c];
  return std::max(0.0, q);
}
}  // namespace

double ContactPredictor::Fit::sigma_y_m(double tau_s, double noise_m) const {
  const double s = tau_s / window_s_;
  const std::array<double, kMaxTerms> g{1, s, s * s, s * s * s};
  return noise_m * std::sqrt(quadratic_form(inverse_, g, terms_));
}

double ContactPredictor::Fit::sigma_vy_m_per_s(double tau_s, double noise_m) const {
  const double s = tau_s / window_s_;
  const std::array<double, kMaxTerms> h{0, 1, 2 * s, 3 * s * s};
  return noise_m * std::sqrt(quadratic_form(inverse_, h, terms_)) / window_s_;
}

const char* to_string(PredictionVerdict v) { return name_in(kPredictionVerdictNames, v); }

std::optional<PredictedContact> ContactPredictor::predict(const std::vector<ContactZone>& zones) {
  verdict_ = PredictionVerdict::off;
  if (!(config_.horizon_ms > 0)) return std::nullopt;
  // Nothing to strike (a texture scene): no fit on the reading thread's every sample.
  verdict_ = PredictionVerdict::no_crossing;
  if (zones.empty()) return std::nullopt;
  verdict_ = PredictionVerdict::few_samples;
  const std::optional<Fit> f = fit();
  const std::optional<Nanos> interval = expected_interval_ns();
  if (!f || !interval) return std::nullopt;
  verdict_ = PredictionVerdict::poor_fit;
  if (!(f->rms_residual_m <= config_.max_fit_residual_m)) return std::nullopt;
  const double down_m_per_s = -f->vy_m_per_s(0);
  verdict_ = PredictionVerdict::slow;
  if (!(down_m_per_s >= config_.min_predicted_speed_m_per_s)) return std::nullopt;
  // Already going down at the window's start: a downswing seen whole, not a turn (a
  // rebound, a stroke just begun) whose acceleration the fit cannot know yet.
  verdict_ = PredictionVerdict::turning;
  if (!(-f->vy_m_per_s(-f->span_s) >= config_.min_predicted_speed_m_per_s)) return std::nullopt;
  // Still speeding up: the hand is in the first half of its move and will brake before
  // the bar by an amount nothing in the samples tells.
  verdict_ = PredictionVerdict::speeding_up;
  if (!(f->ay_m_per_s2(0) >= -config_.max_speedup_m_per_s2)) return std::nullopt;

  // A camera's frame is held sample_delay_ms after its time: a crossing before the next
  // one is held is still earlier than the solver can call it. The horizon still counts
  // from the last sample's time: how far the fit is trusted. No delay (the Wii): the next
  // sample's time itself.
  const double next_s = to_seconds(*interval) + config_.sample_delay_ms * 1e-3;
  const double ahead_s = std::min(config_.horizon_ms * 1e-3, next_s);
  const double stopping_m = down_m_per_s * down_m_per_s / (2.0 * config_.braking_m_per_s2);
  const double y_now = f->y_m(0);
  // Each zone's verdict is the first test it fails; the call's is the furthest any got.
  verdict_ = PredictionVerdict::no_crossing;
  auto reached = [this](PredictionVerdict v) { verdict_ = std::max(verdict_, v); };
  std::optional<PredictedContact> best;
  double best_s = ahead_s;
  for (std::size_t i = 0; i < zones.size(); ++i) {
    const ContactZone& z = zones[i];
    const double above_m = y_now - z.plane_y;
    if (!(above_m > 0)) continue;  // at or below: the solver's business
    // The first crossing within the next interval: coarse steps, then bisection.
    constexpr int kSteps = 8;
    double lo = 0, hi = -1;
    for (int k = 1; k <= kSteps; ++k) {
      const double t = next_s * k / kSteps;
      if (f->y_m(t) <= z.plane_y) {
        hi = t;
        break;
      }
      lo = t;
    }
    if (hi < 0) continue;
    for (int k = 0; k < 40; ++k) {
      const double mid = 0.5 * (lo + hi);
      (f->y_m(mid) > z.plane_y ? lo : hi) = mid;
    }
    const double tau_s = hi;
    const double speed = -f->vy_m_per_s(tau_s);
    if (!(speed >= config_.min_predicted_speed_m_per_s)) continue;
    reached(PredictionVerdict::could_stop);
    if (!(above_m - config_.clearance_m < stopping_m)) continue;
    reached(PredictionVerdict::after_next_sample);
    if (!(tau_s <= best_s)) continue;
    reached(PredictionVerdict::uncertain);
    const double timing_sigma_ms = 1e3 * f->sigma_y_m(tau_s, config_.noise_m) / speed;
    const double speed_sigma_pct = 100 * f->sigma_vy_m_per_s(tau_s, config_.noise_m) / speed;
    if (timing_sigma_ms > config_.max_timing_sigma_ms || speed_sigma_pct > config_.max_speed_sigma_pct) continue;
    // The fit must go on well below the plane before the next sample: a crossing that only
    // grazes it is one the noise, or a stop just above, could fake.
    reached(PredictionVerdict::grazing);
    if (!(f->y_m(next_s) <= z.plane_y - config_.min_overshoot_m)) continue;
    reached(PredictionVerdict::outside_zone);
    const double x = f->x_m + f->vx_m_per_s * tau_s;
    if (!z.contains(x)) continue;
    reached(PredictionVerdict::predicted);
    best_s = tau_s;
    const Nanos last_t = back(0).t_ns;
    best = PredictedContact{i, std::max(last_t + 1, last_t + static_cast<Nanos>(std::llround(tau_s * 1e9))), speed, x};
  }
  return best;
}

}  // namespace mallet
