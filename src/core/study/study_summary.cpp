#include "core/study/study_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include <fmt/format.h>

#include "core/study/balanced_schedule.hpp"
#include "core/study/study_protocol.hpp"
#include "core/study/visitor_offer.hpp"

namespace mallet::study {

namespace {
//! Where a condition stands in the table's order (unknown names last).
int condition_rank(const std::string& name) {
  const std::size_t n = kStudyConditionNames.size();
  for (std::size_t i = 0; i < n; ++i)
    if (kStudyConditionNames[i].second == name) return static_cast<int>(i);
  return static_cast<int>(n);
}

//! The bootstrap's seed for one participant's (or the pool's, "") condition: the schedule's
//! own mixing of a name into a seed (participant_seed), over both names.
std::uint64_t interval_seed(std::uint64_t seed, const std::string& participant, const std::string& condition) {
  return participant_seed(seed, participant + '\x1f' + condition);
}

//! "[lo, hi]" with the given decimals, or "-" without an interval.
std::string interval_text(const std::optional<PsychometricIntervals>& ci, bool threshold) {
  if (!ci || !ci->ok) return "-";
  const Interval& i = threshold ? ci->threshold : ci->slope;
  return threshold ? fmt::format("[{:.2f}, {:.2f}]", i.lo, i.hi) : fmt::format("[{:.3f}, {:.3f}]", i.lo, i.hi);
}
//! One condition's fit as a row: condition, levels, threshold, slope, their intervals, note.
std::string fit_columns(const ConditionSummary& c) {
  const PsychometricFit& f = *c.fit;
  if (f.ok)
    return fmt::format("{:<14} {:7} {:14.3f} {:14.4f} {:>18} {:>18}  {}\n", c.condition, f.levels, f.threshold, f.slope,
                       interval_text(c.intervals, true), interval_text(c.intervals, false), f.reason);
  return fmt::format("{:<14} {:7} {:>14} {:>14} {:>18} {:>18}  {}\n", c.condition, f.levels, "-", "-", "-", "-",
                     f.reason);
}
}  // namespace

StudySummary summarize(const std::vector<ResultRow>& rows, const std::string& participant,
                       const SummaryOptions& options) {
  StudySummary s;
  s.resamples = options.resamples;
  std::map<std::string, ConditionSummary> by_condition;
  std::map<std::string, std::map<double, PsychometricLevel>> levels;
  std::map<std::string, double> rt_sum;
  for (const ResultRow& r : rows) {
    if (!participant.empty() && r.participant != participant) continue;
    ++s.rows;
    if (std::find(s.participants.begin(), s.participants.end(), r.participant) == s.participants.end())
      s.participants.push_back(r.participant);
    if (r.source == "simulated") ++s.simulated_rows;
    ConditionSummary& c = by_condition[r.condition];
    c.condition = r.condition;
    ++c.trials;
    c.correct += r.correct ? 1 : 0;
    c.response_ms.push_back(r.response_time_ms);
    rt_sum[r.condition] += r.response_time_ms;
    if (std::isfinite(r.difference_pct)) {
      PsychometricLevel& l = levels[r.condition][r.difference_pct];
      l.x = r.difference_pct;
      ++l.trials;
      l.correct += r.correct ? 1 : 0;
    }
  }
  // Visitor sessions: complete when a session's rows reach the trials it planned.
  std::map<std::string, std::pair<int, int>> visitor_rows;  // participant → (rows, planned)
  for (const ResultRow& r : rows) {
    if ((!participant.empty() && r.participant != participant) || !is_visitor_session(r.participant)) continue;
    auto& [count, planned] = visitor_rows[r.participant];
    ++count;
    planned = std::max(planned, r.planned_trials);
  }
  for (const auto& [who, counts] : visitor_rows)
    ++(counts.first >= counts.second ? s.visitor_sessions_completed : s.visitor_sessions_abandoned);
  // Adaptive tracks: each participant's rows of a condition in trial order.
  std::map<std::string, std::map<std::string, std::map<int, const ResultRow*>>> tracks;  // condition → track → trial
  std::map<std::string, std::vector<std::string>> track_order;
  for (const ResultRow& r : rows) {
    if (!participant.empty() && r.participant != participant) continue;
    if (r.procedure != "staircase" && r.procedure != "quest" && r.procedure != "quest_plus") continue;
    std::string& procedure = by_condition[r.condition].procedure;
    procedure = procedure.empty() || procedure == r.procedure ? r.procedure : "mixed";
    // A track: one participant's rows of one protocol in this condition.
    const std::string track = r.participant + '\x1f' + r.protocol;
    auto& who = tracks[r.condition];
    if (!who.contains(track)) track_order[r.condition].push_back(track);
    who[track][r.trial] = &r;
  }
  for (auto& [name, c] : by_condition) {
    for (const std::string& who : track_order[name]) {
      const auto& mine = tracks[name][who];
      std::vector<double> tested;
      for (const auto& [trial, row] : mine) tested.push_back(row->difference_pct);
      c.tracks.push_back(std::move(tested));
      const ResultRow& last = *mine.rbegin()->second;
      if (std::isfinite(last.estimate_pct)) c.final_estimates.push_back(last.estimate_pct);
      if (track_order[name].size() == 1 && std::isfinite(last.estimate_sd_pct)) c.final_sd = last.estimate_sd_pct;
    }
  }
  for (auto& [name, c] : by_condition) {
    c.mean_response_ms = rt_sum[name] / c.trials;
    if (auto it = levels.find(name); it != levels.end()) {
      for (const auto& [x, l] : it->second) c.levels.push_back(l);
      c.fit = fit_psychometric_2afc(c.levels);
      if (options.resamples > 0 && c.fit->ok)
        c.intervals = bootstrap_2afc(c.levels, *c.fit, options.resamples,
                                     interval_seed(options.seed, participant, name));
    }
    s.conditions.push_back(c);
  }
  std::stable_sort(s.conditions.begin(), s.conditions.end(), [](const ConditionSummary& a, const ConditionSummary& b) {
    return condition_rank(a.condition) < condition_rank(b.condition);
  });
  return s;
}

std::string format_summary(const StudySummary& s) {
  std::string out = fmt::format("{} trial{}, {} participant{}\n", s.rows, s.rows == 1 ? "" : "s",
                                s.participants.size(), s.participants.size() == 1 ? "" : "s");
  auto line = std::back_inserter(out);
  if (s.simulated_rows)
    out += "note: " + std::to_string(s.simulated_rows) + " row(s) were answered by the simulated observer (source=simulated)\n";
  if (const int n = s.visitor_sessions_completed + s.visitor_sessions_abandoned; n > 0) {
    fmt::format_to(line, "visitor sessions: {} ({} completed, {} abandoned)\n", n, s.visitor_sessions_completed,
                   s.visitor_sessions_abandoned);
  }
  fmt::format_to(line, "{:<14} {:>7} {:>8} {:>9} {:>10}\n", "condition", "trials", "correct", "accuracy", "mean_rt_ms");
  for (const ConditionSummary& c : s.conditions)
    fmt::format_to(line, "{:<14} {:7} {:8} {:8.1f}% {:10.1f}\n", c.condition, c.trials, c.correct, 100.0 * c.accuracy(),
                   c.mean_response_ms);
  bool header = false;
  for (const ConditionSummary& c : s.conditions) {
    if (!c.fit) continue;
    if (!header) {
      out += "psychometric fit, 2AFC: P(correct) = 0.5 + 0.5/(1 + exp(-slope*(x - threshold))), "
             "x = difference in B (%), maximum likelihood\n";
      fmt::format_to(line, "{:<14} {:>7} {:>14} {:>14} {:>18} {:>18}  {}\n", "condition", "levels", "threshold_pct",
                     "slope_per_pct", "threshold_95ci", "slope_95ci", "note");
      header = true;
    }
    out += fit_columns(c);
  }
  if (header)
    for (const ConditionSummary& c : s.conditions)
      if (c.intervals) {
        fmt::format_to(line, "95 % intervals: parametric bootstrap, {} resamples, bias-corrected percentiles\n",
                       s.resamples);
        break;
      }
  bool adaptive = false;
  for (const ConditionSummary& c : s.conditions) {
    if (c.procedure.empty()) continue;
    if (!adaptive) {
      out += "adaptive tracks: the estimate at each track's last trial (staircase: the mean level at its last "
             "reversals; quest: the posterior mean)\n";
      fmt::format_to(line, "{:<14} {:<10} {:>6} {:>13} {:>13}\n", "condition", "procedure", "tracks", "estimate_pct",
                     "spread_pct");
      adaptive = true;
    }
    double mean = 0, spread = 0;
    for (double e : c.final_estimates) mean += e;
    if (!c.final_estimates.empty()) mean /= static_cast<double>(c.final_estimates.size());
    for (double e : c.final_estimates) spread += (e - mean) * (e - mean);
    // Between participants' estimates (their SD); one participant's QUEST: its posterior SD.
    const bool between = c.final_estimates.size() > 1;
    if (between) spread = std::sqrt(spread / static_cast<double>(c.final_estimates.size() - 1));
    const std::string est = c.final_estimates.empty() ? "-" : fmt::format("{:.2f}", mean);
    const std::string spr = between     ? fmt::format("{:.2f}", spread)
                            : c.final_sd ? fmt::format("{:.2f} (SD)", *c.final_sd)
                                         : "-";
    fmt::format_to(line, "{:<14} {:<10} {:6} {:>13} {:>13}\n", c.condition, c.procedure, c.tracks.size(), est, spr);
  }
  return out;
}

std::vector<std::pair<std::string, StudySummary>> summarize_participants(const std::vector<ResultRow>& rows,
                                                                          const SummaryOptions& options) {
  std::vector<std::string> order;
  for (const ResultRow& r : rows)
    if (std::find(order.begin(), order.end(), r.participant) == order.end()) order.push_back(r.participant);
  std::vector<std::pair<std::string, StudySummary>> out;
  for (const std::string& p : order) out.emplace_back(p, summarize(rows, p, options));
  return out;
}

std::string format_participant_fits(const std::vector<std::pair<std::string, StudySummary>>& participants) {
  std::string out;
  for (const auto& [p, summary] : participants) {
    for (const ConditionSummary& c : summary.conditions) {
      if (!c.fit) continue;
      if (out.empty()) {
        out = "per participant, the same fit:\n";
        fmt::format_to(std::back_inserter(out), "{:<12} {:<14} {:>7} {:>14} {:>14} {:>18} {:>18}  {}\n", "participant",
                       "condition", "levels", "threshold_pct", "slope_per_pct", "threshold_95ci", "slope_95ci", "note");
      }
      out += fmt::format("{:<12} ", p) + fit_columns(c);
    }
  }
  return out;
}

}  // namespace mallet::study
