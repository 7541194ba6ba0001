#include "app/study/study_stimuli.hpp"

#include <algorithm>
#include <tuple>
#include <utility>

namespace mallet::app {

namespace {
int condition_index(study::StudyCondition c) { return static_cast<int>(c); }
constexpr int kConditions = 4;
//! The answer instruments are named "answer 1", "answer 2", ... (strike log lines say so).
constexpr const char* kAnswerInstrument = "answer ";
//! General MIDI's Woodblock (program 116, 0-based 115): the midi route's neutral click.
constexpr int kWoodblockProgram = 115;

//! The answer bars' x centres: `n` bars of the reference's width spread evenly over the
//! wider side of the instruments' span beside the reference bar, three widths away from it
//! (a side too short for them is lengthened outwards, two widths per bar).
std::vector<double> answer_centres(const Scene& base, const Target& reference, std::size_t n) {
  double lo = reference.x_min, hi = reference.x_max;
  for (const Target& t : base.targets) {
    lo = std::min(lo, t.x_min);
    hi = std::max(hi, t.x_max);
  }
  const double width = reference.x_max - reference.x_min, need = 2 * width * static_cast<double>(n);
  const double right_from = reference.x_max + 3 * width, left_to = reference.x_min - 3 * width;
  double from = right_from, to = std::max(hi, right_from + need);
  if (left_to - lo > hi - right_from) {
    from = std::min(lo, left_to - need);
    to = left_to;
  }
  std::vector<double> centres;
  for (std::size_t k = 0; k < n; ++k)
    centres.push_back(from + (to - from) * (static_cast<double>(k) + 0.5) / static_cast<double>(n));
  return centres;
}
}  // namespace

Scene make_study_scene(const Scene& base, const study::StudyProtocol& protocol) {
  if (protocol.texture()) return base;  // each crossing's scene: texture_trial_scene
  const Target& reference = base.targets.at(static_cast<std::size_t>(protocol.reference_bar));
  Scene scene = base;
  scene.materials.clear();
  scene.targets.clear();
  for (Instrument& inst : scene.instruments) inst.targets.clear();
  Instrument* owner = nullptr;
  for (Instrument& inst : scene.instruments)
    if (inst.name == reference.instrument) owner = &inst;
  if (owner) owner->speaker = protocol.sound;
  for (std::size_t s = 0; s < protocol.stimuli.size(); ++s) {
    for (const auto& [c, condition] : study::kStudyConditionNames) {
      Material m = protocol.stimuli[s].material;
      m.name = protocol.stimuli[s].name + "@" + condition;
      if (!study::shows_visual(c)) m.visual.amplitude = 0;
      if (!study::plays_actuator(c)) m.actuator.amplitude = 0;
      Target t = reference;
      t.id = static_cast<int>(scene.targets.size());
      t.material = static_cast<int>(scene.materials.size());
      t.hand_strikes = false;
      scene.materials.push_back(std::move(m));
      scene.targets.push_back(t);
      if (owner) owner->targets.push_back(t.id);
    }
  }
  if (protocol.response != study::StudyResponse::strike) return scene;
  // The answer bars: one material for all, the protocol's feel, or none at all (a stimulus's
  // triples with A = 0, which the engine's checks accept as any material).
  const std::optional<Material>& felt = protocol.answer_strike.feel;
  Material feel = felt ? *felt : protocol.stimuli.front().material;
  if (!felt) feel.visual.amplitude = feel.actuator.amplitude = 0;
  feel.name = "answer";
  const int material = static_cast<int>(scene.materials.size());
  scene.materials.push_back(feel);
  const std::vector<std::string> choices = protocol.answer_choices();
  const std::vector<double> centres = answer_centres(base, reference, choices.size());
  const Instrument stimulus_instrument = owner ? *owner : Instrument{};  // scene.instruments grows below
  for (std::size_t k = 0; k < choices.size(); ++k) {
    Instrument inst = stimulus_instrument;
    inst.name = kAnswerInstrument + std::to_string(k + 1);
    if (!protocol.answer_strike.voice.empty()) inst.voice = protocol.answer_strike.voice;
    inst.speaker = !protocol.answer_strike.voice.empty();
    inst.midi_program = kWoodblockProgram;
    inst.material = material;
    // Told apart from the stimulus bar at a glance: the other bar model.
    inst.bar_model = stimulus_instrument.bar_model == "metal_bar.glb" ? "wood_bar.glb" : "metal_bar.glb";
    // On the rails that go with that bar (grey metal bars on wooden rails looked borrowed),
    // unless the stimulus's instrument has rails of its own making.
    if (stimulus_instrument.rail_model == "xylophone_rail.glb" || stimulus_instrument.rail_model == "glockenspiel_rail.glb")
      inst.rail_model = inst.bar_model == "metal_bar.glb" ? "glockenspiel_rail.glb" : "xylophone_rail.glb";
    Target t = reference;
    const double half = (reference.x_max - reference.x_min) / 2;
    t.x_min = centres[k] - half;
    t.x_max = centres[k] + half;
    t.id = static_cast<int>(scene.targets.size());
    t.instrument = inst.name;
    t.material = material;
    t.hand_strikes = true;
    inst.targets = {t.id};
    scene.targets.push_back(t);
    scene.instruments.push_back(std::move(inst));
  }
  return scene;
}

namespace {

//! The answer bars' places mirrored among themselves: the first answer where the last was.
void mirror_answers(Scene& scene, const std::vector<AnswerBar>& answers) {
  std::vector<std::pair<double, double>> places;
  for (const AnswerBar& a : answers) {
    const Target& t = scene.targets.at(static_cast<std::size_t>(a.target));
    places.push_back({t.x_min, t.x_max});
  }
  for (std::size_t k = 0; k < answers.size(); ++k) {
    Target& t = scene.targets.at(static_cast<std::size_t>(answers[k].target));
    std::tie(t.x_min, t.x_max) = places[places.size() - 1 - k];
  }
}

}  // namespace

Scene study_scene_for(const Scene& base, const study::StudyProtocol& protocol, double aspect, bool right_to_left) {
  Scene scene = make_study_scene(base, protocol);
  // Each crossing's scene is made from the base; keys need no bars.
  if (protocol.texture() || protocol.response != study::StudyResponse::strike) return scene;
  if (!(aspect > 0 && aspect < 1)) {  // a landscape screen: the bars spread as made
    if (right_to_left) mirror_answers(scene, answer_bars(scene, protocol));
    return scene;
  }
  // Portrait: the bars side by side, close, in a band as wide as the screen (stacked, they
  // were thin sticks a third of the height apart): the answers first in their order, the
  // stimulus bar last, on the right, where the offer's "Yes" was (a visitor's second strike
  // there taps a bar that answers nothing).
  const std::vector<AnswerBar> answers = answer_bars(scene, protocol);
  const Target& stimulus = scene.targets.front();
  const double width = stimulus.x_max - stimulus.x_min, step = 2.5 * width;
  const double right = stimulus.x_max + width;
  const double stimulus_centre = 0.5 * (stimulus.x_min + stimulus.x_max);
  const double n = static_cast<double>(answers.size());
  for (std::size_t k = 0; k < answers.size(); ++k) {
    Target& t = scene.targets.at(static_cast<std::size_t>(answers[k].target));
    const double centre = stimulus_centre - (n - static_cast<double>(k)) * step;
    t.x_min = centre - width / 2;
    t.x_max = centre + width / 2;
  }
  if (right_to_left) mirror_answers(scene, answers);
  scene.screen_to_world.left_m = stimulus_centre - n * step - width / 2 - width;
  scene.screen_to_world.right_m = right;
  scene.camera.eye_x_m = 0.5 * (scene.screen_to_world.left_m + scene.screen_to_world.right_m);
  scene.layout = SceneLayout::portrait;
  return scene;
}

Scene texture_trial_scene(const Scene& base, const study::Stimulus& stimulus, study::StudyCondition condition) {
  Scene scene = base;
  TextureStimulus& t = scene.texture.value();
  t.relief.shape = stimulus.relief.value().shape;
  t.relief.height_m = stimulus.relief->height_m;
  if (!study::shows_visual(condition)) t.speed.slope_gain = 0;
  if (!study::plays_actuator(condition)) t.stripes.amplitude = 0;
  return scene;
}

std::vector<AnswerBar> answer_bars(const Scene& study_scene, const study::StudyProtocol& protocol) {
  std::vector<AnswerBar> out;
  if (protocol.response != study::StudyResponse::strike) return out;
  const std::vector<std::string> choices = protocol.answer_choices();
  for (std::size_t k = 0; k < choices.size(); ++k)
    for (const Instrument& inst : study_scene.instruments)
      if (inst.name == kAnswerInstrument + std::to_string(k + 1) && !inst.targets.empty())
        out.push_back({inst.targets.front(), choices[k]});
  return out;
}

Impact stimulus_impact(const Scene& study_scene, const study::StudyProtocol& protocol, int stimulus,
                       study::StudyCondition condition, Nanos t) {
  const Target& bar = study_scene.targets.at(static_cast<std::size_t>(stimulus * kConditions + condition_index(condition)));
  Impact i;
  i.t_ns = t;
  i.target = bar.id;
  i.material = bar.material;
  i.note = bar.note;
  i.speed_m_per_s = protocol.impact_speed_m_per_s;
  i.x_m = 0.5 * (bar.x_min + bar.x_max);
  return i;
}

}  // namespace mallet::app
