#pragma once
// `mallet study summary`: per-condition accuracy of a results file and, for 2AFC rows,
// the psychometric fit of each condition (see psychometric_fit.hpp).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/study/psychometric_bootstrap.hpp"
#include "core/study/psychometric_fit.hpp"
#include "core/study/results_csv.hpp"

namespace mallet::study {

struct ConditionSummary {
  std::string condition;
  int trials = 0;
  int correct = 0;
  double mean_response_ms = 0;
  double accuracy() const { return trials ? static_cast<double>(correct) / trials : 0.0; }
  std::optional<PsychometricFit> fit;  //!< only when the rows carry a difference_pct (2AFC)
  std::optional<PsychometricIntervals> intervals;  //!< the fit's, when asked for and the fit is ok
  std::vector<PsychometricLevel> levels;           //!< the fit's data, ascending difference
  std::vector<double> response_ms;                 //!< every trial's, in row order
  //! Adaptive rows (procedure staircase, quest or quest_plus): the procedure ("mixed" when
  //! more than one), and each track's estimate at its last trial (a track: one participant's
  //! rows of one protocol in this condition; staircase: the mean level at its last reversals,
  //! once it has them; QUEST: the posterior mean; QUEST+: the threshold's posterior mean), in
  //! first-seen order.
  std::string procedure;
  std::vector<double> final_estimates;
  std::optional<double> final_sd;  //!< QUEST, one participant: the posterior SD at the last trial
  //! The tested differences in track order, per participant (the staircase tracks' plot).
  std::vector<std::vector<double>> tracks;
};

//! How the fits' confidence intervals are made: `resamples` parametric bootstrap refits (0:
//! none), the draws seeded from `seed`, the participant and the condition, so that each
//! interval is the same whichever files it was read with.
struct SummaryOptions {
  int resamples = 0;
  std::uint64_t seed = 1;
  FitOptions fit;  //!< the curve fitted: shape, criterion, lapse (default: 2AFC logistic, 75 %, no lapse)
};

struct StudySummary {
  int rows = 0;
  std::vector<std::string> participants;
  int simulated_rows = 0;               //!< answered by the simulated observer
  std::vector<ConditionSummary> conditions;  //!< visual_only, tactile_only, both, none, then others
  int resamples = 0;                         //!< the bootstrap's, per fit (0: no intervals)
  FitOptions fit;                            //!< what was fitted
  //! The kiosk's visitor micro-study: its sessions (participants "visitor-…") whose rows reach
  //! their planned_trials, and those that stopped before (the visitor walked away).
  int visitor_sessions_completed = 0, visitor_sessions_abandoned = 0;
};

//! `participant`: only that participant's rows (empty: everyone's, pooled).
StudySummary summarize(const std::vector<ResultRow>& rows, const std::string& participant = {},
                       const SummaryOptions& options = {});

//! The summary as printed: a table of accuracies, then the fits (with their 95 % intervals
//! when they were made).
std::string format_summary(const StudySummary& summary);

//! The fit's formula and its x, as the summary's header line says them.
std::string fit_description(const FitOptions& options);

//! Each participant's summary, in first-seen order.
std::vector<std::pair<std::string, StudySummary>> summarize_participants(const std::vector<ResultRow>& rows,
                                                                          const SummaryOptions& options = {});
//! Each participant's 2AFC fit per condition, one line each (conditions as in StudySummary);
//! "" when no row carries a difference_pct.
std::string format_participant_fits(const std::vector<std::pair<std::string, StudySummary>>& participants);

//! One condition's thresholds over the participants, each from that participant's own fit
//! (not the pooled fit): their mean ± standard error and median, over those with a threshold
//! inside the tested range; the others (none, or extrapolated) are counted, not guessed at.
struct GroupThresholds {
  std::string condition;
  int participants = 0;   //!< with a fit in this condition
  int estimated = 0;      //!< of those, with a threshold inside the tested range
  double mean = 0, se = 0, median = 0;  //!< over `estimated` (se: needs 2)
};
std::vector<GroupThresholds> group_thresholds(const std::vector<std::pair<std::string, StudySummary>>& participants);
//! The group table as printed ("" with fewer than 2 participants).
std::string format_group(const std::vector<GroupThresholds>& group);

//! Every fit, pooled ("pooled") and each participant's, as one CSV row each (`--table`):
//! see kFitTableColumns.
inline constexpr const char* kFitTableColumns =
    "condition,participant,shape,criterion,lapse_mode,levels,trials,threshold_pct,threshold_lo,threshold_hi,"
    "slope,slope_lo,slope_hi,slope_at_least,lapse,lapse_lo,lapse_hi,log_likelihood,deviance,deviance_p,resamples,"
    "flags,note";
//! What a fit's maximum means, as the table's `flags` and the JSON's `flags` name it:
//! no_fit, threshold_below_range, threshold_above_range, extrapolated, step, flat,
//! lapse_at_limit (those that hold, in that order).
std::vector<const char*> fit_flags(const PsychometricFit& fit);

std::string fit_table_csv(const StudySummary& pooled,
                          const std::vector<std::pair<std::string, StudySummary>>& participants);

}  // namespace mallet::study
