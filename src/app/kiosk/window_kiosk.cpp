#include "app/kiosk/window_kiosk.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <fmt/format.h>
#include <fmt/printf.h>

#include "audio/audio_setup.hpp"
#include "app/kiosk/calibration_screen.hpp"
#include "core/journal.hpp"
#include "core/strike_line.hpp"
#include "core/data_paths.hpp"
#include "render/overlay_text.hpp"
#include "render/text_shaping.hpp"
#include "app/kiosk/visitor_words.hpp"
#include "app/kiosk/input_choice.hpp"
#include "app/kiosk/kiosk_health.hpp"
#include "app/kiosk/kiosk_stage.hpp"
#include "app/kiosk/latency_test.hpp"
#include "app/kiosk/photodiode_latency.hpp"
#include "app/common/timing_drop_in.hpp"
#include "app/kiosk/operator_page.hpp"
#include "app/strike/mouse_pointer.hpp"
#include "app/strike/remote_pointer.hpp"
#include "render/render_setup.hpp"
#include "core/strike_loop.hpp"
#include "app/strike/strike_route.hpp"
#include "audio/portaudio_output.hpp"
#include "core/bar_lights.hpp"
#include "core/config/app_config_loader.hpp"
#include "core/config/scene_config.hpp"
#include "core/scene_layout.hpp"
#include "core/kiosk_states.hpp"
#include "core/language_choice.hpp"
#include "core/operator_knobs.hpp"
#include "input/clock.hpp"
#include "core/quality.hpp"
#include "core/study/visitor_offer.hpp"
#include "core/visitor_language.hpp"
#include "render/overlay.hpp"
#include "render/window_target.hpp"

namespace mallet::app {
namespace {

//! The texts drawn while it lives are in `language`; the one in use before comes back after.
//! A visitor study is shown wholly in one language, which may not be the kiosk's.
class ShownLanguage {
 public:
  explicit ShownLanguage(std::string_view language) : before_(visitor_language()) {
    if (language != before_) use_visitor_language(language);
  }
  ~ShownLanguage() {
    if (visitor_language() != before_) use_visitor_language(before_);
  }
  ShownLanguage(const ShownLanguage&) = delete;
  ShownLanguage& operator=(const ShownLanguage&) = delete;

 private:
  std::string before_;
};

std::atomic<bool> g_reload{false};
void on_sighup(int) { g_reload.store(true); }
std::atomic<bool> g_stop{false};
volatile std::sig_atomic_t g_stop_signal = 0;
void on_stop(int signal) {
  g_stop_signal = signal;
  g_stop.store(true);
}

//! Whether `file` lies in the folder `dir` (or below it).
bool in_folder(const std::filesystem::path& file, const std::filesystem::path& dir) {
  const std::filesystem::path rel = file.lexically_normal().lexically_relative(dir.lexically_normal());
  return !rel.empty() && *rel.begin() != "..";
}

KioskStatesConfig states_config(const AppConfig& c, const KioskOptions& o) {
  KioskStatesConfig k;
  k.idle_after_s = o.idle_after_s.value_or(c.attract.idle_after_s);
  return k;
}

class WindowKiosk {
 public:
  WindowKiosk(const KioskOptions& o, KioskSetup setup);
  int run();

 private:
  void build(KioskSetup setup);
  void on_key(int key, int mods, bool repeat);
  void handle_keys(Nanos now);
  void reload();
  //! The screen's shape changed (a rotated screen, a resized window): the stage built anew
  //! on the same settings and scene, laid out for it, when its layout changes.
  void follow_screen_shape();
  //! Keeps `text` as the last good settings in the state folder (kiosk_setup.hpp), unless it
  //! is kept already; a failed write is the state folder's to say.
  void keep_last_good(const std::string& text);
  //! A reload refused: said on the operator page (the journal has it already).
  void refused_reload(const std::string& why);
  void next_wall_material();  //!< operator page M: the wall's next material
  void next_scene();          //!< operator page S: the next of [scenes] choices
  void on_cursor(double x, double y);  //!< the window system's cursor event, stamped as it is read
  void seed_window_cursor();           //!< the cursor's position at start-up, before any event
  float latency_square_side() const { return win_.font->pixel_height() * 4; }  //!< T's white square
  void draw_overlay(Nanos now, double frame_ms);
  //! The visitors' words this frame (attract, play): hints, the offer, the staff's notes.
  VisitorWords visitor_words(Nanos now);
  void apply_volume();
  void poll_remote(Nanos now);
  void calibration_frame(Nanos now, std::optional<Vec2> mouse_screen);
  std::string timing_line() const;  //!< the strike route's policy and the figures it uses
  //! The stage's scene renderer on the window's current device.
  std::unique_ptr<render::SceneRenderer> make_renderer(const KioskStage& stage);
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
  //! The same for the frames that drew (not those an unchanged screen skipped): what the
  //! doctor's vulkan check measures, a frame with the mallet moving, so both say one figure.
  double drawn_ms_ = 0;
  std::unique_ptr<KioskStage> stage_;
  std::unique_ptr<KioskStates> states_;
  std::optional<AttractLoop> ghost_;
  LanguageChoice language_;  //!< [kiosk] language, [attract] languages, the page's L
  input::wiimote::HidDeviceFinder finder_;
  input::SteadyClock clock_;
  std::unique_ptr<CalibrationScreen> calibration_;  //!< while the Calibration state lasts
  std::string notice_;                             //!< the last calibration's outcome ...
  Nanos notice_until_ = 0;                         //!< ... shown until then
  std::string reloaded_;                           //!< the last reload that took, on the page ...
  Nanos reloaded_until_ = 0;                       //!< ... until then
  LatencyTest latency_test_;  //!< the operator page's T
  //! T's photodiode, when the stream records one ([timing] photodiode_channel)
  std::optional<PhotodiodeLatency> photodiode_;
  //! The operator page's latency test, with its photodiode's measurement when there is one.
  void start_latency_test(Nanos now);
  //! The photodiode's answer (Enter: saved; Esc: kept as measured only), and a run of
  //! `calibrate latency --photodiode` then ends.
  void answer_photodiode(bool save);
  //! `calibrate latency --photodiode`: when its test starts, and its exit status once it ended.
  Nanos display_run_starts_ = 0;
  std::optional<int> display_run_status_;
  struct Key {
    int key;
    int mods;
    bool repeat;  //!< the window system's auto-repeat of a held key
  };
  std::vector<Key> keys_;  //!< pressed since the last frame
  std::vector<PageLine> doctor_;           //!< the page's doctor lines (D); empty: the page's own
  int page_ = 0;                           //!< the page's screen shown (PgDn), when it takes several
  //! The page's frame and timing lines, sampled once a second.
  struct PageFigures {
    std::string frame, timing;
    Nanos at = 0;
  };
  std::optional<PageFigures> page_figures_;
  //! The page as last laid out, and for what: laid out again only when one of them changes.
  struct PageShown {
    std::vector<PageLine> lines;
    float width = 0, height = 0, clear_corner = 0;
    PageLayout layout;
  };
  std::optional<PageShown> page_shown_;
  bool doctor_asked_ = false;              //!< D pressed: the checks run in this frame's overlay
  std::vector<PointerSample> cursor_;      //!< the window's cursor events since the last frame
  std::optional<Vec2> last_cursor_;        //!< the latest of them (normalised screen)
  double volume_ = 0.8, gain_ = 0.2;       //!< the operator's knobs
  //! Liveness (systemd's watchdog, the heartbeat) and [metrics].
  KioskHealth health_{monotonic_now()};
  std::optional<study::VisitorOffer> offer_;  //!< [study]: when the visitor study is offered
  bool offer_shown_ = false;                  //!< this frame's overlay shows the offer
  Nanos offer_since_ = 0;             //!< the current offer's start: strikes before it do not accept
};

WindowKiosk::WindowKiosk(const KioskOptions& o, KioskSetup setup)
    : options_(o), win_(setup.config.render, o.device, o.size, o.windowed, "Mallet") {
  install_callbacks();
  volume_ = setup.config.audio.volume;
  gain_ = setup.config.actuator.gain;
  build(std::move(setup));
  journal::info("mallet run: {}, {}x{}, {}", win_.ctx->device_name().c_str(), win_.window->extent().width,
                win_.window->extent().height, stage_->audio_status.c_str());
}

std::unique_ptr<render::SceneRenderer> WindowKiosk::make_renderer(const KioskStage& stage) {
  return std::make_unique<render::SceneRenderer>(*win_.ctx, stage.scene, render::models_dir(), win_.window->format(),
                                                 render::render_settings(*win_.ctx, stage.config.render),
                                                 win_.cache->get());
}

void WindowKiosk::install_callbacks() {
  glfwSetWindowUserPointer(win_.window->window(), this);
  glfwSetKeyCallback(win_.window->window(), [](GLFWwindow* w, int key, int, int action, int mods) {
    if (action == GLFW_PRESS || action == GLFW_REPEAT)
      static_cast<WindowKiosk*>(glfwGetWindowUserPointer(w))->on_key(key, mods, action == GLFW_REPEAT);
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
    journal::info("visitor study: offered ({})", stage_->visitor->visitor->offer.c_str());
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
  journal::info("visitor study: a visitor accepted; the instrument pauses");
  // The study's own audio and strike route play meanwhile: the kiosk's output is closed (a
  // device may take only one stream), and its pointers' threads strike nothing (they still
  // hand their samples over).
  const bool sound = stage_->output != nullptr;
  health_.output_closed(*stage_);
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
  // The study in one language: the kiosk's where the protocol has its words, else wholly in
  // the protocol's own (the kiosk's texts too: prompts, Yes/No, thanks); the kiosk's back after.
  const std::string shown = stage_->visitor->visitor->language_for(visitor_language());
  if (shown != visitor_language())
    journal::info("visitor study: in {} (the protocol has no words in {})", shown.c_str(), visitor_language().c_str());
  const ShownLanguage language(shown);
  study::StudyProtocol protocol = *stage_->visitor;
  const study::VisitorTexts words = protocol.visitor->text_in(shown);
  protocol.visitor->offer = words.offer;
  protocol.visitor->consent = words.consent;
  try {
    std::random_device random;
    const std::uint64_t id = (static_cast<std::uint64_t>(random()) << 32) ^ random();
    // The study's frames are the kiosk's life meanwhile: they feed its watchdog.
    const study::VisitorSessionResult r = options_.visitor_sessions.run(
        win_, stage_->config, stage_->file_scene, protocol, study::visitor_session_id(id),
        study::utc_date(std::time(nullptr)), pointer, [this] {
          health_.feed_watchdog(monotonic_now());
          return !g_stop.load();
        });
    journal::info("visitor study: {} {}, {} of {} trials, {}", r.id,
                  !r.consented ? (r.abandoned ? "walked away at the consent" : "declined")
                  : r.abandoned ? "abandoned"
                  : "completed", r.answered, r.planned, r.csv.string());
    ++health_.metrics().visitor_study[r.abandoned ? "abandoned" : r.consented ? "completed" : "declined"];
    if (r.consented && in_folder(r.csv, health_.state().dir())) health_.state().wrote("visitor study results", {});
  } catch (const std::exception& e) {  // the kiosk plays on
    journal::error("visitor study: {}", e.what());
    // Its results are the state folder's by default: a write there that failed is its to say.
    if (const std::string what = e.what(); what.find(health_.state().dir().string()) != std::string::npos)
      health_.state().wrote("visitor study results", refused(what));
  }
  install_callbacks();
  cursor_.clear();
  // The swapchain's images hold the study's frames: a new renderer draws them whole.
  stage_->renderer = make_renderer(*stage_);
  stage_->route->reset();
  if (sound)
    stage_->output = audio::start_output(*stage_->rig.engine, stage_->config.audio, stage_->audio_status,
                                         photodiode_capture(stage_->config.timing));
  offer_->session_ended(monotonic_now());
  offer_since_ = 0;
}

void WindowKiosk::build(KioskSetup setup) {
  auto stage = std::make_unique<KioskStage>();
  const std::string last_good = last_good_text(setup);
  stage->refused = std::move(setup.refused);
  stage->config = std::move(setup.config);
  if (const auto& run = options_.measure_display_latency) {
    stage->config.timing.photodiode_channel = run->photodiode_channel;
    stage->config.timing.photodiode_input = run->input;
  }
  stage->file_scene = std::move(setup.scene);
  stage->laid_out_for_aspect = win_.aspect.get();
  stage->scene = laid_out(stage->file_scene, layout_for(stage->file_scene, stage->laid_out_for_aspect));
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
  // A bad replay file throws here, before anything running is touched.
  choose_input(*stage, {finder_, clock_, win_, last_cursor_});
  if (!c.study.visitor_protocol.empty() && stage->scene.kind == SceneKind::percussion) {
    try {  // a protocol that does not load: one line, and no offer
      if (!options_.visitor_sessions) throw std::runtime_error("this kiosk was started without the study");
      stage->visitor = options_.visitor_sessions.load(c.study, stage->file_scene);
    } catch (const std::exception& e) {
      stage->visitor_problems.push_back(std::string("visitor study off: ") + e.what());
      journal::warning("visitor study off: {}", e.what());
    }
  }
  if (stage->visitor && stage->visitor->visitor) {
    // Words the kiosk's font cannot draw are not shown: that language's visitors see the
    // study in the protocol's own language, and the page says why.
    study::VisitorProtocol& v = *stage->visitor->visitor;
    std::erase_if(v.texts, [&](const std::pair<std::string, study::VisitorTexts>& t) {
      std::string missing;
      for (const std::string& letter : win_.font->missing_letters(t.first, t.second.offer + t.second.consent, 8))
        missing += (missing.empty() ? "" : " ") + letter;
      if (missing.empty()) return false;
      const std::string line = fmt::format("visitor study: its {} words need letters the kiosk's font lacks ({}); "
                                           "{} visitors are shown it in {}",
                                           t.first, missing, t.first, v.language);
      stage->visitor_problems.push_back(line);
      journal::warning("{}", line.c_str());
      return true;
    });
  }
  // The old output must stop before the new one opens the device; so must the old remote.
  if (stage_ && stage_->output) stage_->output->stop();
  if (stage_) stop_ir_tracker(*stage_);
  if (stage_ && stage_->evdev) stage_->evdev->stop();
  // Null: the scene plays silently.
  stage->output = audio::start_output(*stage->rig.engine, c.audio, stage->audio_status, photodiode_capture(c.timing));
  if (c.timing.photodiode_channel > 0) photodiode_.emplace(c.timing.photodiode_channel, c.timing.photodiode_input);
  else photodiode_.reset();
  // `calibrate latency --photodiode`: its test once the stream has run a while.
  if (options_.measure_display_latency && !display_run_status_) display_run_starts_ = monotonic_now() + 2 * kNanosPerSecond;
  if (stage->visitor)
    if (const std::string why = study::undeliverable_cues(*stage->visitor, stage->output != nullptr); !why.empty()) {
      stage->visitor_problems.push_back("visitor study off: " + why);
      journal::warning("visitor study off: {}", why);
      stage->visitor.reset();
    }
  const Nanos now = monotonic_now();
  ghost_.reset();
  calibration_.reset();
  if (stage_) health_.retire(*stage_);
  const bool languages_changed = !stage_ || stage_->config.language != c.language ||
                                 stage_->config.attract.languages != c.attract.languages ||
                                 stage_->config.attract.language_every_s != c.attract.language_every_s;
  stage_ = std::move(stage);
  offer_.reset();
  offer_since_ = 0;
  if (stage_->visitor)
    offer_.emplace(static_cast<Nanos>(std::llround(c.study.offer_every_s * 1e9)),
                   static_cast<Nanos>(std::llround(c.study.offer_for_s * 1e9)), now);
  health_.stage_built(*stage_);
  if (!last_good.empty()) keep_last_good(last_good);
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
  if (stage_->source == InputSource::mouse && !stage_->mouse) {
    seed_window_cursor();
    // The mallet where the cursor rests from the new stage's first frame (a scene switched
    // by S, a reload): its route has no sample until the pointer moves, and drew no mallet.
    if (last_cursor_)
      stage_->route->feed(now, framed(stage_->scene.screen_to_world, &win_.aspect).map(last_cursor_->x, last_cursor_->y),
                          now);
  }
  if (stage_->device || stage_->camera) {
    states_->remote_connected(now, false);  // until its link runs (says nothing for a replay)
    start_ir_tracker(*stage_);
  }
  if (stage_->evdev) {
    MousePointer* m = stage_->mouse.get();
    stage_->evdev->start([m](std::span<const PointerSample> samples) { m->on_samples(samples); });
  }
  journal::info("{}", input_line(*stage_).c_str());
  journal::info("{}", timing_line().c_str());
  if (stage_->scene.layout != SceneLayout::landscape)
    journal::info("scene: laid out {} for the screen's {:.2f}:1", to_string(stage_->scene.layout),
                  stage_->laid_out_for_aspect);
  apply_volume();
}

//! `line` with its head `english` ("input: ") said as `shown` (its translation); as it is when
//! it does not start so, and in a right-to-left language, where a head in its letters would
//! turn the whole row of Latin text right to left, ragged again (its rows read from the left).
std::string page_head(const std::string& line, std::string_view english, std::string_view shown) {
  if (line.rfind(english, 0) != 0 || render::right_to_left(visitor_language())) return line;
  return std::string(shown) + line.substr(english.size());
}

//! "off", or "10 ms ahead".
std::string predict_text(const PredictionConfig& p) {
  if (!(p.horizon_ms > 0)) return "off";
  return fmt::format("{:.0f} ms ahead", p.horizon_ms);
}

std::string WindowKiosk::timing_line() const {
  const AppConfig& c = stage_->config;
  const TimingConfig& t = c.timing;
  const double audio_ms = stage_->output ? stage_->output->output_latency_s() * 1e3 : 0.0;
  // The frames in the log's own words (the budget's pace), then how they are presented.
  std::string pace = win_.pace_said();
  if (pace.rfind("render: ", 0) == 0) pace.erase(0, 8);
  return fmt::format("timing: align {}, prediction {}, {}{}presented {}, display {:.0f} ms, audio out {:.1f} ms{}",
                     to_string(t.align), predict_text(t.predict), pace, pace.empty() ? "" : "; ",
                     win_.window->present_clock().describe(),
                     t.display_latency_ms, audio_ms, c.audio.output_latency_ms >= 0 ? " (set)" : " (the device's)");
}

void WindowKiosk::poll_remote(Nanos now) {
  KioskStage& s = *stage_;
  const IrLink link = ir_link(s);
  const bool up = link.up;
  const char* what = s.camera ? "" : "Wii Remote ";
  // Every loss is told, also one the reading thread reopened from before this look.
  for (const LinkChange& change : s.link.look(link)) {
    states_->remote_connected(now, change.connected);
    if (change.connected) journal::notice("{}{} connected", what, link.identity.c_str());
    else journal::warning("{}{} lost: {}", what, link.identity.empty() ? "camera" : link.identity.c_str(),
                          change.why.c_str());
    // A recording's timeline on the kiosk's clock (`mallet bench latency` maps its strokes' true
    // contacts with it).
    if (change.connected && s.replay)
      journal::info("replay: the recording's time 0 is t={}", format_seconds(s.replay->last_origin()).c_str());
  }
  if (up && !s.checked_calibration && live_ir_tracker(s.source)) {
    // Start-up: no valid calibration, or one made with another remote or camera → calibrate now.
    s.checked_calibration = true;
    const std::string& id = link.identity;
    if (!s.calibration || (!s.calibration->remote.empty() && s.calibration->remote != id)) {
      journal::notice("calibration needed: {}",
                      s.calibration ? "it was made with " + s.calibration->remote + ", this remote is " + id
                      : std::string("none valid"));
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
    if (const std::optional<std::string> preset = calibration_->sensitivity_request(); preset && s.device)
      s.device->request_sensitivity(*preset);
  }
}

void WindowKiosk::calibration_frame(Nanos now, std::optional<Vec2> mouse_screen) {
  if (states_->state() != KioskState::calibration) {
    // Abandoned (the operator chord): the previous calibration stays, and so does the
    // configured sensitivity if the tuner was trying another.
    if (calibration_)  // a mouse's calibration keeps nothing: there is no previous one
      journal::notice("operator: calibration abandoned{}",
                      stage_->source == InputSource::mouse ? "" : ", the previous one stays");
    if (calibration_ && calibration_->tuning() && stage_->device)
      stage_->device->request_sensitivity(kiosk_sensitivity(stage_->config, stage_->calibration));
    calibration_.reset();
    return;
  }
  if (!calibration_) {
    CalibrationSessionConfig cc;
    cc.screen = {static_cast<double>(win_.window->extent().width), static_cast<double>(win_.window->extent().height)};
    const bool remote = stage_->device != nullptr || stage_->camera != nullptr;
    // A replay calibrates in memory only: the file belongs to the real remote (or camera).
    const bool save = live_ir_tracker(stage_->source);
    calibration_ = std::make_unique<CalibrationScreen>(
        cc, save ? std::optional<std::filesystem::path>(calibration_path()) : std::nullopt,
        remote ? ir_link(*stage_).identity : std::string("mouse"));
    // The Wii camera's sensitivity blocks are the remote's; a V4L2 camera's exposure is set.
    if (stage_->device) calibration_->tune_sensitivity({}, kiosk_sensitivity(stage_->config, stage_->calibration));
  }
  // The mouse stands in for the IR dot while it is the input (measured on the ring only).
  if (stage_->source == InputSource::mouse && mouse_screen) calibration_->feed_pointer(now, *mouse_screen);
  if (stage_->device || stage_->camera) calibration_->link(ir_link(*stage_).up, stage_->camera != nullptr);
  if (calibration_->outcome() == CalibrationScreen::Outcome::measuring) return;
  if (!calibration_->sensitivity().empty())
    stage_->calibration_status_sensitivity = "IR sensitivity " + calibration_->sensitivity();
  if (const std::optional<Check>& saved = calibration_->saved())
    health_.state().wrote(calibration_path().filename().string(), *saved);
  notice_ = calibration_->message();
  notice_until_ = now + 6 * kNanosPerSecond;
  if (const std::string& why = calibration_->session().failure(); !why.empty())
    journal::notice("{} ({})", notice_.c_str(), why.c_str());  // the screen's plain words, and the fit's own
  else
    journal::notice("{}", notice_.c_str());
  if (calibration_->outcome() == CalibrationScreen::Outcome::accepted) {
    if (stage_->remote) {
      stage_->calibration = calibration_->result();
      stage_->remote->set_calibration(stage_->calibration);
      stage_->calibration_status = live_ir_tracker(stage_->source)
                                       ? "calibration: " + calibration_path().string() + " (" + notice_ + ")"
                                       : "calibration: in memory (" + notice_ + ")";
    }
    states_->calibration_accepted(now);
  } else {
    states_->calibration_cancelled(now);
  }
  calibration_.reset();
}

void WindowKiosk::apply_volume() {
  const double attract = states_ && states_->attract_volume() ? stage_->config.attract.volume : 1.0;
  stage_->rig.engine->set_acoustic_volume(volume_ * attract);
  stage_->rig.engine->set_actuator_gain(gain_);
}

void WindowKiosk::on_key(int key, int mods, bool repeat) { keys_.push_back({key, mods, repeat}); }

void WindowKiosk::start_latency_test(Nanos now) {
  // T again while the photodiode records: the test under way goes on (its recording is the
  // stream's, and its squares are the ones being timed).
  if (photodiode_ && photodiode_->phase() == PhotodiodeLatency::Phase::recording) return;
  latency_test_.start(now, stage_->scene, *stage_->rig.engine);
  if (photodiode_) photodiode_->start(stage_->output.get());
}

void WindowKiosk::answer_photodiode(bool save) {
  if (photodiode_->phase() == PhotodiodeLatency::Phase::asking) {
    const DisplayLatencyMeasurement m = photodiode_->measurement(save);
    try {
      const std::filesystem::path written = keep_display_latency(m);
      if (save) {
        journal::notice("operator: display latency {:.3f} ms saved in {}; the kiosk reloads with it", m.display_latency_ms,
                        written.c_str());
        g_reload.store(true);
      } else {
        journal::notice("operator: display latency {:.3f} ms not saved ([timing] display_latency_ms stays {:.1f} ms)",
                        m.display_latency_ms, stage_->config.timing.display_latency_ms);
      }
      health_.state().wrote("display latency", {});
    } catch (const std::exception& e) {  // the state folder: said, and the kiosk plays on
      journal::error("display latency: {}", e.what());
      health_.state().wrote("display latency", refused(e.what()));
    }
    if (options_.measure_display_latency) display_run_status_ = 0;
  } else if (options_.measure_display_latency) {
    display_run_status_ = 2;  // nothing usable measured: its line was said
  }
  photodiode_->answered();
}

void WindowKiosk::handle_keys(Nanos now) {
  for (const auto& [key, mods, repeat] : keys_) {
    // The photodiode's question (or its failure) takes Enter and Esc while it is on the page.
    if (photodiode_ && !repeat && states_->state() == KioskState::operator_page &&
        (photodiode_->phase() == PhotodiodeLatency::Phase::asking ||
         photodiode_->phase() == PhotodiodeLatency::Phase::failed)) {
      if ((key == GLFW_KEY_ENTER || key == GLFW_KEY_KP_ENTER) && photodiode_->phase() == PhotodiodeLatency::Phase::asking) {
        answer_photodiode(true);
        continue;
      }
      if (key == GLFW_KEY_ESCAPE) {
        answer_photodiode(false);
        continue;
      }
    }
    if (key == GLFW_KEY_ESCAPE && !repeat && states_->state() == KioskState::calibration) {
      states_->calibration_cancelled(now);  // Esc stops it: the previous calibration stays (calibration_frame)
      continue;
    }
    const OperatorAction action = operator_action(key, mods, states_->state() == KioskState::operator_page);
    if (repeat && !operator_action_repeats(action)) continue;
    // Any key of the page but Q withdraws Q's question and restarts the page's timer.
    if (action != OperatorAction::none && action != OperatorAction::quit) states_->operator_key(now);
    switch (action) {
      case OperatorAction::none: break;  // visitors' keys do nothing
      case OperatorAction::open:
        states_->operator_chord(now);
        page_ = 0;
        journal::notice("operator: page {}", states_->state() == KioskState::operator_page ? "open" : "closed");
        break;
      case OperatorAction::close:
        states_->operator_page_closed(now);
        journal::notice("operator: page closed");
        break;
      case OperatorAction::quit:
        if (states_->quit_requested(now))
          journal::notice("operator: quit");
        else if (states_->quit_asked())
          journal::notice("operator: Q asks first: Q again within {:g} s quits", states_->config().quit_confirm_s);
        break;
      case OperatorAction::recalibrate:  // the screen itself starts in the frame
        journal::notice("operator: recalibrate");
        states_->recalibrate(now);
        break;
      // A knob at its end stays there, and the journal gets no second line for it.
      case OperatorAction::volume_up:
      case OperatorAction::volume_down:
        if (const double v = knob_step(volume_, kVolumeKnob, action == OperatorAction::volume_up); v != volume_) {
          volume_ = v;
          journal::notice("operator: volume {:.0f} %", volume_ * 100);
        }
        break;
      case OperatorAction::gain_up:
      case OperatorAction::gain_down:
        if (const double g = knob_step(gain_, kGainKnob, action == OperatorAction::gain_up); g != gain_) {
          gain_ = g;
          journal::notice("operator: actuator gain {:.2f}", gain_);
        }
        break;
      case OperatorAction::next_material: next_wall_material(); break;
      case OperatorAction::next_scene: next_scene(); break;
      case OperatorAction::next_language:
        use_visitor_language(language_.next());
        journal::notice("operator: language {}", visitor_language().c_str());
        break;
      case OperatorAction::latency_test: start_latency_test(now); break;
      case OperatorAction::doctor:
        if (doctor_.empty()) doctor_asked_ = true;
        else doctor_.clear();  // D again: back to the page
        page_ = 0;
        break;
      case OperatorAction::next_page: ++page_; break;  // wraps at the last (layout_operator_page)
      case OperatorAction::previous_page: --page_; break;
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
  const Material& material = stage_->scene.materials[static_cast<std::size_t>(m)];
  journal::notice("operator: wall material {} ({})", material.display_name, material.name);
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
  journal::notice("switching to the scene {}", options_.scene.c_str());
  reload();
  if (std::filesystem::path(stage_->scene.file) != options_.scene) options_.scene = previous;  // refused: stays
}

void WindowKiosk::seed_window_cursor() {
  // Where the window system's cursor already is: the mallet starts there, and the first move
  // from it is a visitor's. A move to where the cursor already is sends no event (the X
  // server starts it at the screen's centre; the window does not move it: WindowTarget), so
  // without this the mallet and the mouse calibration's centre target would wait for one.
  double x = 0, y = 0;
  int w = 1, h = 1;
  glfwGetCursorPos(win_.window->window(), &x, &y);
  glfwGetWindowSize(win_.window->window(), &w, &h);
  const Vec2 at{x / std::max(w, 1), y / std::max(h, 1)};
  if (!(at.x >= 0 && at.x <= 1 && at.y >= 0 && at.y <= 1)) return;  // outside a window: no position
  last_cursor_ = at;
  states_->pointer_rests(at);
}

void WindowKiosk::on_cursor(double x, double y) {
  int w = 1, h = 1;
  glfwGetWindowSize(win_.window->window(), &w, &h);
  cursor_.push_back({monotonic_now(), x / std::max(w, 1), y / std::max(h, 1)});
}

void WindowKiosk::reload() {
  Result<KioskSetup, std::string> setup = load_setup(options_);
  if (!setup) {
    journal::warning("reload refused, the running configuration stays: {}", setup.error());
    refused_reload(setup.error());
    return;
  }
  try {
    vkDeviceWaitIdle(win_.ctx->device());
    volume_ = setup->config.audio.volume;
    gain_ = setup->config.actuator.gain;
    const std::vector<std::string> problems = setup->problems;
    const std::string settings = setup->settings_line;
    build(std::move(*setup));
    journal::notice("reloaded the settings and the scene ({})", settings.c_str());
    // Said on the page for a minute too: the operator who pressed S, or reloaded from a
    // terminal and walks to the kiosk, sees that it took.
    char clock[16] = "";
    const std::time_t wall = std::time(nullptr);
    std::tm local{};
    if (localtime_r(&wall, &local)) std::strftime(clock, sizeof clock, "%H:%M:%S", &local);
    reloaded_ = "reloaded at " + std::string(clock) + ": " + settings;
    reloaded_until_ = monotonic_now() + 60 * kNanosPerSecond;
    for (const std::string& p : problems) journal::warning("{}", p.c_str());
  } catch (const std::exception& e) {  // e.g. a model the new scene names is broken: whatever is thrown
    journal::warning("reload refused, the running configuration stays: {}", e.what());
    refused_reload(e.what());
  }
}

void WindowKiosk::follow_screen_shape() {
  const double aspect = win_.aspect.get();
  if (aspect == stage_->laid_out_for_aspect) return;
  stage_->laid_out_for_aspect = aspect;
  const SceneLayout layout = layout_for(stage_->file_scene, aspect);
  if (layout == stage_->scene.layout) return;
  KioskSetup setup;
  setup.config = stage_->config;
  setup.scene = stage_->file_scene;
  setup.settings_line = stage_->settings_line;
  setup.scene_choices = stage_->scene_choices;
  setup.problems = stage_->problems;
  setup.refused = stage_->refused;
  try {
    vkDeviceWaitIdle(win_.ctx->device());
    build(std::move(setup));
    journal::notice("the screen is now {:.2f}:1: the scene laid out {}", aspect, to_string(layout));
  } catch (const std::exception& e) {  // whatever the build throws: the running stage stays
    journal::warning("the screen is now {:.2f}:1, the scene stays laid out {}: {}", aspect,
                     to_string(stage_->scene.layout), e.what());
  }
}

void WindowKiosk::refused_reload(const std::string& why) {
  // On the operator page too, in place of an earlier refusal, until a reload loads.
  std::vector<std::string>& problems = stage_->problems;
  const std::string prefix = "reload refused, the running configuration stays: ";
  std::erase_if(problems, [&](const std::string& p) { return p.rfind(prefix, 0) == 0; });
  problems.insert(problems.begin(), prefix + why);
}

void WindowKiosk::keep_last_good(const std::string& text) {
  const std::filesystem::path file = health_.state().file(kLastGoodSettings);
  std::ifstream in(file, std::ios::binary);
  std::ostringstream kept;
  kept << in.rdbuf();
  if (in && kept.str() == text) return;  // kept already: no write at each start
  if (health_.state().write(kLastGoodSettings, text))
    journal::info("settings kept as the last good ones: {}", file.string());
}

VisitorWords WindowKiosk::visitor_words(Nanos now) {
  VisitorWords words;
  words.note_names = stage_->config.note_names;
  if (stage_->scene.kind == SceneKind::wall) {
    // The shipped wall materials' names (config/materials.toml) are in the catalogues; a name
    // a lab gives its own material shows as written.
    [[maybe_unused]] static constexpr const char* kShippedWallNames[] = {N_("Rubber"), N_("Wood"), N_("Aluminium")};
    const int wall = stage_->route->loop().wall_material();
    if (wall >= 0) words.wall_name = tr(stage_->scene.materials[static_cast<std::size_t>(wall)].display_name.c_str());
  }
  const KioskHint hint = states_->hint();
  // The visitor study's offer, and its "Yes" under the last bar, in place of the invitation
  // (a hint that something needs doing, a lost remote, comes first). While it shows, the
  // screen is wholly in the language the study will be shown in: the kiosk's where the
  // protocol has its words, else the protocol's own (never its words beside another
  // language's).
  const bool offering = (hint == KioskHint::none || hint == KioskHint::invitation) && visitor_offered(now);
  std::optional<ShownLanguage> shown;  // the study's language, until the corner notes are written
  if (offering) {
    const study::VisitorProtocol& visitor = *stage_->visitor->visitor;
    const std::string language = visitor.language_for(visitor_language());
    shown.emplace(language);
    words.banner = visitor.text_in(language).offer + " " + tr("(strike Yes)");
    words.called_out = render::BarLabel{visitor_yes_bar(), tr("Yes")};
  } else if (hint != KioskHint::none) {
    words.banner = hint_text(hint, stage_->scene.kind, stage_->source == InputSource::mouse);
  } else if (now < notice_until_) {
    words.banner = notice_;
  }
  // Notes for the staff walking past, discreet on their own dark bands in the corners
  // (contrast measured on every scene's frames: tests/app/strike/text_contrast_test.cpp),
  // worded so that a visitor reads no fault in them: a refused close, the mouse standing in
  // for the remote (why is the operator page's), a kiosk without sound.
  const KioskOverlay overlay = states_->overlay();
  if (overlay.close_needs_chord) words.staff_left = hint_text(KioskHint::close_needs_chord);
  else if (overlay.mouse_notice) words.staff_left = tr("Mouse");
  if (!stage_->output && (states_->state() == KioskState::attract || states_->state() == KioskState::play))
    words.staff_right = tr("No sound");
  return words;
}

void WindowKiosk::draw_overlay(Nanos now, double frame_ms) {
  render::Overlay& o = *win_.overlay;
  o.clear();
  const VkExtent2D extent = win_.window->extent();
  const float w = static_cast<float>(extent.width), h = static_cast<float>(extent.height);
  offer_shown_ = false;
  // The operator page and the calibration have their own words, with nothing of the
  // visitors' showing through them.
  if (states_->state() == KioskState::calibration) {
    if (calibration_) calibration_->draw(o, w, h);
  } else if (states_->state() != KioskState::operator_page) {
    const VisitorWords words = visitor_words(now);
    offer_shown_ = words.called_out.has_value();  // the offer's "Yes": its bar is lit too
    draw_visitor_words(o, stage_->scene, words, w, h);
  }
  if (states_->state() != KioskState::operator_page) {
    doctor_.clear();
    return;
  }
  if (doctor_asked_) {
    doctor_asked_ = false;
    // What a frame costs, not the budget's interval; and the state folder as the kiosk found it.
    doctor_ = doctor_page_lines(*stage_, win_, options_, drawn_ms_, health_.state().problem());
  }
  // The page's figures change once a second, not each frame: an unchanged page is not drawn
  // again (the window's skip_unchanged), so the open page costs no more than play.
  if (!page_figures_ || now - page_figures_->at >= kNanosPerSecond) {
    const double uptime = to_seconds(now - health_.started());
    page_figures_ =
        PageFigures{fmt::sprintf(tr("frame: %.1f ms (its work %.1f ms)   uptime: %.0f h %02.0f min"), frame_ms,
                                 work_ms_, std::floor(uptime / 3600), std::fmod(std::floor(uptime / 60), 60.0)),
                    timing_line(), now};
  }
  std::vector<PageLine> lines;
  // The page's words are the operator's language (translated texts keep printf's syntax,
  // which gettext checks: fmt::sprintf); its status lines (input, audio, timing, settings,
  // the doctor's checks) stay as the journal and `mallet doctor` write them.
  lines.push_back({PageTone::title, fmt::sprintf(tr("Mallet: operator page   quality: %s   language: %s"),
                                                 to_string(stage_->config.quality), visitor_language())});
  // What needs the operator first, before the status: settings refused (at start, on a
  // reload), drop-ins and scene choices skipped, a state folder that cannot be written.
  if (states_->quit_asked()) lines.push_back({PageTone::warning, tr("Q again quits the kiosk (any other key: stay)")});
  // A calibration's outcome (R from the page comes back to it): a line of its own, not a
  // banner drawn over the page's words.
  if (now < notice_until_) lines.push_back({PageTone::status, notice_});
  if (now < reloaded_until_) lines.push_back({PageTone::status, reloaded_});
  if (const std::string test = latency_test_.status(now); !test.empty()) lines.push_back({PageTone::status, test});
  if (photodiode_)
    for (PageLine& l : photodiode_->page_lines(stage_->config.timing.display_latency_ms)) lines.push_back(std::move(l));
  for (const std::string& p : stage_->problems) lines.push_back({PageTone::warning, p});
  for (const std::string& p : stage_->visitor_problems) lines.push_back({PageTone::warning, p});
  if (health_.state().failing()) lines.push_back({PageTone::warning, health_.state().problem()});
  if (!doctor_.empty()) {  // D: the doctor's checks instead of the page's status
    lines.insert(lines.end(), doctor_.begin(), doctor_.end());
    lines.push_back({PageTone::keys, tr("D back to the page    Esc close")});
  } else {
    // The status lines in the journal's words (an operator searches the log with them), their
    // heads in the page's language.
    lines.push_back({PageTone::status, page_head(input_line(*stage_), "input: ", tr("input: "))});
    lines.push_back({PageTone::status, page_head(stage_->audio_status, "audio: ", tr("audio: "))});
    lines.push_back({PageTone::status, page_figures_->frame});
    lines.push_back({PageTone::status, fmt::sprintf(tr("volume %.0f %%  (Up / Down)"), volume_ * 100)});
    lines.push_back({PageTone::status, fmt::sprintf(tr("actuator gain %.2f  (Left / Right)"), gain_)});
    lines.push_back(
        {PageTone::keys, tr("R recalibrate    T latency test    D doctor    L language    Q quit    Esc close")});
    const int wall = stage_->route->loop().wall_material();
    std::string scene_line =
        fmt::sprintf(tr("scene: %s  (S next)"), std::filesystem::path(stage_->scene.file).filename().string());
    if (wall >= 0) {  // its name as on the screen, and as the log and the results write it
      const Material& m = stage_->scene.materials[static_cast<std::size_t>(wall)];
      scene_line += fmt::sprintf(tr("   wall: %s  (M next)"), m.display_name + " (" + m.name + ")");
    }
    lines.push_back({PageTone::status, scene_line});
    const std::string& tuned = stage_->calibration_status_sensitivity;
    lines.push_back({PageTone::status, stage_->remote
                                           ? stage_->calibration_status + (tuned.empty() ? "" : ", ") + tuned
                                           : tr("calibration: R runs the screen with the mouse (not saved)")});
    lines.push_back({PageTone::status, page_head(page_figures_->timing, "timing: ", tr("timing: "))});
    lines.push_back({PageTone::status, page_head(stage_->settings_line, "settings: ", tr("settings: "))});
  }
  // Laid out only when its lines, the screen, the latency square or the screen asked for
  // change (at most once a second while nothing else does), not at every frame.
  const float corner = latency_test_.pulsing(now) ? latency_square_side() : 0.0f;
  if (!page_shown_ || page_shown_->lines != lines || page_shown_->width != w || page_shown_->height != h ||
      page_shown_->clear_corner != corner || page_shown_->layout.page != page_) {
    PageLayout layout = layout_operator_page(*win_.font, lines, w, h, corner, page_);
    page_shown_ = PageShown{std::move(lines), w, h, corner, std::move(layout)};
  }
  page_ = page_shown_->layout.page;
  draw_operator_page(o, page_shown_->layout);
}

int WindowKiosk::run() {
  const Nanos quit_after = static_cast<Nanos>(std::llround(options_.quit_after_s * 1e9));
  Nanos last_frame = monotonic_now();
  double frame_ms = 0;
  for (;;) {
    win_.pace();  // the frame budget: [render] max_fps
    glfwPollEvents();
    const Nanos now = monotonic_now();
    // This frame begins now: strikes this frame decides (the window system's mouse, the ghost)
    // are shown by it, so the present model's grid is anchored here before they are fed.
    win_.window->present_clock().frame_started(now, win_.held_ns(), !win_.window->still(), win_.window->display_wait_ns());
    frame_ms = 0.9 * frame_ms + 0.1 * to_seconds(now - last_frame) * 1e3;
    last_frame = now;
    health_.polled();
    if (reload_requested()) {
      health_.notifier().reloading();
      reload();
      health_.ready();
    }
    follow_screen_shape();
    handle_keys(now);
    if (win_.window->close_requested()) {
      glfwSetWindowShouldClose(win_.window->window(), GLFW_FALSE);
      if (options_.windowed) states_->operator_chord(now);  // a windowed kiosk closes as a window does
      const bool granted = states_->window_close_requested(now);
      journal::notice("window close requested: {}", granted ? (options_.windowed ? "the windowed kiosk quits"
                                                                                  : "the kiosk quits (operator page)")
                                                             : "refused outside the operator page");
    }
    if (g_stop.load()) {  // systemd's stop (SIGTERM), or Ctrl+C: a clean end, as the operator's Q
      journal::notice("mallet run: {} received, stopping", g_stop_signal == SIGINT ? "SIGINT" : "SIGTERM");
      break;
    }
    if (states_->should_quit() || (quit_after > 0 && now - health_.started() >= quit_after)) break;
    if (photodiode_) {
      photodiode_->poll(now, latency_test_, stage_->output.get());
      if (options_.measure_display_latency) {
        // `calibrate latency --photodiode`: the page stays open (its timer restarted) until
        // the answer; the test starts once the stream has run a while.
        if (states_->state() != KioskState::operator_page) states_->operator_chord(now);
        states_->operator_key(now);
        if (display_run_starts_ > 0 && now >= display_run_starts_) {
          display_run_starts_ = 0;
          start_latency_test(now);
        }
        if (photodiode_->phase() == PhotodiodeLatency::Phase::failed && !display_run_status_) {
          std::fprintf(stderr, "mallet: %s\n", photodiode_->problem().c_str());
          display_run_status_ = 2;
        }
        if (display_run_status_) break;
      }
    }

    // The mouse's samples since the last frame: from its reading thread (evdev), else the
    // window system's cursor events, each stamped as it was read.
    std::vector<PointerSample> cursor = std::exchange(cursor_, {});
    if (stage_->mouse) cursor = stage_->mouse->take();
    if (!cursor.empty()) last_cursor_ = Vec2{cursor.back().x, cursor.back().y};
    const bool mouse = stage_->source == InputSource::mouse;
    if (mouse)
      for (const PointerSample& p : cursor) states_->pointer(p.t_ns, {p.x, p.y});
    if (stage_->device || stage_->camera) poll_remote(now);
    const int page_timeouts = states_->page_timeouts();
    states_->tick(now);
    if (states_->page_timeouts() != page_timeouts)
      journal::notice("operator: page closed by itself after {:g} s without a key",
                      states_->config().operator_page_timeout_s);
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
      if (ghost_) route.loop().set_cycle_materials(false);  // the operator's wall material back
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
    if (latency_test_.square_shown(present))
      win_.overlay->fill_rect(0, 0, latency_square_side(), latency_square_side(), {1.0f, 1.0f, 1.0f, 1.0f});
    const StrikeLoop::View view = !states_->visitor_plays() ? route.view()
                                  : !mouse                 ? stage_->remote->view()
                                  : stage_->mouse          ? stage_->mouse->view()
                                                           : route.view();
    if (visitor_accepted(now, view)) {
      run_visitor_session();
      continue;
    }
    state.mallet_centre = view.displayed(present);
    // The mallet shows where it strikes: not under the operator page's text nor the
    // calibration's instructions, where its ball would sit, dimmed, on the words.
    state.draw_mallet =
        states_->state() != KioskState::operator_page && states_->state() != KioskState::calibration;
    // The bar under the mallet (where it is held, not where it bounces) and the bar struck.
    state.bar_lights = bar_lights(stage_->scene, view.shown, view.vibration, present);
    if (offer_shown_) state.bar_lights[2] = {visitor_yes_bar(), kCalledOutGlow};  // the offer's "Yes", lit
    state.overlay = win_.overlay.get();
    // A lost device: the renderer and the window's device, pipelines and background made
    // anew; the sound, the remote's and the evdev mouse's strikes go on on their threads.
    const bool drew = win_.draw_or_recover(
        *stage_->renderer, state, [&] { stage_->renderer.reset(); },
        [&] { stage_->renderer = make_renderer(*stage_); });
    if (drew) health_.frame_drawn();
    else if (win_.window->still()) health_.frame_still();  // nothing changed: the screen shows this frame already
    const double this_ms = to_seconds(monotonic_now() - now) * 1e3;
    work_ms_ = 0.9 * work_ms_ + 0.1 * this_ms;
    if (drew) drawn_ms_ = drawn_ms_ > 0 ? 0.9 * drawn_ms_ + 0.1 * this_ms : this_ms;
    // READY=1 once the frames cost what they will: after the first frame drawn whole and the
    // first drawn over the cached background (only what changed), whose pipelines a software
    // driver compiles at that first use. Mesa 25's lavapipe takes 1.6 s for that second frame
    // where Mesa 22.3's took 0.4 s (a PC's CPU; then 50 ms a frame); in a slow machine that
    // was over the watchdog's 10 s, which killed the kiosk right after READY=1, and each
    // restart began again (the compile, lost with the kiosk, was never cached). Before
    // READY=1, TimeoutStartSec= waits, as it does for the first frame. A still scene draws
    // no second frame: it is ready as soon as the first is on the screen.
    if (!health_.said_ready() && (health_.frames() >= 2 || (health_.frames() == 1 && win_.window->still())))
      health_.ready();
    health_.beat(now, *stage_, *states_, win_);
  }
  health_.stop(monotonic_now(), *stage_, win_);
  vkDeviceWaitIdle(win_.ctx->device());
  stop_ir_tracker(*stage_);
  if (stage_->evdev) stage_->evdev->stop();
  if (stage_->output) stage_->output->stop();
  if (win_.ctx->validation_messages() > 0) {
    journal::error("{} Vulkan validation message(s); first: {}", win_.ctx->validation_messages(),
                   win_.ctx->first_validation_message().c_str());
    return 1;
  }
  return display_run_status_.value_or(0);
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
  int status = 0;
  {
    WindowKiosk kiosk(options, std::move(setup));
    status = kiosk.run();
  }  // the window closed and the display's connection with it
  // STOPPING=1 only now: it makes systemd stop the kiosk's display at once (mallet-session
  // is bound to mallet.service), and a display that vanishes while the window is still open
  // ends the kiosk with Xlib's fatal IO error, status 1, which the unit restarts. So the
  // operator's Q restarted the kiosk instead of stopping it (found by the VM system test).
  SystemdNotifier::from_environment().stopping();
  return status;
}

}  // namespace mallet::app
