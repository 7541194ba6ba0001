#include "input/camera/led_finder.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mallet::input::camera {

Check validate(const LedFinderConfig& c) {
  if (c.min_contrast < 1 || c.min_contrast > 254) return refused("min_contrast must be 1..254 grey levels");
  if (!std::isfinite(c.threshold_fraction) || c.threshold_fraction < 0 || c.threshold_fraction >= 1)
    return refused("threshold_fraction must be a number in [0, 1)");
  if (c.min_area_px < 1) return refused("min_area_px must be >= 1");
  if (c.max_area_px < c.min_area_px) return refused("max_area_px must be >= min_area_px");
  if (!std::isfinite(c.max_elongation) || c.max_elongation < 1) return refused("max_elongation must be a number >= 1");
  if (c.roi_radius_px < 1) return refused("roi_radius_px must be >= 1");
  if (c.centroid_margin_px < 0 || c.centroid_margin_px > 16) return refused("centroid_margin_px must be 0..16");
  if (!std::isfinite(c.track_min_sum_ratio) || c.track_min_sum_ratio < 0 || c.track_min_sum_ratio > 1)
    return refused("track_min_sum_ratio must be a number in [0, 1]");
  if (c.max_runs < 1) return refused("max_runs must be >= 1");
  return {};
}

namespace {

// The brightest luma of row y, x0..x1. Step 1 (GREY, MJPEG) is a plain byte loop the
// compiler vectorises: this pass reads every pixel of a full search, so it is the cost.
int row_max(const LumaView& v, int y, int x0, int x1) {
  const std::uint8_t* p = v.data + y * v.row_stride;
  std::uint8_t m = 0;
  if (v.pixel_step == 1) {
    for (int x = x0; x <= x1; ++x) m = std::max(m, p[x]);
  } else if (v.pixel_step == 2) {
    for (int x = x0; x <= x1; ++x) m = std::max(m, p[2 * x]);
  } else {
    for (int x = x0; x <= x1; ++x) m = std::max(m, p[static_cast<std::ptrdiff_t>(x) * v.pixel_step]);
  }
  return m;
}

double dist2(double ax, double ay, double bx, double by) { return (ax - bx) * (ax - bx) + (ay - by) * (ay - by); }

}  // namespace

LedFinder::LedFinder(LedFinderConfig config) : config_(config) {
  if (const Check why = validate(config_); !why) throw std::invalid_argument("LED finder: " + why.error());
}

void LedFinder::reset() {
  last_.reset();
  step_x_ = step_y_ = 0;
}

int LedFinder::find_root(int i) {
  while (runs_[static_cast<std::size_t>(i)].parent != i) {
    Run& r = runs_[static_cast<std::size_t>(i)];
    r.parent = runs_[static_cast<std::size_t>(r.parent)].parent;  // path halving
    i = r.parent;
  }
  return i;
}

LedFind LedFinder::find(const LumaView& luma) {
  LedFind out;
  ++counters_.frames;
  if (luma.data == nullptr || luma.width < 1 || luma.height < 1) {
    reset();
    ++counters_.lost;
    return out;
  }
  const Region whole{0, 0, luma.width - 1, luma.height - 1};
  bool found = false;
  if (last_) {
    const double px = last_->x + step_x_, py = last_->y + step_y_;
    const int r = config_.roi_radius_px;
    const Region roi{std::max(0, static_cast<int>(std::lround(px)) - r), std::max(0, static_cast<int>(std::lround(py)) - r),
                     std::min(whole.x1, static_cast<int>(std::lround(px)) + r),
                     std::min(whole.y1, static_cast<int>(std::lround(py)) + r)};
    if (roi.x0 <= roi.x1 && roi.y0 <= roi.y1) found = search(luma, roi, true, out);
    if (!found) ++counters_.roi_misses;
  }
  if (!found) {
    out = LedFind{};
    out.full_search = true;
    ++counters_.full_searches;
    found = search(luma, whole, false, out);
  }
  LedRejections& total = counters_.rejected;
  total.too_small += out.rejected.too_small;
  total.too_large += out.rejected.too_large;
  total.elongated += out.rejected.elongated;
  total.too_dim += out.rejected.too_dim;
  total.cluttered += out.rejected.cluttered;
  if (!found) {
    reset();
    ++counters_.lost;
    return out;
  }
  ++counters_.found;
  // The step predicts the next square; after a full search it may be a jump, not a motion.
  const bool continued = last_ && !out.full_search;
  step_x_ = continued ? out.led->x - last_->x : 0;
  step_y_ = continued ? out.led->y - last_->y : 0;
  last_ = out.led;
  return out;
}

bool LedFinder::search(const LumaView& v, const Region& r, bool nearest, LedFind& out) {
  const int rows = r.y1 - r.y0 + 1, cols = r.x1 - r.x0 + 1;
  // Pass 1: each row's maximum (rows without the threshold are then skipped) and the peak.
  row_max_.resize(static_cast<std::size_t>(rows));
  int peak = 0;
  for (int y = r.y0; y <= r.y1; ++y) {
    const int m = row_max(v, y, r.x0, r.x1);
    row_max_[static_cast<std::size_t>(y - r.y0)] = static_cast<std::uint8_t>(m);
    peak = std::max(peak, m);
  }
  // The background: the median of about a thousand pixels spread over the region. The LED
  // and any lights cover a few hundred pixels of 300 000, so they cannot move it.
  const int step = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(rows) * cols / 1024.0)));
  std::array<int, 256> hist{};
  int samples = 0;
  for (int y = r.y0 + step / 2; y <= r.y1; y += step)
    for (int x = r.x0 + step / 2; x <= r.x1; x += step, ++samples) ++hist[v.at(x, y)];
  int background = 0;
  for (int seen = 0; background < 255; ++background) {
    seen += hist[static_cast<std::size_t>(background)];
    if (2 * seen >= samples) break;
  }
  out.background = background;
  if (peak - background < config_.min_contrast) return false;  // all dark, all white, or flat
  const int threshold = background + std::max(config_.min_contrast,
                                              static_cast<int>(std::ceil(config_.threshold_fraction * (peak - background))));
  out.threshold = threshold;

  // Pass 2: runs of pixels >= threshold, joined to the previous row's runs they touch
  // (8-connected: overlapping or diagonal) by union–find.
  runs_.clear();
  std::size_t prev_begin = 0, prev_end = 0;
  for (int y = r.y0; y <= r.y1; ++y) {
    const std::size_t cur_begin = runs_.size();
    if (row_max_[static_cast<std::size_t>(y - r.y0)] >= threshold) {
      for (int x = r.x0; x <= r.x1; ++x) {
        if (v.at(x, y) < threshold) continue;
        const int x0 = x;
        while (x + 1 <= r.x1 && v.at(x + 1, y) >= threshold) ++x;
        if (runs_.size() >= static_cast<std::size_t>(config_.max_runs)) {
          ++out.rejected.cluttered;
          return false;
        }
        const int self = static_cast<int>(runs_.size());
        runs_.push_back({y, x0, x, self});
        // Previous row's runs are sorted by x: skip those ending left of x0 − 1.
        while (prev_begin < prev_end && runs_[prev_begin].x1 < x0 - 1) ++prev_begin;
        for (std::size_t p = prev_begin; p < prev_end && runs_[p].x0 <= x + 1; ++p) {
          const int a = find_root(self), b = find_root(static_cast<int>(p));
          if (a != b) runs_[static_cast<std::size_t>(std::max(a, b))].parent = std::min(a, b);
        }
      }
    }
    prev_begin = cur_begin;  // empty when this row had no run: nothing to join below
    prev_end = runs_.size();
  }

  // Components: moments over their pixels, weights luma − background.
  comps_.clear();
  boxes_.clear();
  comp_of_root_.assign(runs_.size(), -1);
  for (std::size_t i = 0; i < runs_.size(); ++i) {
    const int root = find_root(static_cast<int>(i));
    int& c = comp_of_root_[static_cast<std::size_t>(root)];
    if (c < 0) {
      c = static_cast<int>(comps_.size());
      comps_.emplace_back();
      boxes_.push_back({runs_[i].x0, runs_[i].y, runs_[i].x1, runs_[i].y});
    }
    Moments& m = comps_[static_cast<std::size_t>(c)];
    Region& b = boxes_[static_cast<std::size_t>(c)];
    const Run& run = runs_[i];
    b = {std::min(b.x0, run.x0), std::min(b.y0, run.y), std::max(b.x1, run.x1), std::max(b.y1, run.y)};
    const double dy = run.y - r.y0;  // region-relative: keeps the sums' cancellation small
    for (int x = run.x0; x <= run.x1; ++x) {
      const int l = v.at(x, run.y);
      const double w = l - background, dx = x - r.x0;
      m.s += w;
      m.sx += w * dx;
      m.sy += w * dy;
      m.sxx += w * dx * dx;
      m.syy += w * dy * dy;
      m.sxy += w * dx * dy;
      m.peak = std::max(m.peak, l);
    }
    m.area += run.x1 - run.x0 + 1;
  }
  out.candidates = static_cast<int>(comps_.size());

  const double px = last_ ? last_->x + step_x_ : 0, py = last_ ? last_->y + step_y_ : 0;
  int best = -1;
  double best_key = 0;
  for (std::size_t c = 0; c < comps_.size(); ++c) {
    const Moments& m = comps_[c];
    if (m.area < config_.min_area_px) {
      ++out.rejected.too_small;
      continue;
    }
    if (m.area > config_.max_area_px) {
      ++out.rejected.too_large;
      continue;
    }
    // The weighted covariance, plus each pixel's own extent (1/12 px²): a one-pixel-wide
    // line is then long, not infinitely so.
    const double mx = m.sx / m.s, my = m.sy / m.s;
    const double a = m.sxx / m.s - mx * mx + 1.0 / 12, cc = m.syy / m.s - my * my + 1.0 / 12, b = m.sxy / m.s - mx * my;
    const double half_diff = std::sqrt(0.25 * (a - cc) * (a - cc) + b * b);
    const double l1 = 0.5 * (a + cc) + half_diff, l2 = std::max(0.5 * (a + cc) - half_diff, 1e-9);
    const double elongation = std::sqrt(l1 / l2);
    if (elongation > config_.max_elongation) {
      ++out.rejected.elongated;
      continue;
    }
    // While tracking (the square, and the whole frame after an empty square) the LED's
    // brightness is known: a much dimmer blob is a reflection or a second light.
    if (last_ && m.s < config_.track_min_sum_ratio * last_->sum) {
      ++out.rejected.too_dim;
      continue;
    }
    const double key = nearest ? -dist2(mx + r.x0, my + r.y0, px, py) : m.s;
    if (best < 0 || key > best_key) {
      best = static_cast<int>(c);
      best_key = key;
    }
    comps_[c].elongation = elongation;
  }
  if (best < 0) return false;
  out.led = refine(v, comps_[static_cast<std::size_t>(best)], background, boxes_[static_cast<std::size_t>(best)]);
  return true;
}

LedBlob LedFinder::refine(const LumaView& v, const Moments& m, int background, const Region& box) const {
  LedBlob blob;
  blob.area_px = m.area;
  blob.sum = m.s;
  blob.peak = m.peak;
  blob.elongation = m.elongation;
  // The centroid over the bounding box grown on each side by half its size and the margin,
  // luma − background clamped at 0: the Gaussian's shoulders below the threshold then pull
  // their share. Over the component alone, a σ 4 px LED's centroid is pulled ≈ 0.1 px toward
  // pixel centres; over this window < 0.01 px at any σ (measured on led_frame_synth's
  // noiseless frames; with noise the clamp costs < 0.012 px of bias, and saves a third of
  // the spread that unclamped noise adds).
  // Another blob near (a reflection beside the LED) would pull the centroid: the window
  // stops short of halfway to the nearest one.
  int g = config_.centroid_margin_px + std::max(box.x1 - box.x0, box.y1 - box.y0) / 2 + 1;
  for (const Region& o : boxes_) {
    const int gap = std::max({o.x0 - box.x1, box.x0 - o.x1, o.y0 - box.y1, box.y0 - o.y1});
    if (gap > 0) g = std::min(g, (gap - 1) / 2);  // gap <= 0: the box itself (or overlapping)
  }
  const int x0 = std::max(0, box.x0 - g), x1 = std::min(v.width - 1, box.x1 + g);
  const int y0 = std::max(0, box.y0 - g), y1 = std::min(v.height - 1, box.y1 + g);
  double s = 0, sx = 0, sy = 0;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const int w = v.at(x, y) - background;
      if (w <= 0) continue;
      s += w;
      sx += static_cast<double>(w) * (x - x0);
      sy += static_cast<double>(w) * (y - y0);
    }
  blob.x = x0 + sx / s;  // s > 0: the component's own pixels are inside
  blob.y = y0 + sy / s;
  return blob;
}

}  // namespace mallet::input::camera
