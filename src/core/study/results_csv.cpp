#include "core/study/results_csv.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

#include <fmt/format.h>

#include "core/csv_file.hpp"
#include "core/file_error.hpp"

namespace mallet::study {

namespace {

//! `v` with `decimals` digits after the point (fixed) or significant digits (`general`), or
//! empty for NaN (a column the row does not have).
std::string g(double v, int digits, bool general = false) {
  if (std::isnan(v)) return "";
  return general ? fmt::format("{:.{}g}", v, digits) : fmt::format("{:.{}f}", v, digits);
}

//! `v` in full: the shortest decimal that reads back as the same double (an estimate is
//! analysed, not read; 4 digits would hide a track's last changes), or empty for NaN.
std::string exact(double v) { return std::isnan(v) ? "" : fmt::format("{}", v); }

struct Columns {
  static constexpr int kMissing = -1;
  int participant = kMissing, trial = kMissing, condition = kMissing, stimuli = kMissing, answer = kMissing,
      correct = kMissing, response_time_ms = kMissing, protocol = kMissing, task = kMissing,
      difference_pct = kMissing, source = kMissing, session = kMissing, visual_peak_m = kMissing,
      actuator_peak = kMissing, actuator_onset_ms = kMissing, picture_onset_ms = kMissing, procedure = kMissing,
      track_trial = kMissing, reversals = kMissing, estimate_pct = kMissing, estimate_sd_pct = kMissing,
      planned_trials = kMissing, estimate_mode_pct = kMissing, language = kMissing, actuator_eq_hash = kMissing,
      actuator_eq_utc = kMissing;
};

Columns find_columns(const std::vector<std::string>& header, const std::string& file) {
  Columns c;
  const std::pair<const char*, int*> names[] = {
      {"participant", &c.participant}, {"trial", &c.trial},       {"condition", &c.condition},
      {"stimuli", &c.stimuli},         {"answer", &c.answer},     {"correct", &c.correct},
      {"response_time_ms", &c.response_time_ms}, {"protocol", &c.protocol}, {"task", &c.task},
      {"difference_pct", &c.difference_pct}, {"source", &c.source}, {"session", &c.session},
      {"visual_peak_m", &c.visual_peak_m}, {"actuator_peak", &c.actuator_peak},
      {"actuator_onset_ms", &c.actuator_onset_ms}, {"picture_onset_ms", &c.picture_onset_ms},
      {"procedure", &c.procedure}, {"track_trial", &c.track_trial}, {"reversals", &c.reversals},
      {"estimate_pct", &c.estimate_pct}, {"estimate_sd_pct", &c.estimate_sd_pct},
      {"planned_trials", &c.planned_trials}, {"estimate_mode_pct", &c.estimate_mode_pct},
      {"language", &c.language}, {"actuator_eq_hash", &c.actuator_eq_hash}, {"actuator_eq_utc", &c.actuator_eq_utc}};
  for (const auto& [name, index] : names)
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) *index = static_cast<int>(i);
  for (int i = 0; i < 7; ++i)
    if (*names[i].second == Columns::kMissing)
      throw FileError(file, 1, 0, std::string("missing column \"") + names[i].first + "\" (expected a header " +
                                      "starting participant,trial,condition,stimuli,answer,correct,response_time_ms)");
  return c;
}

double number(const std::string& s, const std::string& file, std::uint32_t line, const char* column,
              bool empty_is_nan) {
  if (s.empty() && empty_is_nan) return std::nan("");
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v))
    throw FileError(file, line, 0, std::string(column) + ": \"" + s + "\" is not a number");
  return v;
}

ResultRow parse_row(const std::vector<std::string>& f, const Columns& c, const std::string& file,
                    std::uint32_t line) {
  const auto field = [&](int i) -> std::string { return i == Columns::kMissing ? std::string() : f[static_cast<std::size_t>(i)]; };
  ResultRow r;
  r.participant = field(c.participant);
  const double trial = number(field(c.trial), file, line, "trial", false);
  if (trial < 1 || trial != std::floor(trial) || trial > 1e9)
    throw FileError(file, line, 0, "trial: \"" + field(c.trial) + "\" is not a trial number (1, 2, ...)");
  r.trial = static_cast<int>(trial);
  r.condition = field(c.condition);
  r.stimuli = field(c.stimuli);
  r.answer = field(c.answer);
  const std::string correct = field(c.correct);
  if (correct != "0" && correct != "1") throw FileError(file, line, 0, "correct: \"" + correct + "\" is not 0 or 1");
  r.correct = correct == "1";
  r.response_time_ms = number(field(c.response_time_ms), file, line, "response_time_ms", false);
  r.protocol = field(c.protocol);
  r.task = field(c.task);
  r.difference_pct = number(field(c.difference_pct), file, line, "difference_pct", true);
  r.source = field(c.source);
  r.session = field(c.session);
  r.visual_peak_m = number(field(c.visual_peak_m), file, line, "visual_peak_m", true);
  r.actuator_peak = number(field(c.actuator_peak), file, line, "actuator_peak", true);
  r.actuator_onset_ms = number(field(c.actuator_onset_ms), file, line, "actuator_onset_ms", true);
  r.picture_onset_ms = number(field(c.picture_onset_ms), file, line, "picture_onset_ms", true);
  r.procedure = field(c.procedure);
  if (!r.procedure.empty() && r.procedure != "constant" && r.procedure != "staircase" && r.procedure != "quest" &&
      r.procedure != "quest_plus")
    throw FileError(file, line, 0, "procedure: \"" + r.procedure + "\" is not constant, staircase, quest or quest_plus");
  const double track_trial = number(field(c.track_trial), file, line, "track_trial", true);
  const double reversals = number(field(c.reversals), file, line, "reversals", true);
  const double planned = number(field(c.planned_trials), file, line, "planned_trials", true);
  for (const auto& [v, name] : {std::pair{track_trial, "track_trial"}, std::pair{reversals, "reversals"},
                                std::pair{planned, "planned_trials"}})
    if (!std::isnan(v) && (v < 0 || v > 1e6 || v != std::floor(v)))
      throw FileError(file, line, 0, std::string(name) + ": not a count");
  r.track_trial = std::isnan(track_trial) ? 0 : static_cast<int>(track_trial);
  r.reversals = std::isnan(reversals) ? -1 : static_cast<int>(reversals);
  r.planned_trials = std::isnan(planned) ? 0 : static_cast<int>(planned);
  r.estimate_pct = number(field(c.estimate_pct), file, line, "estimate_pct", true);
  r.estimate_sd_pct = number(field(c.estimate_sd_pct), file, line, "estimate_sd_pct", true);
  r.estimate_mode_pct = number(field(c.estimate_mode_pct), file, line, "estimate_mode_pct", true);
  r.language = field(c.language);
  r.actuator_eq_hash = field(c.actuator_eq_hash);
  r.actuator_eq_utc = field(c.actuator_eq_utc);
  return r;
}

[[noreturn]] void fail_io(const std::filesystem::path& path, const std::string& what, int e) {
  throw std::runtime_error(path.string() + ": " + what + ": " + std::strerror(e));
}

}  // namespace

std::size_t results_columns(std::string_view header) {
  const std::string_view all = kResultsHeader;
  const std::string_view oldest = kResultsHeaderWithoutTiming;
  if (header.size() < oldest.size() || !all.starts_with(header) ||
      (header.size() < all.size() && all[header.size()] != ','))
    return 0;
  return static_cast<std::size_t>(std::count(header.begin(), header.end(), ',')) + 1;
}

std::string format_row(const ResultRow& r, std::size_t columns) {
  const std::string fields[kResultsColumns] = {
      r.participant, std::to_string(r.trial), r.condition, r.stimuli, r.answer, r.correct ? "1" : "0",
      g(r.response_time_ms, 3), r.protocol, r.task, g(r.difference_pct, 6, true), r.source, r.session,
      g(r.visual_peak_m, 6, true), g(r.actuator_peak, 6, true), g(r.actuator_onset_ms, 3),
      g(r.picture_onset_ms, 3), r.procedure, r.track_trial > 0 ? std::to_string(r.track_trial) : "",
      r.reversals >= 0 ? std::to_string(r.reversals) : "", exact(r.estimate_pct), exact(r.estimate_sd_pct),
      r.planned_trials > 0 ? std::to_string(r.planned_trials) : "", exact(r.estimate_mode_pct), r.language,
      r.actuator_eq_hash, r.actuator_eq_utc};
  std::string out;
  for (std::size_t i = 0; i < std::min(columns, kResultsColumns); ++i) out += (i ? "," : "") + fields[i];
  out += '\n';
  return out;
}

ResultsFile read_results(const std::filesystem::path& path) {
  ResultsFile out;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return out;
  if (std::filesystem::is_directory(path, ec)) throw FileError(path.string(), 0, 0, "is a directory, expected a CSV file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path.string(), 0, 0, "cannot open");
  out.exists = true;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const csv::Table table = csv::parse(text, path.string(), {.incomplete_last_line = true});
  for (const std::string& w : table.warnings) out.warnings.push_back(w + "; that trial will be run again");
  out.complete_bytes = table.complete_bytes;
  if (!table.has_header()) return out;
  const Columns columns = find_columns(table.header, table.file);
  out.header = table.header_text;
  out.has_header = true;
  for (const csv::Row& row : table.rows) {
    out.rows.push_back(parse_row(row.fields, columns, table.file, row.line));
    out.lines.push_back(row.line);
  }
  return out;
}

ResultsWriter::ResultsWriter(const std::filesystem::path& path, const ResultsFile& existing) : path_(path) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) fail_io(path, "cannot open for appending", errno);
  const auto keep = existing.has_header ? static_cast<off_t>(existing.complete_bytes) : 0;
  if (::ftruncate(fd_, keep) != 0) fail_io(path, "cannot cut off the incomplete last line", errno);
  if (::lseek(fd_, 0, SEEK_END) < 0) fail_io(path, "cannot seek", errno);
  if (const std::size_t columns = existing.has_header ? results_columns(existing.header) : 0; columns > 0)
    columns_ = columns;
  if (!existing.has_header) {
    write_durably(std::string(kResultsHeader) + "\n");
    // A new file: its folder entry must reach the disk too.
    const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dfd >= 0) {
      ::fsync(dfd);
      ::close(dfd);
    }
  }
}

ResultsWriter::~ResultsWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void ResultsWriter::write_durably(const std::string& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail_io(path_, "write failed", errno);
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd_) != 0) fail_io(path_, "fsync failed", errno);
}

void ResultsWriter::append(const ResultRow& row) { write_durably(format_row(row, columns_)); }

}  // namespace mallet::study
