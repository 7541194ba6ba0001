// Writing `mallet bench report`: report.md (tables, presets marked, the Pareto front),
// one whitespace-separated .dat per knob, and a PNG per knob drawn by gnuplot (Debian's
// gnuplot-nox) when it is installed; without it the data and the report are still written
// and the report says the plots were skipped.
#include <algorithm>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include <fmt/format.h>

#include "app/bench/bench_report.hpp"
#include "core/gnuplot.hpp"
#include "core/file_error.hpp"

namespace mallet::app {

void mark_front(TradeTable& table) {
  for (TradePoint& p : table.points) {
    p.front = true;
    for (const TradePoint& q : table.points)
      if (&q != &p && q.time <= p.time && q.error <= p.error && (q.time < p.time || q.error < p.error)) p.front = false;
  }
}

namespace {

std::string num(double v) {
  if (v != 0 && (std::fabs(v) < 1e-3 || std::fabs(v) >= 1e5)) return fmt::format("{:.2e}", v);
  return fmt::format("{:.3g}", v);
}

void write_plot(const TradeTable& t, const std::filesystem::path& dir) {
  {
    std::ofstream dat(dir / (t.id + ".dat"));
    dat << "# time error front preset setting\n";
    for (const TradePoint& p : t.points)
      dat << p.time << ' ' << p.error << ' ' << (p.front ? 1 : 0) << " \"" << (p.presets.empty() ? "-" : p.presets)
          << "\" \"" << p.setting << "\"\n";
    std::vector<TradePoint> front;
    for (const TradePoint& p : t.points)
      if (p.front) front.push_back(p);
    std::sort(front.begin(), front.end(), [](const TradePoint& a, const TradePoint& b) { return a.time < b.time; });
    std::ofstream f(dir / (t.id + ".front.dat"));
    for (const TradePoint& p : front) f << p.time << ' ' << p.error << '\n';
  }
  std::ofstream gp(dir / (t.id + ".gp"));
  gp << "set terminal pngcairo size 640,400 font 'DejaVu Sans,9' noenhanced\n"
     << "set output '" << t.id << ".png'\n"
     << "set title \"" << t.title << "\" noenhanced\n"
     << "set xlabel \"" << t.time_label << " (faster ←)\" noenhanced\n"
     << "set ylabel \"" << t.error_label << " (more exact ↓)\" noenhanced\n"
     << "set key top right noenhanced\nset grid\nset offsets graph 0.08, graph 0.25, graph 0.1, graph 0.1\n"
     << (t.log_error ? "set logscale y\nset format y '%.0e'\n" : "") << (t.log_time ? "set logscale x\n" : "")
     << "plot '" << t.id << ".front.dat' using 1:2 with lines lw 2 lc rgb '#999999' title 'Pareto front', \\\n"
     << "     '" << t.id << ".dat' using 1:2 with points pt 7 ps 1.2 lc rgb '#1f77b4' title 'settings', \\\n"
     << "     '' using 1:2:5 with labels offset 0,-1 font ',7' notitle, \\\n"
     << "     '' using 1:(strcol(4) eq \"-\" ? 1/0 : $2):4 with labels offset 0,1.2 tc rgb '#d62728' font ',8' notitle, \\\n"
     << "     '' using 1:(strcol(4) eq \"-\" ? 1/0 : $2) with points pt 6 ps 2.5 lc rgb '#d62728' title 'quality presets'\n";
}

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

std::string markdown(const TextTable& t) {
  std::ostringstream md;
  md << "## " << t.title << "\n\n|";
  for (const std::string& h : t.header) md << ' ' << escape(h) << " |";
  md << "\n|";
  for (std::size_t i = 0; i < t.header.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& row : t.rows) {
    md << "|";
    for (const std::string& c : row) md << ' ' << escape(c) << " |";
    md << "\n";
  }
  if (!t.note.empty()) md << "\n" << t.note << "\n";
  md << "\n";
  return md.str();
}

std::vector<std::string> write_report(const ReportSections& in, const ReportOptions& o) {
  ReportSections s = in;
  for (TradeTable& t : s.trades) mark_front(t);
  std::filesystem::create_directories(o.out);
  const bool plots = have_gnuplot();
  std::ostringstream md;
  md << "# mallet bench report\n\n"
     << "Made by `mallet bench report" << (o.quick ? " --quick" : "") << " --out " << o.out.string()
     << "` in one process run on one machine. Times are medians on this machine (noisy when it is shared: "
        "read the ratios); errors are against exact references (long double, supersampled images, scripted strikes). "
        "Presets: `quality = \"fast\" | \"balanced\" | \"exact\"` (src/core/quality.hpp). ★ = on the Pareto front "
        "(nothing is both faster and more exact).\n\n";
  if (o.quick) md << "**--quick: tiny workloads; the numbers below only show that every part runs.**\n\n";
  for (const TradeTable& t : s.trades) {
    md << "## " << t.title << "\n\n";
    if (plots) md << "![" << t.id << "](" << t.id << ".png)\n\n";
    md << "| setting | " << t.time_label << " | " << t.error_label << " | front | presets | note |\n"
       << "|---|---|---|---|---|---|\n";
    for (const TradePoint& p : t.points)
      md << "| " << escape(p.setting) << " | " << num(p.time) << " | " << num(p.error) << " | " << (p.front ? "★" : "")
         << " | " << (p.presets.empty() ? "" : "**" + p.presets + "**") << " | " << escape(p.note) << " |\n";
    if (!t.note.empty()) md << "\n" << t.note << "\n";
    md << "\n";
    write_plot(t, o.out);
  }
  for (const TextTable& t : s.tables) md << markdown(t);
  std::vector<std::string> lines;
  if (!plots) {
    md << "## Plots skipped\n\ngnuplot is not installed (`apt-get install gnuplot-nox`); the data is in the .dat files "
          "and each .gp script draws its plot.\n\n";
    lines.push_back("bench report: gnuplot not found: plots skipped (apt-get install gnuplot-nox); data and .gp scripts written");
  }
  if (!s.skipped.empty()) {
    md << "## Not measured here\n\n";
    for (const std::string& k : s.skipped) md << "- " << k << "\n";
    md << "\n";
  }
  {
    std::ofstream f(o.out / "report.md");
    f << md.str();
    if (!f) throw FileError((o.out / "report.md").string(), 0, 0, "cannot write");
  }
  if (plots)
    for (const TradeTable& t : s.trades) {
      if (!run_gnuplot(o.out, t.id + ".gp")) lines.push_back("bench report: gnuplot failed on " + t.id + ".gp");
    }
  lines.push_back("bench report: wrote " + (o.out / "report.md").string() + (plots ? " and the plots" : ""));
  return lines;
}

}  // namespace mallet::app
