#include "app/offline/scene_describe.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include <nlohmann/json.hpp>

#include <fmt/format.h>

namespace mallet::app {

namespace {

// A number as the contract prints it: twelve significant digits (523.251130601, not
// 523.2511306011972), a whole number without a decimal point (440), null for what JSON
// cannot hold (nothing should produce a NaN).
nlohmann::ordered_json number(double v) {
  if (!std::isfinite(v)) return nullptr;
  const std::string digits = fmt::format("{:.12g}", v);
  long long whole = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), whole);
  if (error == std::errc() && end == digits.data() + digits.size()) return whole;
  return std::strtod(digits.c_str(), nullptr);
}

}  // namespace

std::string describe_scene_json(const Scene& scene) {
  nlohmann::ordered_json j;
  j["kind"] = to_string(scene.kind);
  j["name"] = scene.name;
  if (scene.texture) {  // the texture scene: the disc, its relief and its stripes
    const TextureStimulus& tex = *scene.texture;
    j["texture"] = {
        {"shape", to_string(tex.relief.shape)},
        {"profile", to_string(tex.relief.profile)},
        {"center_x", number(tex.relief.center.x)},
        {"center_y", number(tex.relief.center.y)},
        {"radius", number(tex.relief.radius_m)},
        {"height", number(tex.relief.height_m)},
        {"stripe_wavelength", number(tex.stripes.wavelength_m)},
        {"stripe_amplitude", number(tex.stripes.amplitude)},
        {"stripe_phase", number(tex.stripes.phase_rad)},
    };
    j["speed_technique"] = {
        {"law", "g = clamp(1 - slope_gain * (grad h . u), gain_min, gain_max)"},
        {"slope_gain", number(tex.speed.slope_gain)},
        {"gain_min", number(tex.speed.gain_min)},
        {"gain_max", number(tex.speed.gain_max)},
        {"relax_distance", number(tex.speed.relax_distance_m)},
        {"max_offset", number(tex.speed.max_offset_m)},
    };
  }
  j["mallet_radius"] = number(scene.mallet_radius_m);
  j["tuning_a4_hz"] = number(scene.tuning_a4_hz);
  j["targets"] = nlohmann::ordered_json::array();
  for (const Target& t : scene.targets) {
    j["targets"].push_back({
        {"id", t.id},
        {"instrument", t.instrument},
        {"material", scene.materials[t.material].name},
        {"note", t.note},
        {"frequency_hz", number(t.frequency_hz)},
        {"x_min", number(t.x_min)},
        {"x_max", number(t.x_max)},
        {"top_y", number(t.top_y)},
        {"length", number(t.length_m)},
        {"thickness", number(t.thickness_m)},
    });
  }
  if (scene.kind == SceneKind::wall) {
    j["wall_materials"] = nlohmann::ordered_json::array();
    for (int m : scene.wall_materials) j["wall_materials"].push_back(scene.materials[static_cast<std::size_t>(m)].name);
  }
  j["materials"] = nlohmann::ordered_json::object();
  for (const Material& m : scene.materials) {
    j["materials"][m.name] = {
        {"visual",
         {{"amplitude_s", number(m.visual.amplitude)},
          {"decay_per_s", number(m.visual.decay_per_s)},
          {"freq_hz", number(m.visual.freq_hz)}}},
        {"actuator",
         {{"amplitude", number(m.actuator.amplitude)},
          {"decay_per_s", number(m.actuator.decay_per_s)},
          {"freq_hz", number(m.actuator.freq_hz)}}},
    };
  }
  const ScreenToWorld& s = scene.screen_to_world;
  j["screen_to_world"] = {
      {"left_m", number(s.left_m)},
      {"right_m", number(s.right_m)},
      {"top_m", number(s.top_m)},
      {"bottom_m", number(s.bottom_m)},
      {"world_x", "left_m + screen_x * (right_m - left_m)"},
      {"world_y", "top_m + screen_y * (bottom_m - top_m)"},
  };
  // Names come from the scene's files: bytes that are not UTF-8 become U+FFFD, not an exception.
  return j.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

}  // namespace mallet::app
