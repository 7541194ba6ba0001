#pragma once
// The psychometric function of a forced-choice task, in the four shapes labs fit (psignifit 4,
// PsychoPy's data.FitLogistic/FitWeibull/FitCumNormal, Wichmann & Hill 2001):
//     P(correct | x) = γ + (1 − γ − λ)·F(x)
// γ is the guess rate (0.5 for 2AFC), λ the lapse rate (a wrong answer whatever the
// difference), F a sigmoid from 0 to 1. Every shape is written in the same two parameters:
//   threshold  the x at which the lapse-free curve, γ + (1 − γ)·F(x), reaches the criterion
//              (0.75 by default: for 2AFC, F = 1/2, the midpoint of every shape). The lapse
//              does not move it, as in psignifit.
//   slope      how fast F rises: logistic, normal and Gumbel β per unit of x (the logistic's
//              dP/dx at its midpoint is (1 − γ − λ)·β/4, 2AFC β/8); Weibull β is the
//              exponent, without unit.
//   logistic  F = 1/(1 + exp(−(β(x − T) + logit f)))
//   normal    F = Φ(β(x − T) + Φ⁻¹(f))                  (the cumulative normal, σ = 1/β)
//   gumbel    F = 1 − exp(−exp(β(x − T) + ln(−ln(1 − f))))   (psignifit's "gumbel")
//   weibull   F = 1 − exp(−(−ln(1 − f))·(x/T)^β), x > 0; 0 for x ≤ 0   (T > 0)
// with f = (criterion − γ)/(1 − γ), so that F(T) = f in each. At the default criterion the
// logistic is Mallet's original fit unchanged: P = 0.5 + 0.5/(1 + exp(−β(x − T))).
#include <array>

#include "core/enum_names.hpp"

namespace mallet::study {

enum class PsychometricShape { logistic, weibull, normal, gumbel };
inline constexpr EnumNames<PsychometricShape, 4> kPsychometricShapeNames{{{PsychometricShape::logistic, "logistic"},
                                                                          {PsychometricShape::weibull, "weibull"},
                                                                          {PsychometricShape::normal, "normal"},
                                                                          {PsychometricShape::gumbel, "gumbel"}}};

//! What the curve is, apart from its fitted parameters.
struct PsychometricModel {
  PsychometricShape shape = PsychometricShape::logistic;
  double guess = 0.5;       //!< γ: 0.5 for 2AFC
  double criterion = 0.75;  //!< the lapse-free P(correct) that defines the threshold, in (γ, 1)
};

//! The fitted parameters.
struct PsychometricParams {
  double threshold = 0;
  double slope = 0;
  double lapse = 0;  //!< λ
};

//! The constant that puts F(T) at the criterion's f in `model`'s shape (the top of this file):
//! logistic logit f, normal Φ⁻¹(f), Gumbel ln(−ln(1 − f)), Weibull −ln(1 − f).
double criterion_offset(const PsychometricModel& model);

//! F(x), the shape's sigmoid, for `model`'s criterion.
double psychometric_core(const PsychometricModel& model, double threshold, double slope, double x);

//! P(correct | x) = γ + (1 − γ − λ)·F(x).
double psychometric_p(const PsychometricModel& model, const PsychometricParams& params, double x);

//! The standard normal's distribution function Φ, and its inverse (−∞ at 0, +∞ at 1).
double normal_cdf(double z);
double normal_quantile(double p);

}  // namespace mallet::study
