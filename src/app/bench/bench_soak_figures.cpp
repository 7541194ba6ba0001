#include "app/bench/bench_soak_figures.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include <fmt/format.h>

namespace mallet::app::soak {

std::optional<ProcessSample> read_process(pid_t pid) {
  const std::filesystem::path dir = "/proc/" + std::to_string(pid);
  std::ifstream status(dir / "status");
  if (!status) return std::nullopt;
  ProcessSample s;
  bool rss = false, threads = false;
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) {
      s.rss_bytes = std::strtoull(line.c_str() + 6, nullptr, 10) * 1024;  // "VmRSS:   1234 kB"
      rss = true;
    } else if (line.rfind("Threads:", 0) == 0) {
      s.threads = std::atoi(line.c_str() + 8);
      threads = true;
    }
  }
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir / "fd", ec), end; !ec && it != end; it.increment(ec)) ++s.fds;
  if (ec || !rss || !threads) return std::nullopt;
  // /proc/PID/stat: "pid (comm) state ..." — utime and stime are the 14th and 15th fields,
  // the 12th and 13th after the ")" that ends a comm which may itself hold spaces.
  std::ifstream stat(dir / "stat");
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  const std::size_t close = text.rfind(')');
  if (close == std::string::npos) return std::nullopt;
  std::istringstream fields(text.substr(close + 1));
  std::string field;
  unsigned long long utime = 0, stime = 0;
  for (int i = 1; i <= 13 && fields >> field; ++i) {
    if (i == 12) utime = std::strtoull(field.c_str(), nullptr, 10);
    if (i == 13) stime = std::strtoull(field.c_str(), nullptr, 10);
  }
  if (!fields) return std::nullopt;
  const long ticks = sysconf(_SC_CLK_TCK);
  s.cpu_ns = static_cast<std::int64_t>((utime + stime) * (1'000'000'000ULL / static_cast<unsigned long long>(ticks)));
  return s;
}

namespace {

//! "name{labels} value" → (name, labels, value); nothing for comments and blank lines.
struct Sample {
  std::string_view name, labels;
  double value = 0;
};
std::optional<Sample> parse_sample(std::string_view line) {
  if (line.empty() || line[0] == '#') return std::nullopt;
  Sample s;
  const std::size_t brace = line.find('{'), space = line.find(' ');
  if (space == std::string_view::npos) return std::nullopt;
  std::size_t value_at = space + 1;
  if (brace != std::string_view::npos && brace < space) {
    const std::size_t close = line.find("} ", brace);
    if (close == std::string_view::npos) return std::nullopt;
    s.name = line.substr(0, brace);
    s.labels = line.substr(brace + 1, close - brace - 1);
    value_at = close + 2;
  } else {
    s.name = line.substr(0, space);
  }
  const std::string value(line.substr(value_at));
  char* end = nullptr;
  s.value = std::strtod(value.c_str(), &end);
  if (end == value.c_str()) return std::nullopt;
  return s;
}

}  // namespace

std::optional<KioskFigures> parse_kiosk_figures(std::string_view text) {
  KioskFigures f;
  bool frames = false, strikes = false, vulkan = false;
  while (!text.empty()) {
    const std::size_t eol = text.find('\n');
    const std::string_view line = text.substr(0, eol);
    text.remove_prefix(eol == std::string_view::npos ? text.size() : eol + 1);
    const std::optional<Sample> s = parse_sample(line);
    if (!s) continue;
    if (s->name == "mallet_frame_seconds_bucket") {
      const std::size_t at = s->labels.find("le=\"");
      if (at == std::string_view::npos) return std::nullopt;
      const std::string le(s->labels.substr(at + 4, s->labels.find('"', at + 4) - at - 4));
      const double bound = le == "+Inf" ? std::numeric_limits<double>::infinity() : std::strtod(le.c_str(), nullptr);
      f.frame_seconds.emplace_back(bound, static_cast<std::uint64_t>(s->value));
    } else if (s->name == "mallet_frames_total") {
      f.frames = static_cast<std::uint64_t>(s->value);
      frames = true;
    } else if (s->name == "mallet_strikes_total") {
      f.strikes += static_cast<std::uint64_t>(s->value);
      strikes = true;
    } else if (s->name == "mallet_vulkan_device_memory_bytes") {
      f.vulkan_bytes = s->value;
      vulkan = true;
    }
  }
  if (!frames || !strikes || !vulkan || f.frame_seconds.empty() || !std::isinf(f.frame_seconds.back().first))
    return std::nullopt;
  return f;
}

double histogram_quantile(double q, const Buckets& now, const Buckets& before) {
  std::vector<double> counts(now.size());
  for (std::size_t i = 0; i < now.size(); ++i) {
    const std::uint64_t was = i < before.size() && before[i].first == now[i].first ? before[i].second : 0;
    counts[i] = static_cast<double>(now[i].second >= was ? now[i].second - was : 0);
  }
  if (counts.empty() || counts.back() <= 0) return std::numeric_limits<double>::quiet_NaN();
  const double rank = q * counts.back();
  std::size_t b = 0;
  while (b + 1 < counts.size() && counts[b] < rank) ++b;
  if (std::isinf(now[b].first)) return b > 0 ? now[b - 1].first : 0.0;
  const double lower = b > 0 ? now[b - 1].first : 0.0;
  const double below = b > 0 ? counts[b - 1] : 0.0;
  const double in_bucket = counts[b] - below;
  if (in_bucket <= 0) return now[b].first;
  return lower + (now[b].first - lower) * (rank - below) / in_bucket;
}

std::string csv_header() {
  return "hours,rss_mib,fds,threads,vulkan_mib,strokes,strikes,actuator_found,note_found,lost_strikes,frames,"
         "frame_p99_ms,visitor,jack_xruns";
}

std::string csv_row(const Minute& m) {
  return fmt::format("{:.4f},{:.2f},{},{},{:.2f},{},{},{},{},{},{},{:.2f},{},{}", m.hours, m.rss_mib,
                     m.fds, m.threads, m.vulkan_mib, m.strokes, m.strikes, m.actuator, m.note, m.lost,
                     m.frames, m.frame_p99_ms, m.state.c_str(), m.xruns);
}

double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = std::min(x.size(), y.size());
  if (n < 2) return 0;
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) mx += x[i], my += y[i];
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < n; ++i) sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
  return sxx > 0 ? sxy / sxx : 0;
}

namespace {

struct Column {
  const char* name;
  const char* unit;
  double (*of)(const Minute&);
  double min_span;  //!< the plot's y range is at least this wide, so that noise looks like noise
};
const Column kColumns[] = {
    {"rss_mib", "MiB", [](const Minute& m) { return m.rss_mib; }, 8.0},
    {"fds", "descriptors", [](const Minute& m) { return static_cast<double>(m.fds); }, 4.0},
    {"threads", "threads", [](const Minute& m) { return static_cast<double>(m.threads); }, 4.0},
    {"vulkan_mib", "MiB", [](const Minute& m) { return m.vulkan_mib; }, 4.0},
    {"lost_strikes", "strikes per row", [](const Minute& m) { return static_cast<double>(m.lost); }, 4.0},
    {"frame_p99_ms", "ms", [](const Minute& m) { return m.frame_p99_ms; }, 10.0},
};

}  // namespace

std::vector<Growth> growth_per_hour(const std::vector<Minute>& rows) {
  std::vector<double> x;
  for (const Minute& m : rows) x.push_back(m.hours);
  std::vector<Growth> out;
  for (const Column& c : kColumns) {
    std::vector<double> y;
    for (const Minute& m : rows) y.push_back(c.of(m));
    out.push_back({c.name, c.unit, slope(x, y)});
  }
  return out;
}

std::string svg_plot(const std::vector<Minute>& rows) {
  constexpr int kPanelW = 460, kPanelH = 200, kCols = 2, kMargin = 50;
  constexpr int kRows = static_cast<int>(std::size(kColumns) + kCols - 1) / kCols;
  const int width = kCols * (kPanelW + kMargin) + kMargin, height = kRows * (kPanelH + kMargin) + kMargin;
  const std::vector<Growth> growth = growth_per_hour(rows);
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  double x_max = 0;
  for (const Minute& m : rows) x_max = std::max(x_max, m.hours);
  if (x_max <= 0) x_max = 1;
  for (std::size_t k = 0; k < std::size(kColumns); ++k) {
    const Column& c = kColumns[k];
    const int left = kMargin + static_cast<int>(k % kCols) * (kPanelW + kMargin);
    const int top = kMargin + static_cast<int>(k / kCols) * (kPanelH + kMargin);
    double lo = 0, hi = 0;
    bool any = false;
    for (const Minute& m : rows) {
      const double v = c.of(m);
      if (!std::isfinite(v)) continue;
      lo = any ? std::min(lo, v) : v;
      hi = any ? std::max(hi, v) : v;
      any = true;
    }
    if (hi - lo < c.min_span) {
      const double mid = 0.5 * (hi + lo);
      lo = mid - 0.5 * c.min_span, hi = mid + 0.5 * c.min_span;
    } else {
      const double pad = 0.1 * (hi - lo);
      lo -= pad, hi += pad;
    }
    svg << "<text x=\"" << left << "\" y=\"" << top - 8 << "\" font-weight=\"bold\">"
        << fmt::format("{}: {:+.3g} {} per hour", c.name, growth[k].per_hour, c.unit) << "</text>\n";
    svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << kPanelW << "\" height=\"" << kPanelH
        << "\" fill=\"none\" stroke=\"#888\"/>\n";
    svg << "<text x=\"" << left + 4 << "\" y=\"" << top + 14 << "\" fill=\"#555\">" << fmt::format("{:.4g}", hi)
        << "</text>\n";
    svg << "<text x=\"" << left + 4 << "\" y=\"" << top + kPanelH - 4 << "\" fill=\"#555\">"
        << fmt::format("{:.4g}", lo) << "</text>\n";
    svg << "<text x=\"" << left << "\" y=\"" << top + kPanelH + 14 << "\" fill=\"#555\">0 h</text>\n";
    svg << "<text x=\"" << left + kPanelW - 40 << "\" y=\"" << top + kPanelH + 14 << "\" fill=\"#555\">"
        << fmt::format("{:.2f} h", x_max) << "</text>\n";
    svg << "<polyline fill=\"none\" stroke=\"#1f5fa8\" stroke-width=\"1.5\" points=\"";
    for (const Minute& m : rows) {
      const double v = c.of(m);
      if (!std::isfinite(v)) continue;
      svg << fmt::format("{:.1f},{:.1f} ", left + m.hours / x_max * kPanelW, top + (hi - v) / (hi - lo) * kPanelH);
    }
    svg << "\"/>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace mallet::app::soak
