#pragma once
// The kiosk's metrics file ([metrics] textfile): core/kiosk_metrics.hpp's text, replaced
// atomically (core/atomic_file: a temporary file renamed over it, so node_exporter's
// textfile collector never reads half a file) every [metrics] interval_s. The window kiosk
// and the headless run feed it on their main thread; a write that fails never ends the
// kiosk: one line says so, the next interval tries again.
//
// Strikes by instrument and material: every route (the main thread's, the remote's and the
// evdev mouse's, each on its own thread) records its strikes in the stage's StrikeTally from
// its on_strike callback — one relaxed atomic add per strike, no lock, no allocation, never
// on the audio thread — and the main thread reads the tally when it writes the file.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "app/kiosk/state_folder.hpp"
#include "core/app_config.hpp"
#include "core/impact.hpp"
#include "core/kiosk_metrics.hpp"
#include "core/scene.hpp"

namespace mallet::app {

//! The program's version (mallet_build_info), as `mallet --version` prints it.
const char* mallet_version();

//! A zero for every (instrument, material) `scene` can strike, so that each series exists
//! from the first write on (a series that appears only with its first strike hides the
//! increase from 0 to 1 from rate()).
void seed_strike_labels(const Scene& scene, StrikeCounts& counts);
//! One strike under its (target's instrument, impact's material) labels.
void count_strike(const Scene& scene, const Impact& impact, StrikeCounts& counts);

//! Strikes by (target, material) of one scene, recorded from any thread.
class StrikeTally {
 public:
  explicit StrikeTally(const Scene& scene);  //!< `scene` must outlive the tally
  //! Any thread: lock-free, never allocates. An impact outside the scene is not counted.
  void record(const Impact& impact);
  //! Adds the counts so far to `counts` under their labels.
  void add_to(StrikeCounts& counts) const;

 private:
  const Scene& scene_;
  std::size_t materials_;
  std::unique_ptr<std::atomic<std::uint64_t>[]> cells_;  //!< target × material
};

//! How many times the kiosk started before this one: the count kept in the state folder's
//! kiosk-starts, which this call increments (written through `state`: atomically replaced,
//! the folder created, a failure said by the state folder, once). A file that cannot be read
//! is said through `warn`, set aside as kiosk-starts.bad, and counts as 0 starts.
std::uint64_t count_kiosk_start(StateFolder& state, const std::function<void(const std::string&)>& warn);

class MetricsFile {
 public:
  using Log = std::function<void(const std::string& line)>;
  //! `starts`: the state folder where count_kiosk_start() keeps its count once the file is
  //! enabled (null: the headless run, which is not a start of the kiosk); it must outlive
  //! this. `warn` gets a write failure (once until a write succeeds again), `note` the recovery.
  MetricsFile(StateFolder* starts, Log warn, Log note);

  //! The settings (at start and after a reload). The next due() is at once when the file
  //! or the interval changed.
  void configure(const MetricsConfig& config);
  bool enabled() const { return !path_.empty(); }
  const std::filesystem::path& path() const { return path_; }
  //! Enabled, and never written or interval_s since the last attempt.
  bool due(Nanos now) const;
  //! Writes `metrics` now (its `restarts` set from the start count) and schedules the
  //! next write interval_s after `now`. Returns whether the file was replaced.
  bool write(KioskMetrics& metrics, Nanos now);
  std::uint64_t restarts() const { return restarts_; }

 private:
  StateFolder* starts_;
  Log warn_, note_;
  std::filesystem::path path_;
  Nanos interval_ns_ = 15 * kNanosPerSecond;
  bool counted_start_ = false;
  std::uint64_t restarts_ = 0;
  bool attempted_ = false;
  Nanos next_ = 0;
  bool failing_ = false;  //!< a failure was said; the next success says so
};

}  // namespace mallet::app
