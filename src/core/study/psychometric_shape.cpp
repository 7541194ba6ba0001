#include "core/study/psychometric_shape.hpp"

#include <algorithm>
#include <cmath>

namespace mallet::study {

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

double normal_quantile(double p) {
  // Acklam's rational approximation (relative error 1.15e-9), then one Halley step on Φ:
  // exact to rounding, and cheap enough to call per likelihood.
  static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                                 1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                 6.680131188771972e+01,  -1.328068155288572e+01};
  static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                 -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                                 3.754408661907416e+00};
  if (!(p > 0)) return -INFINITY;
  if (!(p < 1)) return INFINITY;
  double x;
  if (p < 0.02425) {
    const double q = std::sqrt(-2 * std::log(p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  } else if (p > 1 - 0.02425) {
    const double q = std::sqrt(-2 * std::log(1 - p));
    x = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  } else {
    const double q = p - 0.5, r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
  }
  const double e = normal_cdf(x) - p, u = e * std::sqrt(2 * M_PI) * std::exp(x * x / 2);
  return x - u / (1 + x * u / 2);
}

double criterion_offset(const PsychometricModel& model) {
  const double f = std::clamp((model.criterion - model.guess) / (1.0 - model.guess), 1e-9, 1.0 - 1e-9);
  switch (model.shape) {
    case PsychometricShape::logistic: return std::log(f / (1.0 - f));
    case PsychometricShape::normal: return normal_quantile(f);
    case PsychometricShape::gumbel: return std::log(-std::log(1.0 - f));
    case PsychometricShape::weibull: return -std::log(1.0 - f);
  }
  return 0.0;
}

double psychometric_core(const PsychometricModel& model, double threshold, double slope, double x) {
  const double offset = criterion_offset(model);
  switch (model.shape) {
    case PsychometricShape::logistic: return 1.0 / (1.0 + std::exp(-(slope * (x - threshold) + offset)));
    case PsychometricShape::normal: return normal_cdf(slope * (x - threshold) + offset);
    case PsychometricShape::gumbel: return 1.0 - std::exp(-std::exp(slope * (x - threshold) + offset));
    case PsychometricShape::weibull:
      if (x <= 0 || threshold <= 0) return 0.0;
      return 1.0 - std::exp(-offset * std::pow(x / threshold, slope));
  }
  return 0.0;
}

double psychometric_p(const PsychometricModel& model, const PsychometricParams& params, double x) {
  return model.guess + (1.0 - model.guess - params.lapse) * psychometric_core(model, params.threshold, params.slope, x);
}

}  // namespace mallet::study
