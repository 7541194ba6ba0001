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
#include <stdexcept>
#include <string>
#include <vector>

#include "core/app_config.hpp"
#include "core/impact.hpp"
#include "core/mallet.hpp"
#include "core/scene.hpp"
#include "core/strike_line.hpp"
#include "app/strike/replay.hpp"

namespace mallet::app {

//! A trajectory whose t goes past this (seconds after t = 0, where audio.wav and cursor.csv
//! start) is refused unless SimulateOptions::allow_long: the outputs grow with it (an hour
//! at the defaults is 1.38 GB of audio.wav, 48 kHz × 2 channels × 4 bytes, and 3.6 million
//! rows of cursor.csv), and a t written in milliseconds instead of seconds turns a few
//! seconds of strokes into hours of silence (an operator's 522 samples gave 2.3 GB and no
//! impact). An hour is more than any session we simulate (a study session or a kiosk
//! recording lasts minutes) and matches the longest --tail.
inline constexpr double kLongTrajectoryS = 3600.0;

//! SIGINT or SIGTERM arrived while the outputs were being written: they were removed
//! (no *.partial is left). The conventional exit status is 128 + signal().
class SimulateInterrupted : public std::runtime_error {
 public:
  explicit SimulateInterrupted(int signal);
  int signal() const { return signal_; }

 private:
  int signal_;
};

struct SimulateOptions {
  std::filesystem::path scene;
  std::filesystem::path input;
  std::filesystem::path out_dir;
  std::optional<std::filesystem::path> config;  //!< mallet.toml; built-in defaults if absent
  std::optional<std::filesystem::path> config_dir;  //!< its drop-ins (none: FILE.d)
  InputSpace input_space = InputSpace::screen;
  //! The scene as a screen of that shape lays it out (core/scene_layout.hpp).
  SceneLayout layout = SceneLayout::landscape;
  std::optional<int> sample_rate_hz;             //!< overrides [audio].sample_rate_hz
  double trace_rate_hz = 1000.0;
  double tail_s = 1.0;                           //!< rendered after the last sample
  bool allow_long = false;      //!< a trajectory past kLongTrajectoryS is simulated, not refused
  bool causal = false;          //!< decide strikes as the live kiosk does
  double input_delay_ms = 0;    //!< --causal: a sample is known this long after its time
  //! --causal --camera: as the kiosk's camera route (core/camera_prediction.hpp:
  //! camera_route_timing): prediction tuned for [camera], and input_delay_ms its read-out
  //! unless given.
  bool camera = false;
  bool input_delay_given = false;
  double display_hz = 60;       //!< --causal: the frames' pacing ...
  PresentPacing present_mode = PresentPacing::fifo;  //!< ... and present mode
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
//! written; a t past kLongTrajectoryS without allow_long is bad input, at its row's line),
//! std::runtime_error for a failure to write (exit status 1: partial files are removed),
//! and SimulateInterrupted when SIGINT or SIGTERM arrives while writing (partial files are
//! removed; the caller's previous handlers are back by then). While the outputs are being
//! written, those two signals only set a flag that the writing loops check.
SimulateResult run_simulate(const SimulateOptions& options);

}  // namespace mallet::app
