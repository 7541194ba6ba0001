#include <cstdio>

#include "app/cli/commands.hpp"
#include "core/data_paths.hpp"
#include "app/offline/scene_describe.hpp"
#include "core/config/scene_config.hpp"

namespace mallet::app {

void register_scene(CLI::App& app) {
  CLI::App* scene = app.add_subcommand("scene", "Inspect a scene file");
  scene->require_subcommand(1);
  auto path = std::make_shared<std::filesystem::path>(default_scene());
  CLI::App* describe = scene->add_subcommand("describe", "Print the scene's targets, materials and mapping as JSON");
  describe->footer(R"(Print the scene as JSON (metres; note = MIDI number):
  {"mallet_radius": m, "targets": [{"id", "instrument", "material", "note",
   "frequency_hz", "x_min", "x_max", "top_y", ...}, ...], "materials": {...},
   "screen_to_world": {"left_m", "right_m", "top_m", "bottom_m", ...}}
A scene that does not load prints FILE:LINE:COLUMN: problem and exits 2.)");
  describe->add_option("--scene", *path, "Scene file")->capture_default_str();
  describe->callback([path] {
    const Scene s = config::load_scene(*path);
    std::fputs(describe_scene_json(s).c_str(), stdout);
  });
}

}  // namespace mallet::app
