#pragma once
// The could_stop guarantee as a check shared by the predictor's tests for every tracker: a
// hand that stops clearance_m or more above a bar, its braking peaking at no more than half
// of braking_m_per_s2, is never predicted, on exact samples, for any peak speed in the
// corpus's range (0.2–4 m/s), stop height and sample phase. (Half: the quadratic lags
// braking that is building up, so its speed, and the stopping distance from it, run high.)
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/contact_predictor.hpp"
#include "core/pointer_sample.hpp"
#include "core/scene.hpp"

namespace mallet::test {

//! A minimum-jerk descent from `from_y` to `to_y` over `duration_s`, held there, sampled at
//! `rate_hz` from `phase` of a period on, after 50 ms at rest; times from `t0`.
inline std::vector<PointerSample> min_jerk_descent(Nanos t0, double x, double from_y, double to_y, double duration_s,
                                                   double rate_hz, double phase) {
  std::vector<PointerSample> out;
  for (int k = 0;; ++k) {
    const double t = (k + phase) / rate_hz - 0.05;
    if (t > duration_s + 0.3) break;
    const double u = std::clamp(t / duration_s, 0.0, 1.0);
    const double s = ((6 * u - 15) * u + 10) * u * u * u;
    out.push_back({t0 + static_cast<Nanos>(std::llround(t * 1e9)), x, from_y + (to_y - from_y) * s});
  }
  return out;
}

//! Every stop of the guarantee's range over bar `target` of `scene`, at `rate_hz`, fed to a
//! predictor with `config`: a failure names the stroke. Returns how many strokes were tried.
inline int expect_stops_never_predicted(const PredictionConfig& config, const Scene& scene, int target,
                                        double rate_hz, Nanos t0) {
  constexpr double kMinJerkPeakAccel = 5.7735, kMinJerkPeakSpeed = 1.875;  // × D/T², × D/T
  const std::vector<ContactZone> zones = contact_zones(scene);
  const Target& bar = scene.targets[static_cast<std::size_t>(target)];
  const double x = 0.5 * (bar.x_min + bar.x_max);
  const double plane = bar.top_y + scene.mallet_radius_m;
  int strokes = 0;
  for (double peak : {0.2, 0.5, 1.0, 2.0, 4.0}) {
    // The shortest travel at this peak speed whose braking stays within half the config's.
    const double travel = std::max(0.02, kMinJerkPeakAccel * peak * peak /
                                             (kMinJerkPeakSpeed * kMinJerkPeakSpeed * 0.5 * config.braking_m_per_s2));
    const double duration = kMinJerkPeakSpeed * travel / peak;
    for (double above : {0.0, 0.0005, 0.002, 0.005, 0.010}) {
      const double stop_y = plane + config.clearance_m + above;
      for (double phase : {0.0, 0.25, 0.5, 0.75}) {
        ContactPredictor p(config);
        for (const PointerSample& s : min_jerk_descent(t0, x, stop_y + travel, stop_y, duration, rate_hz, phase)) {
          p.add(s.t_ns, {s.x, s.y});
          if (p.predict(zones)) {
            ADD_FAILURE() << "predicted: peak " << peak << " m/s, stops " << (config.clearance_m + above) * 1e3
                          << " mm above, rate " << rate_hz << ", phase " << phase;
            break;
          }
        }
        ++strokes;
      }
    }
  }
  return strokes;
}

}  // namespace mallet::test
