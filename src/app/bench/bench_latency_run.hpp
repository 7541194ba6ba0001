#pragma once
// `mallet bench latency`: one configuration's run of the kiosk under test, the child's whole
// life. Its settings written; `mallet run --windowed` started under the rig's servers; waited
// for until it is up (its start line, its window at the screen's origin, its audio ports, a
// first frame); the strokes (the mouse's, live, after a warm-up that finds where the head
// rests on each bar; or the remote's recording, which the kiosk plays); then the cues
// collected from the recorder, the picture watch and the kiosk's log, matched to the true
// contacts, and the kiosk stopped.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "app/bench/bench_latency.hpp"
#include "app/bench/bench_latency_rig.hpp"

namespace mallet::app::latency {

//! One configuration: the quality preset, [timing] align and the pointer's source.
struct Config {
  std::string preset, align;
  std::string source = "mouse";  //!< or "remote": a recording played as a live Wii Remote
  std::filesystem::path replay_file;  //!< for "remote"
};

struct ConfigResult {
  Config config;
  Matched matched;
  std::vector<std::string> kiosk_status;
  int rest_row[2] = {0, 0};
  double resolution_ms = 0;  //!< ±1 px / v at the slowest stroke
  std::uint64_t xruns = 0;   //!< JACK xruns during the strokes
};

//! Runs the kiosk once with `config` and measures `strokes` strokes. A remote run needs a
//! mouse run first (its warm-up finds where the head rests). Throws, naming what the kiosk
//! did not do, when it fails.
ConfigResult run_config(Rig& rig, const Config& config, int strokes, const std::string& device,
                        const Deadline& deadline);

}  // namespace mallet::app::latency
