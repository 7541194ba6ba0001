#include "app/kiosk/metrics_file.hpp"

#include <charconv>
#include <cstdio>
#include <fstream>
#include <system_error>

#include <fmt/format.h>

#include "core/atomic_file.hpp"

#ifndef MALLET_VERSION
#define MALLET_VERSION "unknown"
#endif

namespace mallet::app {

namespace {

//! The material's label: the materials file's key ("wood"), as the log's strike lines say it.
std::string material_label(const Scene& scene, int material) {
  const auto m = static_cast<std::size_t>(material);
  return material >= 0 && m < scene.materials.size() ? scene.materials[m].name : "unknown";
}

std::string seconds_text(Nanos ns) {
  return fmt::format("{:g}", static_cast<double>(ns) / 1e9);
}

}  // namespace

const char* mallet_version() { return MALLET_VERSION; }

void seed_strike_labels(const Scene& scene, StrikeCounts& counts) {
  for (const Target& t : scene.targets) {
    counts.try_emplace({t.instrument, material_label(scene, t.material)}, 0);
    // The wall's one target takes each of the materials it switches between.
    if (scene.kind == SceneKind::wall)
      for (int m : scene.wall_materials) counts.try_emplace({t.instrument, material_label(scene, m)}, 0);
  }
}

void count_strike(const Scene& scene, const Impact& impact, StrikeCounts& counts) {
  const auto t = static_cast<std::size_t>(impact.target);
  if (impact.target < 0 || t >= scene.targets.size()) return;
  ++counts[{scene.targets[t].instrument, material_label(scene, impact.material)}];
}

StrikeTally::StrikeTally(const Scene& scene)
    : scene_(scene),
      materials_(scene.materials.size()),
      cells_(std::make_unique<std::atomic<std::uint64_t>[]>(scene.targets.size() * scene.materials.size())) {
  static_assert(std::atomic<std::uint64_t>::is_always_lock_free);
  for (std::size_t i = 0; i < scene.targets.size() * materials_; ++i) cells_[i].store(0, std::memory_order_relaxed);
}

void StrikeTally::record(const Impact& impact) {
  const auto t = static_cast<std::size_t>(impact.target);
  const auto m = static_cast<std::size_t>(impact.material);
  if (impact.target < 0 || t >= scene_.targets.size() || impact.material < 0 || m >= materials_) return;
  cells_[t * materials_ + m].fetch_add(1, std::memory_order_relaxed);
}

void StrikeTally::add_to(StrikeCounts& counts) const {
  for (std::size_t t = 0; t < scene_.targets.size(); ++t)
    for (std::size_t m = 0; m < materials_; ++m)
      if (const std::uint64_t n = cells_[t * materials_ + m].load(std::memory_order_relaxed); n > 0)
        counts[{scene_.targets[t].instrument, scene_.materials[m].name}] += n;
}

std::uint64_t count_kiosk_start(StateFolder& state, const std::function<void(const std::string&)>& warn) {
  const std::filesystem::path file = state.file("kiosk-starts");
  std::uint64_t before = 0;
  std::error_code ec;
  if (std::filesystem::exists(file, ec)) {
    std::ifstream in(file);
    std::string text;
    std::getline(in, text);
    const auto r = std::from_chars(text.data(), text.data() + text.size(), before);
    if (!in || r.ec != std::errc() || r.ptr != text.data() + text.size()) {
      const std::optional<std::filesystem::path> bad = set_aside_as_bad(file);
      warn(file.string() + ":1: expected the number of kiosk starts, got \"" + text + "\"; counting from 0" +
           (bad ? " (the file is kept as " + bad->string() + ")" : ""));
      before = 0;
    }
  }
  // A state folder that cannot be written: the count stays, the kiosk runs, the folder says so.
  state.write("kiosk-starts", std::to_string(before + 1) + "\n");
  return before;
}

MetricsFile::MetricsFile(StateFolder* starts, Log warn, Log note)
    : starts_(starts), warn_(std::move(warn)), note_(std::move(note)) {}

void MetricsFile::configure(const MetricsConfig& config) {
  const Nanos interval = from_seconds(config.interval_s).value_or(15 * kNanosPerSecond);
  if (std::filesystem::path(config.textfile) != path_ || interval != interval_ns_) attempted_ = false;
  path_ = config.textfile;
  interval_ns_ = interval > 0 ? interval : kNanosPerSecond;
  // Counted once per run, when the file is first enabled: a kiosk without metrics writes
  // nothing new in its state folder.
  if (enabled() && starts_ && !counted_start_) {
    counted_start_ = true;
    restarts_ = count_kiosk_start(*starts_, warn_);
  }
}

bool MetricsFile::due(Nanos now) const { return enabled() && (!attempted_ || now >= next_); }

bool MetricsFile::write(KioskMetrics& metrics, Nanos now) {
  if (!enabled()) return false;
  attempted_ = true;
  next_ = now + interval_ns_;
  metrics.restarts = restarts_;
  try {
    write_file_atomically(path_, render_prometheus_text(metrics));
  } catch (const std::exception& e) {
    // Said once until a write succeeds, not every interval: a missing folder would
    // otherwise fill the journal.
    if (!failing_)
      warn_(std::string("[metrics] textfile: ") + e.what() + "; trying again every " + seconds_text(interval_ns_) + " s");
    failing_ = true;
    return false;
  }
  if (failing_) note_("[metrics] textfile: writing " + path_.string() + " again");
  failing_ = false;
  return true;
}

}  // namespace mallet::app
