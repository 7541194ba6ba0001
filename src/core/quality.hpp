#pragma once
// Quality presets: one config key (`quality = "fast" | "balanced" | "exact"`, top of
// config/mallet.toml) that sets the knobs where speed is traded for accuracy. A preset
// only sets defaults: any knob written in the file overrides it. `mallet bench report`
// measures each knob's time against its error and marks the three presets on that front
// (docs/bench-report/report.md); the values below were chosen from it.
//
//   knob                         fast        balanced    exact       why
//   render.msaa                  "1"         "auto"      "4"         lavapipe: 4x MSAA costs ≈3x the frame for
//                                                                    half the RMS error vs a supersampled
//                                                                    reference; "auto" = none on a CPU, 4x on a GPU
//   render.shadow                false       true        true        the analytic shadow: no extra pass, ≤ 10 %
//                                                                    of a lavapipe frame; off where every ms counts
//   render.present_mode          "mailbox"   "fifo"      "fifo"      mailbox shows the newest frame (≤ 1 refresh
//                                                                    less latency, falls back to fifo); fifo's
//                                                                    present time is predictable, which Eq. 1's
//                                                                    evaluation at the predicted time needs
//   audio.frames_per_buffer      128         64          64          half the callbacks; worst impact→sample
//                                                                    2.7 ms, still under the ≈5 ms that tapping
//                                                                    notices
//   audio.schedule_ahead_ms      0           0           12          exact: every strike sounds exactly 12 ms
//                                                                    after its contact (jitter one sample, not
//                                                                    one block). It counts from the contact,
//                                                                    which the 100 Hz camera reveals up to 10 ms
//                                                                    later: with 5 ms about half the strikes were
//                                                                    late (bench report's latency budget); 12 =
//                                                                    10 ms + a 64-frame block + margin. Still
//                                                                    earlier than any frame shows the bounce.
//   audio.max_modes              3           8           8           modes sounding per bar (the strike law's
//                                                                    sums still see all of them, so the modes
//                                                                    kept sound exactly as in "exact"); 3 drops
//                                                                    only the glockenspiel's and the wall's 4th
//                                                                    mode (≈1 ns/sample each); 2 would cost a
//                                                                    31 % error for about as little
//   pointer (1€ filter)          the same    the same    the same    the filter costs ~nothing; its point on the
//                                                                    jitter/lag front (bench input) suits all
//
// What a preset never changes: which strikes happen, when, and how hard (the contact
// solver works on unfiltered samples and none of its settings is a quality knob), the
// actuator's Eq. 1 signal (the re-seeded rotator is within 1e-9 of the formula at
// 2.7 ns/sample, 24x cheaper than exp+sin per sample: there is no cheaper method worth
// its error, so it is not a knob) and the visual vibration (Eq. 1 in double per frame).
//
// Error bounds per preset, asserted by tests/core/quality_extremes_test.cpp (full scale 1):
//   actuator channel vs Eq. 1 in long double          ≤ 1e-9 in every preset
//   acoustic note vs all modes in long double          fast ≤ kFastNoteErrorBound; balanced,
//                                                      exact ≤ 1e-9
//   strike → its first sample, 64/128-frame blocks     fast ≤ 128 frames late, balanced ≤ 64,
//                                                      exact exactly 12 ms after the contact (± one
//                                                      sample) when the block is shorter than that
#include <optional>
#include <string>
#include <string_view>

#include "core/app_config.hpp"

namespace mallet {

//! The knobs a preset sets (a subset of AppConfig).
struct QualityKnobs {
  std::string msaa;
  bool shadow = true;
  std::string present_mode;
  int frames_per_buffer = 64;
  double schedule_ahead_ms = 0;
  int max_modes = kMaxModalModes;
  OneEuroConfig pointer;
};

//! The fast preset's acoustic error bound: the modes it leaves out (the 4th and above) of
//! the shipped instruments carry at most this share of full scale at any strike speed
//! (measured worst: 0.123, the glockenspiel struck at 100 m/s, i.e. at full loudness).
inline constexpr double kFastNoteErrorBound = 0.15;

QualityKnobs quality_knobs(Quality q);

//! Sets the preset's knobs in `config` (and config.quality).
void apply_quality(Quality q, AppConfig& config);

//! "fast", "balanced", "exact"; nothing for any other text.
std::optional<Quality> parse_quality(std::string_view text);
const char* to_string(Quality q);

}  // namespace mallet
