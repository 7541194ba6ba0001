#pragma once
// The trade contact prediction makes (core/contact_predictor.hpp), measured on the stroke
// corpus (core/stroke_corpus.hpp) through the real StrikeDetector: how long after the true
// contact a strike is decided, against false notes, missed notes and speed error, for
// each prediction horizon × confidence level × camera (the Wii's at 100 and 200 Hz, a
// V4L2 camera's at 120 and 240 Hz).
//
// `mallet bench prediction [--scene FILE] [--config FILE] [--camera-noise-px X]
// [--camera-read-delay-ms X]` prints it (the V4L2 camera's rows also with the presets tuned
// for it, core/camera_prediction.hpp); `mallet bench report` includes it.
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/contact_predictor.hpp"
#include "core/mallet.hpp"
#include "core/scene.hpp"
#include "core/stroke_corpus.hpp"

namespace mallet::app {

//! A confidence level: every knob of PredictionConfig but the horizon.
struct PredictionLevel {
  std::string name;
  PredictionConfig config;  //!< horizon_ms is overwritten by the sweep
  //! Tuned for each camera by prediction_for_camera (the kiosk's camera route); measured on
  //! the V4L2 camera only: the Wii's route runs the presets as they are.
  bool for_camera = false;
};

//! What `mallet bench prediction` may change in the V4L2 camera's model.
struct PredictionBenchOptions {
  double camera_noise_px = kV4l2CentroidNoisePx;  //!< its centroid noise σ per axis
  double camera_read_delay_ms = -1;               //!< < 0: v4l2_read_delay_ms at 500 µs
};

//! One row of the table: one camera at one rate, one horizon, one confidence level, the
//! whole corpus.
struct PredictionBenchRow {
  std::string camera;         //!< CameraModel::name
  double rate_hz = 0;
  double horizon_ms = 0;
  std::string level;
  int contacts = 0;           //!< true contacts in the corpus at this rate
  int strikes = 0;            //!< strikes decided
  int predicted = 0;          //!< of which predicted
  //! True contact → strike decided (the sample it was decided on), matched strikes, ms;
  //! a predicted strike counts max(0, decision − contact).
  double latency_median_ms = 0, latency_p99_ms = 0, latency_max_ms = 0;
  //! |heard − true contact| (heard: the later of the strike's time and its decision, as the
  //! strike route schedules a strike with align = asap), matched strikes, 99th percentile, ms.
  double sound_p99_ms = 0;
  //! Predicted strikes' scheduled time − true contact time, ms (1st and 99th percentiles).
  double schedule_error_p1_ms = 0, schedule_error_p99_ms = 0;
  double false_pct = 0;       //!< strikes matching no contact, per 100 true contacts
  //! false_pct minus the exact solver's on the same strokes (its own false notes are the
  //! camera noise dipping below the plane under a hand that stops within ≈1 mm of a bar)
  double false_added_pct = 0;
  double missed_pct = 0;      //!< true contacts with no strike, per 100
  double speed_error_p99_pct = 0;       //!< |v − v_true| / v_true over matched strikes
  double speed_error_p99_fast_pct = 0;  //!< the same over contacts at ≥ 1 m/s
  std::vector<int> false_by_kind;       //!< index: StrokeKind
};

//! The corpus every prediction table is measured on (bench prediction, bench report).
inline constexpr std::uint32_t kPredictionCorpusSeed = 20240611;

//! The confidence levels the bench sweeps, from the most eager to the most careful.
std::vector<PredictionLevel> prediction_levels();
//! The same levels tuned for the camera ("eager*", "balanced*", "exact*").
std::vector<PredictionLevel> camera_prediction_levels();

//! Runs the corpus through StrikeDetector for each camera in `corpus.cameras` × horizon ×
//! level (horizon 0 once per camera: prediction off, the exact solver). A strike is decided
//! at its sample's time plus the camera's read_delay_ms. A strike matches a true contact on
//! the same bar within 25 ms; each contact matches at most one strike.
std::vector<PredictionBenchRow> measure_prediction_trade(const Scene& scene, const ContactConfig& contact,
                                                         const CorpusConfig& corpus,
                                                         const std::vector<double>& horizons_ms,
                                                         const std::vector<PredictionLevel>& levels);

//! Prints the table for horizons {0, 5, 10, 15} ms × prediction_levels() × every_camera()
//! (Wii 100, 200 Hz; V4L2 120, 240 Hz, with `options`' noise and read delay; for them also
//! camera_prediction_levels()) on the bench's corpus. Returns 0.
int run_bench_prediction(const Scene& scene, const ContactConfig& contact, const PredictionBenchOptions& options,
                         std::ostream& out);

}  // namespace mallet::app
