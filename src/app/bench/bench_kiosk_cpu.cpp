// The windowed kiosk's CPU: see bench_kiosk_cpu.hpp.
#include "app/bench/bench_kiosk_cpu.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string_view>

#include <fmt/format.h>

#include "app/bench/bench_kiosk_child.hpp"
#include "app/bench/bench_latency_child.hpp"
#include "app/bench/bench_latency_jack.hpp"
#include "app/bench/bench_latency_x11.hpp"
#include "app/bench/bench_soak_figures.hpp"
#include "core/data_paths.hpp"
#include "core/config/scene_config.hpp"

namespace mallet::app {

namespace {

using latency::Child;

//! The pointer at rest before the still phase is measured: the last strike's bounce and
//! glow have faded (Eq. 1's visual decay) and the frames stop changing.
constexpr double kSettleS = 2.0;

std::string settings_text(const std::filesystem::path& metrics) {
  std::string t = "# written by `mallet bench render` for the kiosk under test\n";
  t += "[audio]\ndevice = \"system\"   # the JACK host API's device, on the bench's own JACK server\n";
  t += "sample_rate_hz = 48000\n";
  t += "[input]\nsource = \"mouse\"\nmouse = \"window\"\n";
  t += "[metrics]\ntextfile = \"" + metrics.string() + "\"\ninterval_s = 1\n";
  return t;
}

//! The kiosk's line saying how its frames are paced ("render: frames paced ..."), kept from
//! its output as it comes (the reader thread).
struct PaceLine {
  std::mutex mutex;
  std::string text = "(the kiosk did not say how its frames are paced)";
  void see(std::string_view line) {
    if (const std::size_t at = line.find("render: frames"); at != std::string_view::npos) {
      std::lock_guard lock(mutex);
      text = std::string(line.substr(at));
    }
  }
  std::string get() {
    std::lock_guard lock(mutex);
    return text;
  }
};

//! CPU time of a process so far; throws when it is gone.
std::int64_t cpu_ns(pid_t pid, const char* what) {
  const std::optional<soak::ProcessSample> s = soak::read_process(pid);
  if (!s) throw std::runtime_error(std::string("bench render: cannot read the ") + what + "'s CPU time from /proc");
  return s->cpu_ns;
}

std::uint64_t frames_of(const std::filesystem::path& metrics) {
  const std::optional<soak::KioskFigures> f = soak::parse_kiosk_figures(latency::read_all(metrics));
  return f ? f->frames : 0;
}

//! One kiosk, its two phases.
void measure_one(bool capped, int width, int height, double seconds, const std::string& device,
                 std::vector<KioskCpuRow>& rows) {
  const latency::KioskFolders folders("mallet-bench-cpu");
  const std::filesystem::path& metrics = folders.metrics;
  latency::write_text(folders.settings, settings_text(metrics));
  const Scene scene = config::load_scene(default_scene());

  latency::VirtualDisplay x(width, height);
  latency::JackServer jack("mallet-cpu-" + std::to_string(getpid()), 48000, 256);
  latency::FakePointer hand(x.name());
  const std::filesystem::path exe = latency::kiosk_executable("bench render");
  latency::ChildOptions o;
  // The attract mode after this long with nobody there: long enough for the still phase
  // (the visitor's pointer at rest) to be measured before it comes back.
  const double idle_after_s = kSettleS + seconds + 3.0;
  o.argv = {exe.string(), "run", "--config", folders.settings.string(), "--idle-after", std::to_string(idle_after_s)};
  if (!capped) o.argv.emplace_back("--no-frame-cap");
  if (!device.empty()) o.argv.insert(o.argv.end(), {"--device", device});
  o.env = folders.kiosk_env(x.name(), jack.name());
  auto pace = std::make_shared<PaceLine>();
  o.on_line = [pace](Nanos, std::string_view line) { pace->see(line); };
  Child kiosk(std::move(o));
  auto wait_for = [&](const char* what, const std::function<bool()>& done) {
    latency::wait_for_kiosk(kiosk, "bench render", what, 60 * kNanosPerSecond, done, [] {
      if (latency::stop_signal()) throw std::runtime_error("bench render: stopped by a signal");
    });
  };
  wait_for("a fullscreen window", [&] { return hand.find_window(width, height).has_value(); });
  wait_for("its metrics file", [&] { return frames_of(metrics) > 0; });

  const Nanos span = static_cast<Nanos>(std::llround(seconds * 1e9));
  // The frames as the metrics file has them just after one of its writes (every second):
  // polled every 10 ms until its count moves, so the count is at most that old.
  auto fresh_frames = [&](const std::function<void()>& during) {
    const std::uint64_t before = frames_of(metrics);
    for (const Nanos until = monotonic_now() + 3 * kNanosPerSecond; monotonic_now() < until;) {
      if (const std::uint64_t now = frames_of(metrics); now != before) return now;
      during();
      latency::sleep_ms(10);
    }
    throw std::runtime_error("bench render: the kiosk's metrics file stopped moving; its last lines:\n" +
                             kiosk.tail(10));
  };
  // A still phase draws no frames: its count is read as it is (at most a second old).
  auto measure = [&](const char* phase, const std::function<void()>& during, bool frames_move = true) {
    const std::uint64_t f0 = frames_move ? fresh_frames(during) : frames_of(metrics);
    const std::int64_t k0 = cpu_ns(kiosk.pid(), "kiosk"), x0 = cpu_ns(x.server().pid(), "X server");
    const Nanos t0 = monotonic_now();
    while (monotonic_now() - t0 < span && !latency::stop_signal()) during();
    const std::uint64_t f1 = frames_move ? fresh_frames(during) : frames_of(metrics);
    const std::int64_t k1 = cpu_ns(kiosk.pid(), "kiosk"), x1 = cpu_ns(x.server().pid(), "X server");
    const double wall = to_seconds(monotonic_now() - t0);
    KioskCpuRow r;
    r.capped = capped;
    r.phase = phase;
    r.cpu_percent = 100.0 * to_seconds(k1 - k0) / wall;
    r.x_server_percent = 100.0 * to_seconds(x1 - x0) / wall;
    r.fps = static_cast<double>(f1 - f0) / wall;
    rows.push_back(r);
  };
  // Nobody there: the attract mode starts after idle_after_s (and the present model has settled).
  latency::sleep_ms(1000 * (idle_after_s + 2.0));
  measure("attract", [] { latency::sleep_ms(50); });
  // A visitor: the pointer sweeps across the screen, dipping into the bars every 0.6 s.
  const double top = scene.screen_to_world.unmap({0.0, 0.08}).y, bottom = scene.screen_to_world.unmap({0.0, -0.02}).y;
  const Nanos start = monotonic_now();
  measure("play", [&] {
    const double t = to_seconds(monotonic_now() - start);
    const double sx = 0.5 + 0.4 * std::sin(2 * M_PI * t / 7.0);
    const double sy = top + (bottom - top) * 0.5 * (1 - std::cos(2 * M_PI * t / 0.6));
    hand.move_to(static_cast<int>(sx * width), static_cast<int>(sy * height));
    latency::sleep_ms(4);
  });
  // The visitor holds the mallet still above the bars: nothing on the screen changes.
  hand.move_to(width / 2, static_cast<int>((top - 0.05) * height));
  latency::sleep_ms(1000 * kSettleS);
  measure("still", [] { latency::sleep_ms(50); }, false);
  kiosk.stop();
  std::printf("  %s: %s\n", capped ? "capped" : "uncapped", pace->get().c_str());
}

}  // namespace

std::vector<KioskCpuRow> measure_kiosk_cpu(int width, int height, double seconds, const std::string& device) {
  latency::require_x_and_jack("bench render (the kiosk's CPU)");
  latency::StopSignals signals;
  std::vector<KioskCpuRow> rows;
  measure_one(true, width, height, seconds, device, rows);
  measure_one(false, width, height, seconds, device, rows);
  return rows;
}

TextTable kiosk_cpu_table(const std::vector<KioskCpuRow>& rows, int width, int height) {
  TextTable t;
  t.title = "The kiosk's CPU at " + std::to_string(width) + "x" + std::to_string(height) +
            ", with and without the frame budget";
  t.header = {"frames", "phase", "kiosk CPU % of a core", "frames/s", "X server CPU %"};
  for (const KioskCpuRow& r : rows)
    t.rows.push_back({r.capped ? "capped (max_fps = refresh)" : "uncapped (--no-frame-cap)", r.phase,
                      fmt::format("{:.1f}", r.cpu_percent), fmt::format("{:.1f}", r.fps),
                      fmt::format("{:.1f}", r.x_server_percent)});
  t.note = "The real kiosk, fullscreen on its own Xvfb (lavapipe), its sound on its own JACK server: the attract "
           "mode with nobody there, then play (an XTest pointer sweeping over the bars), then still (the pointer "
           "at rest above the bars: a frame that changes nothing is not drawn). The X server's share is the "
           "virtual display's copy of each frame, which a real display does not cost.";
  return t;
}

}  // namespace mallet::app
