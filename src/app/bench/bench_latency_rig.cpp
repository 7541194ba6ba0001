#include "app/bench/bench_latency_rig.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include <toml++/toml.h>

#include "core/data_paths.hpp"

namespace mallet::app::latency {

void Deadline::check() const {
  if (const int s = stop_signal()) throw std::runtime_error("bench latency: stopped by signal " + std::to_string(s));
  if (monotonic_now() > end) throw std::runtime_error("bench latency: the run took longer than its bound; stopped");
}

std::filesystem::path still_scene(const std::filesystem::path& dir) {
  const std::filesystem::path shipped = default_scene();
  toml::table scene = toml::parse_file(shipped.string());
  const auto beside = [&](std::string_view key, const char* shipped_default) {
    return (shipped.parent_path() / scene[key].value_or(std::string(shipped_default))).lexically_normal();
  };
  const std::filesystem::path materials = beside("materials_file", "../materials.toml");
  scene.insert_or_assign("materials_file", (dir / "materials.toml").string());
  scene.insert_or_assign("instruments_file", beside("instruments_file", "../instruments.toml").string());
  toml::table still = toml::parse_file(materials.string());
  if (toml::table* all = still["material"].as_table())
    for (auto& [name, material] : *all)
      if (toml::table* visual = material.as_table() ? (*material.as_table())["visual"].as_table() : nullptr)
        visual->insert_or_assign("amplitude_s", 0.0);
  std::ostringstream materials_text, scene_text;
  materials_text << still;
  scene_text << scene;
  write_text(dir / "materials.toml", materials_text.str());
  std::filesystem::create_directories(dir / "scenes");
  const std::filesystem::path file = dir / "scenes" / "percussion.toml";
  write_text(file, scene_text.str());
  return file;
}

std::vector<Bar> choose_bars(const Scene& scene, const Mapping& map) {
  std::vector<Bar> bars;
  for (const char* material : {"metal", "wood"}) {
    for (const Instrument& inst : scene.instruments) {
      if (inst.targets.empty() || scene.materials.at(static_cast<std::size_t>(inst.material)).name != material)
        continue;
      const Target& t = scene.targets.at(static_cast<std::size_t>(inst.targets[inst.targets.size() / 2]));
      Bar b;
      b.target = t.id;
      b.name = inst.name + " bar " + std::to_string(inst.targets.size() / 2 + 1) + " (" + material + ")";
      b.x_m = 0.5 * (t.x_min + t.x_max);
      b.contact_y_m = t.top_y + scene.mallet_radius_m;
      b.x_px = static_cast<int>(std::lround(map.col_of_x(b.x_m)));
      const double centre_row = map.row_of_y(b.contact_y_m);
      const double radius_px = scene.mallet_radius_m / std::fabs(map.y_of_row(0) - map.y_of_row(1));
      // From 70 px above the resting head's centre (the hovering head is in view) to just
      // below its lowest pixel; 5 px wide around the bar's middle.
      const int top = std::max(0, static_cast<int>(centre_row) - 70);
      const int bottom = std::min(kHeight - 1, static_cast<int>(centre_row + radius_px) + 8);
      b.strip = {std::clamp(b.x_px - 2, 0, kWidth - 5), top, 5, bottom - top + 1};
      bars.push_back(b);
      break;
    }
  }
  if (bars.size() != 2) throw std::runtime_error("bench latency: the scene needs a metal and a wood instrument");
  return bars;
}

}  // namespace mallet::app::latency
