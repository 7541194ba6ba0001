#include "core/study/protocol_loader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <set>

#include <fmt/format.h>

#include "core/config/toml_reader.hpp"
#include "core/named.hpp"
#include "core/visitor_language.hpp"

namespace mallet::study {

bool is_plain_name(std::string_view s) {
  if (s.empty() || s.size() > 64) return false;
  for (char c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                    c == '-' || c == '.';
    if (!ok) return false;
  }
  return true;
}

namespace {

using config::TableReader;

constexpr const char* kPlain = "must be 1-64 letters, digits, '_', '-' or '.'";

Nanos seconds_key(TableReader& t, std::string_view key, double fallback_s, double lo, double hi) {
  const double s = t.number_or(key, fallback_s);
  t.require_range(key, s, lo, hi);
  return static_cast<Nanos>(std::llround(s * 1e9));
}

//! `paired`: two stimuli a trial, so the second may start only once the first is over.
StudyTiming read_timing(TableReader t, bool paired) {
  const StudyTiming d;
  StudyTiming timing;
  timing.lead = seconds_key(t, "lead_s", to_seconds(d.lead), 0, 60);
  timing.stimulus = seconds_key(t, "stimulus_s", to_seconds(d.stimulus), 0.05, 60);
  timing.stimulus_interval = seconds_key(t, "stimulus_interval_s", to_seconds(d.stimulus_interval), 0.05, 60);
  timing.inter_trial = seconds_key(t, "inter_trial_s", to_seconds(d.inter_trial), 0, 60);
  if (paired && timing.stimulus_interval < timing.stimulus)
    t.fail("stimulus_interval_s", "must be >= stimulus_s, so the first stimulus is over before the second");
  t.finish();
  return timing;
}

Stimulus read_stimulus(TableReader t, const std::vector<Material>& materials) {
  Stimulus s;
  s.name = t.string("name");
  if (!is_plain_name(s.name)) t.fail("name", "\"" + s.name + "\" " + kPlain);
  const std::string material = t.string("material");
  const Material* found = find_named(materials, material);
  if (!found)
    t.fail("material", "unknown material \"" + material + "\" (the scene has: " + names_of(materials) + ")");
  s.decay_scale = 1.0;
  t.read("decay_scale", s.decay_scale, 0.01, 100);
  s.material = *found;
  s.material.visual.decay_per_s *= s.decay_scale;
  s.material.actuator.decay_per_s *= s.decay_scale;
  t.finish();
  return s;
}

//! A texture_slope stimulus: the relief's shape and height (the scene gives its profile,
//! centre and radius).
Stimulus read_texture_stimulus(TableReader t) {
  Stimulus s;
  s.name = t.string("name");
  if (!is_plain_name(s.name)) t.fail("name", "\"" + s.name + "\" " + kPlain);
  TextureRelief relief;
  relief.shape = t.choice("relief", kReliefShapeNames);
  relief.height_m = t.number("height_m");
  t.require_range("height_m", relief.height_m, 0.0002, 0.05);
  s.relief = relief;
  t.finish();
  return s;
}

int stimulus_index(TableReader& t, std::string_view key, const std::vector<Stimulus>& stimuli) {
  const std::string name = t.string(key);
  if (const Stimulus* found = find_named(stimuli, name)) return static_cast<int>(found - stimuli.data());
  t.fail(key, "no [[stimulus]] named \"" + name + "\" (known: " + names_of(stimuli) + ")");
}

StimulusPair read_pair(TableReader t, const std::vector<Stimulus>& stimuli) {
  StimulusPair p;
  p.a = stimulus_index(t, "a", stimuli);
  p.b = stimulus_index(t, "b", stimuli);
  t.finish();
  if (p.a == p.b) t.fail("b", "a pair needs two different stimuli");
  if (const auto& ra = stimuli[static_cast<std::size_t>(p.a)].relief) {  // texture_slope: the steeper
    const TextureRelief& rb = *stimuli[static_cast<std::size_t>(p.b)].relief;
    if (ra->shape != rb.shape) t.fail("b", "\"which was steeper\" compares two bumps or two holes");
    if (ra->height_m == rb.height_m) t.fail("b", "\"steeper\" is the higher relief; these two are as high");
    p.harder = rb.height_m > ra->height_m ? p.b : p.a;
    const double hard = std::max(ra->height_m, rb.height_m), soft = std::min(ra->height_m, rb.height_m);
    p.difference_pct = 100.0 * (hard / soft - 1.0);
    return p;
  }
  const Material& a = stimuli[static_cast<std::size_t>(p.a)].material;
  const Material& b = stimuli[static_cast<std::size_t>(p.b)].material;
  const double dv = b.visual.decay_per_s - a.visual.decay_per_s;
  const double da = b.actuator.decay_per_s - a.actuator.decay_per_s;
  if (dv == 0 || da == 0 || (dv > 0) != (da > 0))
    t.fail("b",
           "\"harder\" is the stimulus with the larger decay_per_s (B), visual and actuator alike; these two "
           "are equal or ordered differently by the two triples");
  p.harder = dv > 0 ? p.b : p.a;
  const Material& hard = p.harder == p.a ? a : b;
  const Material& soft = p.harder == p.a ? b : a;
  p.difference_pct = 100.0 * (hard.visual.decay_per_s / soft.visual.decay_per_s - 1.0);
  return p;
}

AnswerStrike read_answer_strike(TableReader t, const std::vector<Material>& materials) {
  AnswerStrike a;
  const std::string sound = t.string_or("sound", a.voice);
  a.voice = sound == "none" ? "" : sound;
  a.voice_at = t.place("sound");
  const std::string feel = t.string_or("feel", "none");
  if (feel != "none") {
    const Material* found = find_named(materials, feel);
    if (!found)
      t.fail("feel", "expected \"none\" or a material of the scene (" + names_of(materials) + "), got \"" +
                         feel + "\"");
    a.feel = *found;
  }
  t.finish();
  return a;
}

//! The offer and the consent of one language, checked as the attract screen and the consent
//! screen need them.
VisitorTexts read_visitor_texts(TableReader& t, const VisitorTexts& fallback) {
  VisitorTexts w;
  w.offer = t.string_or("offer", fallback.offer);
  if (w.offer.empty() || w.offer.size() > 120) t.fail("offer", "must be 1-120 characters (one line on the attract screen)");
  w.consent = t.string("consent");
  if (w.consent.empty() || w.consent.size() > 1200)
    t.fail("consent", "must be 1-1200 characters (it is shown on one screen)");
  return w;
}

//! A language the kiosk can show (a catalogue of its own, or English).
std::string visitor_language_key(TableReader& t, std::string_view key, std::string value) {
  if (!is_visitor_language(value))
    t.fail(key, "\"" + value + "\": not a language the kiosk has (" + visitor_languages_text() + ")");
  return value;
}

VisitorProtocol read_visitor(TableReader t) {
  VisitorProtocol v;
  const VisitorTexts own = read_visitor_texts(t, {v.offer, ""});
  v.offer = own.offer;
  v.consent = own.consent;
  v.language = visitor_language_key(t, "language", t.string_or("language", v.language));
  if (auto text = t.optional_table("text")) {
    for (const std::string& lang : text->keys()) {
      TableReader words = text->table(lang);
      visitor_language_key(*text, lang, lang);
      if (lang == v.language) text->fail(lang, "is the protocol's own language ([visitor] language): its words are [visitor]'s");
      v.texts.emplace_back(lang, read_visitor_texts(words, {"", ""}));
      words.finish();
    }
    text->finish();
  }
  t.read("trials", v.trials, 1, 50);
  v.answer_timeout = seconds_key(t, "answer_timeout_s", to_seconds(v.answer_timeout), 3, 600);
  t.finish();
  return v;
}

//! A difference (%) an adaptive track may test: on the grid of generated stimuli.
double grid_pct(TableReader& t, std::string_view key, double fallback, double lo, double hi) {
  double v = fallback;
  t.read(key, v, lo, hi);
  const double steps = v / kAdaptiveGridPct;
  if (std::abs(steps - std::round(steps)) > 1e-9)
    t.fail(key, "must be a multiple of 0.5 % (the grid of stimuli an adaptive track tests)");
  return v;
}

//! A staircase's steps that multiply the level (step_type "db" or "log"): `key` lists them,
//! each in (0, most].
std::vector<double> multiplying_steps(TableReader& t, std::string_view key, std::string_view type, double most,
                                      std::string_view example) {
  if (!t.has(key))
    t.fail(key, fmt::format("step_type = \"{}\" needs its steps as {} (e.g. {} = {})", type, key, key, example));
  std::vector<double> steps = t.numbers(key);
  if (steps.empty()) t.fail(key, "lists no step");
  for (double step : steps)
    if (!(step > 0) || step > most)
      t.fail(key, fmt::format("each step must be > 0 and <= {} (got {})", most, config::number_text(step)));
  return steps;
}

void read_staircase(TableReader t, AdaptiveProtocol& a) {
  StaircaseRule& r = a.staircase;
  t.read("down", r.down, 1, 4);
  a.min_pct = grid_pct(t, "min_pct", a.min_pct, kAdaptiveGridPct, 100);
  a.max_pct = grid_pct(t, "max_pct", a.max_pct, a.min_pct, 100);
  r.start = grid_pct(t, "start_pct", std::clamp(r.start, a.min_pct, a.max_pct), a.min_pct, a.max_pct);
  r.step_type = t.choice_or("step_type", kStaircaseStepTypeNames, StaircaseStepType::linear);
  // Each step type has its steps in its own unit, in a key that names it.
  const std::pair<StaircaseStepType, const char*> step_keys[] = {{StaircaseStepType::linear, "steps_pct"},
                                                                 {StaircaseStepType::db, "steps_db"},
                                                                 {StaircaseStepType::log, "steps_log10"}};
  const char* steps_key = "steps_pct";
  for (const auto& [type, key] : step_keys)
    if (type == r.step_type) steps_key = key;
  for (const auto& [type, key] : step_keys)
    if (type != r.step_type && t.has(key))
      t.fail(key, fmt::format("step_type = \"{}\" takes its steps as {}", name_in(kStaircaseStepTypeNames, r.step_type),
                              steps_key));
  if (r.step_type == StaircaseStepType::db) {
    r.steps = multiplying_steps(t, "steps_db", "db", 40, "[4, 2, 1]");
  } else if (r.step_type == StaircaseStepType::log) {
    r.steps = multiplying_steps(t, "steps_log10", "log", 2, "[0.2, 0.1, 0.05]");
  } else if (t.has("steps_pct")) {
    r.steps = t.numbers("steps_pct");
    if (r.steps.empty()) t.fail("steps_pct", "lists no step");
    for (double step : r.steps) {
      const double k = step / kAdaptiveGridPct;
      if (!(step > 0) || std::abs(k - std::round(k)) > 1e-9)
        t.fail("steps_pct", "each step must be a positive multiple of 0.5 % (the grid of stimuli)");
    }
  }
  r.initial_one_up_one_down = t.boolean_or("initial_one_up_one_down", r.initial_one_up_one_down);
  t.read("stop_reversals", r.stop_reversals, 1, 100);
  t.read("threshold_reversals", r.threshold_reversals, 1, r.stop_reversals);
  t.read("discard_reversals", r.discard_reversals, 0, 99);
  if (r.discard_reversals + r.threshold_reversals > r.stop_reversals)
    t.fail("discard_reversals",
           fmt::format("the first {} reversals discarded and the last {} averaged (threshold_reversals) need {} "
                       "reversals, and a track stops at {} (stop_reversals): it would never have an estimate; "
                       "lower one of them or raise stop_reversals",
                       r.discard_reversals, r.threshold_reversals, r.discard_reversals + r.threshold_reversals,
                       r.stop_reversals));
  t.read("max_trials", r.max_trials, 1, 1000);
  r.min = a.min_pct;
  r.max = a.max_pct;
  t.finish();
}

void read_quest(TableReader t, AdaptiveProtocol& a) {
  const std::string shape = t.string_or("shape", "weibull");
  if (shape == "weibull") a.quest_model.shape = QuestShape::weibull;
  else if (shape == "logistic") a.quest_model.shape = QuestShape::logistic;
  else t.fail("shape", "expected \"weibull\" or \"logistic\", got \"" + shape + "\"");
  t.read("beta", a.quest_model.beta, 0.01, 20);
  t.read("delta", a.quest_model.delta, 0, 0.2);
  a.min_pct = grid_pct(t, "min_pct", a.min_pct, kAdaptiveGridPct, 100);
  a.max_pct = grid_pct(t, "max_pct", a.max_pct, a.min_pct, 100);
  // The prior is on the scale's own axis: % (linear), or log10 of % (log10, as PsychoPy's
  // QuestHandler's startVal and startValSd on a log10 intensity), each in keys that say so.
  a.quest_model.scale = t.choice_or("scale", kQuestScaleNames, QuestScale::linear);
  const bool log = a.quest_model.scale == QuestScale::log10;
  const std::array<const char*, 2> other_scale =
      log ? std::array{"prior_mean_pct", "prior_sd_pct"} : std::array{"prior_mean_log10", "prior_sd_log10"};
  for (const char* key : other_scale)
    if (t.has(key))
      t.fail(key, log ? "scale = \"log10\" takes its prior in log10 units of the difference: prior_mean_log10, "
                        "prior_sd_log10"
                      : "only scale = \"log10\" uses it (this prior is in %: prior_mean_pct, prior_sd_pct)");
  if (log) {
    a.quest_prior.mean = std::log10(20.0);
    a.quest_prior.sd = 0.5;
    t.read("prior_mean_log10", a.quest_prior.mean, std::log10(a.min_pct), std::log10(a.max_pct));
    t.read("prior_sd_log10", a.quest_prior.sd, 0.01, 5);
  } else {
    a.quest_prior.mean = 20;
    t.read("prior_mean_pct", a.quest_prior.mean, a.min_pct, a.max_pct);
    t.read("prior_sd_pct", a.quest_prior.sd, 0.1, 100);
  }
  a.quest_model.placement = t.choice_or("placement", kQuestPlacementNames, QuestPlacement::mean);
  if (a.quest_model.placement == QuestPlacement::quantile) {
    t.read("quantile", a.quest_model.quantile, 0.01, 0.99);
  } else if (t.has("quantile")) {
    t.fail("quantile", "only placement = \"quantile\" uses it");
  }
  a.quest_prior.lo = a.min_pct;
  a.quest_prior.hi = a.max_pct;
  t.read("trials", a.quest_trials, 1, 1000);
  t.finish();
}

//! A QUEST+ parameter's values: a list, increasing, each in [lo, hi].
std::vector<double> grid_values(TableReader& t, std::string_view key, double lo, double hi) {
  const std::vector<double> v = t.numbers(key);
  if (v.empty()) t.fail(key, "lists no value");
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!(v[i] >= lo && v[i] <= hi))
      t.fail(key, "each must be in [" + config::number_text(lo) + ", " + config::number_text(hi) + "], got " +
                      config::number_text(v[i]));
    if (i > 0 && !(v[i] > v[i - 1]))
      t.fail(key, "must increase (" + config::number_text(v[i - 1]) + " then " + config::number_text(v[i]) + ")");
  }
  return v;
}

enum class QuestPlusPriorKind { uniform, gaussian };
constexpr EnumNames<QuestPlusPriorKind, 2> kQuestPlusPriorNames{
    {{QuestPlusPriorKind::uniform, "uniform"}, {QuestPlusPriorKind::gaussian, "gaussian"}}};

//! The most likelihoods (stimuli × parameter vectors) a QUEST+ table may hold: 24 MB, and a
//! trial's choice a few milliseconds.
constexpr double kQuestPlusMaxTable = 1e6;

void read_quest_plus(TableReader t, AdaptiveProtocol& a) {
  QuestPlusSetup& q = a.quest_plus;
  q.model.shape = t.choice_or("shape", kPsychometricShapeNames, PsychometricShape::logistic);
  q.model.guess = 0.5;  // 2AFC
  q.model.criterion = t.number_or("criterion", 0.75);
  if (!(q.model.criterion > q.model.guess && q.model.criterion < 1))
    t.fail("criterion", "must lie between the 2AFC guess rate 0.5 and 1 (both excluded), got " +
                            config::number_text(q.model.criterion));
  a.min_pct = grid_pct(t, "min_pct", a.min_pct, kAdaptiveGridPct, 100);
  a.max_pct = grid_pct(t, "max_pct", a.max_pct, a.min_pct, 100);
  const double stimuli = std::round((a.max_pct - a.min_pct) / kAdaptiveGridPct) + 1;
  // The thresholds: a list, or lo, hi and points evenly spaced; by default the stimuli's grid.
  q.grid.thresholds.clear();
  if (t.has_table("threshold_pct")) {
    TableReader g = t.table("threshold_pct");
    const double lo = g.number("lo");
    g.require_range("lo", lo, 0.01, 100);
    const double hi = g.number("hi");
    if (!(hi > lo && hi <= 100))
      g.fail("hi", "must be > lo (" + config::number_text(lo) + ") and <= 100, got " + config::number_text(hi));
    const std::int64_t points = g.integer("points");
    g.require_range("points", static_cast<double>(points), 2, 1000);
    g.finish();
    for (std::int64_t i = 0; i < points; ++i)
      q.grid.thresholds.push_back(lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(points - 1));
  } else if (t.has("threshold_pct")) {
    q.grid.thresholds = grid_values(t, "threshold_pct", 0.01, 100);
  } else {
    for (double k = 0; k < stimuli; ++k) q.grid.thresholds.push_back(a.min_pct + k * kAdaptiveGridPct);
  }
  q.grid.slopes = grid_values(t, "slope", 0.001, 100);
  q.grid.lapses = t.has("lapse") ? grid_values(t, "lapse", 0, 0.2) : std::vector<double>{0.02};
  const double table = stimuli * static_cast<double>(q.grid.size());
  if (table > kQuestPlusMaxTable)
    t.fail("threshold_pct", fmt::format("{} thresholds × {} slopes × {} lapses × {} stimuli make {:g} likelihoods, "
                                        "more than QUEST+ tables ({:g}): fewer points, or a narrower min_pct-max_pct",
                                        q.grid.thresholds.size(), q.grid.slopes.size(), q.grid.lapses.size(),
                                        stimuli, table, kQuestPlusMaxTable));
  q.threshold_prior.reset();
  if (t.choice_or("prior", kQuestPlusPriorNames, QuestPlusPriorKind::uniform) == QuestPlusPriorKind::gaussian) {
    QuestPlusThresholdPrior prior;
    prior.mean = t.number("prior_mean_pct");
    t.require_range("prior_mean_pct", prior.mean, 0, 100);
    prior.sd = t.number("prior_sd_pct");
    t.require_range("prior_sd_pct", prior.sd, 0.1, 100);
    q.threshold_prior = prior;
  } else {
    for (const char* key : {"prior_mean_pct", "prior_sd_pct"})
      if (t.has(key)) t.fail(key, "only prior = \"gaussian\" uses it");
  }
  t.read("trials", a.quest_plus_trials, 1, 1000);
  t.finish();
}

//! The adaptive tracks' stimuli and pairs: the reference, and for each difference on the
//! grid from min_pct to max_pct the reference with both triples' B larger by it.
void make_adaptive_pairs(StudyProtocol& p) {
  const Stimulus reference = p.stimuli.at(static_cast<std::size_t>(p.adaptive.reference));
  const int steps = static_cast<int>(std::llround((p.adaptive.max_pct - p.adaptive.min_pct) / kAdaptiveGridPct));
  for (int k = 0; k <= steps; ++k) {
    const double level = p.adaptive.min_pct + k * kAdaptiveGridPct;
    Stimulus s = reference;
    const std::string name = fmt::format("+{:g}", level);
    s.name = reference.name + name;
    s.decay_scale = reference.decay_scale * (1 + level / 100);
    s.material.visual.decay_per_s *= 1 + level / 100;
    s.material.actuator.decay_per_s *= 1 + level / 100;
    p.stimuli.push_back(s);
    StimulusPair pair;
    pair.a = p.adaptive.reference;
    pair.b = static_cast<int>(p.stimuli.size() - 1);
    pair.harder = pair.b;
    pair.difference_pct = level;
    p.pairs.push_back(pair);
  }
}

StudyProtocol read(const toml::table& root, const std::string& file, const std::vector<Material>& materials,
                   std::size_t bar_count) {
  TableReader top(root, file);
  StudyProtocol p;
  p.file = file;
  p.name = top.string("name");
  if (!is_plain_name(p.name)) top.fail("name", "\"" + p.name + "\" " + kPlain);

  p.task = top.choice("task", kStudyTaskNames);
  if (!p.texture() && bar_count == 0)
    top.fail("task", "\"" + std::string(task_name(p.task)) +
                         "\" strikes bars, and the scene has none (a texture scene? task = \"texture_slope\" "
                         "crosses its disc)");
  if (p.texture()) {
    p.question = top.choice("question", kTextureQuestionNames);
  } else if (top.has("question")) {
    top.fail("question", "only task = \"texture_slope\" asks one");
  }

  std::set<std::string> seen;
  for (const std::string& c : top.strings("conditions")) {
    const auto condition = condition_from_name(c);
    if (!condition) top.fail("conditions", "unknown condition \"" + c + "\" (visual_only, tactile_only, both, none)");
    if (!seen.insert(c).second) top.fail("conditions", "\"" + c + "\" is listed twice");
    p.conditions.push_back(*condition);
  }
  if (p.conditions.empty()) top.fail("conditions", "lists no condition");

  p.procedure = top.choice_or("procedure", kStudyProcedureNames, StudyProcedure::constant);
  const bool adaptive = p.procedure != StudyProcedure::constant;
  if (adaptive && p.task != StudyTask::two_afc_harder)
    top.fail("procedure", "an adaptive procedure needs task = \"2afc_harder\" (it adapts a difference)");
  if (!adaptive) {
    const std::int64_t reps = top.integer("repetitions");
    top.require_range("repetitions", static_cast<double>(reps), 1, 1000);
    if (p.paired() && reps % 2 != 0)
      top.fail("repetitions", "must be even for 2afc_harder and steeper, so each pair is shown in both orders equally often");
    p.repetitions = static_cast<int>(reps);
  } else if (top.has("repetitions")) {
    top.fail("repetitions", "an adaptive protocol's trials end by its own stop rule ([" +
                                std::string(procedure_name(p.procedure)) + "]); remove it");
  }

  const std::int64_t seed = top.integer("seed");
  if (seed < 0) top.fail("seed", "must be >= 0");
  p.seed = static_cast<std::uint64_t>(seed);
  p.output = top.string_or("output", "study-results.csv");
  if (p.output.empty()) top.fail("output", "must not be empty");
  top.read("impact_speed_m_per_s", p.impact_speed_m_per_s, 0.01, 10);
  p.sound = top.boolean_or("sound", false);
  if (p.texture()) {
    for (const char* key : {"reference_bar", "sound"})
      if (top.has(key)) top.fail(key, "a texture_slope trial strikes no bar; remove it");
  } else {
    const std::int64_t bar = top.integer_or("reference_bar", 0);
    if (bar < 0 || static_cast<std::size_t>(bar) >= bar_count)
      top.fail("reference_bar", "must name a bar of the scene: 0 to " + std::to_string(bar_count - 1));
    p.reference_bar = static_cast<int>(bar);
  }
  if (auto timing = top.optional_table("timing")) p.timing = read_timing(*timing, p.paired());
  p.response = top.choice_or("response", kStudyResponseNames, StudyResponse::keys);
  if (p.response == StudyResponse::strike && p.texture())
    top.fail("response", "a texture_slope trial has no bars to strike: its answers are keys");
  if (auto answer = top.optional_table("answer_strike")) {
    if (p.response != StudyResponse::strike)
      top.fail("answer_strike", "only response = \"strike\" uses it");
    p.answer_strike = read_answer_strike(*answer, materials);
  } else {
    p.answer_strike.voice_at = top.place("response");
  }
  if (auto visitor = top.optional_table("visitor")) {
    if (p.response != StudyResponse::strike)
      top.fail("visitor", "a visitor answers by striking: it needs response = \"strike\"");
    p.visitor = read_visitor(*visitor);
  }

  std::set<std::string> names;
  std::vector<TableReader> stimulus_tables = top.tables("stimulus");
  for (TableReader& t : stimulus_tables) {
    p.stimuli.push_back(p.texture() ? read_texture_stimulus(t) : read_stimulus(t, materials));
    if (!names.insert(p.stimuli.back().name).second)
      t.fail("name", "a second [[stimulus]] named \"" + p.stimuli.back().name + "\"");
  }

  if (adaptive) {
    if (top.has("pair")) top.fail("pair", "an adaptive protocol makes its pairs from `reference`; remove [[pair]]");
    p.adaptive.reference = stimulus_index(top, "reference", p.stimuli);
    if (p.procedure == StudyProcedure::staircase) read_staircase(top.table("staircase"), p.adaptive);
    else if (p.procedure == StudyProcedure::quest_plus) read_quest_plus(top.table("quest_plus"), p.adaptive);
    else read_quest(top.table("quest"), p.adaptive);
    make_adaptive_pairs(p);
  } else if (p.paired()) {
    for (const char* key : {"reference", "staircase", "quest", "quest_plus"})
      if (top.has(key))
        top.fail(key, "only an adaptive procedure (procedure = \"staircase\", \"quest\" or \"quest_plus\") uses it");
    for (TableReader& t : top.tables("pair")) p.pairs.push_back(read_pair(t, p.stimuli));
  } else {
    if (top.has("pair")) top.fail("pair", "only a 2afc_harder or steeper protocol has pairs");
    for (std::size_t i = 0; i < p.stimuli.size(); ++i) p.named.push_back(static_cast<int>(i));
    if (p.texture()) {
      bool bump = false, hole = false;
      for (const Stimulus& st : p.stimuli) (st.relief->shape == ReliefShape::bump ? bump : hole) = true;
      if (!bump || !hole) top.fail("stimulus", "\"bump or hole\" needs at least one of each");
    }
  }
  if (p.visitor && p.answer_choices().size() < 2)
    top.fail("visitor", "a visitor's consent is struck on the first two answer bars (Yes, No): the protocol "
                        "needs at least two answers");
  top.finish();
  return p;
}

}  // namespace

StudyProtocol load_study_protocol(const std::filesystem::path& path, const std::vector<Material>& materials,
                                  std::size_t bar_count) {
  return read(config::parse_file(path), path.string(), materials, bar_count);
}

StudyProtocol parse_study_protocol(std::string_view text, const std::string& name,
                                   const std::vector<Material>& materials, std::size_t bar_count) {
  return read(config::parse_text(text, name), name, materials, bar_count);
}

}  // namespace mallet::study
