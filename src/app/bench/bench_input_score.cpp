#include "app/bench/bench_input_score.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "app/bench/bench_report.hpp"
#include "core/mallet.hpp"

namespace mallet::app::input_bench {

ImpactScore score(const std::vector<StrikeTrack>& tracks, const std::vector<std::vector<Found>>& found) {
  ImpactScore s;
  double bias = 0, abs_err = 0, tsum = 0;
  for (std::size_t k = 0; k < tracks.size(); ++k) {
    std::vector<bool> used(found[k].size(), false);
    for (std::size_t i = 0; i < tracks[k].strikes.size(); ++i) {
      const Nanos tc = tracks[k].contacts[i];
      int best = -1;
      for (std::size_t j = 0; j < found[k].size(); ++j) {
        const Found& f = found[k][j];
        if (used[j] || f.target != tracks[k].strikes[i].target || std::llabs(f.t - tc) > 60'000'000) continue;
        if (best < 0 || std::llabs(f.t - tc) < std::llabs(found[k][std::size_t(best)].t - tc)) best = int(j);
      }
      if (best < 0) {
        ++s.missed;
        continue;
      }
      used[std::size_t(best)] = true;
      const Found& f = found[k][std::size_t(best)];
      const double v = tracks[k].strikes[i].speed_m_per_s;
      const double e = (f.speed - v) / v * 100.0;
      bias += e;
      abs_err += std::fabs(e);
      const double dt_ms = double(f.t - tc) * 1e-6;
      tsum += dt_ms;
      s.time_max_abs_ms = std::max(s.time_max_abs_ms, std::fabs(dt_ms));
      ++s.matched;
    }
    for (bool u : used) s.extra += u ? 0 : 1;
  }
  if (s.matched > 0) {
    s.speed_bias_pct = bias / s.matched;
    s.speed_abs_pct = abs_err / s.matched;
    s.time_mean_ms = tsum / s.matched;
  }
  return s;
}

double jitter_mm(const std::vector<Observed>& still, const OneEuroConfig* cfg) {
  double var = 0;
  std::size_t n = 0;
  for (const Observed& o : still) {
    std::optional<OneEuroFilter> f;
    if (cfg) f.emplace(*cfg);
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < o.t.size(); ++i) {
      const Vec2 p = f ? *f->update(o.t[i], o.raw[i]) : o.raw[i];
      if (o.t[i] - o.t.front() >= kNanosPerSecond) out.push_back(p);
    }
    Vec2 m{};
    for (const Vec2& p : out) m = {m.x + p.x, m.y + p.y};
    m = {m.x / double(out.size()), m.y / double(out.size())};
    for (const Vec2& p : out) var += 0.5 * ((p.x - m.x) * (p.x - m.x) + (p.y - m.y) * (p.y - m.y));
    n += out.size();
  }
  return std::sqrt(var / double(n)) * 1e3;
}

double lag_ms(const std::vector<StrikeTrack>& tracks, const std::vector<std::vector<Vec2>>& filtered) {
  auto error_at = [&](double tau_ms) {
    const Nanos tau = static_cast<Nanos>(std::llround(tau_ms * 1e6));
    double err = 0;
    for (std::size_t k = 0; k < tracks.size(); ++k)
      for (std::size_t i : tracks[k].moving) {
        const Vec2 w = tracks[k].path.at(tracks[k].obs.t[i] - tau);
        const Vec2 f = filtered[k][i];
        err += (f.x - w.x) * (f.x - w.x) + (f.y - w.y) * (f.y - w.y);
      }
    return err;
  };
  double best_tau = 0, best_err = std::numeric_limits<double>::infinity();
  for (double tau_ms = -10; tau_ms <= 150; tau_ms += 1.0)
    if (const double e = error_at(tau_ms); e < best_err) {
      best_err = e;
      best_tau = tau_ms;
    }
  const double coarse = best_tau;
  for (double tau_ms = coarse - 1.0; tau_ms <= coarse + 1.0; tau_ms += 0.05)
    if (const double e = error_at(tau_ms); e < best_err) {
      best_err = e;
      best_tau = tau_ms;
    }
  return best_tau;
}

std::vector<std::vector<Vec2>> filter_tracks(const std::vector<StrikeTrack>& tracks, const OneEuroConfig& cfg) {
  std::vector<std::vector<Vec2>> out(tracks.size());
  for (std::size_t k = 0; k < tracks.size(); ++k) {
    OneEuroFilter f(cfg);
    for (std::size_t i = 0; i < tracks[k].obs.t.size(); ++i) out[k].push_back(*f.update(tracks[k].obs.t[i], tracks[k].obs.raw[i]));
  }
  return out;
}

Result evaluate(const Scene& scene, const std::vector<Observed>& still, const std::vector<StrikeTrack>& slow,
                const std::vector<StrikeTrack>& tracks, const OneEuroConfig& cfg) {
  Result r;
  r.cfg = cfg;
  r.jitter_mm = jitter_mm(still, &cfg);
  r.slow_lag_ms = lag_ms(slow, filter_tracks(slow, cfg));
  std::vector<std::vector<Vec2>> filtered(tracks.size());
  std::vector<std::vector<Found>> by_segments(tracks.size()), by_derivative(tracks.size());
  for (std::size_t k = 0; k < tracks.size(); ++k) {
    OneEuroFilter f(cfg);
    Mallet m(scene, ContactConfig{});
    const Observed& o = tracks[k].obs;
    for (std::size_t i = 0; i < o.t.size(); ++i) {
      const Vec2 p = *f.update(o.t[i], o.raw[i]);
      filtered[k].push_back(p);
      if (const std::optional<Impact> imp = m.update(o.t[i], p)) {
        by_segments[k].push_back({imp->t_ns, imp->target, imp->speed_m_per_s});
        by_derivative[k].push_back({imp->t_ns, imp->target, std::max(0.0, -f.velocity().y)});
      }
    }
  }
  r.lag_ms = lag_ms(tracks, filtered);
  r.segments = score(tracks, by_segments);
  r.derivative = score(tracks, by_derivative);
  return r;
}

std::vector<std::vector<Found>> filtered_impacts(const Scene& scene, const std::vector<StrikeTrack>& tracks,
                                                 const OneEuroConfig* cfg) {
  std::vector<std::vector<Found>> found(tracks.size());
  for (std::size_t k = 0; k < tracks.size(); ++k) {
    std::optional<OneEuroFilter> f;
    if (cfg) f.emplace(*cfg);
    Mallet m(scene, ContactConfig{});
    for (std::size_t i = 0; i < tracks[k].obs.t.size(); ++i) {
      const Vec2 p = f ? *f->update(tracks[k].obs.t[i], tracks[k].obs.raw[i]) : tracks[k].obs.raw[i];
      if (const std::optional<Impact> imp = m.update(tracks[k].obs.t[i], p))
        found[k].push_back({imp->t_ns, imp->target, imp->speed_m_per_s});
    }
  }
  return found;
}

}  // namespace mallet::app::input_bench

namespace mallet::app {

using namespace input_bench;

std::vector<PointerTradeRow> measure_pointer_trade(const Scene& scene, std::uint64_t seed, int strikes_per_track,
                                                   int still_tracks, const std::vector<OneEuroConfig>& configs) {
  const Workload w = make_workload(scene, seed, strikes_per_track, still_tracks);
  std::vector<PointerTradeRow> rows;
  {
    PointerTradeRow raw;
    raw.label = "raw";
    const ImpactScore sc = score(w.tracks, filtered_impacts(scene, w.tracks, nullptr));
    std::vector<std::vector<Vec2>> raw_tracks, raw_slow;
    for (const StrikeTrack& t : w.tracks) raw_tracks.push_back(t.obs.raw);
    for (const StrikeTrack& t : w.slow) raw_slow.push_back(t.obs.raw);
    raw.jitter_mm = jitter_mm(w.still, nullptr);
    raw.lag_ms = lag_ms(w.tracks, raw_tracks);
    raw.slow_lag_ms = lag_ms(w.slow, raw_slow);
    raw.speed_abs_pct = sc.speed_abs_pct;
    raw.time_max_ms = sc.time_max_abs_ms;
    raw.missed = sc.missed;
    raw.extra = sc.extra;
    rows.push_back(raw);
  }
  for (const OneEuroConfig& cfg : configs) {
    const Result r = evaluate(scene, w.still, w.slow, w.tracks, cfg);
    PointerTradeRow row;
    const std::string label = fmt::format("min_cutoff {:g} Hz, beta {:g} /m", cfg.min_cutoff_hz, cfg.beta_per_m);
    row.label = label;
    row.cfg = cfg;
    row.jitter_mm = r.jitter_mm;
    row.lag_ms = r.lag_ms;
    row.slow_lag_ms = r.slow_lag_ms;
    row.speed_abs_pct = r.segments.speed_abs_pct;
    row.time_max_ms = r.segments.time_max_abs_ms;
    row.missed = r.segments.missed;
    row.extra = r.segments.extra;
    rows.push_back(row);
  }
  return rows;
}

}  // namespace mallet::app
