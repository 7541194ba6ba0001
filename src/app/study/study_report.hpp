#pragma once
// `mallet study summary --plots DIR --report FILE.md`: the group summary as pictures and as
// a short markdown report. The plots are gnuplot PNGs (app/gnuplot.hpp), each with its .dat
// and .gp beside it:
//   psychometric.png   per condition, the pooled proportion correct at each difference (a
//                      point sized by its trials), the fitted curve, and the threshold's 95 %
//                      interval at 75 % correct;
//   thresholds.png     each participant's threshold per condition with its 95 % interval;
//   response_times.png per condition, the distribution of response times (50 ms bins);
//   tracks.png         with adaptive rows: each track's tested difference, trial by trial.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/study/study_summary.hpp"

namespace mallet::app {

struct StudyReport {
  std::vector<std::filesystem::path> files;  //!< the results files read
  std::string pooled_text;                   //!< format_summary of the pool
  std::string participants_text;             //!< format_participant_fits, "" for one participant
  study::StudySummary pooled;
  std::vector<std::pair<std::string, study::StudySummary>> participants;
  std::vector<study::GroupThresholds> group;  //!< each condition over the participants' own fits
  int resamples = 0;
  std::uint64_t seed = 1;
};

//! Writes the plots into `dir` (made if missing). Returns what it says on stdout: the PNGs
//! written, or that gnuplot is missing (the .dat and .gp are written all the same).
std::vector<std::string> write_study_plots(const StudyReport& report, const std::filesystem::path& dir);

//! Writes the markdown report to `file`, embedding the plots of `plots_dir` (empty: none) by a
//! path relative to the report. FileError when it cannot be written.
void write_study_report(const StudyReport& report, const std::filesystem::path& file,
                        const std::filesystem::path& plots_dir);

//! `--table FILE.csv`: every fit, pooled and per participant, one row each
//! (study::fit_table_csv), written atomically. FileError when it cannot be written.
void write_fit_table(const StudyReport& report, const std::filesystem::path& file);

//! `--json FILE.json`: the same fits, and the group's thresholds, written atomically:
//!   {"fit": {shape, criterion, lapse}, "resamples", "seed",
//!    "fits": [{condition, participant, levels: [{x, trials, correct, residual}], threshold_pct,
//!              threshold_lo, threshold_hi, slope, slope_lo, slope_hi, slope_at_least, lapse,
//!              lapse_lo, lapse_hi, log_likelihood, deviance, deviance_p, flags: [...], note}],
//!    "group": [{condition, participants, estimated, mean_pct, se_pct, median_pct}]}
//! A number that does not exist (no threshold, an open end) is null.
void write_fit_json(const StudyReport& report, const std::filesystem::path& file);

}  // namespace mallet::app
