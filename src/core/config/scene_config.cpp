#include "core/config/scene_config.hpp"

#include <algorithm>
#include <cmath>

#include "core/config/materials_config.hpp"
#include "core/config/toml_reader.hpp"
#include "core/tuning.hpp"

namespace mallet::config {

namespace {

int add_material(Scene& scene, const Material& m) {
  for (std::size_t i = 0; i < scene.materials.size(); ++i)
    if (scene.materials[i].name == m.name) return static_cast<int>(i);
  scene.materials.push_back(m);
  return static_cast<int>(scene.materials.size() - 1);
}

void read_instrument(TableReader t, const MaterialLibrary& library, Scene& scene) {
  Instrument inst;
  inst.name = t.string("name");
  inst.voice = t.string_or("voice", inst.name);
  inst.midi_program = static_cast<int>(t.integer_or("midi_program", 0));
  t.require_range("midi_program", inst.midi_program, 0, 127);
  const std::string material_name = t.string("material");
  const Material* material = library.find(material_name);
  if (!material)
    t.fail("material", "unknown material \"" + material_name + "\" (known: " + library.names() + ")");
  inst.material = add_material(scene, *material);
  // Drawn models (files in models/): a metal-looking bar for metals, wood otherwise.
  const bool metallic = material_name.find("metal") != std::string::npos ||
                        material_name.find("alumin") != std::string::npos;
  inst.bar_model = t.string_or("bar_model", metallic ? "metal_bar.glb" : "wood_bar.glb");
  inst.rail_model = t.string_or("rail_model", inst.name + "_rail.glb");

  const double x_start = t.number("x_start_m");
  const double top_y = t.number("top_y_m");
  const double width = t.number("bar_width_m");
  t.require_positive("bar_width_m", width);
  const double gap = t.number("gap_m");
  t.require_non_negative("gap_m", gap);
  const double thickness = t.number_or("bar_thickness_m", 0.02);
  t.require_positive("bar_thickness_m", thickness);
  const std::vector<std::int64_t> notes = t.integers("notes");
  const std::vector<double> lengths = t.numbers("bar_lengths_m");
  if (notes.empty()) t.fail("notes", "needs at least one note");
  if (lengths.size() != notes.size())
    t.fail("bar_lengths_m", "has " + std::to_string(lengths.size()) + " lengths for " +
                                std::to_string(notes.size()) + " notes");
  for (std::int64_t n : notes)
    if (n < 0 || n > 127) t.fail("notes", "MIDI notes are 0..127, got " + std::to_string(n));
  for (double l : lengths)
    if (!(l > 0)) t.fail("bar_lengths_m", "lengths must be > 0");
  t.finish();

  for (std::size_t i = 0; i < notes.size(); ++i) {
    Target bar;
    bar.id = static_cast<int>(scene.targets.size());
    bar.instrument = inst.name;
    bar.material = inst.material;
    bar.note = static_cast<int>(notes[i]);
    bar.frequency_hz = note_frequency_hz(bar.note, scene.tuning_a4_hz);
    bar.x_min = x_start + static_cast<double>(i) * (width + gap);
    bar.x_max = bar.x_min + width;
    bar.top_y = top_y;
    bar.length_m = lengths[i];
    bar.thickness_m = thickness;
    inst.targets.push_back(bar.id);
    scene.targets.push_back(std::move(bar));
  }
  scene.instruments.push_back(std::move(inst));
}

Scene read(const toml::table& root, const std::string& file, const MaterialLibrary& library) {
  TableReader top(root, file);
  Scene scene;
  scene.file = file;
  scene.name = top.string("name");
  top.string_or("materials_file", "");  // resolved by the caller
  scene.instruments_file = top.string_or("instruments_file", "../instruments.toml");
  scene.mallet_radius_m = top.number("mallet_radius_m");
  top.require_positive("mallet_radius_m", scene.mallet_radius_m);
  scene.tuning_a4_hz = top.number_or("tuning_a4_hz", 440.0);
  top.require_range("tuning_a4_hz", scene.tuning_a4_hz, 300.0, 600.0);

  TableReader s2w = top.table("screen_to_world");
  scene.screen_to_world = {s2w.number("left_m"), s2w.number("right_m"), s2w.number("top_m"),
                           s2w.number("bottom_m")};
  if (!(scene.screen_to_world.right_m > scene.screen_to_world.left_m))
    s2w.fail("right_m", "must be greater than left_m");
  if (!(scene.screen_to_world.top_m > scene.screen_to_world.bottom_m))
    s2w.fail("top_m", "must be greater than bottom_m (world y points up)");
  s2w.finish();

  if (std::optional<TableReader> cam = top.optional_table("camera")) {
    scene.camera.eye_x_m = cam->number_or("eye_x_m", scene.camera.eye_x_m);
    scene.camera.eye_y_m = cam->number_or("eye_y_m", scene.camera.eye_y_m);
    scene.camera.eye_z_m = cam->number_or("eye_z_m", scene.camera.eye_z_m);
    cam->require_range("eye_z_m", scene.camera.eye_z_m, 0.05, 20.0);
    cam->finish();
  }

  for (TableReader& t : top.tables("instrument")) read_instrument(std::move(t), library, scene);
  top.finish();

  // Bars may touch but never overlap: a strike must name exactly one bar.
  std::vector<const Target*> sorted;
  for (const Target& t : scene.targets) sorted.push_back(&t);
  std::sort(sorted.begin(), sorted.end(), [](auto* a, auto* b) { return a->x_min < b->x_min; });
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    if (sorted[i]->x_min < sorted[i - 1]->x_max)
      top.fail("instrument", "bars overlap: " + sorted[i - 1]->instrument + " note " +
                                 std::to_string(sorted[i - 1]->note) + " and " +
                                 sorted[i]->instrument + " note " + std::to_string(sorted[i]->note));
  }
  return scene;
}

}  // namespace

Scene load_scene(const std::filesystem::path& path) {
  const toml::table root = parse_file(path);
  TableReader top(root, path.string());
  const std::string materials_file = top.string_or("materials_file", "../materials.toml");
  std::filesystem::path materials_path = path.parent_path() / materials_file;
  if (std::filesystem::path(materials_file).is_absolute()) materials_path = materials_file;
  MaterialLibrary library;
  try {
    library = load_materials(materials_path);
  } catch (const ConfigError& e) {
    if (e.line() == 0)  // the file itself is missing: say who asked for it
      top.fail("materials_file", std::string(e.what()));
    throw;
  }
  Scene scene = read(root, path.string(), library);
  if (!std::filesystem::path(scene.instruments_file).is_absolute())
    scene.instruments_file = (path.parent_path() / scene.instruments_file).lexically_normal().string();
  return scene;
}

Scene parse_scene(std::string_view text, const std::string& name, const MaterialLibrary& materials) {
  return read(parse_text(text, name), name, materials);
}

}  // namespace mallet::config
