// The study summary's plots and report: see study_report.hpp.
#include "app/study/study_report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/gnuplot.hpp"
#include "core/file_error.hpp"

namespace mallet::app {

namespace {

constexpr double kRtBinMs = 50;

void write_file(const std::filesystem::path& file, const std::string& text) {
  std::ofstream f(file);
  f << text;
  if (!f) throw FileError(file.string(), 0, 0, "cannot write");
}

//! The fitted curve as a gnuplot expression of x.
std::string gnuplot_curve(const study::FitOptions& o, const study::PsychometricFit& f) {
  const study::PsychometricModel& m = o.model;
  const double c = study::criterion_offset(m);
  std::string core;
  switch (m.shape) {
    case study::PsychometricShape::logistic:
      core = fmt::format("1/(1 + exp(-({:.9g}*(x - {:.9g}) + {:.9g})))", f.slope, f.threshold, c);
      break;
    case study::PsychometricShape::normal:
      core = fmt::format("norm({:.9g}*(x - {:.9g}) + {:.9g})", f.slope, f.threshold, c);
      break;
    case study::PsychometricShape::gumbel:
      core = fmt::format("(1 - exp(-exp({:.9g}*(x - {:.9g}) + {:.9g})))", f.slope, f.threshold, c);
      break;
    case study::PsychometricShape::weibull:
      core = fmt::format("(x > 0 ? 1 - exp(-{:.9g}*(x/{:.9g})**{:.9g}) : 0)", c, f.threshold, f.slope);
      break;
  }
  return fmt::format("{:.9g} + {:.9g}*{}", m.guess, 1 - m.guess - f.lapse, core);
}

//! The conditions with a fit, as the pool has them.
std::vector<const study::ConditionSummary*> fitted(const study::StudySummary& s) {
  std::vector<const study::ConditionSummary*> out;
  for (const study::ConditionSummary& c : s.conditions)
    if (c.fit && !c.levels.empty()) out.push_back(&c);
  return out;
}

//! One more curve of a gnuplot `plot` command: block `block` of `dat`, drawn as `how`.
void add_curve(std::string& plot, int block, const std::string& dat, const std::string& how) {
  plot += (block ? ", \\\n     " : "") + ("'" + dat + "' index " + std::to_string(block) + " " + how);
}

const char* kHeader =
    "set terminal pngcairo size 720,450 font 'DejaVu Sans,10' noenhanced\n"
    "set grid\nset key outside right top noenhanced\n";

//! NAME.dat and NAME.gp in `dir`: the script draws NAME.png from the data, in the common
//! terminal and style, with the plot's own `settings` and `plot` command (an empty plot when
//! it has no curve).
void write_plot(const std::filesystem::path& dir, const std::string& name, const std::ostringstream& dat,
                const std::ostringstream& settings, const std::string& plot, int curves) {
  write_file(dir / (name + ".dat"), dat.str());
  write_file(dir / (name + ".gp"), std::string(kHeader) + "set output '" + name + ".png'\n" + settings.str() +
                                       (curves ? plot : "plot 0 notitle") + "\n");
}

void psychometric_plot(const StudyReport& r, const std::filesystem::path& dir) {
  std::ostringstream dat, gp;
  dat << "# per condition (blocks): difference_pct proportion_correct trials\n";
  int max_trials = 1;
  double x_max = 0;
  for (const study::ConditionSummary* c : fitted(r.pooled))
    for (const study::PsychometricLevel& l : c->levels) max_trials = std::max(max_trials, l.trials), x_max = std::max(x_max, l.x);
  gp << "set title 'Pooled psychometric functions (2AFC); points sized by trials, bars: 95 % intervals'\n"
     << "set xlabel 'difference in B (%)'\nset ylabel 'proportion correct'\nset yrange [0.3:1.05]\n"
     << "set xrange [" << 0 << ":" << x_max * 1.05 + 1 << "]\n"
     << fmt::format("set arrow from graph 0, first {0:g} to graph 1, first {0:g} nohead dt 2 lc rgb '#888888'\n",
                    r.pooled.fit.model.criterion);
  std::string plot = "plot ";
  int block = 0;
  for (const study::ConditionSummary* c : fitted(r.pooled)) {
    for (const study::PsychometricLevel& l : c->levels)
      dat << l.x << ' ' << static_cast<double>(l.correct) / l.trials << ' ' << l.trials << '\n';
    dat << "\n\n";
    const int colour = block + 1;
    const std::string size = fmt::format("(0.6 + 2.4 * sqrt($3 / {}.0))", max_trials);
    add_curve(plot, block, "psychometric.dat",
              "using 1:2:" + std::string(size) + " with points pt 7 ps variable lc " + std::to_string(colour) +
                  " title '" + c->condition + "'");
    const study::PsychometricFit& f = *c->fit;
    if (f.has_threshold()) {  // a maximum on the search's edge is no curve to show
      plot += ", \\\n     " + gnuplot_curve(r.pooled.fit, f) + " with lines lc " + std::to_string(colour) + " notitle";
      if (c->intervals && c->intervals->ok) {
        const double at = study::psychometric_p(r.pooled.fit.model, {f.threshold, f.slope, f.lapse}, f.threshold);
        const std::string bar =
            fmt::format("'+' using ({:.9g}):({:.9g}):({:.9g}):({:.9g}) every ::0::0 with xerrorbars lc {} pt 1 notitle",
                        f.threshold, at, c->intervals->threshold.lo, c->intervals->threshold.hi, colour);
        plot += ", \\\n     " + std::string(bar);
      }
    }
    ++block;
  }
  write_plot(dir, "psychometric", dat, gp, plot, block);
}

//! False (nothing written) with no participant of one's own (only visitors' sessions).
bool thresholds_plot(const StudyReport& r, const std::filesystem::path& dir) {
  if (r.participants.empty()) return false;
  std::ostringstream dat, gp;
  dat << "# per condition (blocks): participant_index threshold_pct ci_lo ci_hi participant\n";
  std::vector<std::string> conditions;
  for (const study::ConditionSummary* c : fitted(r.pooled)) conditions.push_back(c->condition);
  gp << "set title \"Each participant's threshold with its 95 % interval\"\n"
     << fmt::format("set ylabel 'threshold: difference in B (%) at {:g} % correct'\nset xrange [0.5:",
                    r.pooled.fit.model.criterion * 100)
     << static_cast<double>(r.participants.size()) + 0.5 << "]\nset xtics (";
  for (std::size_t i = 0; i < r.participants.size(); ++i)
    gp << (i ? ", " : "") << "'" << r.participants[i].first << "' " << i + 1;
  gp << ") rotate by -45\n";
  std::string plot = "plot ";
  int block = 0;
  const double spread = 0.6 / static_cast<double>(std::max<std::size_t>(1, conditions.size()));
  for (std::size_t k = 0; k < conditions.size(); ++k) {
    int points = 0;
    for (std::size_t i = 0; i < r.participants.size(); ++i)
      for (const study::ConditionSummary& c : r.participants[i].second.conditions) {
        // A maximum on the search's edge is no threshold to plot (the summary says why).
        if (c.condition != conditions[k] || !c.fit || !c.fit->has_threshold()) continue;
        const bool ci = c.intervals && c.intervals->ok;
        const double x = static_cast<double>(i + 1) - 0.3 + spread * (static_cast<double>(k) + 0.5);
        dat << x << ' ' << c.fit->threshold << ' ' << (ci ? c.intervals->threshold.lo : c.fit->threshold) << ' '
            << (ci ? c.intervals->threshold.hi : c.fit->threshold) << ' ' << r.participants[i].first << '\n';
        ++points;
      }
    if (points == 0) continue;  // no participant has a threshold here: no empty block for gnuplot to warn of
    dat << "\n\n";
    add_curve(plot, block, "thresholds.dat",
              "using 1:2:3:4 with yerrorbars pt 7 lc " + std::to_string(k + 1) + " title '" + conditions[k] + "'");
    ++block;
  }
  write_plot(dir, "thresholds", dat, gp, plot, block);
  return true;
}

void response_time_plot(const StudyReport& r, const std::filesystem::path& dir) {
  std::ostringstream dat, gp;
  dat << "# per condition (blocks): bin_centre_ms trials (" << kRtBinMs << " ms bins)\n";
  gp << "set title 'Response times per condition (" << kRtBinMs << " ms bins)'\n"
     << "set xlabel 'response time (ms)'\nset ylabel 'trials'\n";
  std::string plot = "plot ";
  int block = 0;
  for (const study::ConditionSummary& c : r.pooled.conditions) {
    std::map<long, int> bins;
    for (double ms : c.response_ms)
      if (std::isfinite(ms)) ++bins[static_cast<long>(std::floor(ms / kRtBinMs))];
    if (bins.empty()) continue;
    for (long b = bins.begin()->first - 1; b <= bins.rbegin()->first + 1; ++b)
      dat << (static_cast<double>(b) + 0.5) * kRtBinMs << ' ' << (bins.count(b) ? bins[b] : 0) << '\n';
    dat << "\n\n";
    add_curve(plot, block, "response_times.dat",
              "using 1:2 with histeps lw 2 lc " + std::to_string(block + 1) + " title '" + c.condition + "'");
    ++block;
  }
  write_plot(dir, "response_times", dat, gp, plot, block);
}

//! The adaptive tracks: each track's tested difference against its trial, per condition.
bool tracks_plot(const StudyReport& r, const std::filesystem::path& dir) {
  std::ostringstream dat, gp;
  dat << "# per condition (blocks), per track (separated by a blank line): track_trial difference_pct\n";
  gp << "set title 'Adaptive tracks: the difference each trial tested'\n"
     << "set xlabel \"trial in the condition's track\"\nset ylabel 'difference in B (%)'\n";
  std::string plot = "plot ";
  int block = 0;
  for (const study::ConditionSummary& c : r.pooled.conditions) {
    if (c.tracks.empty()) continue;
    for (const std::vector<double>& track : c.tracks) {
      for (std::size_t i = 0; i < track.size(); ++i) dat << i + 1 << ' ' << track[i] << '\n';
      dat << '\n';
    }
    dat << '\n';
    add_curve(plot, block, "tracks.dat",
              "using 1:2 with steps lw 1.5 lc " + std::to_string(block + 1) + " title '" + c.condition + " (" +
                  c.procedure + ")'");
    ++block;
  }
  if (block == 0) return false;
  write_plot(dir, "tracks", dat, gp, plot, block);
  return true;
}

constexpr const char* kPlots[] = {"psychometric", "thresholds", "response_times", "tracks"};

}  // namespace

std::vector<std::string> write_study_plots(const StudyReport& report, const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw FileError(dir.string(), 0, 0, "cannot make the folder: " + ec.message());
  psychometric_plot(report, dir);
  const bool thresholds = thresholds_plot(report, dir);
  response_time_plot(report, dir);
  const bool tracks = tracks_plot(report, dir);
  std::vector<std::string> lines;
  if (!have_gnuplot()) {
    lines.push_back("study summary: gnuplot not found: plots skipped (apt-get install gnuplot-nox); their .dat and "
                    ".gp written to " + dir.string());
    return lines;
  }
  for (const char* p : kPlots) {
    if (std::string_view(p) == "tracks" && !tracks) continue;          // no adaptive rows
    if (std::string_view(p) == "thresholds" && !thresholds) continue;  // visitors only
    const std::string script = std::string(p) + ".gp";
    lines.push_back(run_gnuplot(dir, script) ? "wrote " + (dir / (std::string(p) + ".png")).string()
                                             : "study summary: gnuplot failed on " + (dir / script).string());
  }
  return lines;
}

void write_study_report(const StudyReport& r, const std::filesystem::path& file,
                        const std::filesystem::path& plots_dir) {
  std::ostringstream md;
  md << "# Study summary\n\n"
     << r.files.size() << " results file" << (r.files.size() == 1 ? "" : "s") << ", " << r.pooled.rows << " trials, "
     << r.pooled.participants.size() << " participant" << (r.pooled.participants.size() == 1 ? "" : "s") << ".";
  if (r.pooled.simulated_rows)
    md << " " << r.pooled.simulated_rows << " of the trials were answered by the simulated observer.";
  md << "\n\nMade by `mallet study summary`. The fits are maximum likelihood of\n"
     << study::fit_description(r.pooled.fit) << ";\nthe threshold is the difference answered correctly "
     << r.pooled.fit.model.criterion * 100 << " % of the time (without lapses). A maximum on the search's edge is "
     << "not an estimate: it prints \"-\" and says why.";
  if (r.resamples > 0)
    md << " The 95 % intervals are from the parametric bootstrap (" << r.resamples
       << " resamples, bias-corrected percentiles, seed " << r.seed << ").";
  md << "\n\n## Pooled over the participants\n\n```\n" << r.pooled_text << "```\n\n";
  if (!plots_dir.empty()) {
    const std::filesystem::path rel = std::filesystem::relative(plots_dir, file.parent_path().empty()
                                                                               ? std::filesystem::path(".")
                                                                               : file.parent_path());
    md << "![Pooled psychometric functions](" << (rel / "psychometric.png").generic_string() << ")\n\n";
    md << "![Response times](" << (rel / "response_times.png").generic_string() << ")\n\n";
    bool adaptive = false;
    for (const study::ConditionSummary& c : r.pooled.conditions) adaptive = adaptive || !c.tracks.empty();
    if (adaptive) md << "![Adaptive tracks](" << (rel / "tracks.png").generic_string() << ")\n\n";
    if (!r.participants_text.empty())
      md << "## Each participant\n\n![Thresholds](" << (rel / "thresholds.png").generic_string() << ")\n\n";
  }
  if (!r.participants_text.empty()) {
    if (plots_dir.empty()) md << "## Each participant\n\n";
    md << "```\n" << r.participants_text << "```\n";
  }
  if (const std::string group = study::format_group(r.group); !group.empty())
    md << "\n## The group\n\nFrom each participant's own fit, beside the pooled fit above:\n\n```\n" << group
       << "```\n";
  md << "\nFiles read:\n\n";
  for (const std::filesystem::path& f : r.files) md << "- `" << f.string() << "`\n";
  write_file(file, md.str());
}

void write_fit_table(const StudyReport& r, const std::filesystem::path& file) {
  try {
    write_file_atomically(file, study::fit_table_csv(r.pooled, r.participants));
  } catch (const std::runtime_error& e) {
    throw FileError(file.string(), 0, 0, e.what());
  }
}

namespace {

nlohmann::ordered_json number_or_null(bool has, double v) { return has ? nlohmann::ordered_json(v) : nullptr; }

void json_fits(nlohmann::ordered_json& fits, const study::StudySummary& s, const std::string& who) {
  for (const study::ConditionSummary& c : s.conditions) {
    if (!c.fit) continue;
    const study::PsychometricFit& f = *c.fit;
    const bool ci = c.intervals && c.intervals->ok && f.has_threshold();
    nlohmann::ordered_json j;
    j["condition"] = c.condition;
    j["participant"] = who;
    j["levels"] = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < c.levels.size(); ++i)
      j["levels"].push_back({{"x", c.levels[i].x},
                             {"trials", c.levels[i].trials},
                             {"correct", c.levels[i].correct},
                             {"residual", number_or_null(i < f.residuals.size(), i < f.residuals.size() ? f.residuals[i] : 0)}});
    j["threshold_pct"] = number_or_null(f.has_threshold(), f.threshold);
    j["threshold_lo"] = number_or_null(ci && !c.intervals->threshold.lo_open, ci ? c.intervals->threshold.lo : 0);
    j["threshold_hi"] = number_or_null(ci && !c.intervals->threshold.hi_open, ci ? c.intervals->threshold.hi : 0);
    j["slope"] = number_or_null(f.has_slope(), f.slope);
    const bool slope_ci = ci && f.has_slope();
    j["slope_lo"] = number_or_null(slope_ci && !c.intervals->slope.lo_open, slope_ci ? c.intervals->slope.lo : 0);
    j["slope_hi"] = number_or_null(slope_ci && !c.intervals->slope.hi_open, slope_ci ? c.intervals->slope.hi : 0);
    j["slope_at_least"] = number_or_null(f.step && f.has_threshold(), f.slope_at_least);
    j["lapse"] = number_or_null(f.ok, f.lapse);
    const bool lapse_ci = ci && s.fit.fit_lapse;
    j["lapse_lo"] = number_or_null(lapse_ci, lapse_ci ? c.intervals->lapse.lo : 0);
    j["lapse_hi"] = number_or_null(lapse_ci, lapse_ci ? c.intervals->lapse.hi : 0);
    j["log_likelihood"] = number_or_null(f.ok, f.log_likelihood);
    j["deviance"] = number_or_null(f.ok, f.deviance);
    j["deviance_p"] = number_or_null(ci, ci ? c.intervals->deviance_p : 0);
    j["resamples"] = ci ? c.intervals->resamples : 0;
    j["flags"] = nlohmann::ordered_json::array();
    for (const char* name : study::fit_flags(f)) j["flags"].push_back(name);
    j["note"] = f.reason;
    fits.push_back(std::move(j));
  }
}

}  // namespace

void write_fit_json(const StudyReport& r, const std::filesystem::path& file) {
  const study::FitOptions& o = r.pooled.fit;
  nlohmann::ordered_json j;
  j["fit"] = {{"shape", name_in(study::kPsychometricShapeNames, o.model.shape)},
              {"criterion", o.model.criterion},
              {"guess", o.model.guess},
              {"lapse", o.fit_lapse ? nlohmann::ordered_json("fit") : nlohmann::ordered_json(o.lapse)},
              {"lapse_limit", o.lapse_limit},
              {"formula", study::fit_description(o)}};
  j["resamples"] = r.resamples;
  j["seed"] = r.seed;
  j["fits"] = nlohmann::ordered_json::array();
  json_fits(j["fits"], r.pooled, "pooled");
  for (const auto& [who, s] : r.participants) json_fits(j["fits"], s, who);
  j["group"] = nlohmann::ordered_json::array();
  for (const study::GroupThresholds& g : r.group)
    j["group"].push_back({{"condition", g.condition},
                          {"participants", g.participants},
                          {"estimated", g.estimated},
                          {"mean_pct", number_or_null(g.estimated > 0, g.mean)},
                          {"se_pct", number_or_null(g.estimated > 1, g.se)},
                          {"median_pct", number_or_null(g.estimated > 0, g.median)}});
  try {
    write_file_atomically(file, j.dump(2) + "\n");
  } catch (const std::runtime_error& e) {
    throw FileError(file.string(), 0, 0, e.what());
  }
}

}  // namespace mallet::app
