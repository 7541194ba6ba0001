#include "app/study/study_headless.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/ghost_player.hpp"

namespace mallet::app {

using namespace mallet::study;

HeadlessStage::HeadlessStage(const Scene& scene, const StudyPlan& plan, const std::optional<std::filesystem::path>& wav)
    : loop_(scene, plan.config, HeadlessLoop::kNoAttract),  // the speaker per instrument (study_stimuli.hpp)
      config_(plan.config), actuator_channel_(plan.config.audio.routing.actuator) {
  if (wav) wav_ = std::make_unique<audio::WavWriter>(*wav, loop_.channels(), plan.config.audio.sample_rate_hz);
  const auto channels = static_cast<std::size_t>(loop_.channels());
  loop_.on_audio = [this, channels](std::span<const float> block) {
    if (wav_) wav_->write(block);
    for (std::size_t i = static_cast<std::size_t>(actuator_channel_); i < block.size(); i += channels)
      peak_ = std::max(peak_, static_cast<double>(std::fabs(block[i])));
  };
}

bool HeadlessStage::wait_until(Nanos t) {
  loop_.advance(std::max(t, loop_.now()));
  return true;
}

Exploration HeadlessStage::explore(const Scene& scene, Nanos until) {
  const TextureRelief& relief = scene.texture.value().relief;
  const Nanos from = loop_.now();
  std::vector<PointerSample> hand;
  for (Nanos t = from; t <= until; t += 1'000'000) {
    const double s = until > from ? static_cast<double>(t - from) / static_cast<double>(until - from) : 1.0;
    hand.push_back({t, relief.center.x + (2 * s - 1) * 1.4 * relief.radius_m, relief.center.y});
  }
  const Exploration e = measure_crossing(scene, config_, hand);
  loop_.advance(until);
  return e;
}

double HeadlessStage::take_actuator_peak() { return std::exchange(peak_, 0.0); }

void HeadlessStage::finish() {
  loop_.drain_audio(loop_.now() + kNanosPerSecond);
  if (wav_) wav_->close();
}

ScriptedAnswers::ScriptedAnswers(const StudyPlan& plan, std::vector<ObserverAnswer> script, bool simulated)
    : observer_(plan.protocol, plan.participant), script_(std::move(script)), simulated_(simulated) {}

std::optional<TrialAnswer> ScriptedAnswers::answer(const ScheduledTrial& trial, Nanos opens) {
  if (!has_more()) return std::nullopt;
  const ObserverAnswer a = simulated_ ? observer_.respond(trial) : script_[next_++];
  return TrialAnswer{a.answer, opens + a.response_time};
}

TrialAnswer strike_answer_bar(StudyStage& stage, const Scene& scene, const std::vector<AnswerBar>& bars,
                              std::size_t index, Nanos at, Nanos opens, double speed) {
  constexpr double kHandRateHz = 1000;  // a 1000 Hz mouse
  ScriptedStrike strike{bars.at(index).target, at, speed};
  GhostPath path = ghost_player(scene, {strike}, kHandRateHz);
  // A stroke starts above the bar: an answer sooner than its descent lands that much later.
  if (const Nanos early = stage.now() + 1 - path.samples.front().t_ns; early > 0) {
    strike.t_ns += early;
    path = ghost_player(scene, {strike}, kHandRateHz);
  }
  std::optional<TrialAnswer> given;
  for (const PointerSample& p : path.samples) {
    const std::optional<Strike> struck = stage.hand(p.t_ns, {p.x, p.y});
    if (!struck || given || struck->impact.t_ns < opens) continue;
    for (const AnswerBar& b : bars)
      if (b.target == struck->impact.target) given = TrialAnswer{b.answer, struck->impact.t_ns};
  }
  if (!given) throw std::logic_error("an answer stroke struck no answer bar");
  return *given;
}

StrikeAnswers::StrikeAnswers(AnswerSource& choices, StudyStage& stage, const Scene& scene,
                             const StudyProtocol& protocol)
    : choices_(choices), stage_(stage), scene_(scene), bars_(answer_bars(scene, protocol)),
      speed_(protocol.impact_speed_m_per_s) {}

std::optional<TrialAnswer> StrikeAnswers::answer(const ScheduledTrial& trial, Nanos opens) {
  const std::optional<TrialAnswer> wanted = choices_.answer(trial, opens);
  if (!wanted) return std::nullopt;
  const auto bar =
      std::find_if(bars_.begin(), bars_.end(), [&](const AnswerBar& b) { return b.answer == wanted->answer; });
  if (bar == bars_.end()) throw std::logic_error("no answer bar for \"" + wanted->answer + "\"");
  return strike_answer_bar(stage_, scene_, bars_, static_cast<std::size_t>(bar - bars_.begin()), wanted->at, opens,
                           speed_);
}

}  // namespace mallet::app
