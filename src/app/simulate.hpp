#pragma once
// `mallet simulate`: replays a trajectory through the core exactly as the kiosk would
// and writes the stimuli a researcher needs to reproduce a session:
//   events.csv  t,target,instrument,material,note,velocity       (one row per impact)
//               --causal adds ,contact_t,sound_t,shown_t,predicted (when the kiosk would
//               have decided, sounded and shown each strike: see cmd_simulate.cpp)
//   cursor.csv  t,hand_x,hand_y,cursor_x,cursor_y,offset         (at --trace-rate)
//               texture scenes add ,gain,stripe_phase (the Speed technique's gain, Eq. 1's phase)
//   audio.wav   float32, channels as routed in the config (default 0 acoustic, 1 actuator)
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/app_config.hpp"
#include "core/impact.hpp"
#include "core/mallet.hpp"
#include "core/scene.hpp"
#include "app/replay.hpp"

namespace mallet::app {


struct SimulateOptions {
  std::filesystem::path scene;
  std::filesystem::path input;
  std::filesystem::path out_dir;
  std::optional<std::filesystem::path> config;  //!< mallet.toml; built-in defaults if absent
  std::optional<std::filesystem::path> config_dir;  //!< its drop-ins (none: FILE.d)
  InputSpace input_space = InputSpace::screen;
  std::optional<int> sample_rate_hz;             //!< overrides [audio].sample_rate_hz
  double trace_rate_hz = 1000.0;
  double tail_s = 1.0;                           //!< rendered after the last sample
  bool causal = false;          //!< decide strikes as the live kiosk does
  double input_delay_ms = 0;    //!< --causal: a sample is known this long after its time
  double display_hz = 60;       //!< --causal: the frames' pacing ...
  std::string present_mode = "fifo";  //!< ... and present mode
};

struct SimulateResult {
  Scene scene;
  std::vector<Impact> impacts;
  Mallet::Counters counters;
  std::uint64_t cursor_rows = 0;
  std::uint64_t audio_frames = 0;
  int sample_rate_hz = 0;
  std::uint64_t clipped_samples = 0;
  std::vector<std::filesystem::path> written;
};

//! Runs the whole simulation. Throws FileError for bad input (exit status 2: nothing is
//! written) and std::runtime_error for a failure to write (exit status 1: partial
//! files are removed).
SimulateResult run_simulate(const SimulateOptions& options);

//! "12.000000042": seconds with all nine nanosecond digits.
std::string format_seconds(Nanos t_ns);

}  // namespace mallet::app
