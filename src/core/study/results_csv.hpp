#pragma once
// The study's results file: one CSV row per answered trial, appended and made durable
// (one write(2) of the whole row, then fsync) before the next trial starts, so a crash
// or a power cut loses at most the trial in progress. Columns:
//   participant,trial,condition,stimuli,answer,correct,response_time_ms   (the required ones)
//   ,protocol,task,difference_pct,source,session,visual_peak_m,actuator_peak  (extras)
//   ,actuator_onset_ms,picture_onset_ms                                      (timing)
//   ,procedure,track_trial,reversals,estimate_pct,estimate_sd_pct            (adaptive)
//   ,planned_trials                                                          (sessions)
//   ,estimate_mode_pct                                                       (QUEST's mode; QUEST+: its joint mode's threshold)
//   ,language                                                                (the words shown: en, de, fr, ja)
//   ,actuator_eq_hash,actuator_eq_utc                                        (the actuator calibration in force)
// `correct` is 1 or 0; `difference_pct` the 2AFC pair's difference in B (empty for
// name_material); `source` who answered (file, simulated); `session` when that run began
// (UTC); the two peaks are what the condition really presented (measured on the rendered
// output): the largest visual displacement in metres and the largest actuator sample; the
// two onsets when the strike route had the cues reach the participant, in ms after the
// tap's contact (the latest of the trial's taps): the actuator and the note (heard), the
// first frame that shows the bounce (shown). `procedure` is constant, staircase, quest or
// quest_plus; for an adaptive one, after the trial's answer: the trial's number in its
// condition's track, the staircase's reversals, the estimate (the staircase's mean level at
// its last reversals once it has them; QUEST's posterior mean; QUEST+'s of the threshold)
// and its posterior SD (empty where they do not apply), written in full (the shortest
// decimal that reads back as the same double). `planned_trials` is how many trials the run that wrote the row meant to give
// (the schedule's, an adaptive protocol's bound, a visitor's few): a participant with fewer
// rows stopped early (a visitor who walked away). `estimate_mode_pct` is QUEST's posterior
// mode after the answer (the grid's most probable threshold; QUEST+: the threshold of its
// joint mode; in full; empty for the other procedures). `language` is the language the
// trial's words were shown in (the prompts, the answer labels; a visitor study's consent).
// `actuator_eq_hash` and `actuator_eq_utc` name the actuator calibration whose inverse the
// actuator channel passed (core/actuator_eq_file.hpp: its identity and when it was measured),
// both empty when none was in force (none measured, or [actuator] equalize = false).
// Columns are only ever added at the end. A file begun before some of these
// columns keeps its header: its rows are appended with the columns it has.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace mallet::study {

inline constexpr const char* kResultsHeaderWithoutTiming =
    "participant,trial,condition,stimuli,answer,correct,response_time_ms,"
    "protocol,task,difference_pct,source,session,visual_peak_m,actuator_peak";
inline constexpr const char* kResultsHeader =
    "participant,trial,condition,stimuli,answer,correct,response_time_ms,"
    "protocol,task,difference_pct,source,session,visual_peak_m,actuator_peak,"
    "actuator_onset_ms,picture_onset_ms,procedure,track_trial,reversals,estimate_pct,estimate_sd_pct,"
    "planned_trials,estimate_mode_pct,language,actuator_eq_hash,actuator_eq_utc";
//! The columns this version writes.
inline constexpr std::size_t kResultsColumns = 26;
//! How many of kResultsHeader's columns a file's header has: kResultsHeaderWithoutTiming
//! or longer, up to all of them, in this order; 0 for any other header (not resumable).
std::size_t results_columns(std::string_view header);

struct ResultRow {
  std::string participant;
  int trial = 0;
  std::string condition;
  std::string stimuli;
  std::string answer;
  bool correct = false;
  double response_time_ms = 0;
  std::string protocol;
  std::string task;
  double difference_pct = 0;  //!< NaN: none (written as an empty field)
  std::string source;
  std::string session;
  double visual_peak_m = 0;
  double actuator_peak = 0;
  double actuator_onset_ms = std::numeric_limits<double>::quiet_NaN();  //!< NaN: not recorded (an older file)
  double picture_onset_ms = std::numeric_limits<double>::quiet_NaN();
  std::string procedure;  //!< "constant", "staircase", "quest"; empty in an older file
  int track_trial = 0;    //!< adaptive: the trial's number in its condition's track; 0: none
  int reversals = -1;     //!< staircase: its reversals after this answer; −1: none
  double estimate_pct = std::numeric_limits<double>::quiet_NaN();
  double estimate_sd_pct = std::numeric_limits<double>::quiet_NaN();
  int planned_trials = 0;  //!< 0: not recorded
  double estimate_mode_pct = std::numeric_limits<double>::quiet_NaN();  //!< QUEST: posterior mode; NaN: none
  std::string language;  //!< the words' language; empty in an older file
  std::string actuator_eq_hash;  //!< the actuator calibration in force; empty: none
  std::string actuator_eq_utc;   //!< when it was measured; empty: none
};

//! The row as written, ending in '\n': its first `columns` columns (kResultsHeader's order).
std::string format_row(const ResultRow& row, std::size_t columns = kResultsColumns);

struct ResultsFile {
  bool exists = false;
  bool has_header = false;            //!< a complete header line is there
  std::string header;                 //!< that line
  std::vector<ResultRow> rows;        //!< complete rows, in file order
  std::vector<std::uint32_t> lines;   //!< each row's line number
  std::vector<std::string> warnings;  //!< "FILE:LINE: ..." for an incomplete last line
  std::uintmax_t complete_bytes = 0;  //!< the file's length up to its last complete line
};

//! Reads a results file. A last line without its '\n' (a crash in the middle of a write)
//! is ignored with a warning naming FILE:LINE; any other bad line is a FileError. Needs
//! the seven required columns; `difference_pct` and the other extras are optional.
//! A missing file reads as empty (exists = false).
ResultsFile read_results(const std::filesystem::path& path);

//! Appends rows durably. Opening cuts the file back to `complete_bytes` (dropping an
//! incomplete last line, which would otherwise glue itself to the next row) and writes
//! the header if the file holds none. Throws std::runtime_error naming the file.
class ResultsWriter {
 public:
  ResultsWriter(const std::filesystem::path& path, const ResultsFile& existing);
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  //! One write(2) of the row, then fsync(2): on return the row survives a crash.
  void append(const ResultRow& row);

 private:
  void write_durably(const std::string& bytes);
  std::filesystem::path path_;
  int fd_ = -1;
  std::size_t columns_ = kResultsColumns;  //!< as many as the file's header has
};

}  // namespace mallet::study
