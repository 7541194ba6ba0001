#include "core/config/scene_config.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

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
  inst.midi_program = 0;
  t.read("midi_program", inst.midi_program, 0, 127);
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
  scene.model_refs.push_back({inst.bar_model, t.place("bar_model"), t.dotted("bar_model")});
  scene.model_refs.push_back({inst.rail_model, t.place("rail_model"), t.dotted("rail_model")});

  const double x_start = t.number("x_start_m");
  const double top_y = t.number("top_y_m");
  const double width = t.positive("bar_width_m");
  const double gap = t.non_negative("gap_m");
  const double thickness = t.positive_or("bar_thickness_m", 0.02);
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
    // Far out, the sum loses the bar's width to rounding (or overflows): the bar would be
    // one no strike can hit.
    if (!std::isfinite(bar.x_min) || !std::isfinite(bar.x_max) || !(bar.x_max > bar.x_min))
      t.fail("x_start_m", "bar " + std::to_string(i + 1) + " of " + std::to_string(notes.size()) + " would start at " +
                              number_text(bar.x_min) + " m, too far out to keep its width of " + number_text(width) +
                              " m (keep the instruments within a few metres of 0)");
    inst.targets.push_back(bar.id);
    scene.targets.push_back(std::move(bar));
  }
  scene.instruments.push_back(std::move(inst));
}

void read_texture(TableReader& top, Scene& scene) {
  TextureStimulus tex;
  {
    TableReader t = top.table("texture");
    tex.relief.shape = t.choice("shape", kReliefShapeNames);
    tex.relief.profile = t.choice_or("profile", kReliefProfileNames, ReliefProfile::gaussian);
    tex.relief.center = {t.number("center_x_m"), t.number("center_y_m")};
    tex.relief.radius_m = t.positive("radius_m");
    tex.relief.height_m = t.positive("height_m");
    t.finish();
  }
  if (std::optional<TableReader> t = top.optional_table("speed_technique")) {
    SpeedTechniqueConfig& c = tex.speed;
    t->read("slope_gain", c.slope_gain, 0.0, 1000.0);
    t->read("gain_min", c.gain_min, 0.01, 1.0);
    t->read("gain_max", c.gain_max, 1.0, 100.0);
    c.relax_distance_m = t->positive_or("relax_distance_m", c.relax_distance_m);
    c.max_offset_m = t->positive_or("max_offset_m", c.max_offset_m);
    t->finish();
  }
  if (std::optional<TableReader> t = top.optional_table("stripes")) {
    StripeParams& p = tex.stripes;
    t->read("amplitude", p.amplitude, 0.0, 10.0);
    t->read("wavelength_m", p.wavelength_m, 1e-5, 1.0);
    t->read("phase_rad", p.phase_rad, -100.0, 100.0);
    p.fade_s = t->number_or("fade_ms", p.fade_s * 1e3) / 1e3;
    t->require_range("fade_ms", p.fade_s * 1e3, 0.0, 1000.0);
    p.rest_speed_m_per_s = t->non_negative_or("rest_speed_m_per_s", p.rest_speed_m_per_s);
    t->read("max_freq_hz", p.max_freq_hz, 1.0, 20000.0);
    p.motion_timeout_s = t->number_or("motion_timeout_ms", p.motion_timeout_s * 1e3) / 1e3;
    t->require_range("motion_timeout_ms", p.motion_timeout_s * 1e3, 1.0, 10000.0);
    t->finish();
  }
  scene.texture = tex;
}

void read_wall(TableReader& top, const MaterialLibrary& library, Scene& scene) {
  TableReader t = top.table("wall");
  Instrument inst;
  inst.name = "wall";
  inst.voice = t.string_or("voice", "wall");
  inst.midi_program = 115;  // GM Woodblock
  t.read("midi_program", inst.midi_program, 0, 127);
  inst.bar_model = t.string_or("model", "wall_panel.glb");
  inst.rail_model.clear();
  scene.model_refs.push_back({inst.bar_model, t.place("model"), t.dotted("model")});
  const std::vector<std::string> names = t.strings("materials");
  if (names.empty()) t.fail("materials", "needs at least one material");
  for (const std::string& n : names) {
    const Material* m = library.find(n);
    if (!m) t.fail("materials", "unknown material \"" + n + "\" (known: " + library.names() + ")");
    scene.wall_materials.push_back(add_material(scene, *m));
  }
  const std::string first = t.string_or("material", names.front());
  const auto it = std::find(names.begin(), names.end(), first);
  if (it == names.end()) t.fail("material", "\"" + first + "\" is not one of the wall's materials");
  inst.material = scene.wall_materials[static_cast<std::size_t>(it - names.begin())];

  Target wall;
  wall.id = 0;
  wall.instrument = inst.name;
  wall.material = inst.material;
  wall.note = 60;
  t.read("note", wall.note, 0, 127);
  wall.frequency_hz = note_frequency_hz(wall.note, scene.tuning_a4_hz);
  wall.x_min = t.number("x_min_m");
  wall.x_max = t.number("x_max_m");
  if (!(wall.x_max > wall.x_min)) t.fail("x_max_m", "must be greater than x_min_m");
  wall.top_y = t.number("top_y_m");
  const double bottom = t.number("bottom_y_m");
  if (!(wall.top_y > bottom)) t.fail("top_y_m", "must be greater than bottom_y_m");
  wall.thickness_m = wall.top_y - bottom;
  if (!std::isfinite(wall.thickness_m))
    t.fail("top_y_m", "top_y_m - bottom_m overflows (keep the wall within a few metres of 0)");
  wall.length_m = t.positive_or("depth_m", 2 * scene.mallet_radius_m);
  t.finish();
  inst.targets.push_back(wall.id);
  scene.targets.push_back(std::move(wall));
  scene.instruments.push_back(std::move(inst));
}

Scene read(const toml::table& root, const std::string& file, const MaterialLibrary& library) {
  TableReader top(root, file);
  Scene scene;
  scene.file = file;
  scene.name = top.string("name");
  scene.kind = top.choice_or("kind", kSceneKindNames, SceneKind::percussion);
  top.string_or("materials_file", "");  // resolved by the caller
  scene.instruments_file = top.string_or("instruments_file", "../instruments.toml");
  scene.mallet_radius_m = top.positive("mallet_radius_m");
  scene.tuning_a4_hz = 440.0;
  top.read("tuning_a4_hz", scene.tuning_a4_hz, 300.0, 600.0);

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
    cam->read("eye_z_m", scene.camera.eye_z_m, 0.05, 20.0);
    cam->finish();
  }

  if (top.has("background_srgb")) {
    const std::vector<double> bg = top.numbers("background_srgb");
    if (bg.size() != 3) top.fail("background_srgb", "needs three numbers (red, green, blue in 0..1)");
    for (double c : bg)
      if (!(c >= 0 && c <= 1)) top.fail("background_srgb", "components must be in 0..1");
    scene.background_srgb = std::array<double, 3>{bg[0], bg[1], bg[2]};
  }
  scene.mallet_model = top.string_or("mallet_model", scene.mallet_model);
  scene.model_refs.push_back({scene.mallet_model, top.place("mallet_model"), top.dotted("mallet_model")});

  if (scene.kind == SceneKind::percussion) {
    for (TableReader& t : top.tables("instrument")) read_instrument(std::move(t), library, scene);
  } else {
    if (top.has("instrument"))
      top.fail("instrument", std::string("a ") + to_string(scene.kind) + " scene has no [[instrument]]");
    if (scene.kind == SceneKind::texture) read_texture(top, scene);
    else read_wall(top, library, scene);
  }
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
