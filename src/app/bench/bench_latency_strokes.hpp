#pragma once
// `mallet bench latency`'s strokes: the hand's downswings on the two bars. The mouse's are
// XTest motion, one event a millisecond, sent live; the remote's are a recording of the Wii
// Remote's IR reports, written before the run and played by the kiosk as a live remote.
#include <filesystem>
#include <functional>
#include <iterator>
#include <vector>

#include "app/bench/bench_latency.hpp"
#include "app/bench/bench_latency_rig.hpp"
#include "core/time.hpp"

namespace mallet::app::latency {

//! Every stroke starts this far above the contact plane and goes this far below it.
inline constexpr double kAboveM = 0.04, kBelowM = 0.03;
//! The downswings' speeds, m/s, in turn.
inline constexpr double kStrokeSpeeds[] = {1.0, 1.5, 2.0, 1.25, 1.75};
//! Stroke k's speed (k ≥ 0), m/s: kStrokeSpeeds in turn, the mouse's and the remote's alike.
inline double stroke_speed(int k) { return kStrokeSpeeds[static_cast<std::size_t>(k) % std::size(kStrokeSpeeds)]; }

//! The hand (the sphere's centre) at world (x, y): the pointer at that window pixel.
struct Hand {
  const Rig& rig;
  //! Moves the pointer; returns when the event was sent (CLOCK_MONOTONIC). `row_out`: the
  //! window row it went to.
  Nanos move(double x_m, double y_m, int* row_out = nullptr) const;
};

//! One mouse stroke on bar `b` at `v` m/s: hover above it, a straight downswing (an event
//! every 1 ms) to kBelowM under the contact plane, a pause there (`on_hold` may look at the
//! screen meanwhile), back up at about 1 m/s. Returns the true contact, the path's crossing
//! of the contact plane interpolated between the two events around it (−1 if it never crossed).
Nanos mouse_stroke(const Rig& rig, const Bar& b, double v, const std::function<void()>& on_hold);

//! The remote's strokes, as a recording (the `mallet wiimote monitor --record` format) the
//! kiosk plays as a live remote (`[input] source = "replay"`): one report every 10 ms (the
//! camera's 100 Hz), the camera's view mirrored onto the screen (the kiosk's mapping when it
//! has no calibration), whole camera pixels. After `lead` of a hovering hand (the kiosk
//! starts and takes it for a visitor), `strokes` downswings alternating between the bars,
//! one every 600 ms plus 3.3 ms more each time, so that contacts fall anywhere between two
//! camera frames. Times relative to the recording's time 0.
struct RemoteScript {
  std::vector<Recording::Contact> contacts;
  Nanos first_stroke = 0, end = 0;
};
RemoteScript write_remote_script(const Rig& rig, const std::filesystem::path& file, int strokes, Nanos lead);

}  // namespace mallet::app::latency
