#include "core/texture_relief.hpp"

#include <cmath>
#include <numbers>

namespace mallet {

namespace {

//! h(r)/(s·H) and its derivative d/dr, for r < R.
struct Radial {
  double value, slope;
};

Radial radial(ReliefProfile profile, double r, double R) {
  if (profile == ReliefProfile::cosine) {
    const double k = std::numbers::pi / R;
    return {(1 + std::cos(k * r)) / 2, -k * std::sin(k * r) / 2};
  }
  const double sigma = R / 3;
  const double two_s2 = 2 * sigma * sigma;
  const double rim = std::exp(-R * R / two_s2);
  const double g = std::exp(-r * r / two_s2);
  return {(g - rim) / (1 - rim), (-2 * r / two_s2) * g / (1 - rim)};
}

double sign(ReliefShape s) { return s == ReliefShape::bump ? 1.0 : -1.0; }

}  // namespace

bool TextureRelief::covers(Vec2 p) const {
  return std::hypot(p.x - center.x, p.y - center.y) < radius_m;
}

double TextureRelief::height_at(Vec2 p) const {
  const double r = std::hypot(p.x - center.x, p.y - center.y);
  if (!(r < radius_m)) return 0.0;
  return sign(shape) * height_m * radial(profile, r, radius_m).value;
}

Vec2 TextureRelief::gradient_at(Vec2 p) const {
  const double dx = p.x - center.x, dy = p.y - center.y;
  const double r = std::hypot(dx, dy);
  if (!(r < radius_m) || r == 0.0) return {0.0, 0.0};  // flat outside; the summit is flat
  const double dh_dr = sign(shape) * height_m * radial(profile, r, radius_m).slope;
  return {dh_dr * dx / r, dh_dr * dy / r};
}

const char* to_string(ReliefShape s) { return name_in(kReliefShapeNames, s); }
const char* to_string(ReliefProfile p) { return name_in(kReliefProfileNames, p); }

}  // namespace mallet
