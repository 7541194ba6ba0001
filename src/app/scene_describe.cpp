#include "app/scene_describe.hpp"

#include "app/json_writer.hpp"

namespace mallet::app {

std::string describe_scene_json(const Scene& scene) {
  JsonWriter j;
  j.begin_object();
  j.field("kind", to_string(scene.kind));
  j.field("name", scene.name);
  if (scene.texture) {  // the texture scene: the disc, its relief and its stripes
    const TextureStimulus& tex = *scene.texture;
    j.key("texture").begin_object();
    j.field("shape", to_string(tex.relief.shape));
    j.field("profile", to_string(tex.relief.profile));
    j.field("center_x", tex.relief.center.x);
    j.field("center_y", tex.relief.center.y);
    j.field("radius", tex.relief.radius_m);
    j.field("height", tex.relief.height_m);
    j.field("stripe_wavelength", tex.stripes.wavelength_m);
    j.field("stripe_amplitude", tex.stripes.amplitude);
    j.field("stripe_phase", tex.stripes.phase_rad);
    j.end_object();
    j.key("speed_technique").begin_object();
    j.field("law", "g = clamp(1 - slope_gain * (grad h . u), gain_min, gain_max)");
    j.field("slope_gain", tex.speed.slope_gain);
    j.field("gain_min", tex.speed.gain_min);
    j.field("gain_max", tex.speed.gain_max);
    j.field("relax_distance", tex.speed.relax_distance_m);
    j.field("max_offset", tex.speed.max_offset_m);
    j.end_object();
  }
  j.field("mallet_radius", scene.mallet_radius_m);
  j.field("tuning_a4_hz", scene.tuning_a4_hz);
  j.key("targets").begin_array();
  for (const Target& t : scene.targets) {
    j.begin_object();
    j.field("id", t.id);
    j.field("instrument", t.instrument);
    j.field("material", scene.materials[t.material].name);
    j.field("note", t.note);
    j.field("frequency_hz", t.frequency_hz);
    j.field("x_min", t.x_min);
    j.field("x_max", t.x_max);
    j.field("top_y", t.top_y);
    j.field("length", t.length_m);
    j.field("thickness", t.thickness_m);
    j.end_object();
  }
  j.end_array();
  if (scene.kind == SceneKind::wall) {
    j.key("wall_materials").begin_array();
    for (int m : scene.wall_materials) j.value(scene.materials[static_cast<std::size_t>(m)].name);
    j.end_array();
  }
  j.key("materials").begin_object();
  for (const Material& m : scene.materials) {
    j.key(m.name).begin_object();
    for (auto [label, p] : {std::pair{"visual", &m.visual}, {"actuator", &m.actuator}}) {
      j.key(label).begin_object();
      j.field(label == std::string_view("visual") ? "amplitude_s" : "amplitude", p->amplitude);
      j.field("decay_per_s", p->decay_per_s);
      j.field("freq_hz", p->freq_hz);
      j.end_object();
    }
    j.end_object();
  }
  j.end_object();
  const ScreenToWorld& s = scene.screen_to_world;
  j.key("screen_to_world").begin_object();
  j.field("left_m", s.left_m);
  j.field("right_m", s.right_m);
  j.field("top_m", s.top_m);
  j.field("bottom_m", s.bottom_m);
  j.field("world_x", "left_m + screen_x * (right_m - left_m)");
  j.field("world_y", "top_m + screen_y * (bottom_m - top_m)");
  j.end_object();
  j.end_object();
  return j.str() + "\n";
}

}  // namespace mallet::app
