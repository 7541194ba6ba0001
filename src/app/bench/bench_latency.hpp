#pragma once
// `mallet bench latency`: the time from a true contact to each of the three cues, measured
// on the real windowed kiosk running as a child process — not modelled.
//
//   true contact   the moment the injected pointer path crosses the bar's contact plane
//                  (top + mallet radius), interpolated between the injected motion events
//   actuator/note  the first sample of the strike on each audio channel, as a JACK
//                  recorder hears it (the dummy driver's cycles are paced in wall time)
//   picture        the first frame in the X server's framebuffer that shows the mallet at
//                  the bar (where the bounce starts; the bench's scene has no bounce)
//
// The matching and the statistics are pure functions here (bench_latency_match.cpp). The
// bench is carved by job: bench_latency.cpp runs every configuration and prints the table;
// bench_latency_rig what the runs share (the servers, the still scene, the two bars);
// bench_latency_run one configuration's run of the kiosk, from its start to its cues;
// bench_latency_strokes the hand's strokes (the mouse's, and the remote's recording). The
// machinery (Xvfb, XTest, XGetImage, jackd, the recorder, the kiosk process) is in
// bench_latency_{x11,jack,child}.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/time.hpp"

namespace mallet::app::latency {

inline constexpr Nanos kMs = 1'000'000;
inline constexpr Nanos kStrikeWindow = 50 * kMs;  //!< a logged strike within ±50 ms of a contact is its strike
inline constexpr Nanos kCueBefore = 50 * kMs;     //!< a cue may lead its contact (prediction) by this much
inline constexpr Nanos kCueAfter = 300 * kMs;     //!< and lag it by this much at most
//! ns → ms, the nearest double (12 ms is 12.0).
inline double ms_of(Nanos dt) { return static_cast<double>(dt) / 1e6; }

struct LatencyOptions {
  std::filesystem::path out = ".";
  bool quick = false;
  int strokes = 0;     //!< per configuration; 0 = 20 (6 with --quick)
  std::string device;  //!< the kiosk's Vulkan device (substring); empty = its own choice
};

//! Runs every configuration, prints the table, writes OUT/latency.csv. Throws on failure.
void run_bench_latency(const LatencyOptions& options);

//! What one configuration's run recorded, all on the monotonic clock.
struct Recording {
  struct Contact {
    Nanos t = 0;       //!< the true contact
    int bar = 0;       //!< which of the bench's bars (0, 1, ...)
    double speed = 0;  //!< the downswing's speed, m/s
  };
  std::vector<Contact> contacts;
  std::vector<Nanos> strikes;               //!< the kiosk's strike log lines (t=), in the window
  std::vector<Nanos> actuator, note;        //!< onsets per channel
  std::vector<std::vector<Nanos>> picture;  //!< per bar: "the mallet at the bar" first seen
};

//! One cue's (or asynchrony's) samples in ms; a missing sample is left out.
struct CueSamples {
  std::string cue;
  std::vector<double> ms;
};

//! One true contact and what followed it, ms after it (nothing: not found).
struct StrikeRow {
  Recording::Contact contact;
  std::optional<double> strike_ms, actuator_ms, note_ms, picture_ms;
};

struct Matched {
  std::vector<StrikeRow> rows;   //!< per true contact, in time order
  std::vector<CueSamples> cues;  //!< actuator, note, picture, actuator-picture, note-actuator
  int strikes = 0;               //!< true contacts the kiosk logged a strike for (±50 ms)
  int false_strikes = 0;         //!< logged strikes with no true contact within ±50 ms
  int missed_strikes = 0;        //!< true contacts with no logged strike
};

//! Pairs each true contact with its logged strike and with the first onset / picture that
//! follows it (from 50 ms before to 300 ms after), then computes each cue's latency and
//! the two signed asynchronies per strike.
Matched match_recording(const Recording& r);

struct Summary {
  std::optional<double> median, p99, max;  //!< max: the sample of largest magnitude, sign kept
  std::size_t n = 0;
};
Summary summarise(std::vector<double> ms);

}  // namespace mallet::app::latency
