#include "app/kiosk/window_kiosk.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "audio/audio_setup.hpp"
#include "app/kiosk/calibration_screen.hpp"
#include "core/strike_line.hpp"
#include "core/data_paths.hpp"
#include "app/kiosk/doctor.hpp"
#include "render/overlay_text.hpp"
#include "app/kiosk/metrics_file.hpp"
#include "app/strike/mouse_pointer.hpp"
#include "app/strike/remote_pointer.hpp"
#include "render/render_setup.hpp"
#include "core/saved_calibration.hpp"
#include "core/strike_loop.hpp"
#include "app/strike/strike_route.hpp"
#include "app/kiosk/systemd_notify.hpp"
#include "audio/portaudio_output.hpp"
#include "core/bar_lights.hpp"
#include "core/config/app_config_loader.hpp"
#include "core/config/scene_config.hpp"
#include "core/file_error.hpp"
#include "core/kiosk_metrics.hpp"
#include "core/kiosk_states.hpp"
#include "core/language_choice.hpp"
#include "core/operator_knobs.hpp"
#include "input/clock.hpp"
#include "input/evdev/evdev_mouse.hpp"
#include "input/wiimote/hid_transport.hpp"
#include "input/wiimote/replay_transport.hpp"
#include "input/wiimote/wiimote_device.hpp"
#include "core/quality.hpp"
#include "core/study/visitor_offer.hpp"
#include "core/visitor_language.hpp"
#include "render/font_atlas.hpp"
#include "render/overlay.hpp"
#include "render/pipeline_cache.hpp"
#include "render/text_wrap.hpp"
#include "render/vk_handle.hpp"
#include "render/window_target.hpp"

namespace mallet::app {
namespace {

std::atomic<bool> g_reload{false};
void on_sighup(int) { g_reload.store(true); }
std::atomic<bool> g_stop{false};
volatile std::sig_atomic_t g_stop_signal = 0;
void on_stop(int signal) {
  g_stop_signal = signal;
  g_stop.store(true);
}

KioskStatesConfig states_config(const AppConfig& c, const KioskOptions& o) {
  KioskStatesConfig k;
  k.idle_after_s = o.idle_after_s.value_or(c.attract.idle_after_s);
  return k;
}

//! Everything that depends on the scene and the settings, rebuilt on a reload.
struct Stage {
  AppConfig config;
  Scene scene;
  //! Strikes by target and material, recorded by every route of this stage (any thread).
  std::unique_ptr<StrikeTally> tally;
  std::string settings_line;                          //!< where the settings came from
  std::vector<std::filesystem::path> scene_choices;  //!< the usable [scenes] choices (S)
  std::vector<std::string> problems;                  //!< drop-ins and scene choices refused
  audio::AudioRig rig;
  std::unique_ptr<audio::PortAudioOutput> output;
  std::string audio_status;
  std::unique_ptr<render::SceneRenderer> renderer;
  //! The main thread's strike route: the ghost, and the mouse when the window system reads it.
  std::unique_ptr<StrikeRoute> route;
  InputSource source = InputSource::mouse;
  std::string input_why;             //!< how the source was chosen, for the operator page
  std::optional<Calibration> calibration;  //!< the remote's camera → screen map in use
  std::string calibration_status;
  std::string calibration_status_sensitivity;  //!< what the last calibration's tuner chose
  // The Wii Remote (or a recording played as one): its reading thread feeds `remote`,
  // which posts strikes to the engine. The device is declared last so that it (and its
  // thread) goes first.
  std::unique_ptr<input::wiimote::ReplayFinder> replay;
  std::unique_ptr<RemotePointer> remote;
  std::unique_ptr<input::wiimote::WiimoteDevice> device;
  bool link_up = false;
  bool checked_calibration = false;  //!< against the first connected remote's identity
  // The mouse read at its source (input.mouse = auto | evdev): its reading thread feeds
  // `mouse`, which posts strikes itself. Without it the window system's cursor events
  // feed the main thread's route. The source is declared last so that its thread goes first.
  std::string mouse_line;  //!< how the mouse is read, for the log and the operator page
  std::unique_ptr<MousePointer> mouse;
  std::unique_ptr<input::evdev::EvdevMouse> evdev;
  //! [study] visitor_protocol, loaded against this scene (none: off, or it did not load).
  std::optional<study::StudyProtocol> visitor;
};

//! The remote's identity in a calibration file: its Bluetooth address, else its hidraw path.
std::string remote_identity(const input::wiimote::HidDeviceInfo& d) { return d.serial.empty() ? d.path : d.serial; }

class WindowKiosk {
 public:
  WindowKiosk(const KioskOptions& o, KioskSetup setup);
  int run();

 private:
  void build(KioskSetup setup);
  void on_key(int key, int mods);
  void handle_keys(Nanos now);
  void reload();
  void next_wall_material();  //!< operator page M: the wall's next material
  void next_scene();          //!< operator page S: the next of [scenes] choices
  //! Operator page T: kLatencyTestPulses times, one a second, a white square in the top-left
  //! corner, a strike's note on the speaker and its pulse on the actuator, all scheduled for
  //! the same instant; a photodiode and a microphone (or a 240 fps video) show the offsets
  //! the operator then enters as [timing] display_latency_ms and audio_output_latency_ms.
  void start_latency_test(Nanos now);
  void latency_test_frame(Nanos present);  //!< posts the pulses due, draws the square
  void on_cursor(double x, double y);  //!< the window system's cursor event, stamped as it is read
  void draw_overlay(Nanos now, double frame_ms);
  void apply_volume();
  void heartbeat(Nanos now);
  void choose_input(Stage& stage);
  void choose_mouse(Stage& stage);  //!< evdev when it can be opened, else the window system's events
  void poll_remote(Nanos now);
  void calibration_frame(Nanos now, std::optional<Vec2> mouse_screen);
  std::string input_line() const;
  //! Operator page D: `mallet doctor`'s checks, with what the kiosk knows of the devices it
  //! holds (its renderer, audio output and remote) instead of opening them again.
  void run_doctor_checks(double frame_ms);
  std::string timing_line() const;  //!< the strike route's policy and the figures it uses
  //! Strikes delivered since start, over every route and every reload.
  std::uint64_t strikes() const;
  //! Once a frame: the frame, the state and the tracking into metrics_; the file when due.
  void feed_metrics(Nanos now);
  void write_metrics(Nanos now);  //!< the gauges and totals read now, then the file
  void retire_metrics(const Stage& old);  //!< a reload: keep the replaced stage's counts
  //! The stage's scene renderer on the window's current device.
  std::unique_ptr<render::SceneRenderer> make_renderer(const Stage& stage);
  void install_callbacks();  //!< the window's key and cursor events to this kiosk
  //! The visitor micro-study: whether it is offered now (on the percussion scene, in the
  //! attract mode or play); and a visitor's strike on the "Yes" bar while it is.
  bool visitor_offered(Nanos now);
  bool visitor_accepted(Nanos now, const StrikeLoop::View& view);
  //! One visitor's session in this window (blocking), the instrument paused meanwhile.
  void run_visitor_session();
  //! The bar a visitor strikes to accept the offer: the scene's last (rightmost) one.
  int visitor_yes_bar() const { return static_cast<int>(stage_->scene.targets.size()) - 1; }

  KioskOptions options_;
  render::ProductWindow win_;
  // The stage goes before the states and ghost that refer to its scene.
  //! What a frame costs from its start to its present (input, logic, drawing), smoothed: the
  //! frame interval less the frame budget's wait.
  double work_ms_ = 0;
  std::unique_ptr<Stage> stage_;
  std::unique_ptr<KioskStates> states_;
  std::optional<AttractLoop> ghost_;
  LanguageChoice language_;  //!< [kiosk] language, [attract] languages, the page's L
  input::wiimote::HidDeviceFinder finder_;
  input::SteadyClock clock_;
  std::unique_ptr<CalibrationScreen> calibration_;  //!< while the Calibration state lasts
  std::string notice_;                             //!< the last calibration's outcome ...
  Nanos notice_until_ = 0;                         //!< ... shown until then
  static constexpr int kLatencyTestPulses = 10;
  std::vector<Nanos> latency_test_;  //!< the test's instants still to come or on screen
  std::vector<std::pair<int, int>> keys_;  //!< (key, mods) pressed since the last frame
  std::vector<std::string> doctor_;        //!< the page's doctor lines (D); empty: the page's own
  bool doctor_asked_ = false;              //!< D pressed: the checks run in this frame's overlay
  std::vector<PointerSample> cursor_;      //!< the window's cursor events since the last frame
  std::optional<Vec2> last_cursor_;        //!< the latest of them (normalised screen)
  double volume_ = 0.8, gain_ = 0.2;       //!< the operator's knobs
  Nanos started_ = 0;
  // Liveness: the watchdog is fed only while input, audio and render all make progress.
  SystemdNotifier notifier_ = SystemdNotifier::from_environment();
  Nanos next_watchdog_ = 0, next_log_ = 0;
  bool starving_ = false;  //!< the watchdog was not fed at the last beat
  std::uint64_t frames_ = 0, frames_at_beat_ = 0, polls_ = 0, polls_at_beat_ = 0;
  std::uint64_t still_frames_ = 0;  //!< frames not drawn: nothing on the screen would have changed
  std::uint64_t callbacks_at_beat_ = 0;
  std::uint64_t strikes_before_ = 0;  //!< by the stages a reload replaced
  // [metrics]: what the kiosk counts, and the file it writes them to.
  KioskMetrics metrics_;
  MetricsFile metrics_file_{state_dir(), [](const std::string& line) { std::fprintf(stderr, "<4>%s\n", line.c_str()); },
                            [](const std::string& line) { std::fprintf(stderr, "<5>%s\n", line.c_str()); }};
  StrikeCounts strikes_retired_;      //!< by the stages a reload replaced (and a zero per scene's label)
  std::uint64_t xruns_retired_ = 0;   //!< by the audio outputs a reload replaced
  Nanos metrics_frame_at_ = 0;        //!< the last drawn frame's time
  std::optional<study::VisitorOffer> offer_;  //!< [study]: when the visitor study is offered
  Nanos offer_since_ = 0;             //!< the current offer's start: strikes before it do not accept
};

WindowKiosk::WindowKiosk(const KioskOptions& o, KioskSetup setup)
    : options_(o), win_(setup.config.render, o.device, o.size, o.windowed, "Mallet") {
  install_callbacks();
  started_ = monotonic_now();
  volume_ = setup.config.audio.volume;
  gain_ = setup.config.actuator.gain;
  build(std::move(setup));
  std::fprintf(stderr, "<6>mallet run: %s, %ux%u, %s\n", win_.ctx->device_name().c_str(),
               win_.window->extent().width, win_.window->extent().height, stage_->audio_status.c_str());
}

std::unique_ptr<render::SceneRenderer> WindowKiosk::make_renderer(const Stage& stage) {
  return std::make_unique<render::SceneRenderer>(*win_.ctx, stage.scene, render::models_dir(), win_.window->format(),
                                                 render::render_settings(*win_.ctx, stage.config.render), win_.cache->get());
}

void WindowKiosk::install_callbacks() {
  glfwSetWindowUserPointer(win_.window->window(), this);
  glfwSetKeyCallback(win_.window->window(), [](GLFWwindow* w, int key, int, int action, int mods) {
    if (action == GLFW_PRESS || action == GLFW_REPEAT)
      static_cast<WindowKiosk*>(glfwGetWindowUserPointer(w))->on_key(key, mods);
  });
  glfwSetCursorPosCallback(win_.window->window(), [](GLFWwindow* w, double x, double y) {
    static_cast<WindowKiosk*>(glfwGetWindowUserPointer(w))->on_cursor(x, y);
  });
}

bool WindowKiosk::visitor_offered(Nanos now) {
  if (!stage_->visitor || !offer_ || stage_->scene.kind != SceneKind::percussion) return false;
  const KioskState state = states_->state();
  if (state != KioskState::attract && state != KioskState::play) return false;
  const bool was = offer_since_ > 0;
  const bool offered = offer_->offered(now);
  if (offered && !was) {
    offer_since_ = now;
    std::fprintf(stderr, "<6>visitor study: offered (%s)\n", stage_->visitor->visitor->offer.c_str());
  }
  if (!offered) offer_since_ = 0;
  return offered;
}

bool WindowKiosk::visitor_accepted(Nanos now, const StrikeLoop::View& view) {
  if (!visitor_offered(now) || !states_->visitor_plays()) return false;
  // A visitor's own strike: after the offer showed and after they took over from the ghost
  // (whose last strike the main route's bounce may still hold).
  const std::optional<Nanos> struck = view.vibration.impact_time();
  return struck && *struck >= std::max(offer_since_, states_->since()) &&
         view.vibration.target() == visitor_yes_bar();
}

void WindowKiosk::run_visitor_session() {
  std::fprintf(stderr, "<6>visitor study: a visitor accepted; the instrument pauses\n");
  // The study's own audio and strike route play meanwhile: the kiosk's output is closed (a
  // device may take only one stream), and its pointers' threads strike nothing (they still
  // hand their samples over).
  const bool sound = stage_->output != nullptr;
  if (sound) xruns_retired_ += stage_->output->counters().xruns;
  stage_->output.reset();
  if (stage_->remote) stage_->remote->set_playing(false);
  if (stage_->mouse) stage_->mouse->set_playing(false);
  std::function<std::vector<PointerSample>()> pointer;  // empty: the window system's cursor
  if (stage_->source != InputSource::mouse && stage_->remote) {
    pointer = [r = stage_->remote.get()] {
      std::vector<PointerSample> out;
      for (const RemoteSample& s : r->take())
        if (s.screen) out.push_back({s.t_ns, s.screen->x, s.screen->y});
      return out;
    };
  } else if (stage_->mouse) {
    pointer = [m = stage_->mouse.get()] { return m->take(); };
  }
  try {
    std::random_device random;
    const std::uint64_t id = (static_cast<std::uint64_t>(random()) << 32) ^ random();
    // The study's frames are the kiosk's life meanwhile: they feed its watchdog.
    const study::VisitorSessionResult r = options_.visitor_sessions.run(
        win_, stage_->config, stage_->scene, *stage_->visitor, study::visitor_session_id(id),
        study::utc_date(std::time(nullptr)), pointer, [this] {
      const Nanos now = monotonic_now(), interval = notifier_.watchdog_interval().value_or(0);
      if (interval > 0 && now >= next_watchdog_) {
        notifier_.watchdog();
        next_watchdog_ = now + interval;
      }
      return !g_stop.load();
    });
    std::fprintf(stderr, "<6>visitor study: %s %s, %d of %d trials, %s\n", r.id.c_str(),
                 !r.consented ? (r.abandoned ? "walked away at the consent" : "declined")
                 : r.abandoned ? "abandoned"
                               : "completed",
                 r.answered, r.planned, r.csv.c_str());
    ++metrics_.visitor_study[r.abandoned ? "abandoned" : r.consented ? "completed" : "declined"];
  } catch (const std::exception& e) {  // the kiosk plays on
    std::fprintf(stderr, "<3>visitor study: %s\n", e.what());
  }
  install_callbacks();
  cursor_.clear();
  // The swapchain's images hold the study's frames: a new renderer draws them whole.
  stage_->renderer = make_renderer(*stage_);
  stage_->route->reset();
  if (sound) stage_->output = audio::start_output(*stage_->rig.engine, stage_->config.audio, stage_->audio_status);
  callbacks_at_beat_ = 0;  // the new output's callbacks count from 0
  offer_->session_ended(monotonic_now());
  offer_since_ = 0;
}

void WindowKiosk::build(KioskSetup setup) {
  auto stage = std::make_unique<Stage>();
  stage->config = std::move(setup.config);
  stage->scene = std::move(setup.scene);
  stage->tally = std::make_unique<StrikeTally>(stage->scene);
  stage->settings_line = std::move(setup.settings_line);
  stage->scene_choices = std::move(setup.scene_choices);
  stage->problems = std::move(setup.problems);
  const AppConfig& c = stage->config;
  stage->renderer = make_renderer(*stage);
  stage->rig = audio::make_audio_rig(stage->scene, c, c.audio.sample_rate_hz);
  stage->route = std::make_unique<StrikeRoute>(stage->scene, c, stage->rig.engine.get(), &win_.window->present_clock(),
                                               RouteOptions{audio::Producer::main, false, true});
  stage->route->on_strike = [t = stage->tally.get()](const Strike& s) { t->record(s.impact); };
  choose_input(*stage);  // a bad replay file throws here, before anything running is touched
  if (!c.study.visitor_protocol.empty() && stage->scene.kind == SceneKind::percussion) {
    try {  // a protocol that does not load: one line, and no offer
      if (!options_.visitor_sessions) throw std::runtime_error("this kiosk was started without the study");
      stage->visitor = options_.visitor_sessions.load(c.study, stage->scene);
    } catch (const std::exception& e) {
      stage->problems.push_back(std::string("visitor study off: ") + e.what());
      std::fprintf(stderr, "<4>visitor study off: %s\n", e.what());
    }
  }
  // The old output must stop before the new one opens the device; so must the old remote.
  if (stage_ && stage_->output) stage_->output->stop();
  if (stage_ && stage_->device) stage_->device->stop();
  if (stage_ && stage_->evdev) stage_->evdev->stop();
  stage->output = audio::start_output(*stage->rig.engine, c.audio, stage->audio_status);  // null: the scene plays silently
  const Nanos now = monotonic_now();
  ghost_.reset();
  calibration_.reset();
  if (stage_) strikes_before_ = strikes();
  if (stage_) retire_metrics(*stage_);
  const bool languages_changed = !stage_ || stage_->config.language != c.language ||
                                 stage_->config.attract.languages != c.attract.languages ||
                                 stage_->config.attract.language_every_s != c.attract.language_every_s;
  stage_ = std::move(stage);
  offer_.reset();
  offer_since_ = 0;
  if (stage_->visitor)
    offer_.emplace(static_cast<Nanos>(std::llround(c.study.offer_every_s * 1e9)),
                   static_cast<Nanos>(std::llround(c.study.offer_for_s * 1e9)), now);
  seed_strike_labels(stage_->scene, strikes_retired_);
  metrics_file_.configure(stage_->config.metrics);
  win_.set_max_fps(options_.no_frame_cap ? -1 : stage_->config.render.max_fps);  // a reload may change it
  // The languages as set: a reload that changes them starts them afresh; one that does not
  // (the page's S, a SIGHUP for another key) keeps the operator's L.
  if (languages_changed)
    language_ = LanguageChoice(c.language, c.attract.languages,
                               static_cast<Nanos>(std::llround(c.attract.language_every_s * 1e9)));
  // The operator who reloaded from the page (S, or a SIGHUP while it is open) stays on it,
  // as after M, the volume or the gain.
  const bool on_page = states_ && states_->state() == KioskState::operator_page;
  states_ = std::make_unique<KioskStates>(states_config(stage_->config, options_), now);
  if (on_page) states_->operator_chord(now);
  states_->input_source(now, stage_->source);
  if (stage_->device) {
    states_->remote_connected(now, false);  // until its link runs (says nothing for a replay)
    stage_->device->start();
  }
  if (stage_->evdev) {
    MousePointer* m = stage_->mouse.get();
    stage_->evdev->start([m](std::span<const PointerSample> samples) { m->on_samples(samples); });
  }
  std::fprintf(stderr, "<6>%s\n", input_line().c_str());
  std::fprintf(stderr, "<6>%s\n", timing_line().c_str());
  apply_volume();
}

void WindowKiosk::choose_input(Stage& stage) {
  const std::string& want = stage.config.input.source;
  stage.source = InputSource::mouse;
  if (want == "mouse") {
    stage.input_why = "the settings say mouse";
    choose_mouse(stage);
    return;
  }
  if (want == "replay") {
    stage.replay = std::make_unique<input::wiimote::ReplayFinder>(
        input::wiimote::ReplayFinder::open_file(stage.config.input.replay_file, clock_));
    stage.source = InputSource::replay;
    stage.input_why = "replay of " + stage.config.input.replay_file;
  } else if (want == "auto") {
    std::optional<input::wiimote::HidDeviceInfo> found;
    for (const auto& d : finder_.enumerate())
      if (input::wiimote::matches_device(d, stage.config.wiimote.device)) {
        found = d;
        break;
      }
    if (!found) {
      stage.input_why = "no Wii Remote found at start-up";
      choose_mouse(stage);
      return;
    }
    stage.input_why = "found " + remote_identity(*found);
  } else {
    stage.input_why = "the settings say wiimote";
  }
  if (want != "replay") stage.source = InputSource::wiimote;
  SavedCalibration saved = load_saved_calibration(calibration_path());
  stage.calibration = std::move(saved.calibration);
  stage.calibration_status = std::move(saved.status);
  if (!saved.warning.empty()) std::fprintf(stderr, "<4>%s\n", saved.warning.c_str());
  if (stage.source == InputSource::replay && !stage.calibration) {
    // A recording without a calibration: the camera's view mirrored onto the whole screen
    // (the camera faces the visitor), so a demo plays at once.
    Calibration c;
    c.camera_to_screen.h = {-1.0 / 1023.0, 0, 1, 0, 1.0 / 767.0, 0, 0, 0, 1};
    stage.calibration = c;
    stage.calibration_status = "calibration: none; the camera's view mirrored onto the screen";
  }
  stage.remote = std::make_unique<RemotePointer>(stage.scene, stage.config, *stage.rig.engine,
                                                 &win_.window->present_clock(), &win_.aspect);
  stage.remote->set_calibration(stage.calibration);
  input::wiimote::WiimoteDeviceConfig dc = kiosk_device_config(stage.config, stage.calibration);
  if (stage.calibration && !stage.calibration->ir_sensitivity.empty())
    stage.calibration_status_sensitivity = "IR sensitivity " + stage.calibration->ir_sensitivity + " (saved with it)";
  dc.every_frame = true;  // the calibration screen's sensitivity tuner counts every frame's dots
  if (stage.replay) dc.device.clear();  // the recording is the only device
  stage.device = std::make_unique<input::wiimote::WiimoteDevice>(
      stage.replay ? static_cast<input::wiimote::DeviceFinder&>(*stage.replay) : finder_, clock_, dc);
  Stage* s = &stage;
  // The reading thread: strikes go from there through the strike route (RemotePointer);
  // this only pulses the rumble when configured.
  stage.remote->on_strike = [s](const Impact& i) {
    s->tally->record(i);
    s->device->on_impact();
  };
  stage.device->set_sample_sink(
      [s](std::span<const input::wiimote::LedSample> samples, Nanos now) { s->remote->on_samples(samples, now); });
}

//! "off", or "10 ms ahead".
std::string predict_text(const PredictionConfig& p) {
  if (!(p.horizon_ms > 0)) return "off";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.0f ms ahead", p.horizon_ms);
  return buf;
}

std::string WindowKiosk::timing_line() const {
  const AppConfig& c = stage_->config;
  const TimingConfig& t = c.timing;
  char buf[240];
  const double audio_ms = stage_->output ? stage_->output->output_latency_s() * 1e3 : 0.0;
  std::snprintf(buf, sizeof buf, "timing: align %s, prediction %s, frames %s, display %.0f ms, audio out %.1f ms%s",
                to_string(t.align), predict_text(t.predict).c_str(), win_.window->present_clock().describe().c_str(),
                t.display_latency_ms, audio_ms, c.audio.output_latency_ms >= 0 ? " (set)" : " (the device's)");
  return buf;
}

void WindowKiosk::choose_mouse(Stage& stage) {
  const InputConfig& in = stage.config.input;
  if (in.mouse == "window") {
    stage.mouse_line = "mouse: the window system's events, once a frame (the settings say window)";
    return;
  }
  input::evdev::EvdevMouseConfig mc;
  mc.screen_width_px = static_cast<int>(win_.window->extent().width);
  mc.screen_height_px = static_cast<int>(win_.window->extent().height);
  input::evdev::EvdevOpenResult opened =
      input::evdev::EvdevMouse::open(in.mouse_device.empty() ? input::evdev::kAutoDevice : in.mouse_device, mc);
  if (!opened.mouse) {
    stage.mouse_line = "mouse: the window system's events, once a frame (evdev: " + opened.error + ")";
    // Asked for by name: said as a warning; the window system's events keep the kiosk playable.
    if (in.mouse == "evdev")
      std::fprintf(stderr, "<4>[input] mouse = \"evdev\" could not be opened: %s\n", opened.error.c_str());
    return;
  }
  stage.evdev = std::move(opened.mouse);
  stage.mouse = std::make_unique<MousePointer>(stage.scene, stage.config, *stage.rig.engine,
                                               &win_.window->present_clock(), &win_.aspect);
  stage.mouse->on_strike = [t = stage.tally.get()](const Strike& s) { t->record(s.impact); };
  if (last_cursor_) stage.evdev->warp(last_cursor_->x, last_cursor_->y);
  stage.mouse_line = stage.evdev->describe() + ", each report stamped by the kernel";
}

std::uint64_t WindowKiosk::strikes() const {
  return strikes_before_ + stage_->route->strikes() + (stage_->remote ? stage_->remote->strikes() : 0) +
         (stage_->mouse ? stage_->mouse->strikes() : 0);
}

void WindowKiosk::feed_metrics(Nanos now) {
  if (frames_ > metrics_.frames()) {  // this iteration drew a frame (at most one)
    metrics_.count_frame(now - metrics_frame_at_);
    metrics_frame_at_ = now;
  } else if (win_.window->still()) {
    metrics_frame_at_ = now;  // a still scene's gap between drawn frames is not a slow frame
  }
  metrics_.observe_state(states_->state(), states_->since(), states_->last_movement());
  // Lost only where it matters: a visitor plays, the remote runs, its camera sees no LED.
  metrics_.observe_tracking(stage_->device && stage_->link_up && states_->visitor_plays() && !states_->tracking(), now);
  if (metrics_file_.due(now)) write_metrics(now);
}

void WindowKiosk::write_metrics(Nanos now) {
  constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
  metrics_.strikes = strikes_retired_;
  stage_->tally->add_to(metrics_.strikes);
  metrics_.audio_xruns = xruns_retired_ + (stage_->output ? stage_->output->counters().xruns : 0);
  metrics_.audio_output_latency_s = stage_->output ? stage_->output->output_latency_s() : kUnknown;
  metrics_.vulkan_device_memory_bytes = static_cast<double>(render::device_memory_bytes());
  metrics_.render_devices_lost = win_.devices_lost();
  metrics_.remote_connected = stage_->device && stage_->link_up;
  metrics_.remote_battery_ratio = kUnknown;
  if (stage_->device)
    if (const std::optional<std::uint8_t> b = stage_->device->state().remote.battery)
      metrics_.remote_battery_ratio = std::min(1.0, *b / 200.0);  // 0xC8 on fresh cells (reports.hpp)
  metrics_.uptime_ns = now - started_;
  metrics_.version = mallet_version();
  metrics_file_.write(metrics_, now);
}

void WindowKiosk::retire_metrics(const Stage& old) {
  old.tally->add_to(strikes_retired_);  // its input threads have stopped: the counts are final
  if (old.output) xruns_retired_ += old.output->counters().xruns;
}

std::string WindowKiosk::input_line() const {
  const Stage& s = *stage_;
  if (s.source == InputSource::mouse) {
    std::string line = "input: mouse (" + s.input_why + "); " + s.mouse_line;
    if (s.evdev) {
      const input::evdev::EvdevMouseStatus m = s.evdev->status();
      char buf[120];
      if (m.connected) std::snprintf(buf, sizeof buf, ", %.0f reports/s", m.rate_hz);
      else std::snprintf(buf, sizeof buf, ", lost: %s", m.problem.c_str());
      line += buf;
    }
    return line;
  }
  const input::wiimote::WiimoteState w = s.device->state();
  std::string line = s.replay ? "input: " + s.input_why + ", " + to_string(w.link)
                             : "input: Wii Remote " + remote_identity(w.device) + ", " + to_string(w.link);
  if (w.link == input::wiimote::LinkState::running) {
    char buf[120];
    std::snprintf(buf, sizeof buf, ", %.0f reports/s%s", w.remote.ir_rate_hz, w.tracking ? ", LED seen" : ", no LED");
    line += buf;
  } else if (!w.problem.empty()) {
    line += " (" + w.problem + ")";
  }
  return line;
}

void WindowKiosk::poll_remote(Nanos now) {
  Stage& s = *stage_;
  const input::wiimote::WiimoteState w = s.device->state();
  const bool up = w.link == input::wiimote::LinkState::running;
  if (up != s.link_up) {
    s.link_up = up;
    states_->remote_connected(now, up);
    std::fprintf(stderr, up ? "<5>Wii Remote %s connected\n" : "<4>Wii Remote %s lost: %s\n",
                 remote_identity(w.device).c_str(), w.problem.c_str());
    // A recording's timeline on the kiosk's clock (`mallet bench latency` maps its strokes' true
    // contacts with it).
    if (up && s.replay)
      std::fprintf(stderr, "<6>replay: the recording's time 0 is t=%s\n",
                   format_seconds(s.replay->last_origin()).c_str());
  }
  if (up && !s.checked_calibration && s.source == InputSource::wiimote) {
    // Start-up: no valid calibration, or one made with another remote → calibrate now.
    s.checked_calibration = true;
    const std::string id = remote_identity(w.device);
    if (!s.calibration || (!s.calibration->remote.empty() && s.calibration->remote != id)) {
      std::fprintf(stderr, "<5>calibration needed: %s\n",
                   s.calibration ? ("it was made with " + s.calibration->remote + ", this remote is " + id).c_str()
                                 : "none valid");
      states_->calibration_needed(now);
    }
  }
  for (const RemoteSample& r : s.remote->take()) {
    if (r.event == IrTrackerEvent::lost) states_->tracking_lost(r.t_ns);
    if (r.event == IrTrackerEvent::regained) states_->tracking_regained(r.t_ns);
    if (calibration_ && r.frame) calibration_->frame(*r.frame);
    if (calibration_ && r.camera_px) calibration_->feed(r.t_ns, *r.camera_px);
    if (r.screen) states_->pointer(r.t_ns, *r.screen);
  }
  if (calibration_) {
    calibration_->dot_seen(s.remote->tracking());
    if (const std::optional<std::string> preset = calibration_->sensitivity_request())
      s.device->request_sensitivity(*preset);
  }
}

void WindowKiosk::calibration_frame(Nanos now, std::optional<Vec2> mouse_screen) {
  if (states_->state() != KioskState::calibration) {
    // Abandoned (the operator chord): the previous calibration stays, and so does the
    // configured sensitivity if the tuner was trying another.
    if (calibration_) std::fprintf(stderr, "<5>operator: calibration abandoned, the previous one stays\n");
    if (calibration_ && calibration_->tuning() && stage_->device)
      stage_->device->request_sensitivity(kiosk_sensitivity(stage_->config, stage_->calibration));
    calibration_.reset();
    return;
  }
  if (!calibration_) {
    CalibrationSessionConfig cc;
    cc.screen = {static_cast<double>(win_.window->extent().width), static_cast<double>(win_.window->extent().height)};
    const bool remote = stage_->device != nullptr;
    // A replay calibrates in memory only: the file belongs to the real remote.
    const bool save = stage_->source == InputSource::wiimote;
    calibration_ = std::make_unique<CalibrationScreen>(
        cc, save ? std::optional<std::filesystem::path>(calibration_path()) : std::nullopt,
        remote ? remote_identity(stage_->device->state().device) : std::string("mouse"));
    if (remote) calibration_->tune_sensitivity({}, kiosk_sensitivity(stage_->config, stage_->calibration));
  }
  // The mouse stands in for the IR dot while it is the input.
  if (stage_->source == InputSource::mouse && mouse_screen) {
    calibration_->feed(now, mouse_as_camera_px(*mouse_screen));
  }
  if (calibration_->outcome() == CalibrationScreen::Outcome::measuring) return;
  if (!calibration_->sensitivity().empty())
    stage_->calibration_status_sensitivity = "IR sensitivity " + calibration_->sensitivity();
  notice_ = calibration_->message();
  notice_until_ = now + 6 * kNanosPerSecond;
  std::fprintf(stderr, "<5>%s\n", notice_.c_str());
  if (calibration_->outcome() == CalibrationScreen::Outcome::accepted) {
    if (stage_->remote) {
      stage_->calibration = calibration_->result();
      stage_->remote->set_calibration(stage_->calibration);
      stage_->calibration_status = stage_->source == InputSource::wiimote
                                       ? "calibration: " + calibration_path().string() + " (" + notice_ + ")"
                                       : "calibration: in memory (" + notice_ + ")";
    }
    states_->calibration_accepted(now);
  } else {
    states_->calibration_cancelled(now);
  }
  calibration_.reset();
}

void WindowKiosk::run_doctor_checks(double frame_ms) {
  KioskDeviceFacts facts;
  VkPhysicalDeviceProperties props{};
  vkGetPhysicalDeviceProperties(win_.ctx->physical_device(), &props);
  facts.vulkan = judge_renderer(win_.ctx->device_name(), props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU,
                                win_.window->extent().width, win_.window->extent().height, frame_ms);
  facts.vulkan.found += " (the kiosk's frames)";
  facts.audio = stage_->output ? DoctorCheck{"audio", CheckLevel::ok, stage_->audio_status, ""}
                               : DoctorCheck{"audio", CheckLevel::fail, stage_->audio_status,
                                             "connect the sound card and check `aplay -l`; `mallet audio devices`"};
  facts.wiimote = {"wiimote", CheckLevel::ok, input_line(), ""};
  if (stage_->device) {
    const input::wiimote::WiimoteState w = stage_->device->state();
    if (w.link == input::wiimote::LinkState::running) facts.connected_remote = remote_identity(w.device);
    else facts.wiimote = {"wiimote", CheckLevel::fail, input_line(), "press 1+2 on the remote; change its batteries"};
  } else if (stage_->config.input.source == "wiimote") {
    facts.wiimote.level = CheckLevel::fail;
  }
  DoctorOptions o;
  o.config = options_.config;
  o.config_dir = options_.config_dir;
  const std::vector<DoctorCheck> checks = run_doctor_with(o, facts);
  doctor_.clear();
  int failing = 0;
  for (const DoctorCheck& c : checks) {
    // On the page what was found; in the journal the whole line with its fix.
    doctor_.push_back(format_check({c.name, c.level, c.found, ""}));
    std::fprintf(stderr, "<5>doctor: %s\n", format_check(c).c_str());
    failing += c.level == CheckLevel::fail;
  }
  std::fprintf(stderr, "<5>operator: doctor, %d check(s) failing\n", failing);
}

void WindowKiosk::apply_volume() {
  const double attract = states_ && states_->attract_volume() ? stage_->config.attract.volume : 1.0;
  stage_->rig.engine->set_acoustic_volume(volume_ * attract);
  stage_->rig.engine->set_actuator_gain(gain_);
}

void WindowKiosk::on_key(int key, int mods) { keys_.emplace_back(key, mods); }

void WindowKiosk::handle_keys(Nanos now) {
  for (const auto& [key, mods] : keys_) {
    const bool chord = key == GLFW_KEY_O && (mods & GLFW_MOD_CONTROL) && (mods & GLFW_MOD_ALT);
    if (chord) {
      states_->operator_chord(now);
      continue;
    }
    if (states_->state() != KioskState::operator_page) continue;  // visitors' keys do nothing
    switch (key) {
      case GLFW_KEY_ESCAPE: states_->operator_page_closed(now); break;
      case GLFW_KEY_Q:
        std::fprintf(stderr, "<5>operator: quit\n");
        states_->quit_requested(now);
        break;
      case GLFW_KEY_R:  // the screen itself starts in the frame
        std::fprintf(stderr, "<5>operator: recalibrate\n");
        states_->recalibrate(now);
        break;
      case GLFW_KEY_UP:
      case GLFW_KEY_DOWN:
        volume_ = knob_step(volume_, kVolumeKnob, key == GLFW_KEY_UP);
        std::fprintf(stderr, "<5>operator: volume %.0f %%\n", volume_ * 100);
        break;
      case GLFW_KEY_RIGHT:
      case GLFW_KEY_LEFT:
        gain_ = knob_step(gain_, kGainKnob, key == GLFW_KEY_RIGHT);
        std::fprintf(stderr, "<5>operator: actuator gain %.2f\n", gain_);
        break;
      case GLFW_KEY_M: next_wall_material(); break;
      case GLFW_KEY_S: next_scene(); break;
      case GLFW_KEY_L:
        use_visitor_language(language_.next());
        std::fprintf(stderr, "<5>operator: language %s\n", visitor_language().c_str());
        break;
      case GLFW_KEY_T: start_latency_test(now); break;
      case GLFW_KEY_D:
        if (doctor_.empty()) doctor_asked_ = true;
        else doctor_.clear();  // D again: back to the page
        break;
      default: break;
    }
  }
  keys_.clear();
}

void WindowKiosk::next_wall_material() {
  if (stage_->scene.kind != SceneKind::wall) return;
  stage_->route->loop().next_wall_material();
  const int m = stage_->route->loop().wall_material();
  if (stage_->remote) stage_->remote->set_wall_material(m);
  if (stage_->mouse) stage_->mouse->set_wall_material(m);
  std::fprintf(stderr, "<5>operator: wall material %s\n",
               stage_->scene.materials[static_cast<std::size_t>(m)].display_name.c_str());
}

void WindowKiosk::start_latency_test(Nanos now) {
  latency_test_.clear();
  // The first instant far enough ahead that its sound can still be scheduled on time.
  for (int i = 0; i < kLatencyTestPulses; ++i) latency_test_.push_back(now + (i + 1) * kNanosPerSecond);
  for (Nanos t : latency_test_) {
    Impact pulse;  // a firm strike on the first bar: a sharp onset on both channels
    pulse.t_ns = t;
    pulse.target = 0;
    pulse.material = stage_->scene.targets.empty() ? -1 : stage_->scene.targets[0].material;
    pulse.note = stage_->scene.targets.empty() ? 0 : stage_->scene.targets[0].note;
    pulse.speed_m_per_s = 1.0;
    if (!stage_->scene.targets.empty()) stage_->rig.engine->post(pulse);  // heard at t: the engine's clock
  }
  std::fprintf(stderr, "<5>latency test: %d pulses, one a second, from %s (square, note and actuator at each)\n",
               kLatencyTestPulses, format_seconds(latency_test_.front()).c_str());
}

void WindowKiosk::latency_test_frame(Nanos present) {
  // The square is in the frame presented at or after each instant, for 100 ms.
  constexpr Nanos kShown = 100'000'000;
  std::erase_if(latency_test_, [present](Nanos t) { return present >= t + kShown; });
  for (Nanos t : latency_test_)
    if (present >= t) {
      const float side = win_.font->pixel_height() * 4;
      win_.overlay->fill_rect(0, 0, side, side, {1.0f, 1.0f, 1.0f, 1.0f});
      return;
    }
}

void WindowKiosk::next_scene() {
  // Only the choices that loaded (the others are listed on the page with their reasons).
  const std::vector<std::filesystem::path>& choices = stage_->scene_choices;
  if (choices.empty()) return;
  // The next choice after the running scene's file (the first if it is not one of them).
  std::size_t next = 0;
  for (std::size_t i = 0; i < choices.size(); ++i)
    if (choices[i] == std::filesystem::path(stage_->scene.file)) next = (i + 1) % choices.size();
  const std::filesystem::path previous = options_.scene;
  options_.scene = choices[next];
  std::fprintf(stderr, "<5>switching to the scene %s\n", options_.scene.c_str());
  reload();
  if (std::filesystem::path(stage_->scene.file) != options_.scene) options_.scene = previous;  // refused: stays
}

void WindowKiosk::on_cursor(double x, double y) {
  int w = 1, h = 1;
  glfwGetWindowSize(win_.window->window(), &w, &h);
  cursor_.push_back({monotonic_now(), x / std::max(w, 1), y / std::max(h, 1)});
}

void WindowKiosk::reload() {
  std::string why;
  std::optional<KioskSetup> setup = load_setup(options_, why);
  if (!setup) {
    std::fprintf(stderr, "<4>reload refused, the running configuration stays: %s\n", why.c_str());
    return;
  }
  try {
    vkDeviceWaitIdle(win_.ctx->device());
    volume_ = setup->config.audio.volume;
    gain_ = setup->config.actuator.gain;
    const std::vector<std::string> problems = setup->problems;
    const std::string settings = setup->settings_line;
    build(std::move(*setup));
    std::fprintf(stderr, "<5>reloaded the settings and the scene (%s)\n", settings.c_str());
    for (const std::string& p : problems) std::fprintf(stderr, "<4>%s\n", p.c_str());
  } catch (const std::exception& e) {  // e.g. a model the new scene names is broken: whatever is thrown
    std::fprintf(stderr, "<4>reload refused, the running configuration stays: %s\n", e.what());
  }
}

void WindowKiosk::heartbeat(Nanos now) {
  const Nanos interval = notifier_.watchdog_interval().value_or(0);
  const bool beat_due = interval > 0 && now >= next_watchdog_;
  const bool log_due = now >= next_log_;
  if (!beat_due && !log_due) return;
  const audio::OutputCounters a = stage_->output ? stage_->output->counters() : audio::OutputCounters{};
  // Audio is alive when its callbacks advance, or when its supervisor is retrying a lost
  // device (that is survived, silently), or when the kiosk runs without a device at all.
  const bool audio_alive =
      !stage_->output || a.callbacks > callbacks_at_beat_ || !stage_->output->device_ok();
  // A still scene draws no frames; its loop still decides each one.
  const bool render_alive = frames_ + still_frames_ > frames_at_beat_;
  // A remote that is gone is survived (attract, hint, reconnect): the main loop's polls
  // stand for input; the reading thread never blocks for long by design.
  const bool input_alive = polls_ > polls_at_beat_;
  if (beat_due) {
    const bool alive = audio_alive && render_alive && input_alive;
    if (alive) notifier_.watchdog();
    // Why the watchdog goes hungry, said once per stall: systemd's own line only says that it
    // fired (`mallet doctor` shows this line as the watchdog's last reason).
    if (!alive && !starving_)
      std::fprintf(stderr, "<4>watchdog not fed: %s%s%s stalled\n", render_alive ? "" : "render ",
                   audio_alive ? "" : "audio ", input_alive ? "" : "input");
    starving_ = !alive;
    next_watchdog_ = now + interval;
  }
  if (log_due) {
    std::fprintf(stderr, "<6>heartbeat: %s, frames %llu, strikes %llu, audio callbacks %llu, xruns %llu%s\n",
                 to_string(states_->state()), static_cast<unsigned long long>(frames_),
                 static_cast<unsigned long long>(strikes()), static_cast<unsigned long long>(a.callbacks),
                 static_cast<unsigned long long>(a.xruns), stage_->output && !stage_->output->device_ok()
                                                               ? ", audio device lost (retrying)" : "");
    next_log_ = now + 60 * kNanosPerSecond;
  }
  frames_at_beat_ = frames_ + still_frames_;
  polls_at_beat_ = polls_;
  callbacks_at_beat_ = a.callbacks;
}

void WindowKiosk::draw_overlay(Nanos now, double frame_ms) {
  render::Overlay& o = *win_.overlay;
  o.clear();
  const VkExtent2D extent = win_.window->extent();
  const float w = static_cast<float>(extent.width), h = static_cast<float>(extent.height);
  const float px = win_.font->pixel_height();
  if (states_->state() == KioskState::calibration && calibration_) calibration_->draw(o, w, h);
  else if (stage_->config.note_names)
    render::draw_note_names(o, stage_->scene, render::view_projection(stage_->scene, w / h), w, h);
  const KioskHint hint = states_->hint();
  // The visitor study's offer, and its "Yes" on the last bar, in place of the invitation (a
  // hint that something needs doing, a lost remote, comes first).
  if ((hint == KioskHint::none || hint == KioskHint::invitation) && visitor_offered(now)) {
    render::draw_banner(o, stage_->visitor->visitor->offer + " " + tr("(strike Yes)"), w, h);
    render::draw_bar_labels(o, stage_->scene, render::view_projection(stage_->scene, w / h), w, h,
                    {{visitor_yes_bar(), tr("Yes")}});
  } else if (hint != KioskHint::none)
    render::draw_banner(o, hint_text(hint, stage_->scene.kind), w, h);
  else if (now < notice_until_ && states_->state() != KioskState::calibration) render::draw_banner(o, notice_, w, h);
  // Subdued but readable: half-white over the room's grey is 8.3:1 (WCAG 2.1's AAA asks
  // 7:1 of body text; measured on the screenshot: docs/operators.md).
  if (states_->overlay().mouse_notice)
    o.text(px, h - px, stage_->config.input.source == "auto" ? tr("Mouse (no Wii Remote)") : tr("Mouse"),
           {1.0f, 1.0f, 1.0f, 0.5f});
  if (states_->state() != KioskState::operator_page) {
    doctor_.clear();
    return;
  }
  if (doctor_asked_) {
    doctor_asked_ = false;
    run_doctor_checks(work_ms_);  // what a frame costs, not the frame budget's interval
  }
  char buf[240];
  std::vector<std::string> lines;
  const double uptime = to_seconds(now - started_);
  // The page's words are the operator's language; its status lines (input, audio, timing,
  // settings, the doctor's checks) stay as the journal and `mallet doctor` write them.
  std::snprintf(buf, sizeof buf, tr("Mallet: operator page   quality: %s   language: %s"),
                to_string(stage_->config.quality), visitor_language().c_str());
  lines.emplace_back(buf);
  lines.push_back(input_line());
  lines.push_back(stage_->audio_status);
  std::snprintf(buf, sizeof buf, "frame: %.1f ms (its work %.1f ms)   uptime: %.0f h %02.0f min", frame_ms, work_ms_,
                std::floor(uptime / 3600), std::fmod(std::floor(uptime / 60), 60.0));
  lines.emplace_back(buf);
  std::snprintf(buf, sizeof buf, tr("volume %.0f %%  (Up / Down)"), volume_ * 100);
  lines.emplace_back(buf);
  std::snprintf(buf, sizeof buf, tr("actuator gain %.2f  (Left / Right)"), gain_);
  lines.emplace_back(buf);
  lines.emplace_back(tr("R recalibrate    T latency test    D doctor    L language    Q quit    Esc close"));
  const int wall = stage_->route->loop().wall_material();
  const char* wall_name = wall >= 0 ? stage_->scene.materials[static_cast<std::size_t>(wall)].display_name.c_str() : "";
  std::snprintf(buf, sizeof buf, tr("scene: %s  (S next)"),
                std::filesystem::path(stage_->scene.file).filename().c_str());
  if (wall >= 0)
    std::snprintf(buf + std::strlen(buf), sizeof buf - std::strlen(buf), tr("   wall: %s  (M next)"), wall_name);
  lines.emplace_back(buf);
  const std::string& tuned = stage_->calibration_status_sensitivity;
  lines.push_back(stage_->remote ? stage_->calibration_status + (tuned.empty() ? "" : ", ") + tuned
                                 : tr("calibration: R runs the screen with the mouse (not saved)"));
  lines.push_back(timing_line());
  lines.push_back(stage_->settings_line);
  for (const std::string& p : stage_->problems) lines.push_back("! " + p);
  if (!doctor_.empty()) {  // D: the doctor's checks instead of the page's status
    lines.resize(1);
    lines.insert(lines.end(), doctor_.begin(), doctor_.end());
    lines.emplace_back(tr("Each check with its fix: journalctl -u mallet -g doctor"));
    lines.emplace_back(tr("D back to the page    Esc close"));
  }
  const float pw = std::min(w - 2 * px, px * 40);
  // Long lines (how the input is read and why, the timing figures, the key legend) wrap at
  // a semicolon, a comma, before a parenthesis or between two keys' entries onto indented
  // continuation lines, else at a space; the widths are the font's own, in every language.
  struct Break {
    const char* separator;
    std::size_t kept;    //!< its characters that end the line ("," stays, " (" goes on)
    std::size_t resume;  //!< where the continuation starts, from the separator
  };
  static constexpr Break kBreaks[] = {{"; ", 1, 2}, {", ", 1, 2}, {" (", 0, 1}, {"    ", 0, 4}};
  const render::FontAtlas& font = o.atlas();
  const float room = pw - 2 * px;
  std::vector<std::string> page;
  for (std::string text : lines) {
    if (!doctor_.empty()) {  // a check a line, cut to the page; the whole line is in the log
      const std::vector<std::string> cut = render::wrap_text(font, text, room - font.measure("..."));
      page.push_back(cut.size() > 1 ? cut.front() + "..." : text);
      continue;
    }
    std::string indent;
    while (font.measure(indent + text) > room) {
      std::size_t cut = std::string::npos;
      const Break* at_break = nullptr;
      for (const Break& b : kBreaks)
        for (std::size_t at = text.find(b.separator); at != std::string::npos; at = text.find(b.separator, at + 1))
          if (at > 8 && (cut == std::string::npos || at > cut) &&
              font.measure(indent + text.substr(0, at + b.kept)) <= room)
            cut = at, at_break = &b;
      if (!at_break) {  // no separator that fits: the words that do
        const std::vector<std::string> words = render::wrap_text(font, text, room - font.measure(indent));
        if (words.size() < 2) break;
        page.push_back(indent + words.front());
        text.erase(0, words.front().size());  // the first line is the text's start, as written
        text.erase(0, text.find_first_not_of(' '));
        indent = "    ";
        continue;
      }
      page.push_back(indent + text.substr(0, cut + at_break->kept));
      text = text.substr(cut + at_break->resume);
      indent = "    ";
    }
    page.push_back(indent + text);
  }
  const float line = px * 1.4f, ph = line * static_cast<float>(page.size() + 1);
  const float x0 = (w - pw) / 2, y0 = std::max(0.0f, (h - ph) / 2);
  o.fill_rect(x0, y0, pw, ph, {0.05f, 0.05f, 0.07f, 0.88f});
  o.stroke_rect(x0, y0, pw, ph, 2, {1.0f, 1.0f, 1.0f, 0.5f});
  for (std::size_t i = 0; i < page.size(); ++i)
    o.text(x0 + px, y0 + line * static_cast<float>(i + 1), page[i], {1.0f, 1.0f, 1.0f, i == 0 ? 1.0f : 0.85f});
}

int WindowKiosk::run() {
  const Nanos quit_after = static_cast<Nanos>(std::llround(options_.quit_after_s * 1e9));
  Nanos last_frame = monotonic_now();
  next_log_ = last_frame + 60 * kNanosPerSecond;
  metrics_frame_at_ = last_frame;
  double frame_ms = 0;
  for (;;) {
    win_.pace();  // the frame budget: [render] max_fps
    glfwPollEvents();
    const Nanos now = monotonic_now();
    // This frame begins now: strikes this frame decides (the window system's mouse, the ghost)
    // are shown by it, so the present model's grid is anchored here before they are fed.
    win_.window->present_clock().frame_started(now, win_.held_ns(), !win_.window->still());
    frame_ms = 0.9 * frame_ms + 0.1 * to_seconds(now - last_frame) * 1e3;
    last_frame = now;
    ++polls_;
    if (reload_requested()) {
      notifier_.reloading();
      reload();
      notifier_.ready();
    }
    handle_keys(now);
    if (win_.window->close_requested()) {
      glfwSetWindowShouldClose(win_.window->window(), GLFW_FALSE);
      std::fprintf(stderr, "<5>window close requested (%s)\n",
                   options_.windowed ? "the operator page opens" : "refused outside the operator page");
      if (options_.windowed) states_->operator_chord(now);  // a windowed kiosk closes from the page
      states_->window_close_requested(now);
    }
    if (g_stop.load()) {  // systemd's stop (SIGTERM), or Ctrl+C: a clean end, as the operator's Q
      std::fprintf(stderr, "<5>mallet run: %s received, stopping\n", g_stop_signal == SIGINT ? "SIGINT" : "SIGTERM");
      break;
    }
    if (states_->should_quit() || (quit_after > 0 && now - started_ >= quit_after)) break;

    // The mouse's samples since the last frame: from its reading thread (evdev), else the
    // window system's cursor events, each stamped as it was read.
    std::vector<PointerSample> cursor = std::exchange(cursor_, {});
    if (stage_->mouse) cursor = stage_->mouse->take();
    if (!cursor.empty()) last_cursor_ = Vec2{cursor.back().x, cursor.back().y};
    const bool mouse = stage_->source == InputSource::mouse;
    if (mouse)
      for (const PointerSample& p : cursor) states_->pointer(p.t_ns, {p.x, p.y});
    if (stage_->device) poll_remote(now);
    states_->tick(now);
    const std::optional<Vec2> screen = last_cursor_;
    const bool inside = screen && screen->x >= 0 && screen->x <= 1 && screen->y >= 0 && screen->y <= 1;
    calibration_frame(now, mouse && inside ? screen : std::nullopt);
    if (stage_->remote) stage_->remote->set_playing(states_->visitor_plays());
    if (stage_->mouse) stage_->mouse->set_playing(states_->visitor_plays());
    apply_volume();

    StrikeRoute& route = *stage_->route;
    // A live source with its own thread (the remote, the evdev mouse) strikes through its
    // own route; the main thread's route plays the window system's mouse and the ghost.
    const bool threaded = !mouse || stage_->mouse;
    if (threaded && states_->visitor_plays()) {
      ghost_.reset();
    } else if (states_->visitor_plays() && !cursor.empty()) {
      if (ghost_) {  // a visitor takes over from the ghost within this frame
        ghost_.reset();
        route.reset();
        route.loop().set_cycle_materials(false);
      }
      const ScreenToWorld view = framed(stage_->scene.screen_to_world, &win_.aspect);
      for (const PointerSample& p : cursor) route.feed(p.t_ns, view.map(p.x, p.y), now);
    } else if (states_->ghost_plays()) {
      if (!ghost_) {
        ghost_.emplace(stage_->scene, now);
        route.reset();
        route.loop().set_cycle_materials(true);  // the wall shows each of its materials in turn
      }
      // The ghost is a script: its samples up to the next frame are known now, so each of
      // its strikes is heard on its own sample, not at the frame that plays it.
      const Nanos until = now + win_.window->present_clock().period_ns();
      for (const PointerSample& p : ghost_->samples_until(until)) route.feed(p.t_ns, {p.x, p.y});
    } else {
      if (ghost_) route.loop().set_cycle_materials(false);
      ghost_.reset();
    }

    // The visitor's language for this frame: the attract mode's turn, or the one kept.
    if (const std::string& l = language_.at(states_->state(), states_->since(), now); l != visitor_language())
      use_visitor_language(l);
    draw_overlay(now, frame_ms);
    render::FrameState state;
    const Nanos present = win_.window->predicted_present(now);
    if (!latency_test_.empty()) latency_test_frame(present);
    const StrikeLoop::View view = !states_->visitor_plays() ? route.view()
                                  : !mouse                 ? stage_->remote->view()
                                  : stage_->mouse          ? stage_->mouse->view()
                                                           : route.view();
    if (visitor_accepted(now, view)) {
      run_visitor_session();
      continue;
    }
    state.mallet_centre = view.displayed(present);
    // The bar under the mallet (where it is held, not where it bounces) and the bar struck.
    state.bar_lights = bar_lights(stage_->scene, view.shown, view.vibration, present);
    state.overlay = win_.overlay.get();
    // A lost device: the renderer and the window's device, pipelines and background made
    // anew; the sound, the remote's and the evdev mouse's strikes go on on their threads.
    if (win_.draw_or_recover(
            *stage_->renderer, state, [&] { stage_->renderer.reset(); },
            [&] { stage_->renderer = make_renderer(*stage_); }))
      ++frames_;
    else if (win_.window->still())
      ++still_frames_;  // nothing changed: the screen shows this frame already
    work_ms_ = 0.9 * work_ms_ + 0.1 * to_seconds(monotonic_now() - now) * 1e3;
    if (frames_ == 1) notifier_.ready();
    heartbeat(now);
    feed_metrics(now);
  }
  notifier_.stopping();
  std::fprintf(stderr, "<6>mallet run: stopping after %llu frames and %llu strikes\n",
               static_cast<unsigned long long>(frames_), static_cast<unsigned long long>(strikes()));
  if (metrics_file_.enabled()) write_metrics(monotonic_now());  // the final counts, as the line above
  vkDeviceWaitIdle(win_.ctx->device());
  if (stage_->device) stage_->device->stop();
  if (stage_->evdev) stage_->evdev->stop();
  if (stage_->output) stage_->output->stop();
  if (win_.ctx->validation_messages() > 0) {
    std::fprintf(stderr, "<3>%llu Vulkan validation message(s); first: %s\n",
                 static_cast<unsigned long long>(win_.ctx->validation_messages()),
                 win_.ctx->first_validation_message().c_str());
    return 1;
  }
  return 0;
}

}  // namespace

void watch_for_reload() {
  struct sigaction sa {};
  sa.sa_handler = on_sighup;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGHUP, &sa, nullptr);
  sa.sa_handler = on_stop;
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGINT, &sa, nullptr);
}

bool reload_requested() { return g_reload.exchange(false); }

int run_window_kiosk(const KioskOptions& options, KioskSetup setup) {
  watch_for_reload();
  WindowKiosk kiosk(options, std::move(setup));
  return kiosk.run();
}

}  // namespace mallet::app
