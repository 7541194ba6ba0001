#include "app/study_stimuli.hpp"

namespace mallet::app {

namespace {
int condition_index(study::StudyCondition c) { return static_cast<int>(c); }
constexpr int kConditions = 4;
}  // namespace

Scene make_study_scene(const Scene& base, const study::StudyProtocol& protocol) {
  const Target& reference = base.targets.at(static_cast<std::size_t>(protocol.reference_bar));
  Scene scene = base;
  scene.materials.clear();
  scene.targets.clear();
  for (Instrument& inst : scene.instruments) inst.targets.clear();
  Instrument* owner = nullptr;
  for (Instrument& inst : scene.instruments)
    if (inst.name == reference.instrument) owner = &inst;
  for (std::size_t s = 0; s < protocol.stimuli.size(); ++s) {
    for (study::StudyCondition c : study::kAllConditions) {
      Material m = protocol.stimuli[s].material;
      m.name = protocol.stimuli[s].name + "@" + std::string(study::condition_name(c));
      if (!study::shows_visual(c)) m.visual.amplitude = 0;
      if (!study::plays_actuator(c)) m.actuator.amplitude = 0;
      Target t = reference;
      t.id = static_cast<int>(scene.targets.size());
      t.material = static_cast<int>(scene.materials.size());
      scene.materials.push_back(std::move(m));
      scene.targets.push_back(t);
      if (owner) owner->targets.push_back(t.id);
    }
  }
  return scene;
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
