#pragma once
// `mallet study summary`: per-condition accuracy of a results file and, for 2AFC rows,
// the psychometric fit of each condition (see psychometric_fit.hpp).
#include <optional>
#include <string>
#include <vector>

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
};

struct StudySummary {
  int rows = 0;
  std::vector<std::string> participants;
  int simulated_rows = 0;               //!< answered by the simulated observer
  std::vector<ConditionSummary> conditions;  //!< visual_only, tactile_only, both, none, then others
};

//! `participant`: only that participant's rows (empty: everyone's).
StudySummary summarize(const std::vector<ResultRow>& rows, const std::string& participant = {});

//! The summary as printed: a table of accuracies, then the fits.
std::string format_summary(const StudySummary& summary);

//! Each participant's 2AFC fit per condition, one line each (participants in first-seen
//! order, conditions as in StudySummary); "" when no row carries a difference_pct.
std::string format_participant_fits(const std::vector<ResultRow>& rows);

}  // namespace mallet::study
