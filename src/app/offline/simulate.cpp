#include "app/offline/simulate.hpp"

#include <algorithm>
#include <atomic>
#include <cinttypes>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "audio/audio_setup.hpp"
#include "app/common/settings_source.hpp"
#include "audio/wav_file.hpp"
#include "core/scene_layout.hpp"
#include "core/actuator_signal.hpp"
#include "core/camera_prediction.hpp"
#include "core/config/app_config_loader.hpp"
#include "core/config/scene_config.hpp"
#include "core/file_error.hpp"
#include "core/present_clock.hpp"
#include "core/text_lines.hpp"
#include "core/visual_vibration.hpp"
#include "input/trajectory_csv.hpp"

namespace mallet::app {

namespace fs = std::filesystem;

SimulateInterrupted::SimulateInterrupted(int signal)
    : std::runtime_error(std::string("simulate: stopped by ") + (signal == SIGINT ? "SIGINT" : "SIGTERM") +
                         "; the partial outputs were removed"),
      signal_(signal) {}

namespace {

// The signal that asked us to stop while writing (0: none). The handler only stores it
// (async-signal-safe: a lock-free atomic); the writing loops check it and throw, and the
// partial files are removed by StagedOutput's destructor on the ordinary unwinding path.
std::atomic<int> g_stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);
extern "C" void on_stop_signal(int s) { g_stop_signal.store(s); }

//! SIGINT/SIGTERM set g_stop_signal while the outputs are being written; the previous
//! handlers come back afterwards. Before it (reading, validating, the replay) nothing is
//! on disk, so the default action, ending at once, is right.
class StopSignals {
 public:
  StopSignals() {
    g_stop_signal.store(0);
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    for (std::size_t i = 0; i < 2; ++i) sigaction(kSignals[i], &sa, &old_[i]);
  }
  ~StopSignals() {
    for (std::size_t i = 0; i < 2; ++i) sigaction(kSignals[i], &old_[i], nullptr);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

  //! Throws SimulateInterrupted once a signal has arrived.
  static void check() {
    if (const int s = g_stop_signal.load(std::memory_order_relaxed)) throw SimulateInterrupted(s);
  }

 private:
  static constexpr int kSignals[2] = {SIGINT, SIGTERM};
  struct sigaction old_[2]{};
};

//! The line of data row `index` (0-based, as parse_trajectory_csv numbered its samples):
//! the parser keeps one sample per row after the header, skipping blank and '#' lines.
std::uint32_t trajectory_row_line(std::string_view text, std::size_t index) {
  text::Lines lines(text);
  bool header = true;
  std::size_t row = 0;
  while (auto raw = lines.next()) {
    const std::string_view line = text::trim(*raw);
    if (line.empty() || line.front() == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    if (row++ == index) return lines.number();
  }
  return 0;
}

std::string gigabytes(double bytes) {
  return fmt::format("{:.1f} GB", bytes / 1e9);
}

std::string g9(double v) {
  return fmt::format("{:.9g}", v);
}

//! Files are written under temporary names and renamed only when all are complete.
class StagedOutput {
 public:
  explicit StagedOutput(fs::path dir) : dir_(std::move(dir)) {}
  ~StagedOutput() {
    if (committed_) return;
    std::error_code ec;
    for (const fs::path& p : staged_) fs::remove(temp_of(p), ec);
    if (created_dir_) fs::remove(dir_, ec);  // only if we made it and it is empty again
  }

  void prepare() {
    std::error_code ec;
    if (fs::exists(dir_, ec) && !fs::is_directory(dir_, ec))
      throw std::runtime_error(dir_.string() + ": exists and is not a directory");
    if (!fs::exists(dir_, ec)) {
      fs::create_directories(dir_, ec);
      if (ec) throw std::runtime_error(dir_.string() + ": cannot create: " + ec.message());
      created_dir_ = true;
    }
  }
  fs::path stage(const std::string& name) {
    staged_.push_back(dir_ / name);
    return temp_of(staged_.back());
  }
  std::vector<fs::path> commit() {
    for (const fs::path& p : staged_) {
      std::error_code ec;
      fs::rename(temp_of(p), p, ec);
      if (ec) throw std::runtime_error(p.string() + ": cannot write: " + ec.message());
    }
    committed_ = true;
    return staged_;
  }

 private:
  static fs::path temp_of(const fs::path& p) { return p.string() + ".partial"; }
  fs::path dir_;
  std::vector<fs::path> staged_;
  bool created_dir_ = false;
  bool committed_ = false;
};

void check_stream(std::ofstream& out, const fs::path& path) {
  out.flush();
  if (!out) throw std::runtime_error(path.string() + ": write failed");
}

}  // namespace

SimulateResult run_simulate(const SimulateOptions& options) {
  // --- everything that can be wrong with the input is found before anything is written
  AppConfig config = command_settings(options.config, options.config_dir, "simulate");
  SimulateResult result;
  result.scene = laid_out(config::load_scene(options.scene), options.layout);
  const Scene& scene = result.scene;
  double input_delay_ms = options.input_delay_ms;
  if (options.causal && options.camera) {  // the kiosk's camera route, from the same settings
    const CameraRouteTiming camera = camera_route_timing(config, scene);
    config.timing.predict = camera.predict;
    if (!options.input_delay_given) input_delay_ms = camera.read_delay_ms;
  }
  const std::string trajectory_text = text::read_file(options.input);
  const input::Trajectory trajectory = input::parse_trajectory_csv(trajectory_text, options.input.string());

  // --sample-rate, --trace-rate and --tail are checked by their flags (cmd_simulate.cpp).
  const int rate = options.sample_rate_hz.value_or(config.audio.sample_rate_hz);
  for (const Material& m : scene.materials)
    if (auto problem = actuator_band_problem(m, rate)) throw FileError(scene.file, 0, 0, *problem);
  // An hour of trajectory is the most written without asking (kLongTrajectoryS): the row
  // that first goes past it is named, with what would be written.
  const auto past = std::find_if(trajectory.samples.begin(), trajectory.samples.end(), [](const PointerSample& p) {
    return to_seconds(p.t_ns) > kLongTrajectoryS;
  });
  if (past != trajectory.samples.end() && !options.allow_long) {
    const double last_s = to_seconds(trajectory.samples.back().t_ns);
    const double audio_bytes = (last_s + options.tail_s) * rate * config.audio.routing.channels * 4.0;
    const std::string what = fmt::format(
        "t = {:.9g} s is more than an hour after t = 0 (is t in milliseconds? it must be in seconds); the outputs "
        "would run to {:.0f} s (audio.wav alone {}); --allow-long writes them anyway",
        to_seconds(past->t_ns), last_s + options.tail_s, gigabytes(audio_bytes));
    throw FileError(options.input.string(),
                    trajectory_row_line(trajectory_text, static_cast<std::size_t>(past - trajectory.samples.begin())),
                    0, what);
  }
  result.sample_rate_hz = rate;
  audio::AudioRig rig = audio::make_audio_rig(scene, config, rate);

  // --- the contact solver, fed exactly as the kiosk feeds it
  std::optional<CausalTiming> causal;
  const PresentClock picture(options.display_hz, options.present_mode);
  if (options.causal)
    causal = CausalTiming{static_cast<Nanos>(std::llround(input_delay_ms * 1e6)), &picture};
  const Replay replay(scene, config, trajectory, options.input_space, options.input.string(), causal);
  const Nanos ahead = static_cast<Nanos>(std::llround(config.audio.schedule_ahead_ms * 1e6));
  result.impacts = replay.impacts();
  result.counters = replay.counters();
  const std::vector<HandSample>& path = replay.path();

  const Nanos t_end = path.back().t + static_cast<Nanos>(std::llround(options.tail_s * 1e9));

  // Declared before `out`: its handlers stay until the partial files are gone.
  const StopSignals stop_signals;
  StagedOutput out(options.out_dir);
  out.prepare();

  // --- events.csv
  {
    const fs::path path_events = out.stage("events.csv");
    std::ofstream f(path_events);
    f << "t,target,instrument,material,note,velocity" << (causal ? ",contact_t,sound_t,shown_t,predicted" : "")
      << '\n';
    for (const Strike& s : replay.strikes()) {
      StopSignals::check();
      const Impact& i = s.impact;
      const Target& t = scene.targets[i.target];
      f << format_seconds(i.t_ns) << ',' << t.id << ',' << t.instrument << ','
        << scene.materials[i.material].name << ',' << i.note << ',' << g9(i.speed_m_per_s);
      if (causal)
        f << ',' << format_seconds(i.t_ns) << ',' << format_seconds(s.heard_ns + ahead) << ','
          << format_seconds(s.shown_ns) << ',' << (i.predicted ? 1 : 0);
      f << '\n';
    }
    check_stream(f, path_events);
  }

  // --- cursor.csv: the displayed head = held hand + the visual vibration along the normal.
  // Texture scenes add the Speed technique's gain and the stripes' phase (Eq. 1 of the
  // second paper), computed by the same StripeSignal the audio engine runs, fed the same
  // motion updates on the same samples.
  const std::vector<TextureSample>& texture_path = replay.texture_path();
  {
    const fs::path path_cursor = out.stage("cursor.csv");
    std::ofstream f(path_cursor);
    f << "t,hand_x,hand_y,cursor_x,cursor_y,offset" << (scene.texture ? ",gain,stripe_phase" : "") << '\n';
    std::optional<StripeSignal> stripes;
    if (scene.texture) stripes.emplace(scene.texture->stripes, rate);
    std::size_t next_motion = 0;
    std::int64_t stripe_pos = 0;
    std::vector<double> scratch;
    const Nanos t0 = path.front().t;
    for (std::uint64_t k = 0;; ++k) {
      const Nanos t = t0 + static_cast<Nanos>(std::llround(static_cast<double>(k) * 1e9 / options.trace_rate_hz));
      if (t > t_end) break;
      StopSignals::check();
      const CursorState c = replay.cursor_at(t);
      f << format_seconds(t) << ',' << g9(c.hand.x) << ',' << g9(c.hand.y) << ',' << g9(c.shown.x) << ','
        << g9(c.shown.y) << ',' << g9(c.offset);
      if (stripes) {
        // Up to this row's sample: every motion update applied on its own sample, as the
        // engine applies it, and the samples between them rendered.
        const std::int64_t at = std::max<std::int64_t>(0, align_to_sample(t, rate).index);
        for (;;) {
          while (next_motion < texture_path.size() &&
                 align_to_sample(texture_path[next_motion].t, rate).index <= stripe_pos) {
            const StripeMotion& m = texture_path[next_motion++].motion;
            stripes->motion(m.speed_m_per_s, m.on_texture);
          }
          if (stripe_pos >= at) break;
          std::int64_t until = at;
          if (next_motion < texture_path.size())
            until = std::min(until, align_to_sample(texture_path[next_motion].t, rate).index);
          scratch.assign(static_cast<std::size_t>(until - stripe_pos), 0.0);
          stripes->add_to(scratch.data(), static_cast<int>(scratch.size()), 0.0);
          stripe_pos = until;
        }
        f << ',' << g9(c.gain) << ',' << g9(stripes->current_phase());
      }
      f << '\n';
      ++result.cursor_rows;
    }
    check_stream(f, path_cursor);
  }

  // --- audio.wav: sample 0 is t = 0 of the trajectory's clock. The engine is the
  // kiosk's own; each impact is posted just before the block it falls in, as the input
  // thread would, so every strike starts on its own sample.
  {
    const AudioRouting& routing = config.audio.routing;
    audio::WavWriter wav(out.stage("audio.wav"), routing.channels, rate);
    const SampleAlignment end = align_to_sample(t_end, rate);
    const std::int64_t frames = std::max<std::int64_t>(end.index, 1);
    constexpr int kBlock = 1024;
    std::vector<float> block(static_cast<std::size_t>(kBlock * routing.channels));
    std::size_t next_impact = 0, next_motion = 0;
    for (std::int64_t first = 0; first < frames; first += kBlock) {
      StopSignals::check();
      const int n = static_cast<int>(std::min<std::int64_t>(kBlock, frames - first));
      const std::int64_t block_end = first + n;
      // Posted before the block it is heard in (t + the route's delay: --causal).
      while (next_impact < result.impacts.size() &&
             align_to_sample(result.impacts[next_impact].t_ns + result.impacts[next_impact].delay_ns, rate).index <
                 block_end)
        rig.engine->post(result.impacts[next_impact++]);
      // The stripes' motion updates, as the input thread posts them. At most the ring's
      // capacity per block (a 1024-frame block holds far fewer pointer samples).
      for (std::size_t posted = 0; next_motion < texture_path.size() && posted < audio::AudioEngine::kRingCapacity &&
                                   align_to_sample(texture_path[next_motion].t, rate).index < block_end;
           ++posted)
        rig.engine->post_motion(texture_path[next_motion++].motion);
      rig.engine->process(block.data(), n);
      wav.write(std::span<const float>(block.data(), static_cast<std::size_t>(n * routing.channels)));
    }
    wav.close();
    result.audio_frames = static_cast<std::uint64_t>(frames);
    result.clipped_samples = rig.engine->counters().clipped;
  }

  StopSignals::check();  // the last chance: after the renames the outputs are whole
  result.written = out.commit();
  return result;
}

}  // namespace mallet::app
