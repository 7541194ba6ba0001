// The study summary's plots and report: see study_report.hpp.
#include "app/study/study_report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>

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
     << "set arrow from graph 0, first 0.75 to graph 1, first 0.75 nohead dt 2 lc rgb '#888888'\n";
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
    if (f.ok) {
      const std::string curve = fmt::format("0.5 + 0.5 / (1 + exp(-{:.9g} * (x - {:.9g})))", f.slope, f.threshold);
      plot += ", \\\n     " + std::string(curve) + " with lines lc " + std::to_string(colour) + " notitle";
      if (c->intervals && c->intervals->ok) {
        const std::string bar =
            fmt::format("'+' using ({:.9g}):(0.75):({:.9g}):({:.9g}) every ::0::0 with xerrorbars lc {} pt 1 notitle",
                        f.threshold, c->intervals->threshold.lo, c->intervals->threshold.hi, colour);
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
     << "set ylabel 'threshold: difference in B (%) at 75 % correct'\nset xrange [0.5:"
     << static_cast<double>(r.participants.size()) + 0.5 << "]\nset xtics (";
  for (std::size_t i = 0; i < r.participants.size(); ++i)
    gp << (i ? ", " : "") << "'" << r.participants[i].first << "' " << i + 1;
  gp << ") rotate by -45\n";
  std::string plot = "plot ";
  int block = 0;
  const double spread = 0.6 / static_cast<double>(std::max<std::size_t>(1, conditions.size()));
  for (std::size_t k = 0; k < conditions.size(); ++k) {
    for (std::size_t i = 0; i < r.participants.size(); ++i)
      for (const study::ConditionSummary& c : r.participants[i].second.conditions) {
        if (c.condition != conditions[k] || !c.fit || !c.fit->ok) continue;
        const bool ci = c.intervals && c.intervals->ok;
        const double x = static_cast<double>(i + 1) - 0.3 + spread * (static_cast<double>(k) + 0.5);
        dat << x << ' ' << c.fit->threshold << ' ' << (ci ? c.intervals->threshold.lo : c.fit->threshold) << ' '
            << (ci ? c.intervals->threshold.hi : c.fit->threshold) << ' ' << r.participants[i].first << '\n';
      }
    dat << "\n\n";
    add_curve(plot, block, "thresholds.dat",
              "using 1:2:3:4 with yerrorbars pt 7 lc " + std::to_string(block + 1) + " title '" + conditions[k] + "'");
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
        "P(correct) = 0.5 + 0.5 / (1 + exp(−slope·(x − threshold))), x the pair's difference in Eq. 1's B (%);\n"
        "the threshold is the difference answered correctly 75 % of the time.";
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
  md << "\nFiles read:\n\n";
  for (const std::filesystem::path& f : r.files) md << "- `" << f.string() << "`\n";
  write_file(file, md.str());
}

}  // namespace mallet::app
