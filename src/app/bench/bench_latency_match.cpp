// `mallet bench latency`'s matching and statistics: pure functions of a run's recording
// (bench_latency.hpp says what each time means).
#include "app/bench/bench_latency.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "app/bench/bench_report.hpp"

namespace mallet::app::latency {

namespace {

std::optional<Nanos> first_in(const std::vector<Nanos>& sorted, Nanos from, Nanos to) {
  auto it = std::lower_bound(sorted.begin(), sorted.end(), from);
  if (it == sorted.end() || *it >= to) return std::nullopt;
  return *it;
}

}  // namespace

Matched match_recording(const Recording& r) {
  auto sorted = [](std::vector<Nanos> v) {
    std::sort(v.begin(), v.end());
    return v;
  };
  const std::vector<Nanos> strikes = sorted(r.strikes), actuator = sorted(r.actuator), note = sorted(r.note);
  std::vector<std::vector<Nanos>> picture;
  for (const auto& p : r.picture) picture.push_back(sorted(p));
  std::vector<Recording::Contact> contacts = r.contacts;
  std::sort(contacts.begin(), contacts.end(), [](const auto& a, const auto& b) { return a.t < b.t; });

  Matched m;
  m.cues = {{"actuator", {}}, {"note", {}}, {"picture", {}}, {"actuator-picture", {}}, {"note-actuator", {}}};
  std::vector<char> used(strikes.size(), 0);
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Recording::Contact& c = contacts[k];
    // The nearest unused logged strike within the window.
    std::optional<std::size_t> best;
    for (std::size_t i = 0; i < strikes.size(); ++i) {
      if (used[i] || std::llabs(strikes[i] - c.t) > kStrikeWindow) continue;
      if (!best || std::llabs(strikes[i] - c.t) < std::llabs(strikes[*best] - c.t)) best = i;
    }
    StrikeRow row{c, {}, {}, {}, {}};
    if (!best) {
      ++m.missed_strikes;
      m.rows.push_back(row);
      continue;
    }
    used[*best] = 1;
    ++m.strikes;
    row.strike_ms = ms_of(strikes[*best] - c.t);
    // A cue belongs to this contact if it comes before the next contact's own window opens.
    const Nanos to =
        std::min(c.t + kCueAfter, k + 1 < contacts.size() ? contacts[k + 1].t - kCueBefore : c.t + kCueAfter);
    const std::optional<Nanos> a = first_in(actuator, c.t - kCueBefore, to);
    const std::optional<Nanos> n = first_in(note, c.t - kCueBefore, to);
    std::optional<Nanos> p;
    if (c.bar >= 0 && static_cast<std::size_t>(c.bar) < picture.size())
      p = first_in(picture[static_cast<std::size_t>(c.bar)], c.t - kCueBefore, to);
    if (a) m.cues[0].ms.push_back(*(row.actuator_ms = ms_of(*a - c.t)));
    if (n) m.cues[1].ms.push_back(*(row.note_ms = ms_of(*n - c.t)));
    if (p) m.cues[2].ms.push_back(*(row.picture_ms = ms_of(*p - c.t)));
    if (a && p) m.cues[3].ms.push_back(ms_of(*a - *p));
    if (n && a) m.cues[4].ms.push_back(ms_of(*n - *a));
    m.rows.push_back(row);
  }
  for (char u : used) m.false_strikes += u ? 0 : 1;
  return m;
}

Summary summarise(std::vector<double> ms) {
  Summary s;
  s.n = ms.size();
  if (ms.empty()) return s;
  std::sort(ms.begin(), ms.end());
  const std::size_t n = ms.size();
  s.median = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
  s.p99 = nearest_rank(ms, 0.99);
  s.max = std::fabs(ms.front()) > std::fabs(ms.back()) ? ms.front() : ms.back();
  return s;
}

}  // namespace mallet::app::latency
