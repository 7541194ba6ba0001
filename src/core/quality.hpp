#pragma once
// Quality presets: one config key (`quality = "fast" | "balanced" | "exact"`, top of
// config/mallet.toml) that sets the knobs where speed is traded for accuracy. A preset
// only sets defaults: any knob written in the file overrides it. `mallet bench report`
// measures each knob's time against its error and marks the three presets on that front
// (docs/bench-report/report.md); the values below were chosen from it.
//
//   knob                      fast      balanced  exact     why (numbers: docs/bench-report, lavapipe, 2 cores)
//   render.msaa               "1"       "auto"    "4"       image error against a supersampled reference (RMS /255
//                                                           at 1080p): none 1.77; "auto" on a CPU rasteriser = 4x
//                                                           MSAA for the cached instruments only (drawn once per
//                                                           size), 0.90 at no cost per frame; on a GPU 4x for
//                                                           everything, where it is cheap; "4": 0.85 for ≈10x the
//                                                           frame on a CPU rasteriser; fast never pays for it
//   render.shadow             true      true      true      the mallet's analytic shadow: no extra pass; its cost
//                                                           was within the run-to-run noise (32.6 vs 32.7 ms per
//                                                           1080p frame; RMS error 2.16 without, 1.77 with) and
//                                                           it is the only depth cue: off in no preset (the
//                                                           knob stays)
//   render.present_mode       "fifo"    "fifo"    "fifo"    with lavapipe's 2.4–3.5 ms per 1080p frame mailbox would
//                                                           show a strike sooner (model at 60 Hz: 13.5 ms mean vs
//                                                           25), but it draws without pause, ~300 frames a second,
//                                                           on the cores the audio and the pointer share; the bounce's
//                                                           phase is right in either (Eq. 1 at the present time)
//   audio.frames_per_buffer   64        64        64        the engine's cost per frame stops falling at 64 (16
//                                                           frames: 1.3–2x it; 128 and up: the same within the
//                                                           noise), while the wait for the next callback doubles
//                                                           with every step: 64 is the knee
//   audio.schedule_ahead_ms   0         0         12        exact: every strike sounds exactly 12 ms after its
//                                                           contact (jitter one sample instead of one block). It
//                                                           counts from the contact, which the 100 Hz camera
//                                                           reveals up to 10 ms later: with 5 ms, 238 of 400
//                                                           strikes came late; 12 = 10 ms + one 64-frame block +
//                                                           margin, and still sooner than any frame shows the bounce
//   audio.max_modes           8         8         8         the modes run side by side: 3 of the glockenspiel's 4
//                                                           cost 0.85 (one run) to 0.98 (another) of the full
//                                                           voice: dropping the 4th saves ≤ 0.3 % of a core at
//                                                           64 voices and costs up to 12 % of full scale; the
//                                                           knob stays for instruments with many modes
//   timing.predict_horizon_ms 10        10        0         contact prediction (bench prediction, 1200 human-like
//                                                           strokes per camera and rate): Wii at 100 Hz, the median
//                                                           from contact to strike 4.45 → 1.99 ms, no false or
//                                                           missed note added, the speed error's p99 on fast strikes
//                                                           44 → 45 %. A V4L2 camera (σ 0.02 px measured, read-out
//                                                           500 µs/2 + one frame) runs the level tuned for it
//                                                           (core/camera_prediction.hpp): 240 Hz contact → sound
//                                                           6.53 → 0.28 ms median, p99 8.57 → 8.42 (speed error
//                                                           p99 21 → 92 %); 120 Hz 12.82 → 10.27, p99 16.90 →
//                                                           16.89; none added false or missed. The camera's targets
//                                                           (p99 ≤ 3 / 5 ms) are not met by any level: the read-out
//                                                           alone is 4.4 / 8.6 ms and ~4 in 10 contacts cannot be
//                                                           extrapolated (bench_prediction.cpp); exact waits for the
//                                                           samples (its constant 12 ms covers the Wii, not a camera
//                                                           frame's read-out)
//   pointer (1€ filter)       the same in all three         the filter costs ~nothing; its point on the jitter/lag
//                                                           front (bench input) suits every preset
//
// So on the machines measured the trade is the renderer's, and there it is antialiasing and
// resolution: audio is cheap (64 voices ≈ 6 % of one core) and exact already. Rendering at
// half scale and upscaling once saved 3.8x per frame (RMS error 1.77 → 2.71); since the
// renderer draws the static instruments once into a cached background and each frame only
// copies it and draws the mallet and its shadow over it (1080p on lavapipe 16.0 → 2.8 ms,
// 1.9x the clear + read-back floor, the same pixels), a lower resolution would buy ~1 ms for
// that error: it is not a knob. On a CPU rasteriser "fast" differs from "balanced" only by
// the background's antialiasing, paid once per image size; on a GPU it drops the 4x MSAA. What a preset never changes: which strikes the swept solver
// finds and how hard (it works on unfiltered samples and none of its settings is a quality
// knob; prediction may decide a strike before the solver sees it, at its predicted time and
// speed, and exact turns it off), the actuator's Eq. 1 signal (the re-seeded double rotator is within 1e-14
// of the formula at ≈2.6 ns per sample, 10x cheaper than exp + sin per sample: no cheaper
// method comes near it, so it is not a knob) and the visual vibration (Eq. 1 in double per frame).
//
// Error bounds, asserted by tests/app/quality_extremes_test.cpp (full scale 1):
//   actuator oscillator vs Eq. 1 in long double       ≤ 1e-9 in every preset
//   acoustic note vs all modes in long double          ≤ 1e-9 in every preset; with max_modes = 3
//                                                      ≤ kThreeModeNoteErrorBound
//   strike → its first sample                          fast, balanced: within one block;
//                                                      exact: 12 ms after the contact ± one sample
//                                                      when the block is shorter than that
#include <optional>
#include <string>
#include <string_view>

#include "core/app_config.hpp"

namespace mallet {

//! The knobs a preset sets (a subset of AppConfig).
struct QualityKnobs {
  std::string msaa;
  bool shadow = true;
  PresentPacing present_mode = PresentPacing::fifo;
  int frames_per_buffer = 64;
  double schedule_ahead_ms = 0;
  int max_modes = kMaxModalModes;
  OneEuroConfig pointer;
  double predict_horizon_ms = 10;
};

//! With audio.max_modes = 3 (no preset's choice), the modes left out (the 4th and above) of
//! the shipped instruments carry at most this share of full scale at any strike speed
//! (measured worst: 0.123, the glockenspiel struck at 100 m/s, i.e. at full loudness).
inline constexpr double kThreeModeNoteErrorBound = 0.15;

QualityKnobs quality_knobs(Quality q);

//! Sets the preset's knobs in `config` (and config.quality).
void apply_quality(Quality q, AppConfig& config);

//! "fast", "balanced", "exact"; nothing for any other text.
std::optional<Quality> parse_quality(std::string_view text);
const char* to_string(Quality q);

}  // namespace mallet
