#include "core/study/study_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "core/study/study_protocol.hpp"

namespace mallet::study {

namespace {
int condition_rank(const std::string& name) {
  for (int i = 0; i < 4; ++i)
    if (condition_name(kAllConditions[i]) == name) return i;
  return 4;
}
}  // namespace

StudySummary summarize(const std::vector<ResultRow>& rows, const std::string& participant) {
  StudySummary s;
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
    rt_sum[r.condition] += r.response_time_ms;
    if (std::isfinite(r.difference_pct)) {
      PsychometricLevel& l = levels[r.condition][r.difference_pct];
      l.x = r.difference_pct;
      ++l.trials;
      l.correct += r.correct ? 1 : 0;
    }
  }
  for (auto& [name, c] : by_condition) {
    c.mean_response_ms = rt_sum[name] / c.trials;
    if (auto it = levels.find(name); it != levels.end()) {
      std::vector<PsychometricLevel> v;
      for (const auto& [x, l] : it->second) v.push_back(l);
      c.fit = fit_psychometric_2afc(v);
    }
    s.conditions.push_back(c);
  }
  std::stable_sort(s.conditions.begin(), s.conditions.end(), [](const ConditionSummary& a, const ConditionSummary& b) {
    return condition_rank(a.condition) < condition_rank(b.condition);
  });
  return s;
}

std::string format_summary(const StudySummary& s) {
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "%d trial%s, %zu participant%s\n", s.rows, s.rows == 1 ? "" : "s",
                s.participants.size(), s.participants.size() == 1 ? "" : "s");
  out += line;
  if (s.simulated_rows)
    out += "note: " + std::to_string(s.simulated_rows) + " row(s) were answered by the simulated observer (source=simulated)\n";
  std::snprintf(line, sizeof line, "%-14s %7s %8s %9s %10s\n", "condition", "trials", "correct", "accuracy", "mean_rt_ms");
  out += line;
  for (const ConditionSummary& c : s.conditions) {
    std::snprintf(line, sizeof line, "%-14s %7d %8d %8.1f%% %10.1f\n", c.condition.c_str(), c.trials, c.correct,
                  100.0 * c.accuracy(), c.mean_response_ms);
    out += line;
  }
  bool header = false;
  for (const ConditionSummary& c : s.conditions) {
    if (!c.fit) continue;
    if (!header) {
      out += "psychometric fit, 2AFC: P(correct) = 0.5 + 0.5/(1 + exp(-slope*(x - threshold))), "
             "x = difference in B (%), maximum likelihood\n";
      std::snprintf(line, sizeof line, "%-14s %7s %14s %14s  %s\n", "condition", "levels", "threshold_pct",
                    "slope_per_pct", "note");
      out += line;
      header = true;
    }
    const PsychometricFit& f = *c.fit;
    if (f.ok)
      std::snprintf(line, sizeof line, "%-14s %7d %14.3f %14.4f  %s\n", c.condition.c_str(), f.levels, f.threshold,
                    f.slope, f.reason.c_str());
    else
      std::snprintf(line, sizeof line, "%-14s %7d %14s %14s  %s\n", c.condition.c_str(), f.levels, "-", "-",
                    f.reason.c_str());
    out += line;
  }
  return out;
}

std::string format_participant_fits(const std::vector<ResultRow>& rows) {
  std::vector<std::string> order;
  for (const ResultRow& r : rows)
    if (std::find(order.begin(), order.end(), r.participant) == order.end()) order.push_back(r.participant);
  std::string out;
  char line[256];
  for (const std::string& p : order) {
    for (const ConditionSummary& c : summarize(rows, p).conditions) {
      if (!c.fit) continue;
      if (out.empty()) {
        out = "per participant, the same fit:\n";
        std::snprintf(line, sizeof line, "%-12s %-14s %7s %14s %14s  %s\n", "participant", "condition", "levels",
                      "threshold_pct", "slope_per_pct", "note");
        out += line;
      }
      const PsychometricFit& f = *c.fit;
      if (f.ok)
        std::snprintf(line, sizeof line, "%-12s %-14s %7d %14.3f %14.4f  %s\n", p.c_str(), c.condition.c_str(),
                      f.levels, f.threshold, f.slope, f.reason.c_str());
      else
        std::snprintf(line, sizeof line, "%-12s %-14s %7d %14s %14s  %s\n", p.c_str(), c.condition.c_str(), f.levels,
                      "-", "-", f.reason.c_str());
      out += line;
    }
  }
  return out;
}

}  // namespace mallet::study
