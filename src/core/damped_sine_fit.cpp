#include "core/damped_sine_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace mallet {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

struct Params {
  double a, b, f, phi;
};

double model(const Params& p, double t) { return p.a * std::exp(-p.b * t) * std::sin(kTwoPi * p.f * t + p.phi); }

double sum_sq(std::span<const double> y, double rate, double t0, const Params& p) {
  double s = 0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double r = y[i] - model(p, t0 + static_cast<double>(i) / rate);
    s += r * r;
  }
  return s;
}

// Solves the 4×4 system A·x = g by Gaussian elimination with partial pivoting.
bool solve4(std::array<std::array<double, 4>, 4> A, std::array<double, 4> g, std::array<double, 4>& x) {
  for (int c = 0; c < 4; ++c) {
    int pivot = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::fabs(A[r][c]) > std::fabs(A[pivot][c])) pivot = r;
    if (std::fabs(A[pivot][c]) < 1e-300) return false;
    std::swap(A[c], A[pivot]);
    std::swap(g[c], g[pivot]);
    for (int r = c + 1; r < 4; ++r) {
      const double k = A[r][c] / A[c][c];
      for (int cc = c; cc < 4; ++cc) A[r][cc] -= k * A[c][cc];
      g[r] -= k * g[c];
    }
  }
  for (int r = 3; r >= 0; --r) {
    double s = g[r];
    for (int c = r + 1; c < 4; ++c) s -= A[r][c] * x[c];
    x[r] = s / A[r][r];
  }
  return true;
}

}  // namespace

DampedSineFit fit_damped_sine(std::span<const double> y, double rate, double t0) {
  DampedSineFit out;
  if (y.size() < 8 || !(rate > 0)) return out;
  double peak = 0;
  for (double v : y) peak = std::max(peak, std::fabs(v));
  if (!(peak > 0) || !std::isfinite(peak)) return out;

  // Fit the part of the signal down to 2% of its peak: past it, noise and rounding
  // carry more weight than the decay.
  std::size_t n = y.size();
  while (n > 8 && std::fabs(y[n - 1]) < 0.02 * peak) --n;
  y = y.first(n);
  auto time = [&](double i) { return t0 + i / rate; };

  // Start values come from the strong part of the signal (down to 10% of the peak).
  // Zero crossings give f and φ, with hysteresis so that noise around zero does not
  // count: a crossing is confirmed when the signal reaches ±5% of the peak on the other
  // side, and placed where the sign last changed before that.
  std::size_t strong = y.size();
  while (strong > 8 && std::fabs(y[strong - 1]) < 0.1 * peak) --strong;
  const double h = 0.05 * peak;
  std::vector<double> crossings;
  int side = 0;
  std::size_t last_change = 0;
  for (std::size_t i = 1; i < strong; ++i) {
    if ((y[i - 1] < 0) != (y[i] < 0)) last_change = i;
    const int now = y[i] > h ? 1 : (y[i] < -h ? -1 : 0);
    if (now != 0 && side != 0 && now != side && last_change > 0) {
      const double a = y[last_change - 1], b = y[last_change];
      crossings.push_back(time(static_cast<double>(last_change - 1) + a / (a - b)));
    }
    if (now != 0) side = now;
  }
  if (crossings.size() < 2) return out;
  Params p{};
  p.f = 0.5 * static_cast<double>(crossings.size() - 1) / (crossings.back() - crossings.front());

  // Half-cycle peaks of |y| → log-linear regression for b and a.
  std::vector<std::pair<double, double>> peaks;  // (t, ln|y|)
  std::size_t start = 0;
  for (std::size_t k = 0; k <= crossings.size(); ++k) {
    const std::size_t end = k < crossings.size()
                                ? std::min(strong, static_cast<std::size_t>(std::max(0.0, (crossings[k] - t0) * rate)) + 1)
                                : strong;
    std::size_t best = start;
    for (std::size_t i = start; i < end; ++i)
      if (std::fabs(y[i]) > std::fabs(y[best])) best = i;
    if (end > start && std::fabs(y[best]) > 0) peaks.emplace_back(time(static_cast<double>(best)), std::log(std::fabs(y[best])));
    start = end;
  }
  if (peaks.size() >= 2) {
    double st = 0, sl = 0, stt = 0, stl = 0;
    for (auto [t, l] : peaks) {
      st += t;
      sl += l;
      stt += t * t;
      stl += t * l;
    }
    const double m = static_cast<double>(peaks.size());
    const double slope = (m * stl - st * sl) / (m * stt - st * st);
    p.b = std::max(0.0, -slope);
    p.a = std::exp((sl - slope * st) / m);
  } else {
    p.b = 0;
    p.a = peak;
  }
  // Phase from the first crossing: sin(2πf·t + φ) = 0 there, rising or falling.
  const bool rising = y[static_cast<std::size_t>(std::min<double>(static_cast<double>(y.size() - 1), (crossings.front() - t0) * rate + 1))] > 0;
  p.phi = (rising ? 0.0 : std::numbers::pi) - kTwoPi * p.f * crossings.front();
  p.phi = std::remainder(p.phi, kTwoPi);

  // Levenberg–Marquardt.
  double lambda = 1e-3;
  double cost = sum_sq(y, rate, t0, p);
  for (int iter = 0; iter < 200; ++iter) {
    std::array<std::array<double, 4>, 4> JTJ{};
    std::array<double, 4> JTr{};
    for (std::size_t i = 0; i < y.size(); ++i) {
      const double t = time(static_cast<double>(i));
      const double e = std::exp(-p.b * t);
      const double arg = kTwoPi * p.f * t + p.phi;
      const double s = std::sin(arg), c = std::cos(arg);
      const std::array<double, 4> J{e * s, -t * p.a * e * s, kTwoPi * t * p.a * e * c, p.a * e * c};
      const double r = y[i] - p.a * e * s;
      for (int u = 0; u < 4; ++u) {
        JTr[u] += J[u] * r;
        for (int v = 0; v < 4; ++v) JTJ[u][v] += J[u] * J[v];
      }
    }
    bool improved = false;
    for (int tries = 0; tries < 20 && !improved; ++tries) {
      auto A = JTJ;
      for (int u = 0; u < 4; ++u) A[u][u] *= 1.0 + lambda;
      std::array<double, 4> d{};
      if (!solve4(A, JTr, d)) break;
      const Params q{p.a + d[0], p.b + d[1], p.f + d[2], p.phi + d[3]};
      const double qc = sum_sq(y, rate, t0, q);
      if (qc < cost) {
        const double gain = cost - qc;
        p = q;
        cost = qc;
        lambda = std::max(lambda * 0.3, 1e-12);
        improved = true;
        if (gain < 1e-15 * (cost + 1e-300)) iter = 1000;  // converged
      } else {
        lambda *= 10;
      }
    }
    if (!improved) break;
  }
  if (p.a < 0) {
    p.a = -p.a;
    p.phi += std::numbers::pi;
  }
  out.amplitude = p.a;
  out.decay_per_s = p.b;
  out.freq_hz = p.f;
  out.phase_rad = std::remainder(p.phi, kTwoPi);
  out.rms_residual = std::sqrt(cost / static_cast<double>(y.size())) / p.a;
  out.ok = std::isfinite(cost) && p.f > 0;
  return out;
}

}  // namespace mallet
