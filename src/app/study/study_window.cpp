#include "app/study/study_window.hpp"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <atomic>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <deque>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <fmt/printf.h>

#include "audio/audio_setup.hpp"
#include "app/strike/headless_loop.hpp"
#include "core/journal.hpp"
#include "render/overlay_text.hpp"
#include "render/render_setup.hpp"
#include "app/strike/strike_route.hpp"
#include "app/study/study_stimuli.hpp"
#include "app/study/study_words.hpp"
#include "core/visitor_catalogues.hpp"
#include "app/study/visitor_study.hpp"
#include "core/visitor_language.hpp"
#include "audio/portaudio_output.hpp"
#include "render/font_atlas.hpp"
#include "render/overlay.hpp"
#include "render/pipeline_cache.hpp"
#include "render/scene_view.hpp"
#include "render/text_shaping.hpp"
#include "render/window_target.hpp"

namespace mallet::app {
namespace {

using study::ScheduledTrial;

//! How long the consent screen hears no answer after it opens: a visitor's second strike
//! on the offer's "Yes" (struck twice, as a xylophone is) falls in it.
constexpr Nanos kConsentSettles = kNanosPerSecond;

//! SIGINT / SIGTERM (Ctrl-C in the experimenter's terminal, systemd): stop as Esc does.
std::atomic<bool> g_stop{false};
void on_stop_signal(int) { g_stop.store(true); }

//! A key as the answer keys name it: 'A'..'Z', '0'..'9' (the keypad's digits too); 0 otherwise.
char key_char(int key) {
  if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) return static_cast<char>('A' + (key - GLFW_KEY_A));
  if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) return static_cast<char>('0' + (key - GLFW_KEY_0));
  if (key >= GLFW_KEY_KP_0 && key <= GLFW_KEY_KP_9) return static_cast<char>('0' + (key - GLFW_KEY_KP_0));
  return 0;
}

//! How a StudyWindow runs in a window it may not own.
struct StudyWindowRun {
  Nanos quit_after = 0;     //!< stop (as Esc) this long after the start; 0 = never
  Nanos answer_timeout = 0; //!< no answer (or consent) for this long: stop (a visitor walked away); 0 = never
  bool quit_keys = true;    //!< Esc and Q stop (a participant's); a visitor's keyboard is the operator's
  //! The pointer's samples (normalised screen) since the last call; empty: the window system's cursor.
  std::function<std::vector<PointerSample>()> pointer;
  //! Called once a frame (the kiosk feeds its watchdog); false: stop (the kiosk's SIGTERM).
  std::function<bool()> each_frame;
};

//! The window is both the stage (real time, real devices) and the answer source (keys, or
//! strikes on the answer bars; a visitor's consent too).
class StudyWindow final : public StudyStage, public VisitorAnswers {
 public:
  StudyWindow(const StudyPlan& plan, const Scene& scene, render::ProductWindow& win, StudyWindowRun run)
      : plan_(plan), scene_(scene),
        meter_(scene, plan.config, HeadlessLoop::kNoAttract, false), keys_(answer_keys(plan.protocol)),
        bars_(answer_bars(scene, plan.protocol)),
        prompt_(answer_prompt(plan.protocol)),
        win_(win), run_(std::move(run)) {
    const AppConfig& c = plan.config;
    glfwSetWindowUserPointer(win_.window->window(), this);
    glfwSetKeyCallback(win_.window->window(), [](GLFWwindow* w, int key, int, int action, int) {
      if (action == GLFW_PRESS) static_cast<StudyWindow*>(glfwGetWindowUserPointer(w))->pressed_.push_back({key, monotonic_now()});
    });
    if (!bars_.empty() || scene_.texture) {  // striking answers, crossing discs: the mouse, stamped as it is read
      glfwSetCursorPosCallback(win_.window->window(), [](GLFWwindow* w, double x, double y) {
        auto* self = static_cast<StudyWindow*>(glfwGetWindowUserPointer(w));
        int width = 1, height = 1;
        glfwGetWindowSize(w, &width, &height);
        self->cursor_.push_back({monotonic_now(), x / std::max(width, 1), y / std::max(height, 1)});
      });
    }
    for (const AnswerBar& b : bars_) labels_.push_back({b.target, b.answer});
    // The stimulus bar, which the program taps and no answer strikes, says what it is: among
    // the answer bars it was an unlabelled bar of another kind that a visitor could not place.
    if (!bars_.empty())
      for (const Target& t : scene_.targets)
        if (!t.hand_strikes) {
          stimulus_label_ = render::BarLabel{t.id, tr("Taps")};
          labels_.push_back(*stimulus_label_);
          break;
        }
    make_renderer();
    rig_ = audio::make_audio_rig(scene_, c, c.audio.sample_rate_hz);  // the speaker per instrument (study_stimuli.hpp)
    route_ = std::make_unique<StrikeRoute>(scene_, c, rig_.engine.get(), &win_.window->present_clock());
    output_ = audio::start_output(*rig_.engine, c.audio, audio_status_);  // null: the study shows its taps silently
    rig_.engine->set_acoustic_volume(c.audio.volume);
    rig_.engine->set_actuator_gain(c.actuator.gain);
    rest();
    started_ = monotonic_now();
    if (run_.quit_after > 0) quit_at_ = started_ + run_.quit_after;
    const int actuator = c.audio.routing.actuator;
    const auto channels = static_cast<std::size_t>(meter_.channels());
    meter_.on_audio = [this, actuator, channels](std::span<const float> block) {
      for (std::size_t i = static_cast<std::size_t>(actuator); i < block.size(); i += channels)
        peak_ = std::max(peak_, static_cast<double>(std::fabs(block[i])));
    };
    journal::info("mallet study: {}, {}x{}, {}", win_.ctx->device_name().c_str(), win_.window->extent().width,
                  win_.window->extent().height, audio_status_.c_str());
  }

  ~StudyWindow() override {
    vkDeviceWaitIdle(win_.ctx->device());
    if (output_) output_->stop();
  }

  bool quit() const { return quit_; }
  std::uint64_t validation_messages() const { return win_.ctx->validation_messages(); }

  // --- StudyStage
  Nanos now() override { return monotonic_now(); }
  bool wait_until(Nanos t) override {
    while (frame()) {
      if (monotonic_now() >= t) return true;
    }
    return false;
  }
  Strike present(const Impact& impact) override {
    ++tap_;
    banner_ = plan_.stimuli_per_trial() > 1 ? fmt::sprintf(tr("Tap %d"), tap_) : tr("Tap");
    const Strike strike = route_->present(impact, monotonic_now());
    // The actuator's signal, rendered offline by the same engine on its own clock: the
    // device's output is not read back.
    Impact m = impact;
    m.t_ns = meter_.now();
    meter_.present(m);
    meter_.advance(m.t_ns + plan_.protocol.timing.stimulus);
    return strike;
  }
  double visual_offset_m(Nanos t) const override { return route_->view().vibration.offset_m(t); }
  double take_actuator_peak() override { return std::exchange(peak_, 0.0); }
  std::optional<Strike> hand(Nanos t, Vec2 hand) override {
    if (crossing_) {  // a texture crossing: the hand drives its own route, and is recorded
      crossing_->route->feed(t, hand, monotonic_now());
      crossing_->hand.push_back({t, hand.x, hand.y});
      return std::nullopt;
    }
    std::optional<Strike> strike = route_->feed(t, hand, monotonic_now());
    if (strike) struck_.push_back(*strike);
    return strike;
  }
  std::optional<ActuatorEq> actuator_eq() const override { return rig_.actuator_eq; }
  Exploration explore(const Scene& trial_scene, Nanos until) override {
    const AppConfig& c = plan_.config;
    banner_ = tr("Cross the white disc");
    journal::info("crossing for {:.1f} s: {}", to_seconds(until - monotonic_now()), banner_.c_str());
    // The crossing's own engine and route (its relief, its cues); the study's output is
    // closed meanwhile, as a device may take only one stream.
    const bool sound = output_ != nullptr;
    output_.reset();
    Crossing crossing{audio::make_audio_rig(trial_scene, c, c.audio.sample_rate_hz), {}, {}};
    crossing.route = std::make_unique<StrikeRoute>(trial_scene, c, crossing.rig.engine.get(),
                                                   &win_.window->present_clock());
    std::string status;
    std::unique_ptr<audio::PortAudioOutput> out = sound ? audio::start_output(*crossing.rig.engine, c.audio, status) : nullptr;
    crossing.rig.engine->set_actuator_gain(c.actuator.gain);
    crossing.route->feed(monotonic_now(), route_->view().shown);  // the cursor starts where it rests
    crossing_ = &crossing;
    hand_live_ = true;
    while (monotonic_now() < until && frame()) {
    }
    hand_live_ = false;
    crossing_ = nullptr;
    out.reset();
    if (sound) output_ = audio::start_output(*rig_.engine, c.audio, audio_status_);
    banner_.clear();
    const Exploration e = measure_crossing(trial_scene, c, crossing.hand);
    journal::info("crossed: {} samples, the cursor up to {:.2f} mm off the hand, the stripes up to {:.3f}",
                  crossing.hand.size(), e.cursor_offset_peak_m * 1e3, e.actuator_peak);
    return e;
  }
  void trial_starts(const ScheduledTrial& trial) override {
    ++trials_shown_;
    tap_ = 0;
    banner_.clear();
    // An adaptive protocol's tracks stop by their own rules: its count is only a bound.
    status_ = fmt::sprintf(plan_.protocol.procedure == study::StudyProcedure::constant ? tr("Trial %d of %zu")
                                                                                       : tr("Trial %d (at most %zu)"),
                           trial.number, static_cast<std::size_t>(plan_.planned_trials()));
  }

  // --- AnswerSource
  std::optional<TrialAnswer> answer(const ScheduledTrial& trial, Nanos opens) override {
    banner_ = prompt_;
    journal::info("trial {} of {}: {}", trial.number, plan_.planned_trials(), prompt_.c_str());
    // A key pressed (or a bar struck) before the answer window opened is not an answer.
    std::erase_if(pressed_, [opens](const Press& p) { return p.t < opens; });
    if (!bars_.empty()) {  // the answer bar struck, at the contact the strike route found
      const std::optional<std::size_t> k = struck_bar(opens);
      if (!k) return std::nullopt;
      return TrialAnswer{bars_[*k].answer, struck_at_};
    }
    for (;;) {
      while (!pressed_.empty()) {
        const Press p = pressed_.front();
        pressed_.pop_front();
        const char c = key_char(p.key);
        for (const AnswerKey& k : keys_)
          if (c != 0 && k.key == c) {
            banner_.clear();
            return TrialAnswer{k.answer, p.t};
          }
      }
      if (!frame() || timed_out(opens)) return std::nullopt;
    }
  }
  std::string name() const override { return bars_.empty() ? "keys" : "strike"; }

  // --- VisitorAnswers: the consent screen, answered on the first two answer bars
  std::optional<bool> consent(const study::VisitorProtocol& visitor, Nanos opens) override {
    status_.clear();
    banner_ = visitor.consent;
    const std::vector<render::BarLabel> answers = labels_;
    labels_ = {{bars_.at(0).target, tr("Yes")}, {bars_.at(1).target, tr("No")}};
    if (stimulus_label_) labels_.push_back(*stimulus_label_);
    journal::info("mallet study: a visitor's consent screen");
    // A strike in its first moments is the visitor's strike on the offer, struck again as one
    // strikes a xylophone: it does not answer.
    const std::optional<std::size_t> k = struck_bar(opens, 2, opens + kConsentSettles);
    labels_ = answers;
    if (!k) return std::nullopt;
    return *k == 0;
  }
  //! "Thank you" for a moment (a visitor returns to the kiosk).
  void thank_briefly() {
    banner_ = tr("Thank you");
    status_.clear();
    labels_.clear();
    const Nanos until = monotonic_now() + 3 * kNanosPerSecond;
    while (frame() && monotonic_now() < until) {
    }
  }

  //! "Thank you" until a key, the close button or --quit-after.
  void thank_you() {
    banner_ = tr("Thank you");
    status_.clear();
    pressed_.clear();
    thanking_ = true;
    journal::info("mallet study: Thank you (any key closes)");
    while (frame() && pressed_.empty()) {
    }
  }

 private:
  struct Press {
    int key;
    Nanos t;
  };

  //! One frame; false once the participant (or --quit-after) asked to stop.
  bool frame() {
    if (quit_) return false;
    win_.pace();  // the frame budget: [render] max_fps
    glfwPollEvents();
    const Nanos now = monotonic_now();
    win_.window->present_clock().frame_started(now, win_.held_ns(), !win_.window->still(), win_.window->display_wait_ns());  // before this frame's stimuli
    for (const Press& p : pressed_)
      if (run_.quit_keys && (p.key == GLFW_KEY_ESCAPE || p.key == GLFW_KEY_Q)) quit_ = true;
    if (win_.window->close_requested() || (quit_at_ > 0 && now >= quit_at_)) quit_ = true;
    if (g_stop.load() || (run_.each_frame && !run_.each_frame())) quit_ = true;
    // The participant's mallet while an answer is struck, through the stimuli's own route;
    // the stimuli are the program's taps, shown on the stimulus bar.
    const ScreenToWorld view = framed(scene_.screen_to_world, &win_.aspect);
    for (const PointerSample& p : run_.pointer ? run_.pointer() : std::exchange(cursor_, {}))
      if (hand_live_) hand(p.t_ns, view.map(p.x, p.y));
    if (quit_) {
      if (!thanking_)
        journal::notice("mallet study: stopped by the participant after {} trial(s) shown", trials_shown_);
      return false;
    }
    render::Overlay& o = *win_.overlay;
    o.clear();
    const VkExtent2D extent = win_.window->extent();
    const float w = static_cast<float>(extent.width), h = static_cast<float>(extent.height);
    draw_study_words(o, scene_, {banner_, labels_, status_}, w, h);
    render::FrameState state;
    const Nanos present = win_.window->predicted_present(now);
    state.mallet_centre = (crossing_ ? crossing_->route->view() : route_->view()).displayed(present);
    state.overlay = win_.overlay.get();
    win_.draw_or_recover(*renderer_, state, [this] { renderer_.reset(); }, [this] { make_renderer(); });
    return true;
  }

  //! The answer window is over (a visitor walked away) once run_.answer_timeout has passed.
  bool timed_out(Nanos opens) {
    if (run_.answer_timeout <= 0 || monotonic_now() < opens + run_.answer_timeout) return false;
    journal::notice("mallet study: no answer for {:.0f} s: the session ends here", to_seconds(run_.answer_timeout));
    return true;
  }

  //! The first of the answer bars (only the first `among`) struck at or after `counts_from`
  //! (0: `opens`) by the participant's mallet (the contact in struck_at_), the mallet back on
  //! the stimulus bar; nothing when they stopped or the answer timed out (from `opens`).
  std::optional<std::size_t> struck_bar(Nanos opens, std::size_t among = SIZE_MAX, Nanos counts_from = 0) {
    counts_from = std::max(counts_from, opens);
    struck_.clear();
    hand_live_ = true;  // from now on the mouse moves the mallet
    for (;;) {
      for (const Strike& s : std::exchange(struck_, {}))
        for (std::size_t k = 0; k < std::min(among, bars_.size()); ++k)
          if (bars_[k].target == s.impact.target && s.impact.t_ns >= counts_from) {
            banner_.clear();
            rest();
            struck_at_ = s.impact.t_ns;
            return k;
          }
      if (!frame() || timed_out(opens)) {
        rest();
        return std::nullopt;
      }
    }
  }

  //! The mallet back on the stimulus bar, where the program taps it; the mouse lets go.
  void rest() {
    hand_live_ = false;
    route_->reset();
    if (scene_.texture) {  // left of the disc, where a crossing starts
      const TextureRelief& r = scene_.texture->relief;
      route_->feed(monotonic_now(), {r.center.x - 1.4 * r.radius_m, r.center.y});
      return;
    }
    const Target& bar = scene_.targets.at(0);
    route_->feed(monotonic_now(), {0.5 * (bar.x_min + bar.x_max), bar.top_y});  // held on its top
  }

  void make_renderer() {
    renderer_ = std::make_unique<render::SceneRenderer>(*win_.ctx, scene_, render::models_dir(), win_.window->format(),
                                                        render::render_settings(*win_.ctx, plan_.config.render),
                                                        win_.cache->get());
  }

  const StudyPlan& plan_;
  const Scene& scene_;
  HeadlessLoop meter_;
  std::vector<AnswerKey> keys_;
  std::vector<AnswerBar> bars_;  //!< response = strike
  std::vector<render::BarLabel> labels_;
  std::optional<render::BarLabel> stimulus_label_;  //!< "Taps" on the bar the program taps
  std::vector<PointerSample> cursor_;  //!< the window's cursor events since the last frame (no run_.pointer)
  std::vector<Strike> struck_;         //!< the participant's strikes not yet looked at
  std::string prompt_;
  render::ProductWindow& win_;
  StudyWindowRun run_;
  std::unique_ptr<render::SceneRenderer> renderer_;
  audio::AudioRig rig_;
  std::unique_ptr<StrikeRoute> route_;  //!< the stimuli's: actuator, note, bounce and log line
  std::unique_ptr<audio::PortAudioOutput> output_;
  std::string audio_status_, banner_, status_;
  std::deque<Press> pressed_;
  Nanos started_ = 0, quit_at_ = 0, struck_at_ = 0;
  double peak_ = 0;
  int tap_ = 0, trials_shown_ = 0;
  bool quit_ = false, thanking_ = false;
  bool hand_live_ = false;  //!< the mouse moves the mallet (an answer is being struck, a disc crossed)
  //! A texture_slope crossing in progress: its engine, route and the hand's samples (world).
  struct Crossing {
    audio::AudioRig rig;
    std::unique_ptr<StrikeRoute> route;
    std::vector<PointerSample> hand;
  };
  Crossing* crossing_ = nullptr;
};

}  // namespace

StudyRunResult run_study_window(const StudyOptions& options, const StudyWindowOptions& window) {
  const StudyPlan plan = plan_study(options);
  if (plan.finished) return nothing_run(plan);  // nothing left: no window
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  std::vector<std::string> problems;  // the participant reads the settings' [kiosk] language
  start_visitor_language(plan.config.language, problems);
  for (const std::string& p : problems) journal::warning("{}", p.c_str());
  render::ProductWindow win(plan.config.render, window.device, window.size, window.windowed, "Mallet study");
  // For the screen's shape, and read in the participant's language's direction.
  const Scene scene =
      study_scene_for(plan.base, plan.protocol, win.aspect.get(), render::right_to_left(visitor_language()));
  StudyWindowRun run;
  run.quit_after = static_cast<Nanos>(std::llround(window.quit_after_s * 1e9));
  StudyWindow w(plan, scene, win, run);
  StudyRunResult result = run_session(plan, scene, w, w, options.after_row);
  if (!w.quit()) w.thank_you();
  result.validation_failed = w.validation_messages() > 0;
  return result;
}

study::VisitorSessionResult run_visitor_window(render::ProductWindow& win, const StudyPlan& plan,
                                        std::function<std::vector<PointerSample>()> pointer,
                                        std::function<bool()> each_frame) {
  // For the screen's shape, and read in the direction of the language it is shown in (the
  // kiosk's caller has set it: ShownLanguage).
  const Scene scene =
      study_scene_for(plan.base, plan.protocol, win.aspect.get(), render::right_to_left(visitor_language()));
  StudyWindowRun run;
  run.answer_timeout = plan.protocol.visitor->answer_timeout;
  run.quit_keys = false;
  run.pointer = std::move(pointer);
  run.each_frame = std::move(each_frame);
  StudyWindow w(plan, scene, win, std::move(run));
  const study::VisitorSessionResult result = run_visitor_session(plan, scene, w, w);
  if (result.consented && !w.quit()) w.thank_briefly();
  return result;
}

}  // namespace mallet::app
