#include "core/homography.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <fmt/format.h>

namespace mallet {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double frobenius(const std::array<double, 9>& m) {
  double s = 0;
  for (double v : m) s += v * v;
  return std::sqrt(s);
}

std::array<double, 9> multiply(const std::array<double, 9>& a, const std::array<double, 9>& b) {
  std::array<double, 9> c{};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j) c[r * 3 + j] += a[r * 3 + k] * b[k * 3 + j];
  return c;
}

// Scale so h33 = 1 (the readable form) unless h33 is ~0, then to unit Frobenius norm.
std::array<double, 9> canonical(std::array<double, 9> m) {
  const double norm = frobenius(m);
  const double scale = std::abs(m[8]) > 1e-9 * norm ? m[8] : norm;
  for (double& v : m) v /= scale;
  return m;
}

std::string point_text(Vec2 p) {
  return fmt::format("({:.6g}, {:.6g})", p.x, p.y);
}

// Distance of one vertex from the line through the other two, over the longest side:
// 0 for collinear points, √3/2 for an equilateral triangle. Scale invariant.
double flatness(Vec2 a, Vec2 b, Vec2 c) {
  const double cross = std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  auto sq = [](Vec2 p, Vec2 q) { return (p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y); };
  const double longest = std::max({sq(a, b), sq(a, c), sq(b, c)});
  return longest > 0 ? cross / longest : 0.0;
}

// The worst (smallest) flatness of the four triangles of a quadruple, on both sides.
double quad_flatness(std::span<const Vec2> from, std::span<const Vec2> to, const std::array<std::size_t, 4>& q) {
  double worst = std::numeric_limits<double>::infinity();
  for (std::span<const Vec2> pts : {from, to}) {
    worst = std::min({worst, flatness(pts[q[0]], pts[q[1]], pts[q[2]]), flatness(pts[q[0]], pts[q[1]], pts[q[3]]),
                      flatness(pts[q[0]], pts[q[2]], pts[q[3]]), flatness(pts[q[1]], pts[q[2]], pts[q[3]])});
  }
  return worst;
}

// Is there a set of 4 correspondences with no 3 collinear on either side? Exhaustive
// (stopping at the first) for calibration-sized sets, greedy (two far points, the point
// farthest from their line, then the best fourth) for large ones.
bool has_general_quadruple(std::span<const Vec2> from, std::span<const Vec2> to) {
  const std::size_t n = from.size();
  if (n <= 40) {
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = a + 1; b < n; ++b)
        for (std::size_t c = b + 1; c < n; ++c) {
          if (std::min(flatness(from[a], from[b], from[c]), flatness(to[a], to[b], to[c])) < kCollinearTolerance)
            continue;
          for (std::size_t d = c + 1; d < n; ++d)
            if (quad_flatness(from, to, {a, b, c, d}) >= kCollinearTolerance) return true;
        }
    return false;
  }
  auto dist2 = [&](std::size_t i, std::size_t j) {
    return (from[i].x - from[j].x) * (from[i].x - from[j].x) + (from[i].y - from[j].y) * (from[i].y - from[j].y);
  };
  std::size_t a = 0, b = 1;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (dist2(i, j) > dist2(a, b)) a = i, b = j;
  std::size_t c = n;
  double best = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double f = std::min(flatness(from[a], from[b], from[i]), flatness(to[a], to[b], to[i]));
    if (f > best) best = f, c = i;
  }
  if (c == n) return false;
  for (std::size_t d = 0; d < n; ++d)
    if (d != a && d != b && d != c && quad_flatness(from, to, {a, b, c, d}) >= kCollinearTolerance) return true;
  return false;
}

// Hartley's normalisation: T moves the centroid to 0 and the mean distance to √2.
std::optional<std::array<double, 9>> normalising_transform(std::span<const Vec2> pts) {
  double cx = 0, cy = 0;
  for (Vec2 p : pts) cx += p.x, cy += p.y;
  cx /= static_cast<double>(pts.size());
  cy /= static_cast<double>(pts.size());
  double mean = 0;
  for (Vec2 p : pts) mean += std::hypot(p.x - cx, p.y - cy);
  mean /= static_cast<double>(pts.size());
  if (!(mean > 0) || !std::isfinite(mean)) return std::nullopt;
  const double s = std::sqrt(2.0) / mean;
  return std::array<double, 9>{s, 0, -s * cx, 0, s, -s * cy, 0, 0, 1};
}

Vec2 apply(const std::array<double, 9>& m, Vec2 p) {
  const double w = m[6] * p.x + m[7] * p.y + m[8];
  return {(m[0] * p.x + m[1] * p.y + m[2]) / w, (m[3] * p.x + m[4] * p.y + m[5]) / w};
}

// One-sided Jacobi SVD (Hestenes) of the m×9 matrix `a` (row-major): rotates pairs of
// columns until all are orthogonal. On return the column norms are the singular values and
// `v` (9×9, row-major) holds the right singular vectors as columns. Accurate to machine
// precision relative to the largest singular value, and only 40 lines.
void jacobi_svd(std::vector<double>& a, std::size_t m, std::array<double, 81>& v, std::array<double, 9>& sigma) {
  constexpr std::size_t n = 9;
  v.fill(0);
  for (std::size_t i = 0; i < n; ++i) v[i * n + i] = 1;
  for (int sweep = 0; sweep < 60; ++sweep) {
    bool rotated = false;
    for (std::size_t p = 0; p < n; ++p)
      for (std::size_t q = p + 1; q < n; ++q) {
        double alpha = 0, beta = 0, gamma = 0;
        for (std::size_t r = 0; r < m; ++r) {
          const double ap = a[r * n + p], aq = a[r * n + q];
          alpha += ap * ap;
          beta += aq * aq;
          gamma += ap * aq;
        }
        if (!(std::abs(gamma) > 1e-15 * std::sqrt(alpha * beta))) continue;
        rotated = true;
        const double zeta = (beta - alpha) / (2 * gamma);
        const double t = (zeta >= 0 ? 1.0 : -1.0) / (std::abs(zeta) + std::sqrt(1 + zeta * zeta));
        const double c = 1 / std::sqrt(1 + t * t), s = c * t;
        for (std::size_t r = 0; r < m; ++r) {
          const double ap = a[r * n + p], aq = a[r * n + q];
          a[r * n + p] = c * ap - s * aq;
          a[r * n + q] = s * ap + c * aq;
        }
        for (std::size_t r = 0; r < n; ++r) {
          const double vp = v[r * n + p], vq = v[r * n + q];
          v[r * n + p] = c * vp - s * vq;
          v[r * n + q] = s * vp + c * vq;
        }
      }
    if (!rotated) break;
  }
  for (std::size_t j = 0; j < n; ++j) {
    double s = 0;
    for (std::size_t r = 0; r < m; ++r) s += a[r * n + j] * a[r * n + j];
    sigma[j] = std::sqrt(s);
  }
}

void summarise(const std::vector<double>& e, double& rms, double& max) {
  double sum = 0;
  max = 0;
  for (double v : e) sum += v * v, max = std::max(max, v);
  rms = e.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(e.size()));
}

}  // namespace

double Homography::determinant() const {
  return h[0] * (h[4] * h[8] - h[5] * h[7]) - h[1] * (h[3] * h[8] - h[5] * h[6]) + h[2] * (h[3] * h[7] - h[4] * h[6]);
}

Vec2 Homography::map(Vec2 p) const {
  const std::optional<Vec2> q = try_map(p);
  return q ? *q : Vec2{kNaN, kNaN};
}

std::optional<Vec2> Homography::try_map(Vec2 p) const {
  const double w = h[6] * p.x + h[7] * p.y + h[8];
  // |w| tiny next to the terms that make it: p is (numerically) on the vanishing line.
  const double scale = std::abs(h[6] * p.x) + std::abs(h[7] * p.y) + std::abs(h[8]);
  if (!(std::abs(w) > 1e-12 * scale)) return std::nullopt;
  const Vec2 q = apply(h, p);
  if (!std::isfinite(q.x) || !std::isfinite(q.y)) return std::nullopt;
  return q;
}

std::optional<Homography> Homography::inverse() const {
  const double norm = frobenius(h);
  const double det = determinant();
  if (!std::isfinite(det) || !(std::abs(det) > 1e-12 * norm * norm * norm)) return std::nullopt;
  const std::array<double, 9> adj{h[4] * h[8] - h[5] * h[7], h[2] * h[7] - h[1] * h[8], h[1] * h[5] - h[2] * h[4],
                                  h[5] * h[6] - h[3] * h[8], h[0] * h[8] - h[2] * h[6], h[2] * h[3] - h[0] * h[5],
                                  h[3] * h[7] - h[4] * h[6], h[1] * h[6] - h[0] * h[7], h[0] * h[4] - h[1] * h[3]};
  return Homography{canonical(adj)};  // adj = det·H⁻¹; the scale does not matter
}

Result<HomographyFit, std::string> fit_homography(std::span<const Vec2> from, std::span<const Vec2> to,
                                                  ScreenSize screen) {
  if (from.size() != to.size())
    return refused("got " + std::to_string(from.size()) + " camera points but " + std::to_string(to.size()) +
                   " screen points");
  const std::size_t n = from.size();
  if (n < 4)
    return refused("a homography needs at least 4 points, got " + std::to_string(n));
  if (!(screen.width_px > 0 && screen.height_px > 0 && std::isfinite(screen.width_px) &&
        std::isfinite(screen.height_px)))
    return refused("the screen size must be finite and > 0 pixels");
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(from[i].x) || !std::isfinite(from[i].y))
      return refused("point " + std::to_string(i + 1) + ": the camera coordinates are not finite numbers");
    if (!std::isfinite(to[i].x) || !std::isfinite(to[i].y))
      return refused("point " + std::to_string(i + 1) + ": the screen coordinates are not finite numbers");
  }
  // Fit in screen pixels: the isotropic normalisation then weighs x and y errors as they
  // are measured (normalised 0..1 screen units are not square).
  std::vector<Vec2> to_px(n);
  for (std::size_t i = 0; i < n; ++i) to_px[i] = {to[i].x * screen.width_px, to[i].y * screen.height_px};

  for (std::span<const Vec2> pts : {from, std::span<const Vec2>(to_px)}) {
    const bool camera = pts.data() == from.data();
    double extent = 0;
    for (std::size_t i = 1; i < n; ++i) extent = std::max(extent, std::hypot(pts[i].x - pts[0].x, pts[i].y - pts[0].y));
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        if (std::hypot(pts[i].x - pts[j].x, pts[i].y - pts[j].y) <= 1e-9 * extent)
          return refused("points " + std::to_string(i + 1) + " and " + std::to_string(j + 1) + " repeat the same " +
                         (camera ? "camera point " + point_text(from[i]) : "screen point " + point_text(to[i])) +
                         ": every point must be distinct");
  }
  if (!has_general_quadruple(from, to_px)) {
    if (n == 4) {
      for (std::size_t a = 0; a < 4; ++a) {
        const std::size_t b = (a + 1) % 4, c = (a + 2) % 4;
        std::size_t t[3] = {a, b, c};
        std::sort(t, t + 3);
        const bool cam = flatness(from[t[0]], from[t[1]], from[t[2]]) < kCollinearTolerance;
        if (cam || flatness(to_px[t[0]], to_px[t[1]], to_px[t[2]]) < kCollinearTolerance)
          return refused("points " + std::to_string(t[0] + 1) + ", " + std::to_string(t[1] + 1) + " and " +
                         std::to_string(t[2] + 1) + " are (nearly) on one line in " + (cam ? "camera" : "screen") +
                         " coordinates: a homography needs 4 points with no 3 on a line");
      }
    }
    return refused("no 4 of the " + std::to_string(n) +
                   " points are in general position (with no 3 on a line, in camera and screen coordinates): spread "
                   "the points over the screen, e.g. its 4 corners");
  }

  const auto t_from = normalising_transform(from);
  const auto t_to = normalising_transform(to_px);
  if (!t_from || !t_to) return refused("the points are too far apart or too close together to fit");
  std::vector<double> a(std::max<std::size_t>(2 * n, 9) * 9, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 p = apply(*t_from, from[i]);
    const Vec2 q = apply(*t_to, to_px[i]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(q.x) || !std::isfinite(q.y))
      return refused("the coordinates are too large to fit");
    // From q × (H p) = 0: two independent rows per correspondence (H&Z eq. 4.3).
    double* r0 = &a[(2 * i) * 9];
    double* r1 = &a[(2 * i + 1) * 9];
    const double row0[9] = {0, 0, 0, -p.x, -p.y, -1, q.y * p.x, q.y * p.y, q.y};
    const double row1[9] = {p.x, p.y, 1, 0, 0, 0, -q.x * p.x, -q.x * p.y, -q.x};
    std::copy(row0, row0 + 9, r0);
    std::copy(row1, row1 + 9, r1);
  }
  std::array<double, 81> v{};
  std::array<double, 9> sigma{};
  jacobi_svd(a, a.size() / 9, v, sigma);
  std::array<std::size_t, 9> order{0, 1, 2, 3, 4, 5, 6, 7, 8};
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return sigma[i] < sigma[j]; });
  // A unique solution needs rank 8: the second smallest singular value must be clear of 0.
  if (!(sigma[order[1]] > 1e-9 * sigma[order[8]]))
    return refused("the points do not determine a homography (the linear system is rank deficient)");
  std::array<double, 9> hn{};
  for (std::size_t r = 0; r < 9; ++r) hn[r] = v[r * 9 + order[0]];

  // H = T_to⁻¹ · Hn · T_from, then from screen pixels back to normalised screen units.
  const double s_to = (*t_to)[0];
  const std::array<double, 9> t_to_inv{1 / s_to, 0, -(*t_to)[2] / s_to, 0, 1 / s_to, -(*t_to)[5] / s_to, 0, 0, 1};
  const std::array<double, 9> px_to_unit{1 / screen.width_px, 0, 0, 0, 1 / screen.height_px, 0, 0, 0, 1};
  HomographyFit fit;
  fit.screen = screen;
  fit.h.h = canonical(multiply(px_to_unit, multiply(t_to_inv, multiply(hn, *t_from))));
  for (double x : fit.h.h)
    if (!std::isfinite(x)) return refused("the fit is not finite (the coordinates are out of range)");

  const std::optional<Homography> inverse = fit.h.inverse();
  if (!inverse)
    return refused("the fitted map is singular: the points are inconsistent (check that each camera point is "
                   "paired with its own screen point)");
  // All points must be on the same side of the line the map sends to infinity; otherwise
  // the map folds the plane between them (e.g. two corners swapped).
  int positive = 0, negative = 0;
  for (Vec2 p : from) (fit.h.h[6] * p.x + fit.h.h[7] * p.y + fit.h.h[8] > 0 ? positive : negative)++;
  if (positive && negative)
    return refused("the best fit folds the screen over (points straddle its vanishing line): the camera and "
                   "screen points are probably paired in the wrong order");

  fit.reprojection_error_px.resize(n);
  fit.camera_error_px.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 s = fit.h.map(from[i]);
    fit.reprojection_error_px[i] = std::hypot((s.x - to[i].x) * screen.width_px, (s.y - to[i].y) * screen.height_px);
    const Vec2 c = inverse->map(to[i]);
    fit.camera_error_px[i] = std::hypot(c.x - from[i].x, c.y - from[i].y);
  }
  summarise(fit.reprojection_error_px, fit.rms_px, fit.max_px);
  summarise(fit.camera_error_px, fit.camera_rms_px, fit.camera_max_px);
  if (!std::isfinite(fit.rms_px) || !std::isfinite(fit.camera_rms_px))
    return refused("the fit sends a calibration point to infinity: the points are inconsistent");
  return fit;
}

}  // namespace mallet
