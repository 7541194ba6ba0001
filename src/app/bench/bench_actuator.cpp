// `mallet bench actuator`: `mallet calibrate actuator` (and `calibrate latency`, loopback and
// photodiode: bench_photodiode.hpp) run against a known actuator chain and a known display, so
// that what it recovers can be set against the truth. On a JACK server of the bench's own
// (the dummy driver: no sound card), a plant client stands where the amplifier, voice coil,
// stick and sensor would be: it takes the kiosk's actuator output port, filters it through
// audio/simulated_plant.hpp (a resonance, a second pole, a pure delay of whole samples) and
// feeds the result to the kiosk's first capture port, and the unfiltered signal to its
// second (a loopback cable). Then `mallet calibrate actuator --loopback 2` measures, and
// `--verify` plays Table 1's strikes through the same plant.
//
// Prints: the recovered magnitude against the plant's exact response over the usable band,
// the recovered delay against the injected one (the sound card's round trip, measured by
// the loopback, taken off), the felt-signal table before and after the inverse, and the round
// trip `mallet calibrate latency` finds on a loopback delayed by a known amount, and the display
// latency its photodiode finds for the kiosk on an X server of the bench's own. Targets (issue:
// the actuator measured through the sound card): magnitude within 1 dB, delay within 1 sample,
// B and f within 3 % after the inverse, the loopback's latency within 0.5 ms, the display's
// within one frame's scan-out.
#include <X11/keysym.h>
#include <jack/jack.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <unistd.h>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "app/bench/bench_commands.hpp"
#include "app/bench/bench_latency_child.hpp"
#include "app/bench/bench_kiosk_child.hpp"
#include "app/bench/bench_latency.hpp"
#include "app/bench/bench_latency_jack.hpp"
#include "app/bench/bench_latency_rig.hpp"
#include "app/bench/bench_latency_x11.hpp"
#include "app/bench/bench_photodiode.hpp"
#include "app/common/command_support.hpp"
#include "app/common/timing_drop_in.hpp"
#include "app/common/programs.hpp"
#include "audio/simulated_plant.hpp"
#include "core/actuator_eq_file.hpp"
#include "render/image.hpp"

namespace mallet::app {

namespace {

// The plant as a JACK client: in → plant → sensor; in → loopback. Real-time safe: the
// plant's delay line is preallocated and tick() only does arithmetic.
class JackPlant {
 public:
  JackPlant(const std::string& server, const audio::PlantSpec& spec) : plant_(spec), loop_line_(kMaxLoopDelay + 1, 0.0f) {
    jack_status_t status{};
    client_ = jack_client_open("mallet-plant", static_cast<jack_options_t>(JackNoStartServer | JackServerName), &status,
                               server.c_str());
    if (!client_) throw std::runtime_error("bench actuator: cannot open the plant's JACK client");
    in_ = jack_port_register(client_, "in", JACK_DEFAULT_AUDIO_TYPE, JackPortIsInput, 0);
    sensor_ = jack_port_register(client_, "sensor", JACK_DEFAULT_AUDIO_TYPE, JackPortIsOutput, 0);
    loopback_ = jack_port_register(client_, "loopback", JACK_DEFAULT_AUDIO_TYPE, JackPortIsOutput, 0);
    if (!in_ || !sensor_ || !loopback_) throw std::runtime_error("bench actuator: cannot register the plant's ports");
    jack_set_process_callback(client_, &JackPlant::process, this);
    jack_set_xrun_callback(client_, &JackPlant::xrun, this);
    if (jack_activate(client_) != 0) throw std::runtime_error("bench actuator: cannot activate the plant");
  }
  ~JackPlant() {
    jack_deactivate(client_);
    jack_client_close(client_);
  }
  JackPlant(const JackPlant&) = delete;
  JackPlant& operator=(const JackPlant&) = delete;

  //! Wires the plant to the one client that is neither the system nor the plant (the kiosk's
  //! PortAudio stream) once it has `outputs` output ports and an input port: its output port
  //! `actuator` into the plant, the plant's sensor into its input 1 and the loopback into its
  //! input 2 (when the stream records two).
  //! True when wired; waits up to `timeout`.
  bool wire(int outputs, int actuator, std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    do {
      std::map<std::string, std::vector<std::string>> outs = latency::ports_by_client(client_, JackPortIsOutput),
                                                      ins = latency::ports_by_client(client_, JackPortIsInput);
      for (auto& [client, o] : outs) {
        auto in = ins.find(client);
        if (in == ins.end() || static_cast<int>(o.size()) < outputs || in->second.empty()) continue;
        const auto ok = [](int e) { return e == 0 || e == EEXIST; };
        const bool a = ok(jack_connect(client_, o[static_cast<std::size_t>(actuator)].c_str(), jack_port_name(in_)));
        const bool s = ok(jack_connect(client_, jack_port_name(sensor_), in->second[0].c_str()));
        const bool l = in->second.size() < 2 || ok(jack_connect(client_, jack_port_name(loopback_), in->second[1].c_str()));
        if (a && s && l) return true;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    } while (std::chrono::steady_clock::now() < deadline);
    return false;
  }

  static constexpr int kMaxLoopDelay = 48000;
  //! The loopback cable's own delay in samples (0 to kMaxLoopDelay): a sound card's round
  //! trip for `mallet calibrate latency` to find. Set between runs.
  void set_loopback_delay(int samples) { loopback_delay_.store(samples, std::memory_order_relaxed); }
  //! The JACK server's xruns so far (a cycle late: samples lost or repeated on every port).
  std::uint64_t xruns() const { return xruns_.load(std::memory_order_relaxed); }

 private:
  static int xrun(void* self) {
    static_cast<JackPlant*>(self)->xruns_.fetch_add(1, std::memory_order_relaxed);
    return 0;
  }

  static int process(jack_nframes_t frames, void* self) {
    auto& p = *static_cast<JackPlant*>(self);
    const auto* in = static_cast<const float*>(jack_port_get_buffer(p.in_, frames));
    auto* sensor = static_cast<float*>(jack_port_get_buffer(p.sensor_, frames));
    auto* loopback = static_cast<float*>(jack_port_get_buffer(p.loopback_, frames));
    const auto delay = static_cast<std::size_t>(p.loopback_delay_.load(std::memory_order_relaxed));
    const std::size_t n = p.loop_line_.size();
    for (jack_nframes_t i = 0; i < frames; ++i) {
      p.loop_line_[p.loop_pos_] = in[i];
      loopback[i] = p.loop_line_[(p.loop_pos_ + n - delay) % n];
      p.loop_pos_ = (p.loop_pos_ + 1) % n;
      sensor[i] = static_cast<float>(p.plant_.tick(in[i]));
    }
    return 0;
  }

  audio::SimulatedPlant plant_;
  jack_client_t* client_ = nullptr;
  jack_port_t* in_ = nullptr;
  jack_port_t* sensor_ = nullptr;
  jack_port_t* loopback_ = nullptr;
  std::vector<float> loop_line_;  // the loopback's delay line, preallocated
  std::size_t loop_pos_ = 0;      // the process thread's
  std::atomic<int> loopback_delay_{0};
  std::atomic<std::uint64_t> xruns_{0};
};

struct ActuatorBenchOptions {
  std::string kind = "low-pass";
  double resonance_hz = 180, q = 4, rolloff_hz = 1000;
  int delay_samples = 37;
  int period = 1024;  // 21 ms cycles: a busy machine (the sanitizer suite in parallel) keeps up
  int loopback_delay = 240;
  double panel_lag_ms = 25;  // the bench's panel: light this long after the X server shows a frame
  bool photodiode = true;
  std::filesystem::path page_shot;  // the operator page asking, as a PNG (empty: none)
  std::filesystem::path out_dir;
};


// What a run of `mallet` has besides the plant: more of its environment (the bench's X
// server), a look at each of its lines as it comes, and a call in each of the bench's polls
// while it runs (from the bench's thread: the photodiode's wiring, the operator's key).
struct RunExtras {
  std::vector<std::pair<std::string, std::string>> env;
  std::function<void(std::string_view)> on_line;
  std::function<void()> each_poll;
};

// Runs `mallet ARGS` with the bench's JACK server, wiring the plant while it runs; its output
// goes to ours. Returns its exit status.
int run_mallet_once(const std::vector<std::string>& args, const std::string& server, const std::filesystem::path& state,
                    JackPlant& plant, std::vector<std::string>* lines, const RunExtras& extras) {
  const std::filesystem::path mallet = sibling_program("mallet");
  if (mallet.empty()) throw std::runtime_error("bench actuator: the program mallet is not installed beside mallet-bench");
  latency::ChildOptions o;
  o.argv = {mallet.string()};
  o.argv.insert(o.argv.end(), args.begin(), args.end());
  o.env = {{"JACK_DEFAULT_SERVER", server}, {"MALLET_STATE_DIR", state.string()}, {"JACK_NO_AUDIO_RESERVATION", "1"}};
  o.env.insert(o.env.end(), extras.env.begin(), extras.env.end());
  std::mutex lines_mutex;
  o.on_line = [&](Nanos, std::string_view line) {
    std::printf("  | %.*s\n", static_cast<int>(line.size()), line.data());
    if (extras.on_line) extras.on_line(line);
    std::lock_guard lock(lines_mutex);
    if (lines) lines->emplace_back(line);
  };
  latency::Child child(std::move(o));
  // Each recording is a stream of its own (a new JACK client): wired as it appears, as a
  // sound card stays wired.
  bool wired = false;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (child.running()) {
    wired = plant.wire(2, 1, std::chrono::milliseconds(0)) || wired;
    if (extras.each_poll) extras.each_poll();
    if (!wired && std::chrono::steady_clock::now() > give_up) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  child.stop();
  std::lock_guard lock(lines_mutex);
  std::fflush(stdout);
  const std::string how = child.ended_how();
  if (!wired) throw std::runtime_error("bench actuator: the calibration's JACK ports never appeared (" + how + ")");
  return how == "exit 0" ? 0 : (how == "exit 2" ? 2 : 1);
}

// run_mallet_once, again (three times in all) while the JACK server ran late during it: the
// dummy driver on a busy machine skips cycles, which PortAudio's stream does not see, and a
// measurement that lost samples is not one. A real card's xruns reach the stream's own flags.
// `late_kept`, when given, is set to how often the JACK server ran late during the run kept
// (0: a clean run).
int run_mallet(const std::vector<std::string>& args, const std::string& server, const std::filesystem::path& state,
               JackPlant& plant, std::vector<std::string>* lines = nullptr, const RunExtras& extras = {},
               std::uint64_t* late_kept = nullptr) {
  int status = 0;
  for (int attempt = 1; attempt <= 3; ++attempt) {
    const std::uint64_t before = plant.xruns();
    if (lines) lines->clear();
    status = run_mallet_once(args, server, state, plant, lines, extras);
    const std::uint64_t xruns = plant.xruns() - before;
    if (late_kept) *late_kept = xruns;
    if (xruns == 0) break;
    std::printf("  (the JACK server ran late %llu time(s) during that run%s)\n", static_cast<unsigned long long>(xruns),
                attempt < 3 ? ": again" : ": kept, measure on a quieter machine");
    std::fflush(stdout);
  }
  return status;
}

// The exit status when the display latency could not be measured on this machine (the other
// figures are written): automake's and CTest's "skipped".
constexpr int kActuatorBenchUnmeasured = 77;

// A frame's scan-out at 60 Hz: the issue's bound on the display latency's error.
constexpr double kFrameMs = 1000.0 / 60;

struct SquareSeen {
  Nanos present = 0;
  double latency_ms = 0;
};

// The X server's whole screen as a PNG: what the operator sees.
void write_screen(const std::string& display, const std::filesystem::path& file) {
  latency::ScreenReader reader(display);
  latency::Grab g;
  if (!reader.grab({0, 0, latency::kWidth, latency::kHeight}, g))
    throw std::runtime_error("bench actuator: cannot read the screen for " + file.string());
  render::Image image(latency::kWidth, latency::kHeight);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint32_t p = g.rgb[static_cast<std::size_t>(y * image.width + x)];
      std::uint8_t* px = image.at(x, y);
      px[0] = static_cast<std::uint8_t>(p >> 16), px[1] = static_cast<std::uint8_t>(p >> 8);
      px[2] = static_cast<std::uint8_t>(p), px[3] = 255;
    }
  render::write_png(image, file);
  std::printf("  (the operator page asking: %s)\n", file.string().c_str());
}

// `mallet calibrate latency --loopback 2 --photodiode 3` on the bench's own X server: the kiosk
// shows its latency test's squares, the photodiode client lights capture 3 `panel_lag_ms`
// after the X server shows each, and the bench answers the page's question with Enter.
// Writes its rows into `out`. False when the figures are outside their target and the JACK
// server ran late in each of the runs: the light may then have reached the kiosk's stream up
// to a period late, so they time the bench's own JACK, not the kiosk (they are still printed
// and written, beside the late cycles' count). Within the target, a late run still counts.
bool run_photodiode_step(const ActuatorBenchOptions& o, const std::string& server, const std::filesystem::path& settings,
                         JackPlant& plant, std::ofstream& out) {
  latency::require_x_and_jack("bench actuator");
  latency::VirtualDisplay x(latency::kWidth, latency::kHeight);
  const Nanos lag = static_cast<Nanos>(std::llround(o.panel_lag_ms * 1e6));
  latency::JackPhotodiode diode(server, x.name(), {2, 2, 6, 6}, lag);
  latency::FakePointer keyboard(x.name());
  std::printf("\nmallet calibrate latency --loopback 2 --photodiode 3 (the kiosk on the bench's X server %s; a panel "
              "lighting %.1f ms after the X server shows a frame):\n",
              x.name().c_str(), o.panel_lag_ms);
  std::fflush(stdout);
  std::mutex mutex;
  std::vector<SquareSeen> squares;
  std::atomic<bool> measured{false}, answered{false};
  double recovered = -1;
  RunExtras extras;
  extras.env = {{"DISPLAY", x.name()}};
  if (const std::optional<std::string> preload = latency::child_preload()) extras.env.emplace_back("LD_PRELOAD", *preload);
  extras.on_line = [&](std::string_view line) {
    const std::string l(line);
    if (const std::size_t at = l.find("PortAudio's input latency "); at != std::string::npos) {
      // A measurement starts (again, when the bench runs it again): what the last one saw is forgotten.
      diode.set_input_latency(static_cast<Nanos>(std::llround(std::atof(l.c_str() + at + 26) * 1e6)));
      std::lock_guard lock(mutex);
      squares.clear();
      measured = false;
      answered = false;
    }
    if (const std::size_t at = l.find("photodiode: square "); at != std::string::npos) {
      const std::size_t t = l.find("present t=", at), ms = l.find(", light ", at);
      if (t != std::string::npos && ms != std::string::npos)
        if (const std::optional<Nanos> present = latency::parse_log_seconds(l.substr(t + 10, ms - t - 10))) {
          std::lock_guard lock(mutex);
          squares.push_back({*present, std::atof(l.c_str() + ms + 8)});
        }
    }
    if (l.find("photodiode: display latency ") != std::string::npos) measured = true;
    std::sscanf(l.c_str(), "display latency: %lf ms", &recovered);
  };
  extras.each_poll = [&] {
    diode.wire(2);  // each run's stream is a JACK client of its own, wired as it appears
    if (measured && !answered) {  // the operator reads the page's result, then Enter saves it
      latency::sleep_ms(300);
      if (!o.page_shot.empty()) write_screen(x.name(), o.page_shot);
      keyboard.press_key(XK_Return);
      answered = true;
    }
  };
  std::vector<std::string> lines;
  const std::vector<std::string> args = {"calibrate", "latency", "--loopback", "2", "--photodiode", "3",
                                         "--config", settings.string(), "--input", "system"};
  std::uint64_t late = 0;
  if (const int status = run_mallet(args, server, o.out_dir, plant, &lines, extras, &late); status != 0)
    throw std::runtime_error(fmt::format("bench actuator: mallet calibrate latency --photodiode ended with {}", status));
  const std::filesystem::path drop_in = o.out_dir / "measured.d" / kDisplayLatencyDropIn;  // its state folder's
  if (!std::filesystem::exists(drop_in))
    throw std::runtime_error("bench actuator: Enter on the page did not save " + drop_in.string());

  // Each square against the truth: when the X server showed it, plus the panel's lag.
  const std::vector<Nanos> white = diode.turned_white();
  std::vector<double> truth_ms, error_ms;
  for (const SquareSeen& s : squares) {
    const auto near = std::min_element(white.begin(), white.end(), [&](Nanos a, Nanos b) {
      return std::llabs(a - s.present) < std::llabs(b - s.present);
    });
    if (near == white.end() || std::llabs(*near - s.present) > 100'000'000) continue;
    const double truth = static_cast<double>(*near + lag - s.present) / 1e6;
    truth_ms.push_back(truth);
    error_ms.push_back(s.latency_ms - truth);
  }
  if (truth_ms.empty()) throw std::runtime_error("bench actuator: no square of the kiosk's was seen on the X server");
  // The truths' median as the kiosk takes its own; the square whose error is largest, its sign kept.
  const double truth = *latency::summarise(truth_ms).median;
  const double worst = *latency::summarise(error_ms).max;
  std::printf("  display latency: %.3f ms recovered (%zu squares); the truth %.3f ms (the panel's %.1f ms and the X "
              "server's own %.3f ms after the present, the median): error %+.3f ms, worst square %+.3f ms (target: "
              "within one frame's scan-out, %.1f ms); %llu of the photodiode's changes late, %llu polls of the corner\n",
              recovered, squares.size(), truth, o.panel_lag_ms, truth - o.panel_lag_ms, recovered - truth, worst,
              kFrameMs, static_cast<unsigned long long>(diode.late()), static_cast<unsigned long long>(diode.polls()));
  out << fmt::format("display_latency_ms,{:.4f},{:.4f},{:.4f},{:.1f}\n", recovered, truth, recovered - truth, kFrameMs);
  out << fmt::format("display_square_worst_ms,{:.4f},0,{:.4f},{:.1f}\n", worst, worst, kFrameMs);
  out << fmt::format("display_jack_late_cycles,{},0,{},0\n", late, late);
  const bool within = std::abs(recovered - truth) < kFrameMs && std::abs(worst) < kFrameMs;
  return within || late == 0;
}

void run_bench_actuator(const ActuatorBenchOptions& o) {
  const int rate = 48000;
  audio::PlantSpec spec;
  spec.kind = o.kind == "high-pass" ? audio::PlantKind::high_pass : audio::PlantKind::low_pass;
  spec.resonance_hz = o.resonance_hz;
  spec.q = o.q;
  spec.rolloff_hz = o.rolloff_hz;
  spec.delay_samples = o.delay_samples;
  spec.sample_rate_hz = rate;
  const std::string server = fmt::format("mallet-actuator-{}", getpid());
  latency::JackServer jack(server, rate, o.period, 3);  // sensor, loopback, photodiode
  JackPlant plant(server, spec);
  std::filesystem::create_directories(o.out_dir);
  const std::filesystem::path settings = o.out_dir / "mallet.toml";
  std::ofstream(settings) << "# mallet bench actuator: the calibration on the bench's JACK server\n"
                             "[audio]\ndevice = \"system\"\nsample_rate_hz = 48000\n";
  const std::filesystem::path eq_file = o.out_dir / "actuator_eq.toml";
  std::printf("plant: %s resonance %.0f Hz, Q %.1f, second pole %.0f Hz, delay %d samples, on JACK's dummy driver "
              "(%d Hz, period %d)\n",
              o.kind.c_str(), o.resonance_hz, o.q, o.rolloff_hz, o.delay_samples, rate, o.period);
  std::printf("mallet calibrate actuator --loopback 2:\n");
  std::fflush(stdout);
  const std::vector<std::string> common = {"--config", settings.string(), "--input", "system", "--channel", "1",
                                           "--out", eq_file.string()};
  std::vector<std::string> measure = {"calibrate", "actuator", "--loopback", "2", "--sensor", "bench actuator's plant"};
  measure.insert(measure.end(), common.begin(), common.end());
  if (const int status = run_mallet(measure, server, o.out_dir, plant); status != 0)
    throw std::runtime_error(fmt::format("bench actuator: mallet calibrate actuator ended with {}", status));

  // What it recovered, against the truth.
  const ActuatorEq eq = load_actuator_eq(eq_file);
  audio::SimulatedPlant truth(spec);
  double worst_db = 0, worst_hz = 0;
  int points = 0;
  for (std::size_t i = 0; i < eq.frequency_hz.size(); ++i) {
    const double f = eq.frequency_hz[i];
    if (f < eq.band_low_hz || f > eq.band_high_hz) continue;
    const double err = eq.magnitude_db[i] - 20 * std::log10(std::abs(truth.response(f)));
    if (std::abs(err) > std::abs(worst_db)) worst_db = err, worst_hz = f;
    ++points;
  }
  std::printf("\nrecovered against the plant:\n");
  std::printf("  magnitude over the usable band (%.1f to %.1f Hz, %d points): worst error %+.3f dB at %.1f Hz "
              "(target: within 1 dB)\n",
              eq.band_low_hz, eq.band_high_hz, points, worst_db, worst_hz);
  if (eq.round_trip_ms) {
    const double chain = (eq.delay_ms - *eq.round_trip_ms) * rate / 1000.0;
    std::printf("  delay: %.2f samples recovered (%.3f ms of chain after a %.3f ms round trip), %d injected: error "
                "%+.2f samples (target: within 1 sample)\n",
                chain, eq.delay_ms - *eq.round_trip_ms, *eq.round_trip_ms, o.delay_samples, chain - o.delay_samples);
  }
  std::printf("  resonance: %.1f Hz recovered, %.1f Hz in the plant\n\nmallet calibrate actuator --verify:\n",
              eq.resonance_hz, o.resonance_hz);
  std::fflush(stdout);
  std::vector<std::string> verify = {"calibrate", "actuator", "--verify"};
  verify.insert(verify.end(), common.begin(), common.end());
  std::vector<std::string> lines;
  if (const int status = run_mallet(verify, server, o.out_dir, plant, &lines); status != 0)
    throw std::runtime_error(fmt::format("bench actuator: mallet calibrate actuator --verify ended with {}", status));
  double before = -1, after = -1;
  for (const std::string& line : lines)
    std::sscanf(line.c_str(), "worst |error| of B and f: %lf%% without the inverse, %lf%% with it", &before, &after);

  // The table, for scripts: what was recovered against what the plant was given.
  const std::filesystem::path csv = o.out_dir / "actuator.csv";
  std::ofstream out(csv);
  out << "quantity,recovered,injected,error,target\n";
  out << fmt::format("magnitude_worst_db,{:.4f},0,{:.4f},1\n", worst_db, worst_db);
  if (eq.round_trip_ms) {
    const double chain = (eq.delay_ms - *eq.round_trip_ms) * rate / 1000.0;
    out << fmt::format("delay_samples,{:.3f},{},{:.3f},1\n", chain, o.delay_samples, chain - o.delay_samples);
    out << fmt::format("round_trip_samples,{:.3f},{},{:.3f},\n", *eq.round_trip_ms * rate / 1000.0, o.period,
                       *eq.round_trip_ms * rate / 1000.0 - o.period);
  }
  out << fmt::format("resonance_hz,{:.2f},{:.2f},{:.2f},\n", eq.resonance_hz, o.resonance_hz, eq.resonance_hz - o.resonance_hz);
  out << fmt::format("felt_worst_before_percent,{:.2f},0,{:.2f},\n", before, before);
  out << fmt::format("felt_worst_after_percent,{:.2f},0,{:.2f},3\n", after, after);

  // The sound card's latency on the loopback, the cable now delaying by a known amount.
  plant.set_loopback_delay(o.loopback_delay);
  std::printf("\nmallet calibrate latency --loopback 2 (the loopback delayed by %d samples, %.3f ms):\n",
              o.loopback_delay, 1000.0 * o.loopback_delay / rate);
  std::fflush(stdout);
  std::vector<std::string> latency = {"calibrate", "latency", "--loopback", "2", "--config", settings.string(),
                                      "--input", "system"};
  lines.clear();
  if (const int status = run_mallet(latency, server, o.out_dir, plant, &lines); status != 0)
    throw std::runtime_error(fmt::format("bench actuator: mallet calibrate latency ended with {}", status));
  double round_trip = -1;
  for (const std::string& line : lines) std::sscanf(line.c_str(), "round trip: %lf samples", &round_trip);
  const int injected = o.period + o.loopback_delay;  // JACK's loop is one period
  std::printf("  round trip: %.2f samples recovered, %d injected (one JACK period and the cable's delay): error "
              "%+.3f ms (target: within 0.5 ms)\n",
              round_trip, injected, 1000.0 * (round_trip - injected) / rate);
  out << fmt::format("loopback_round_trip_ms,{:.4f},{:.4f},{:.4f},0.5\n", 1000.0 * round_trip / rate,
                     1000.0 * injected / rate, 1000.0 * (round_trip - injected) / rate);
  const bool display_measured = !o.photodiode || run_photodiode_step(o, server, settings, plant, out);
  out.close();
  if (!out) throw std::runtime_error("bench actuator: cannot write " + csv.string());
  std::printf("\nwrote %s\n", csv.string().c_str());
  if (!display_measured) {
    std::printf("the display latency is outside its target, but was timed while the bench's JACK server ran late, "
                "in each of its 3 runs: its figures are not a measurement of the kiosk (exit %d; measure on a quieter "
                "machine)\n",
                kActuatorBenchUnmeasured);
    std::fflush(stdout);
    finish_with(kActuatorBenchUnmeasured);
  }
}

}  // namespace

void add_bench_actuator(CLI::App& bench) {
  auto o = std::make_shared<ActuatorBenchOptions>();
  o->out_dir = std::filesystem::temp_directory_path() / fmt::format("mallet-bench-actuator-{}", getpid());
  CLI::App* cmd = bench.add_subcommand("actuator", "mallet calibrate actuator against a known actuator chain (JACK dummy)");
  cmd->footer(R"(Starts its own JACK server (dummy driver) and a plant client standing for the amplifier,
voice coil, stick and sensor: a second-order resonance (--kind low-pass: a piezo reading the
coil's excursion; high-pass: an accelerometer on an inertial actuator), a second pole and a
pure delay of whole samples. Runs `mallet calibrate actuator --loopback 2` (the plant's sensor on
capture 1, a loopback on capture 2) and then `--verify`, and prints what was recovered against
the plant: the magnitude over the usable band, the delay (the round trip taken off), the
resonance, and the felt-signal table. Then delays the loopback by --loopback-delay samples and
runs `mallet calibrate latency --loopback 2`: the round trip it finds against one JACK period
plus that delay. Last (unless --no-photodiode), `mallet calibrate latency --loopback 2
--photodiode 3` with the kiosk on an X server of the bench's own (Xvfb): a photodiode client
watches the screen's top-left corner (XGetImage, about 1 ms apart) and lights capture 3
--panel-lag ms after the corner turns white, as a panel that late would; the bench presses
Enter when the operator page asks, and sets each square's display latency against the truth
(when the X server showed it, plus the panel's lag, less the frame's present). Writes
actuator.csv (quantity,recovered,injected,error,target) in --out; its row
display_jack_late_cycles counts the bench's JACK server running late during the photodiode's
run. Exit status 77 when the display figures are outside one frame of the truth and the JACK
server ran late in each of the 3 runs (the light may then have reached the stream up to a
period late: the figures are written, but are not a measurement of the kiosk).
Needs jackd (jackd2), Xvfb (for the photodiode) and mallet beside mallet-bench.)");
  cmd->add_option("--kind", o->kind, "The plant's resonance")->check(CLI::IsMember({"low-pass", "high-pass"}))->capture_default_str();
  cmd->add_option("--resonance", o->resonance_hz, "Hz")->capture_default_str()->check(CLI::Range(40.0, 1000.0));
  cmd->add_option("--q", o->q, "The resonance's Q")->capture_default_str()->check(CLI::Range(0.5, 20.0));
  cmd->add_option("--second-pole", o->rolloff_hz, "Hz")->capture_default_str()->check(CLI::Range(200.0, 20000.0));
  cmd->add_option("--delay", o->delay_samples, "The plant's pure delay in samples")->capture_default_str()->check(CLI::Range(0, 4800));
  cmd->add_option("--loopback-delay", o->loopback_delay, "The loopback's own delay for `calibrate latency`, samples")
      ->capture_default_str()
      ->check(CLI::Range(0, JackPlant::kMaxLoopDelay));
  cmd->add_option("--panel-lag", o->panel_lag_ms, "The bench's panel: light this many ms after the X server shows a frame")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 150.0));
  cmd->add_flag("!--no-photodiode", o->photodiode, "Leave out the display's latency (the kiosk on an X server of the bench's)");
  cmd->add_option("--page-shot", o->page_shot, "Also write the operator page asking for the answer, as a PNG");
  cmd->add_option("--period", o->period, "JACK's period in frames")->capture_default_str()->check(CLI::IsMember({64, 128, 256, 512, 1024}));
  cmd->add_option("--out", o->out_dir, "Folder for the settings and the calibration written");
  cmd->callback([o] { run_bench_actuator(*o); });
}

}  // namespace mallet::app
