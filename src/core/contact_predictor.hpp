#pragma once
// Contact prediction: at 100 Hz a strike is seen only at the first camera sample after the
// contact (median ≈5.5 ms, p99 ≈11 ms late). A downswing can be extrapolated, so a
// crossing of a bar's contact plane that will happen before the next sample can be
// announced now and scheduled at its predicted time. A wrong prediction is a note that
// cannot be taken back, so one is made only when every test below passes; any doubt
// leaves the strike to the exact solver, one sample later.
//
// Model: the hand's height over the last `fit_window_ms` (at least `min_samples`
// samples) fitted by least squares with a polynomial (degree 2, constant acceleration: on
// the stroke corpus a cubic, exact on clean strokes, was worse under 0.5 px of camera
// noise at 100 and 200 Hz), its x by a straight line. Tests, in order (PredictionVerdict names the first that failed):
//  1. poor_fit     RMS residual > max_fit_residual_m: not one smooth motion.
//  2. slow         going down slower than min_predicted_speed_m_per_s: a slow hand may
//                  still stop, and a slow strike loses little by waiting.
//  3. turning      not already that fast at the window's start (a rebound, a stroke that
//                  has just begun: the fit cannot know their acceleration yet).
//  4. speeding_up  downward acceleration > max_speedup_m_per_s2: the hand is in the first
//                  half of its move, and will brake before the bar by an amount nothing in
//                  the samples tells. Extrapolating it made predicted speeds 2–3× too high.
//  5. no_crossing  the fit meets no plane below the hand before the next expected sample
//                  (the median of the recent intervals) is held (sample_delay_ms after
//                  its time: a camera's read-out), at min_predicted_speed or more.
//  6. could_stop   the hand, braking at braking_m_per_s2 from its fitted speed u, could still
//                  stop clearance_m or more above the plane: y − plane − clearance ≥ u²/2b.
//                  This is the guarantee: a hand that stops clearance_m or more above a
//                  bar is never predicted if its braking peaks at no more than half of
//                  braking_m_per_s2 (half: the quadratic lags braking that is building up,
//                  so the speed it reads runs high). Tested on exact samples; with camera
//                  noise, on the corpus's stops 1.5 mm beyond the clearance.
//  7. after_next_sample  the crossing is further ahead than horizon_ms.
//  8. uncertain    camera noise alone (σ = noise_m per sample, through the fit's
//                  covariance) makes the contact time uncertain by more than
//                  max_timing_sigma_ms or its speed by more than max_speed_sigma_pct.
//  9. grazing      the fit would not be min_overshoot_m below the plane by the time the
//                  next sample is held: a crossing that only grazes the plane is one that noise, or a
//                  stop just above, could fake.
// 10. outside_zone the crossing's x is not in that plane's zone.
// A prediction reports the predicted contact time and the fitted downward speed there.
// Units: metres, seconds; the clock is int64 ns and the fit works on time differences.
#include <array>
#include <cstddef>
#include <optional>
#include <string_view>
#include <vector>

#include "core/enum_names.hpp"
#include "core/geometry.hpp"
#include "core/mallet.hpp"
#include "core/time.hpp"

namespace mallet {

//! Knobs of contact prediction. `horizon_ms` 0 turns it off (the exact solver alone).
//! The defaults are the "balanced" preset; bench_prediction.cpp says why.
struct PredictionConfig {
  double horizon_ms = 0;                     //!< predict crossings at most this far ahead; 0 = off
  double fit_window_ms = 35;                 //!< samples this recent are fitted
  int fit_degree = 2;                        //!< 2: constant acceleration, 3: constant jerk
  int min_samples = 4;                       //!< at least this many in the window (> fit_degree)
  double max_fit_residual_m = 0.001;         //!< RMS residual of the fit
  double min_predicted_speed_m_per_s = 0.2;  //!< slower hands wait for the samples
  double max_speedup_m_per_s2 = 10;          //!< a hand speeding up more than this is not extrapolated
  double clearance_m = 0.002;                //!< a hand stopping this far above a bar is never predicted
  double braking_m_per_s2 = 60;              //!< braking assumed possible (guarantee: hands braking ≤ half)
  double noise_m = 0.0005;                   //!< σ of one sample's height (camera noise, metres)
  double max_timing_sigma_ms = 4.0;          //!< the noise's share of the contact time's error
  double max_speed_sigma_pct = 80;           //!< the noise's share of the speed's error
  double min_overshoot_m = 0.0005;           //!< the fit must be this far below by the next sample
  //! From a sample's time to the detector holding it (a camera frame's read-out: 0 for the
  //! Wii, stamped on arrival). The next sample is held one interval + this after the last
  //! one's time, so crossings up to then are predicted (horizon_ms still counts from the
  //! last sample's time: how far ahead the fit is trusted).
  double sample_delay_ms = 0;
};

//! What the exact solver alone does: no prediction.
PredictionConfig prediction_off();
//! The defaults above with a 10 ms horizon: the earliest strikes the bench found with no
//! added false or missed note and a speed error on fast strikes near the exact solver's.
PredictionConfig prediction_balanced();
//! Stricter tests: fewer predictions, smaller timing and speed errors.
PredictionConfig prediction_exact();
//! Every test loosened: the earliest strikes, at a cost in speed and timing (a bench level).
PredictionConfig prediction_eager();

//! The confidence levels by name ([timing] predict_confidence), the most eager first.
inline constexpr std::array<std::string_view, 3> kPredictionConfidences{"eager", "balanced", "exact"};
//! The level named so (its horizon 10 ms); nothing for any other name.
std::optional<PredictionConfig> prediction_confidence(std::string_view name);

//! A crossing announced before it happens.
struct PredictedContact {
  std::size_t zone = 0;        //!< index in the zones passed to predict()
  Nanos t_ns = 0;              //!< predicted contact time (after the last sample)
  double speed_m_per_s = 0;    //!< predicted downward speed at contact (not clamped)
  double x_m = 0;              //!< predicted sphere-centre x at contact
};

//! Why the last predict() returned what it did: the first test that failed (for several
//! zones, the zone that got furthest), or `predicted`. Tests 1–10 in the header comment.
enum class PredictionVerdict {
  off,                //!< horizon_ms is 0
  few_samples,        //!< fewer than min_samples in the window
  poor_fit,
  slow,
  turning,
  speeding_up,
  no_crossing,
  could_stop,
  after_next_sample,
  uncertain,
  grazing,
  outside_zone,
  predicted,
};
inline constexpr EnumNames<PredictionVerdict, 13> kPredictionVerdictNames{{
    {PredictionVerdict::predicted, "predicted"}, {PredictionVerdict::off, "off"},
    {PredictionVerdict::few_samples, "few_samples"}, {PredictionVerdict::poor_fit, "poor_fit"},
    {PredictionVerdict::slow, "slow"}, {PredictionVerdict::turning, "turning"},
    {PredictionVerdict::speeding_up, "speeding_up"}, {PredictionVerdict::no_crossing, "no_crossing"},
    {PredictionVerdict::could_stop, "could_stop"}, {PredictionVerdict::after_next_sample, "after_next_sample"},
    {PredictionVerdict::uncertain, "uncertain"}, {PredictionVerdict::grazing, "grazing"},
    {PredictionVerdict::outside_zone, "outside_zone"}}};
const char* to_string(PredictionVerdict v);

class ContactPredictor {
 public:
  //! The least-squares polynomial through the recent heights (degree fit_degree) and the
  //! straight line through the recent x, in time τ after the last sample.
  struct Fit {
    int samples = 0;
    double span_s = 0;          //!< from the oldest fitted sample to the last
    double rms_residual_m = 0;  //!< of the heights, over samples − degree − 1 degrees of freedom
    double x_m = 0, vx_m_per_s = 0;

    double y_m(double tau_s) const;
    double vy_m_per_s(double tau_s) const;
    double ay_m_per_s2(double tau_s) const;
    //! Standard deviations of y_m(τ) and vy_m_per_s(τ) for independent sample noise σ =
    //! noise_m: the least-squares covariance σ²·(XᵀX)⁻¹. Model error is not in them.
    double sigma_y_m(double tau_s, double noise_m) const;
    double sigma_vy_m_per_s(double tau_s, double noise_m) const;

   private:
    friend class ContactPredictor;
    static constexpr int kMaxTerms = 4;
    int terms_ = 0;                                  //!< degree + 1
    std::array<double, kMaxTerms> c_{};              //!< coefficients of (τ / window)^k
    std::array<std::array<double, kMaxTerms>, kMaxTerms> inverse_{};  //!< (XᵀX)⁻¹
    double window_s_ = 1;
    double y_last_ = 0;                              //!< heights are fitted relative to it
  };

  explicit ContactPredictor(PredictionConfig config);

  //! An accepted hand sample (finite, later than the previous one: the solver's rules).
  void add(Nanos t_ns, Vec2 hand);
  //! Forget the samples (tracking was lost: the next stroke starts afresh).
  void reset() { count_ = 0; }

  //! The earliest crossing of a zone's plane that passes every test, or nothing.
  std::optional<PredictedContact> predict(const std::vector<ContactZone>& zones);
  //! Why the last predict() returned what it did.
  PredictionVerdict verdict() const { return verdict_; }

  //! The fit of the samples in the window; nothing with fewer than min_samples.
  std::optional<Fit> fit() const;
  //! Median interval between the recent samples (when the next one is expected), if any.
  std::optional<Nanos> expected_interval_ns() const;

  const PredictionConfig& config() const { return config_; }

 private:
  struct Sample {
    Nanos t_ns;
    Vec2 hand;
  };
  static constexpr std::size_t kHistory = 16;  //!< 35 ms at 400 Hz; no allocation per sample

  const Sample& back(std::size_t i) const { return history_[(head_ + kHistory - 1 - i) % kHistory]; }

  PredictionConfig config_;
  std::array<Sample, kHistory> history_{};
  std::size_t head_ = 0;   //!< where the next sample goes
  std::size_t count_ = 0;  //!< valid samples, at most kHistory
  PredictionVerdict verdict_ = PredictionVerdict::off;
};

}  // namespace mallet
