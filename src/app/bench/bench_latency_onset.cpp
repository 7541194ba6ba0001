#include "app/bench/bench_latency_onset.hpp"

#include <algorithm>
#include <cmath>

namespace mallet::app::latency {

namespace {

//! Solves A·a = b (A symmetric positive definite, n×n, row-major) in place by Cholesky;
//! false when A is not positive definite.
bool solve_spd(std::vector<double>& A, std::vector<double>& b, int n) {
  for (int j = 0; j < n; ++j) {
    double d = A[static_cast<std::size_t>(j * n + j)];
    for (int k = 0; k < j; ++k) d -= A[static_cast<std::size_t>(j * n + k)] * A[static_cast<std::size_t>(j * n + k)];
    if (!(d > 0)) return false;
    const double l = std::sqrt(d);
    A[static_cast<std::size_t>(j * n + j)] = l;
    for (int i = j + 1; i < n; ++i) {
      double s = A[static_cast<std::size_t>(i * n + j)];
      for (int k = 0; k < j; ++k) s -= A[static_cast<std::size_t>(i * n + k)] * A[static_cast<std::size_t>(j * n + k)];
      A[static_cast<std::size_t>(i * n + j)] = s / l;
    }
  }
  for (int i = 0; i < n; ++i) {  // L·y = b
    double s = b[static_cast<std::size_t>(i)];
    for (int k = 0; k < i; ++k) s -= A[static_cast<std::size_t>(i * n + k)] * b[static_cast<std::size_t>(k)];
    b[static_cast<std::size_t>(i)] = s / A[static_cast<std::size_t>(i * n + i)];
  }
  for (int i = n - 1; i >= 0; --i) {  // Lᵀ·a = y
    double s = b[static_cast<std::size_t>(i)];
    for (int k = i + 1; k < n; ++k) s -= A[static_cast<std::size_t>(k * n + i)] * b[static_cast<std::size_t>(k)];
    b[static_cast<std::size_t>(i)] = s / A[static_cast<std::size_t>(i * n + i)];
  }
  return true;
}

}  // namespace

std::optional<std::size_t> find_onset(const std::vector<float>& x, std::size_t from, std::size_t to,
                                      const OnsetSearch& search, const std::vector<Gap>& gaps) {
  to = std::min(to, x.size());
  if (from >= to) return std::nullopt;
  const int p = search.order;
  const std::size_t start = from > search.training ? from - search.training : 0;
  double peak = 0;
  for (std::size_t i = start; i < from; ++i) peak = std::max(peak, static_cast<double>(std::fabs(x[i])));
  // The gap holding i, if any.
  auto gap_at = [&](std::size_t i) -> const Gap* {
    auto it = std::upper_bound(gaps.begin(), gaps.end(), i, [](std::size_t v, const Gap& g) { return v < g.begin; });
    if (it == gaps.begin()) return nullptr;
    --it;
    return i < it->end ? &*it : nullptr;
  };
  // Over silence a seam changes nothing: the first sample above it is the strike's.
  auto first_above = [&](double level) -> std::optional<std::size_t> {
    for (std::size_t i = from; i < to; ++i)
      if (std::fabs(x[i]) > level) return i;
    return std::nullopt;
  };
  if (peak < search.silence || from - start < static_cast<std::size_t>(4 * p)) return first_above(search.silence);

  // The covariance method: least squares of x[n] on x[n−1..n−p] over the training window.
  const auto P = static_cast<std::size_t>(p);
  std::vector<double> A(P * P, 0.0), a(P, 0.0);
  for (std::size_t n = start + P; n < from; ++n)
    for (std::size_t j = 0; j < P; ++j) {
      const double xj = x[n - 1 - j];
      a[j] += x[n] * xj;
      for (std::size_t k = 0; k <= j; ++k) A[j * P + k] += xj * x[n - 1 - k];
    }
  double trace = 0;
  for (std::size_t j = 0; j < P; ++j) {
    for (std::size_t k = 0; k < j; ++k) A[k * P + j] = A[j * P + k];
    trace += A[j * P + j];
  }
  for (std::size_t j = 0; j < P; ++j) A[j * P + j] += 1e-10 * trace / p + 1e-300;  // keeps a pure tone solvable
  if (!solve_spd(A, a, p)) return first_above(search.floor + peak);

  auto residual = [&](std::size_t n) {
    double pred = 0;
    for (std::size_t k = 0; k < P; ++k) pred += a[k] * x[n - 1 - k];
    return x[n] - pred;
  };
  double sum = 0;
  std::size_t count = 0;
  for (std::size_t n = start + P; n < from; ++n, ++count) sum += residual(n) * residual(n);
  const double rms = std::sqrt(sum / static_cast<double>(std::max<std::size_t>(count, 1)));
  const double threshold = std::max(search.floor, search.factor * rms);
  for (std::size_t n = from; n < to; ++n) {
    if (std::fabs(residual(n)) <= threshold) continue;
    const Gap* g = gap_at(n);
    if (!g) return n;
    // A seam, or a strike inside the gap: past it, once the predictor's history is clean
    // again, a ring alone is predicted as before; a new strike is not, and then where it
    // began cannot be told: nothing rather than a wrong time.
    const std::size_t resume = g->end + P;
    for (std::size_t k = resume; k < std::min(resume + 32, to); ++k)
      if (std::fabs(residual(k)) > threshold) return std::nullopt;
    n = resume + 31;
  }
  return std::nullopt;
}

}  // namespace mallet::app::latency
