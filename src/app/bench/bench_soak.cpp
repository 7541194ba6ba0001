// `mallet bench soak`: see bench_soak.hpp.
#include "app/bench/bench_soak.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "app/bench/bench_kiosk_child.hpp"
#include "app/bench/bench_latency_child.hpp"
#include "app/bench/bench_latency_jack.hpp"
#include "app/bench/bench_latency_onset.hpp"
#include "app/bench/bench_latency_x11.hpp"
#include "app/bench/bench_soak_figures.hpp"
#include "app/bench/bench_commands.hpp"
#include "core/data_paths.hpp"
#include "core/config/scene_config.hpp"

namespace mallet::app::soak {

namespace {

using latency::Child;
using latency::sleep_ms;
using latency::sleep_until;

constexpr int kWidth = 960, kHeight = 540;
// 1024 frames a JACK cycle (21 ms): the soak needs every sample and its time, not a short
// latency, and a long cycle keeps the bench's own server on time on a loaded 2-core machine
// (128 frames: 50 to 170 late cycles a minute there, each a seam the onset search skips).
constexpr int kRate = 48000, kPeriod = 1024;
constexpr Nanos kMs = 1'000'000;
constexpr Nanos kPlay = 120 * kNanosPerSecond;  // a visitor strikes for two minutes,
constexpr Nanos kAway = 60 * kNanosPerSecond;   // then leaves for one (the attract mode plays after 20 s)
constexpr double kIdleAfterS = 20.0;
// A strike's audio is scheduled at its impact + the alignment delay + the engine's schedule
// ahead (a few ms to ≈40 ms); its onset is looked for from 10 ms before the impact to
// 300 ms after (or to 10 ms before the next strike's impact).
constexpr Nanos kOnsetBefore = 10 * kMs, kOnsetAfter = 300 * kMs;

//! The kiosk's output: its strike times as they arrive, every line kept in OUT/kiosk.log.
struct SoakKioskLog {
  std::mutex mutex;
  bool started = false;
  std::deque<Nanos> strikes;  //!< not yet audited
  std::ofstream file;

  void line(std::string_view text) {
    std::lock_guard lock(mutex);
    file << text << '\n';
    if (const std::size_t at = text.find("strike t="); at != std::string_view::npos) {
      if (const std::optional<Nanos> t = latency::parse_log_seconds(text.substr(at + 9))) strikes.push_back(*t);
    } else if (text.find("mallet run:") != std::string_view::npos) {
      started = true;
    }
  }
};

//! Window pixels ↔ world metres (the window is the whole screen).
struct Mapping {
  ScreenToWorld s;
  int col_of_x(double x) const { return static_cast<int>(std::lround(s.unmap({x, 0.0}).x * kWidth)); }
  int row_of_y(double y) const {
    return std::clamp(static_cast<int>(std::lround(s.unmap({0.0, y}).y * kHeight)), 0, kHeight - 1);
  }
};

std::string soak_settings_text(const std::filesystem::path& metrics) {
  std::string t = "# written by `mallet bench soak` for the kiosk under test\n";
  t += "[audio]\ndevice = \"system\"   # the JACK host API's device, on the bench's own JACK server\n";
  t += "sample_rate_hz = " + std::to_string(kRate) + "\n";
  t += "[audio.routing]\nchannels = 2\nacoustic = 0\nactuator = 1\n";
  t += "[input]\nsource = \"mouse\"\nmouse = \"window\"\n";
  t += "[attract]\nidle_after_s = " + std::to_string(kIdleAfterS) + "\n";
  t += "[metrics]\ntextfile = \"" + metrics.string() + "\"\ninterval_s = 5\n";
  return t;
}

//! Every logged strike checked against the recorded channels, once its window is recorded.
class StrikeAudit {
 public:
  //! `lost_file`: a line for each lost strike, to look at it closer.
  StrikeAudit(latency::JackRecorder& recorder, SoakKioskLog& log, std::ofstream& lost_file, Nanos start)
      : recorder_(recorder), log_(log), lost_file_(lost_file), start_(start) {
    recorder_.start_recording(track_);
    lost_file_ << "hours,t_s,note_found,actuator_found,late_jack_cycles_near,ms_since_previous,ms_to_next\n" << std::flush;
  }
  //! Drains the recorder and audits the strikes whose window has been recorded.
  void step() {
    recorder_.drain(track_);
    if (track_.blocks.empty()) return;
    if (!recorded_from_) recorded_from_ = track_.blocks.front().t;
    const Nanos recorded_to = track_.time_of(track_.channels[0].size());
    std::deque<Nanos> fresh;
    {
      std::lock_guard lock(log_.mutex);
      fresh.swap(log_.strikes);
    }
    pending_.insert(pending_.end(), fresh.begin(), fresh.end());
    const std::vector<latency::Gap> gaps = track_.irregular(recorder_.period());
    // A strike is audited once its window and the next strike's start are in (600 ms on).
    while (!pending_.empty() && pending_.front() + kOnsetAfter + 300 * kMs < recorded_to) {
      const Nanos t = pending_.front();
      pending_.pop_front();
      const Nanos since = t - previous_;
      previous_ = t;
      // Struck before the recorder listened (the kiosk starting up): nothing to look at.
      if (t - kOnsetBefore - 20 * kMs < *recorded_from_) continue;
      Nanos to = t + kOnsetAfter;
      if (!pending_.empty()) to = std::max(t + kMs, std::min(to, pending_.front() - kOnsetBefore));
      const std::size_t i0 = track_.index_at(t - kOnsetBefore), i1 = track_.index_at(to);
      const bool note = latency::find_onset(track_.channels[0], i0, i1, {}, gaps).has_value();
      const bool actuator = latency::find_onset(track_.channels[1], i0, i1, {}, gaps).has_value();
      ++strikes;
      note_found += note;
      actuator_found += actuator;
      if (note && actuator) continue;
      ++lost;
      int late = 0;  // the JACK cycles around the window that came late: the seams find_onset skips
      for (const latency::Gap& g : gaps) late += g.end > i0 && g.begin < i1 + 2 * static_cast<std::size_t>(kRate) / 10;
      lost_near_late_cycles += late > 0;
      const std::string line = fmt::format("{:.4f},{:.9f},{},{},{},{:.1f},{:.1f}\n", to_seconds(t - start_) / 3600.0,
                                           to_seconds(t), note, actuator, late, to_seconds(since) * 1e3,
                                           pending_.empty() ? -1.0 : to_seconds(pending_.front() - t) * 1e3);
      lost_file_ << line << std::flush;
    }
    // Keep a second before what is still to be audited (the onset search's training window).
    const Nanos keep_from = (pending_.empty() ? recorded_to : std::min(pending_.front(), recorded_to)) -
                            kOnsetBefore - kNanosPerSecond;
    const std::size_t drop = track_.index_at(keep_from);
    if (drop > static_cast<std::size_t>(kRate) * 5) recorder_.forget_before(track_, drop);
  }
  std::uint64_t strikes = 0, actuator_found = 0, note_found = 0, lost = 0;
  std::uint64_t lost_near_late_cycles = 0;  //!< of `lost`: with a late JACK cycle in or near the window

 private:
  latency::JackRecorder& recorder_;
  SoakKioskLog& log_;
  std::ofstream& lost_file_;
  Nanos start_ = 0, previous_ = 0;
  std::optional<Nanos> recorded_from_;  //!< the first recorded sample's time
  latency::AudioTrack track_;
  std::deque<Nanos> pending_;
};

//! The scripted visitor: strokes bar after bar at speeds from soft to hard.
class Visitor {
 public:
  Visitor(const Scene& scene, latency::FakePointer& hand) : scene_(scene), map_{scene.screen_to_world}, hand_(hand) {}
  //! One stroke on the next bar: hover, a straight downswing (an event a millisecond) to
  //! 3 cm below the contact plane, a short hold, back up.
  void stroke() {
    const Target& t = scene_.targets[next_ % scene_.targets.size()];
    const double v = kSpeeds[next_ % std::size(kSpeeds)];
    ++next_;
    const double x = 0.5 * (t.x_min + t.x_max), contact = t.top_y + scene_.mallet_radius_m;
    const double top = contact + 0.04, bottom = contact - 0.03;
    move(x, top);
    sleep_ms(15);
    move(x, top);
    sleep_ms(150);
    const Nanos t0 = monotonic_now() + kMs;
    for (int k = 0;; ++k) {
      const Nanos due = t0 + k * kMs;
      const double y = std::max(bottom, top - v * to_seconds(due - t0));
      sleep_until(due);
      move(x, y);
      if (y <= bottom || latency::stop_signal()) break;
    }
    sleep_ms(80);
    for (int k = 1; k <= 20; ++k) {
      move(x, bottom + (top - bottom) * k / 20.0);
      sleep_ms(3.5);
    }
  }

 private:
  static constexpr double kSpeeds[] = {0.5, 1.0, 1.5, 2.0, 2.5, 0.8, 1.2};
  void move(double x, double y) { hand_.move_to(map_.col_of_x(x), map_.row_of_y(y)); }
  const Scene& scene_;
  Mapping map_;
  latency::FakePointer& hand_;
  std::size_t next_ = 0;
};

void write_file(const std::filesystem::path& p, const std::string& text) { latency::write_text(p, text); }

}  // namespace

int run_bench_soak(const SoakOptions& options) {
  latency::require_x_and_jack("bench soak");
  latency::StopSignals signals;
  std::filesystem::create_directories(options.out);
  const latency::KioskFolders folders("mallet-bench-soak");
  const std::filesystem::path& metrics = folders.metrics;
  latency::write_text(folders.settings, soak_settings_text(metrics));
  const Scene scene = config::load_scene(default_scene());
  if (scene.targets.empty()) throw std::runtime_error("bench soak: the shipped scene has no bars");

  latency::VirtualDisplay x(kWidth, kHeight);
  latency::JackServer jack("mallet-soak-" + std::to_string(getpid()), kRate, kPeriod);
  latency::JackRecorder recorder(jack.name(), 2);
  latency::FakePointer hand(x.name());

  auto log = std::make_shared<SoakKioskLog>();
  log->file.open(options.out / "kiosk.log");
  if (!log->file) throw std::runtime_error("bench soak: cannot write " + (options.out / "kiosk.log").string());
  const std::filesystem::path exe = latency::kiosk_executable("bench soak");
  latency::ChildOptions o;
  o.argv = {exe.string(), "run", "--windowed", "--size", std::to_string(kWidth) + "x" + std::to_string(kHeight),
            "--config", folders.settings.string()};
  if (!options.device.empty()) o.argv.insert(o.argv.end(), {"--device", options.device});
  o.env = folders.kiosk_env(x.name(), jack.name());
  o.on_line = [log](Nanos, std::string_view line) { log->line(line); };
  Child kiosk(std::move(o));

  // Up: it says it runs, its window is on the screen, its ports are connected.
  auto wait_for = [&](const char* what, const std::function<bool()>& done) {
    latency::wait_for_kiosk(kiosk, "bench soak", what, 60 * kNanosPerSecond, done, [] {
      if (latency::stop_signal()) throw std::runtime_error("bench soak: stopped by a signal while starting");
    });
  };
  wait_for("its start line", [&] {
    std::lock_guard lock(log->mutex);
    return log->started;
  });
  wait_for("a window on the screen", [&] { return hand.find_window(kWidth, kHeight).has_value(); });
  wait_for("audio ports on the JACK server", [&] { return !recorder.connect_source(std::chrono::milliseconds(0)).empty(); });
  wait_for("its metrics file", [&] { return parse_kiosk_figures(latency::read_all(metrics)).has_value(); });

  std::ofstream csv(options.out / "soak.csv");
  csv << csv_header() << '\n' << std::flush;
  if (!csv) throw std::runtime_error("bench soak: cannot write " + (options.out / "soak.csv").string());
  std::printf("bench soak: the windowed kiosk (pid %d) on %s, JACK server %s; %.2f h, a row every %.0f s in %s\n",
              static_cast<int>(kiosk.pid()), x.name().c_str(), jack.name().c_str(), options.hours,
              options.sample_every_s, (options.out / "soak.csv").c_str());
  std::printf("%8s %9s %4s %7s %9s %7s %7s %5s %9s %6s\n", "hours", "rss MiB", "fds", "threads", "vulkan MiB",
              "strokes", "strikes", "lost", "p99 ms", "xruns");
  std::fflush(stdout);

  Visitor visitor(scene, hand);
  const Nanos start_of_run = monotonic_now();
  std::ofstream lost_file(options.out / "lost_strikes.csv");
  StrikeAudit audit(recorder, *log, lost_file, start_of_run);
  std::vector<Minute> rows;
  const Nanos start = start_of_run;
  const Nanos end = start + static_cast<Nanos>(options.hours * 3600.0 * 1e9);
  const Nanos period = static_cast<Nanos>(options.sample_every_s * 1e9);
  const Nanos strike_every = static_cast<Nanos>(options.strike_every_s * 1e9);
  Nanos next_sample = start + period, next_stroke = start + kNanosPerSecond, next_clock = start;
  std::optional<KioskFigures> before = parse_kiosk_figures(latency::read_all(metrics));
  std::uint64_t strokes = 0, audited[4] = {0, 0, 0, 0}, xruns_before = recorder.xruns();
  std::string failure;
  while (!latency::stop_signal()) {
    const Nanos now = monotonic_now();
    if (!kiosk.running()) {
      failure = "the kiosk ended (" + kiosk.ended_how() + ") after " + std::to_string(to_seconds(now - start) / 3600.0) +
                " h; its last lines:\n" + kiosk.tail(15);
      break;
    }
    const bool playing = (now - start) % (kPlay + kAway) < kPlay;
    if (now >= next_stroke) {
      if (playing && now < end) {
        visitor.stroke();
        ++strokes;
      }
      next_stroke += strike_every;
    }
    if (now >= next_clock) {
      recorder.measure_clock();
      next_clock = now + 10 * kNanosPerSecond;
    }
    audit.step();
    if (now >= next_sample) {
      Minute m;
      m.hours = to_seconds(now - start) / 3600.0;
      const Nanos middle = now - period / 2 - start;
      m.state = middle % (kPlay + kAway) < kPlay ? "play" : "away";
      m.xruns = recorder.xruns() - xruns_before;
      xruns_before = recorder.xruns();
      if (const std::optional<ProcessSample> p = read_process(kiosk.pid())) {
        m.rss_mib = static_cast<double>(p->rss_bytes) / (1 << 20);
        m.fds = p->fds;
        m.threads = p->threads;
      }
      const std::optional<KioskFigures> f = parse_kiosk_figures(latency::read_all(metrics));
      if (f) {
        m.vulkan_mib = f->vulkan_bytes / (1 << 20);
        m.frames = before ? f->frames - before->frames : f->frames;
        m.frame_p99_ms = 1e3 * histogram_quantile(0.99, f->frame_seconds, before ? before->frame_seconds : Buckets{});
        before = f;
      }
      m.strokes = strokes;
      m.strikes = audit.strikes - audited[0];
      m.actuator = audit.actuator_found - audited[1];
      m.note = audit.note_found - audited[2];
      m.lost = audit.lost - audited[3];
      audited[0] = audit.strikes, audited[1] = audit.actuator_found, audited[2] = audit.note_found;
      audited[3] = audit.lost;
      strokes = 0;
      rows.push_back(m);
      csv << csv_row(m) << '\n' << std::flush;
      std::printf("%8.3f %9.1f %4d %7d %9.1f %7llu %7llu %5llu %9.2f %6llu\n", m.hours, m.rss_mib, m.fds, m.threads,
                  m.vulkan_mib, static_cast<unsigned long long>(m.strokes),
                  static_cast<unsigned long long>(m.strikes), static_cast<unsigned long long>(m.lost), m.frame_p99_ms,
                  static_cast<unsigned long long>(m.xruns));
      std::fflush(stdout);
      next_sample += period;
      if (now >= end) break;
    }
    sleep_ms(50);
  }
  kiosk.stop(std::chrono::milliseconds(3000));
  write_file(options.out / "soak.svg", svg_plot(rows));

  std::uint64_t strikes = 0, lost = 0;
  int fd_lo = 0, fd_hi = 0, th_lo = 0, th_hi = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    strikes += rows[i].strikes;
    lost += rows[i].lost;
    fd_lo = i ? std::min(fd_lo, rows[i].fds) : rows[i].fds;
    fd_hi = i ? std::max(fd_hi, rows[i].fds) : rows[i].fds;
    th_lo = i ? std::min(th_lo, rows[i].threads) : rows[i].threads;
    th_hi = i ? std::max(th_hi, rows[i].threads) : rows[i].threads;
  }
  std::printf("\ngrowth per hour over %zu rows (least squares):\n", rows.size());
  for (const Growth& g : growth_per_hour(rows)) std::printf("  %-13s %+10.4f %s\n", g.column.c_str(), g.per_hour, g.unit.c_str());
  std::printf("fds %d..%d, threads %d..%d; strikes %llu, lost %llu (%llu of them with a late cycle of the bench's "
              "JACK server near: see lost_strikes.csv); JACK xruns %llu\n",
              fd_lo, fd_hi, th_lo, th_hi, static_cast<unsigned long long>(strikes),
              static_cast<unsigned long long>(lost), static_cast<unsigned long long>(audit.lost_near_late_cycles),
              static_cast<unsigned long long>(recorder.xruns()));
  std::printf("wrote %s, %s and %s\n", (options.out / "soak.csv").c_str(), (options.out / "soak.svg").c_str(),
              (options.out / "kiosk.log").c_str());
  if (const int s = latency::stop_signal()) std::printf("stopped early by signal %d\n", s);
  if (!failure.empty()) {
    std::fprintf(stderr, "bench soak: %s\n", failure.c_str());
    return 1;
  }
  return lost == 0 ? 0 : 1;
}

}  // namespace mallet::app::soak

namespace mallet::app {

void add_bench_soak(CLI::App& bench) {
  auto o = std::make_shared<soak::SoakOptions>();
  CLI::App* cmd = bench.add_subcommand("soak", "Hours of the real windowed kiosk with a scripted visitor, watched for growth and lost strikes");
  cmd->footer(R"(Starts its own X server (Xvfb) and JACK server (jackd2, dummy driver, 1024-frame cycles) and runs
`mallet run --windowed` (960x540, the shipped scene, quality as shipped) under them. A scripted
visitor strikes a bar every --strike-every seconds with the X pointer (XTest), bar after bar,
0.5-2.5 m/s, for two minutes, then leaves for one (the attract mode's ghost plays after 20 s). Every --sample-every seconds a row of
OUT/soak.csv (OUT defaults to the current directory):
  hours,rss_mib,fds,threads,vulkan_mib,strokes,strikes,actuator_found,note_found,lost_strikes,frames,
  frame_p99_ms,visitor,jack_xruns
rss_mib, fds, threads: the kiosk process (/proc); vulkan_mib: its mallet_vulkan_device_memory_bytes;
strokes: the visitor's since the last row; strikes: the strikes the kiosk logged (visitor's and
ghost's) whose audio window was recorded since the last row; actuator_found, note_found: of those, the
ones whose onset was found on that channel by a JACK client of the bench's own; lost_strikes: strikes
missing on either channel; frames, frame_p99_ms: drawn since the last row and their p99 (from the
kiosk's mallet_frame_seconds histogram, as Prometheus' histogram_quantile); visitor: play or away
(mid-row); jack_xruns: cycles of the bench's JACK server that came late (this machine's load). Each lost
strike gets a line of OUT/lost_strikes.csv:
  hours,t_s,note_found,actuator_found,late_jack_cycles_near,ms_since_previous,ms_to_next
At the end: OUT/soak.svg (a panel per figure), OUT/kiosk.log (everything the kiosk printed) and the
growth per hour of each figure (least squares). Exit status 0: no strike lost and the kiosk ran to the
end; 1 otherwise, or when a server or the kiosk cannot run here. Ctrl+C ends it early, with the rows so far.)");
  cmd->add_option("--hours", o->hours, "How long (hours, fractions allowed)")->required()->check(CLI::Range(0.001, 336.0));
  cmd->add_option("--out", o->out, "Output directory (default: the current directory)")->capture_default_str();
  cmd->add_option("--strike-every", o->strike_every_s, "Seconds between two strokes of the scripted visitor")
      ->capture_default_str()
      ->check(CLI::Range(0.5, 60.0));
  cmd->add_option("--sample-every", o->sample_every_s, "Seconds between two rows of soak.csv")
      ->capture_default_str()
      ->check(CLI::Range(5.0, 3600.0));
  cmd->add_option("--device", o->device, "The kiosk's Vulkan device (substring of its name; default: its own choice)");
  cmd->callback([o] { finish_with(soak::run_bench_soak(*o)); });
}

}  // namespace mallet::app
