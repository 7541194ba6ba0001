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

//! A limit with the given decimals.
std::string limit(double v, bool threshold) { return threshold ? fmt::format("{:.2f}", v) : fmt::format("{:.3f}", v); }

//! "[lo, hi]", one-sided ("<= hi", ">= lo") where an end is the search's edge, or "-".
std::string interval_text(const Interval& i, bool threshold) {
  if (i.lo_open && i.hi_open) return "any";
  if (i.lo_open) return "<= " + limit(i.hi, threshold);
  if (i.hi_open) return ">= " + limit(i.lo, threshold);
  return "[" + limit(i.lo, threshold) + ", " + limit(i.hi, threshold) + "]";
}
std::string interval_text(const std::optional<PsychometricIntervals>& ci, bool threshold, bool has_estimate) {
  if (!ci || !ci->ok || !has_estimate) return "-";
  return interval_text(threshold ? ci->threshold : ci->slope, threshold);
}

//! One condition's fit as a row: condition, levels, threshold, slope, their intervals, note.
//! A bound is never printed as an estimate: "-", and the note says what the data show.
std::string fit_columns(const ConditionSummary& c) {
  const PsychometricFit& f = *c.fit;
  const std::string threshold = f.has_threshold() ? fmt::format("{:.3f}", f.threshold) : "-";
  const std::string slope = f.has_slope() ? fmt::format("{:.4f}", f.slope) : "-";
  return fmt::format("{:<14} {:7} {:>14} {:>14} {:>18} {:>18}  {}\n", c.condition, f.levels, threshold, slope,
                     interval_text(c.intervals, true, f.has_threshold()),
                     interval_text(c.intervals, false, f.has_slope()), f.reason);
}

//! One condition's goodness of fit: lapse, deviance, its bootstrap p, the levels' residuals.
std::string fit_quality_columns(const ConditionSummary& c) {
  const PsychometricFit& f = *c.fit;
  if (!f.ok) return {};
  std::string residuals;
  for (std::size_t i = 0; i < c.levels.size() && i < f.residuals.size(); ++i)
    residuals += fmt::format("{}{:g}:{:+.2f}", i ? " " : "", c.levels[i].x, f.residuals[i]);
  const std::string p = c.intervals && c.intervals->ok ? fmt::format("{:.3f}", c.intervals->deviance_p) : "-";
  return fmt::format("{:<14} {:6.3f} {:9.3f} {:>8}  {}\n", c.condition, f.lapse, f.deviance, p, residuals);
}

std::string flags_of(const PsychometricFit& f) {
  std::string flags;
  for (const char* name : fit_flags(f)) flags += (flags.empty() ? "" : ";") + std::string(name);
  return flags;
}

//! A CSV field: quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& v) {
  if (v.find_first_of(",\"\n") == std::string::npos) return v;
  std::string q = "\"";
  for (char ch : v) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}
std::string number(double v) { return fmt::format("{}", v); }
std::string lower(const Interval& i) { return i.lo_open ? "" : number(i.lo); }
std::string upper(const Interval& i) { return i.hi_open ? "" : number(i.hi); }

void table_rows(std::string& out, const StudySummary& s, const std::string& who) {
  for (const ConditionSummary& c : s.conditions) {
    if (!c.fit) continue;
    const PsychometricFit& f = *c.fit;
    const bool ci = c.intervals && c.intervals->ok && f.has_threshold();
    int trials = 0;
    for (const PsychometricLevel& l : c.levels) trials += l.trials;
    const std::string lapse_mode = s.fit.fit_lapse ? "fit" : number(s.fit.lapse);
    std::vector<std::string> cells{
        c.condition,
        who,
        name_in(kPsychometricShapeNames, s.fit.model.shape),
        number(s.fit.model.criterion),
        lapse_mode,
        std::to_string(f.levels),
        std::to_string(trials),
        f.has_threshold() ? number(f.threshold) : "",
        ci ? lower(c.intervals->threshold) : "",
        ci ? upper(c.intervals->threshold) : "",
        f.has_slope() ? number(f.slope) : "",
        ci && f.has_slope() ? lower(c.intervals->slope) : "",
        ci && f.has_slope() ? upper(c.intervals->slope) : "",
        f.step && f.has_threshold() ? number(f.slope_at_least) : "",
        f.ok ? number(f.lapse) : "",
        ci && s.fit.fit_lapse ? lower(c.intervals->lapse) : "",
        ci && s.fit.fit_lapse ? upper(c.intervals->lapse) : "",
        f.ok ? number(f.log_likelihood) : "",
        f.ok ? number(f.deviance) : "",
        ci ? number(c.intervals->deviance_p) : "",
        ci ? std::to_string(c.intervals->resamples) : "0",
        flags_of(f),
        f.reason};
    for (std::size_t i = 0; i < cells.size(); ++i) out += (i ? "," : "") + csv_field(cells[i]);
    out += '\n';
  }
}
}  // namespace

StudySummary summarize(const std::vector<ResultRow>& rows, const std::string& participant,
                       const SummaryOptions& options) {
  StudySummary s;
  s.resamples = options.resamples;
  s.fit = options.fit;
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
      c.fit = fit_psychometric(c.levels, options.fit);
      if (options.resamples > 0 && c.fit->has_threshold())
        c.intervals = bootstrap_fit(c.levels, options.fit, *c.fit, options.resamples,
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
      out += "psychometric fit, 2AFC: " + fit_description(s.fit) + "\n";
      fmt::format_to(line, "{:<14} {:>7} {:>14} {:>14} {:>18} {:>18}  {}\n", "condition", "levels", "threshold_pct",
                     "slope_per_pct", "threshold_95ci", "slope_95ci", "note");
      header = true;
    }
    out += fit_columns(c);
  }
  if (header) {
    for (const ConditionSummary& c : s.conditions)
      if (c.intervals) {
        fmt::format_to(line, "95 % intervals: parametric bootstrap, {} resamples, bias-corrected percentiles\n",
                       s.resamples);
        break;
      }
    out += "goodness of fit: deviance against each level's own proportion correct; p_value: the share of the "
           "bootstrap's resamples that fit worse; residuals: each level's deviance residual (x:r)\n";
    fmt::format_to(line, "{:<14} {:>6} {:>9} {:>8}  {}\n", "condition", "lapse", "deviance", "p_value", "residuals");
    for (const ConditionSummary& c : s.conditions)
      if (c.fit) out += fit_quality_columns(c);
  }
  bool adaptive = false;
  for (const ConditionSummary& c : s.conditions) {
    if (c.procedure.empty()) continue;
    if (!adaptive) {
      out += "adaptive tracks: the estimate at each track's last trial (staircase: the mean level at its last "
             "reversals; quest: the posterior mean, on a log10 scale 10^(mean log10); quest_plus: the threshold's "
             "posterior mean)\n";
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

std::string fit_description(const FitOptions& o) {
  const PsychometricModel& m = o.model;
  if (m.shape == PsychometricShape::logistic && m.criterion == 0.75 && !o.fit_lapse && o.lapse == 0)
    return "P(correct) = 0.5 + 0.5/(1 + exp(-slope*(x - threshold))), x = difference in B (%), maximum likelihood";
  const double offset = criterion_offset(m);
  std::string F;
  switch (m.shape) {
    case PsychometricShape::logistic: F = fmt::format("1/(1 + exp(-(slope*(x - threshold) + {:.6g})))", offset); break;
    case PsychometricShape::normal: F = fmt::format("Phi(slope*(x - threshold) + {:.6g})", offset); break;
    case PsychometricShape::gumbel: F = fmt::format("1 - exp(-exp(slope*(x - threshold) + {:.6g}))", offset); break;
    case PsychometricShape::weibull: F = fmt::format("1 - exp(-{:.6g}*(x/threshold)^slope)", offset); break;
  }
  const std::string lapse = o.fit_lapse ? fmt::format("lapse fitted within [0, {:g}]", o.lapse_limit)
                                        : fmt::format("lapse fixed at {:g}", o.lapse);
  return fmt::format("P(correct) = 0.5 + (0.5 - lapse)*F, F = {} ({}), threshold at {:g} correct without lapses, {}, "
                     "x = difference in B (%), maximum likelihood",
                     F, name_in(kPsychometricShapeNames, m.shape), m.criterion, lapse);
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

std::vector<GroupThresholds> group_thresholds(const std::vector<std::pair<std::string, StudySummary>>& participants) {
  std::vector<GroupThresholds> group;
  std::map<std::string, std::vector<double>> values;
  for (const auto& [who, summary] : participants)
    for (const ConditionSummary& c : summary.conditions) {
      if (!c.fit) continue;
      auto it = std::find_if(group.begin(), group.end(), [&](const GroupThresholds& g) { return g.condition == c.condition; });
      if (it == group.end()) it = group.insert(group.end(), GroupThresholds{c.condition});
      ++it->participants;
      if (c.fit->has_threshold() && !c.fit->extrapolated) values[c.condition].push_back(c.fit->threshold);
    }
  std::stable_sort(group.begin(), group.end(), [](const GroupThresholds& a, const GroupThresholds& b) {
    return condition_rank(a.condition) < condition_rank(b.condition);
  });
  for (GroupThresholds& g : group) {
    std::vector<double>& v = values[g.condition];
    g.estimated = static_cast<int>(v.size());
    if (v.empty()) continue;
    double sum = 0;
    for (double t : v) sum += t;
    g.mean = sum / static_cast<double>(v.size());
    double ss = 0;
    for (double t : v) ss += (t - g.mean) * (t - g.mean);
    if (v.size() > 1) g.se = std::sqrt(ss / static_cast<double>(v.size() - 1) / static_cast<double>(v.size()));
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    g.median = n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
  }
  return group;
}

std::string format_group(const std::vector<GroupThresholds>& group) {
  int most = 0;
  for (const GroupThresholds& g : group) most = std::max(most, g.participants);
  if (most < 2) return {};
  std::string out =
      "group: each participant's own threshold (not the pooled fit above), mean ± standard error and median over "
      "the participants with one inside the tested range\n";
  auto line = std::back_inserter(out);
  fmt::format_to(line, "{:<14} {:>12} {:>13} {:>10} {:>13}\n", "condition", "participants", "mean_pct", "se_pct",
                 "median_pct");
  for (const GroupThresholds& g : group) {
    const std::string who = g.estimated == g.participants ? std::to_string(g.participants)
                                                          : fmt::format("{} of {}", g.estimated, g.participants);
    if (g.estimated == 0) {
      fmt::format_to(line, "{:<14} {:>12} {:>13} {:>10} {:>13}\n", g.condition, who, "-", "-", "-");
      continue;
    }
    const std::string se = g.estimated > 1 ? fmt::format("{:.3f}", g.se) : "-";
    fmt::format_to(line, "{:<14} {:>12} {:13.3f} {:>10} {:13.3f}\n", g.condition, who, g.mean, se, g.median);
  }
  return out;
}

std::vector<const char*> fit_flags(const PsychometricFit& f) {
  const std::pair<bool, const char*> all[] = {{!f.ok, "no_fit"},
                                              {f.threshold_below, "threshold_below_range"},
                                              {f.threshold_above, "threshold_above_range"},
                                              {f.extrapolated, "extrapolated"},
                                              {f.step, "step"},
                                              {f.flat, "flat"},
                                              {f.lapse_at_limit, "lapse_at_limit"}};
  std::vector<const char*> on;
  for (const auto& [holds, name] : all)
    if (holds) on.push_back(name);
  return on;
}

std::string fit_table_csv(const StudySummary& pooled,
                          const std::vector<std::pair<std::string, StudySummary>>& participants) {
  std::string out = std::string(kFitTableColumns) + "\n";
  table_rows(out, pooled, "pooled");
  for (const auto& [who, summary] : participants) table_rows(out, summary, who);
  return out;
}

}  // namespace mallet::study
