#pragma once
// `mallet study`: one participant's session of a protocol, headless on a simulated clock.
// Trials are presented through the headless kiosk loop (study_stimuli.hpp); each answered
// trial is appended to the results CSV and fsync'd before the next begins. Starting again
// with the same participant resumes: the schedule is deterministic, so the trials already
// in the file are skipped and the rest run in their original order.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace mallet::app {

struct StudyOptions {
  std::filesystem::path protocol;
  std::string participant;
  std::optional<std::filesystem::path> out;      //!< results CSV; default: the protocol's `output`
  std::filesystem::path scene;
  std::optional<std::filesystem::path> config;   //!< mallet.toml; built-in defaults if absent
  std::optional<std::filesystem::path> answers;  //!< answer script; absent: the simulated observer
  std::optional<std::filesystem::path> audio;    //!< WAV of this run's stimuli (both channels)
  std::function<void(int rows_this_run)> after_row;  //!< called after each row is durable
};

struct StudyRunResult {
  std::filesystem::path csv;
  int total = 0;             //!< trials in the participant's schedule
  int already_recorded = 0;  //!< found in the CSV at start
  int answered = 0;          //!< in this run
  int correct = 0;           //!< in this run
  bool simulated = false;    //!< the simulated observer answered
  bool answers_ran_out = false;
  std::vector<std::string> warnings;  //!< FILE:LINE: ... (an incomplete last line ignored)
  std::vector<std::filesystem::path> written;
};

//! Bad protocol, scene, config, answers or CSV → FileError (exit 2); a failure to write →
//! std::runtime_error (exit 1).
StudyRunResult run_study(const StudyOptions& options);

}  // namespace mallet::app
