#include "app/study_window.hpp"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cmath>
#include <cstdio>
#include <deque>
#include <memory>
#include <utility>
#include <vector>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "app/audio_setup.hpp"
#include "app/headless_loop.hpp"
#include "app/kiosk_text.hpp"
#include "app/render_setup.hpp"
#include "app/strike_route.hpp"
#include "app/study_stimuli.hpp"
#include "app/visitor_catalogues.hpp"
#include "core/visitor_language.hpp"
#include "audio/portaudio_output.hpp"
#include "render/font_atlas.hpp"
#include "render/overlay.hpp"
#include "render/pipeline_cache.hpp"
#include "render/window_target.hpp"

namespace mallet::app {
namespace {

using study::ScheduledTrial;

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

//! The window is both the stage (real time, real devices) and the answer source (keys).
class StudyWindow final : public StudyStage, public AnswerSource {
 public:
  StudyWindow(const StudyPlan& plan, const Scene& scene, const StudyWindowOptions& o)
      : plan_(plan), scene_(scene),
        meter_(scene, plan.config, HeadlessLoop::kNoAttract, false), keys_(answer_keys(plan.protocol)),
        prompt_(answer_prompt(plan.protocol)),
        win_(plan.config.render, o.device, o.size, o.windowed, "Mallet study") {
    const AppConfig& c = plan.config;
    glfwSetWindowUserPointer(win_.window->window(), this);
    glfwSetKeyCallback(win_.window->window(), [](GLFWwindow* w, int key, int, int action, int) {
      if (action == GLFW_PRESS) static_cast<StudyWindow*>(glfwGetWindowUserPointer(w))->pressed_.push_back({key, monotonic_now()});
    });
    make_renderer();
    rig_ = make_audio_rig(scene_, c, c.audio.sample_rate_hz, plan.protocol.sound);
    route_ = std::make_unique<StrikeRoute>(scene_, c, rig_.engine.get(), &win_.window->present_clock());
    output_ = start_output(*rig_.engine, c.audio, audio_status_);  // null: the study shows its taps silently
    rig_.engine->set_acoustic_volume(c.audio.volume);
    rig_.engine->set_actuator_gain(c.actuator.gain);
    const Target& bar = scene_.targets.at(0);
    route_->feed(monotonic_now(), {0.5 * (bar.x_min + bar.x_max), bar.top_y});  // the head rests on the first bar
    started_ = monotonic_now();
    if (o.quit_after_s > 0) quit_at_ = started_ + static_cast<Nanos>(std::llround(o.quit_after_s * 1e9));
    const int actuator = c.audio.routing.actuator;
    const auto channels = static_cast<std::size_t>(meter_.channels());
    meter_.on_audio = [this, actuator, channels](std::span<const float> block) {
      for (std::size_t i = static_cast<std::size_t>(actuator); i < block.size(); i += channels)
        peak_ = std::max(peak_, static_cast<double>(std::fabs(block[i])));
    };
    std::fprintf(stderr, "<6>mallet study: %s, %ux%u, %s\n", win_.ctx->device_name().c_str(),
                 win_.window->extent().width, win_.window->extent().height, audio_status_.c_str());
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
    char tap[64];
    std::snprintf(tap, sizeof tap, tr("Tap %d"), tap_);
    banner_ = plan_.stimuli_per_trial() > 1 ? tap : tr("Tap");
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
  void trial_starts(const ScheduledTrial& trial) override {
    ++trials_shown_;
    tap_ = 0;
    banner_.clear();
    char status[96];
    // An adaptive protocol's tracks stop by their own rules: its count is only a bound.
    std::snprintf(status, sizeof status,
                  plan_.protocol.procedure == study::StudyProcedure::constant ? tr("Trial %d of %zu")
                                                                               : tr("Trial %d (at most %zu)"),
                  trial.number, static_cast<std::size_t>(plan_.total_trials));
    status_ = status;
  }

  // --- AnswerSource
  std::optional<TrialAnswer> answer(const ScheduledTrial& trial, Nanos opens) override {
    banner_ = prompt_;
    std::fprintf(stderr, "<6>trial %d of %d: %s\n", trial.number, plan_.total_trials, prompt_.c_str());
    // A key pressed before the answer window opened is not an answer.
    std::erase_if(pressed_, [opens](const Press& p) { return p.t < opens; });
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
      if (!frame()) return std::nullopt;
    }
  }
  std::string name() const override { return "keys"; }

  //! "Thank you" until a key, the close button or --quit-after.
  void thank_you() {
    banner_ = tr("Thank you");
    status_.clear();
    pressed_.clear();
    thanking_ = true;
    std::fprintf(stderr, "<6>mallet study: Thank you (any key closes)\n");
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
    win_.window->present_clock().frame_started(now, win_.held_ns(), !win_.window->still());  // before this frame's stimuli
    for (const Press& p : pressed_)
      if (p.key == GLFW_KEY_ESCAPE || p.key == GLFW_KEY_Q) quit_ = true;
    if (win_.window->close_requested() || (quit_at_ > 0 && now >= quit_at_)) quit_ = true;
    if (g_stop.load()) quit_ = true;
    if (quit_) {
      if (!thanking_)
        std::fprintf(stderr, "<5>mallet study: stopped by the participant after %d trial(s) shown\n", trials_shown_);
      return false;
    }
    render::Overlay& o = *win_.overlay;
    o.clear();
    const VkExtent2D extent = win_.window->extent();
    const float w = static_cast<float>(extent.width), h = static_cast<float>(extent.height);
    const float px = win_.font->pixel_height();
    if (!banner_.empty()) draw_banner(o, banner_, w, h);
    if (!status_.empty()) o.text(px, h - px, status_, {1.0f, 1.0f, 1.0f, 0.35f});
    render::FrameState state;
    const Nanos present = win_.window->predicted_present(now);
    state.mallet_centre = route_->view().displayed(present);
    state.overlay = win_.overlay.get();
    win_.draw_or_recover(*renderer_, state, [this] { renderer_.reset(); }, [this] { make_renderer(); });
    return true;
  }

  void make_renderer() {
    renderer_ = std::make_unique<render::SceneRenderer>(*win_.ctx, scene_, models_dir(), win_.window->format(),
                                                        render_settings(*win_.ctx, plan_.config.render),
                                                        win_.cache->get());
  }

  const StudyPlan& plan_;
  const Scene& scene_;
  HeadlessLoop meter_;
  std::vector<AnswerKey> keys_;
  std::string prompt_;
  ProductWindow win_;
  std::unique_ptr<render::SceneRenderer> renderer_;
  AudioRig rig_;
  std::unique_ptr<StrikeRoute> route_;  //!< the stimuli's: actuator, note, bounce and log line
  std::unique_ptr<audio::PortAudioOutput> output_;
  std::string audio_status_, banner_, status_;
  std::deque<Press> pressed_;
  Nanos started_ = 0, quit_at_ = 0;
  double peak_ = 0;
  int tap_ = 0, trials_shown_ = 0;
  bool quit_ = false, thanking_ = false;
};

}  // namespace

StudyRunResult run_study_window(const StudyOptions& options, const StudyWindowOptions& window,
                                bool& validation_failed) {
  validation_failed = false;
  const StudyPlan plan = plan_study(options);
  if (plan.finished) {  // nothing left: no window
    StudyRunResult r;
    r.csv = plan.csv;
    r.total = plan.total_trials;
    r.procedure = std::string(study::procedure_name(plan.protocol.procedure));
    r.already_recorded = static_cast<int>(plan.done.size());
    r.warnings = plan.existing.warnings;
    return r;
  }
  const Scene scene = make_study_scene(plan.base, plan.protocol);
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  std::vector<std::string> problems;  // the participant reads the settings' [kiosk] language
  start_visitor_language(plan.config.language, problems);
  for (const std::string& p : problems) std::fprintf(stderr, "<4>%s\n", p.c_str());
  StudyWindow w(plan, scene, window);
  StudyRunResult result = run_session(plan, scene, w, w, options.after_row);
  if (!w.quit()) w.thank_you();
  if (w.validation_messages() > 0) validation_failed = true;
  return result;
}

}  // namespace mallet::app
