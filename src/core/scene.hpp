#pragma once
// A scene: the instruments' bars (targets) in the vertical plane, their materials and
// notes, the mallet head's radius and the screen → world mapping.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/enum_names.hpp"
#include "core/file_error.hpp"
#include "core/material.hpp"
#include "core/screen_to_world.hpp"
#include "core/speed_technique.hpp"
#include "core/stripe_signal.hpp"
#include "core/texture_relief.hpp"

namespace mallet {

//! One strikeable bar. Its top face spans [x_min, x_max] at height top_y.
struct Target {
  int id = 0;                //!< index in Scene::targets, stable in config order
  std::string instrument;    //!< "xylophone", "glockenspiel", ...
  int material = 0;          //!< index in Scene::materials
  int note = 60;             //!< MIDI note number
  double frequency_hz = 0;   //!< equal temperament from the scene's A4
  double x_min = 0;          //!< metres
  double x_max = 0;          //!< metres
  double top_y = 0;          //!< metres
  double length_m = 0;       //!< along the depth axis (drawn, not used by contact)
  double thickness_m = 0;    //!< drawn, not used by contact
  //! False: a hand's mallet rests on it but never strikes it; only the program does (a
  //! study's stimulus bars, which a participant's answer strikes must not play).
  bool hand_strikes = true;
};

//! An instrument as configured: a row of bars of one material.
struct Instrument {
  std::string name;
  std::string voice;         //!< acoustic preset in the instruments file (default: name)
  int midi_program = 0;      //!< General MIDI program for the midi route (0-based)
  int material = 0;
  std::vector<int> targets;  //!< ids, left to right
  std::string bar_model;     //!< glTF file in models/ drawn for each bar (unit bar, scaled)
  std::string rail_model;    //!< glTF file in models/ for the two rails under the bars
  //! False: its strikes are silent on the speaker channel (a study's stimuli without sound,
  //! beside answer bars that click).
  bool speaker = true;
};

//! Where the visitor's eye is for the perspective view. The screen shows exactly the
//! screen_to_world rectangle of the plane z = 0 (the mallet's plane), seen from this
//! eye through an off-axis frustum: the pointer maps onto the plane linearly, and the
//! bars, which extend in depth (z), are seen from above in perspective.
struct Camera {
  double eye_x_m = 0.0;     //!< usually the middle of the instruments
  double eye_y_m = 0.9;     //!< above the bars' tops: the bars are seen from above
  double eye_z_m = 1.6;     //!< in front of the mallet's plane (> 0)
};

//! What a scene is (config key `kind`):
//!  percussion  the first paper's instruments, struck from above (default);
//!  texture     the second paper's bump or hole explored with the Speed technique and
//!              vibrotactile stripes — no targets, nothing is struck;
//!  wall        the second paper's wall to tap: one target whose instrument is "wall",
//!              with a material the operator (or the attract loop) switches.
enum class SceneKind { percussion, texture, wall };
inline constexpr EnumNames<SceneKind, 3> kSceneKindNames{
    {{SceneKind::percussion, "percussion"}, {SceneKind::texture, "texture"}, {SceneKind::wall, "wall"}}};
inline const char* to_string(SceneKind kind) { return name_in(kSceneKindNames, kind, "percussion"); }

//! How a scene is laid out on the screen (core/scene_layout.hpp): as its file says, or,
//! on a screen taller than wide, its instruments stacked and its content narrowed.
enum class SceneLayout { landscape, portrait };
inline constexpr EnumNames<SceneLayout, 2> kSceneLayoutNames{
    {{SceneLayout::landscape, "landscape"}, {SceneLayout::portrait, "portrait"}}};
inline const char* to_string(SceneLayout layout) { return name_in(kSceneLayoutNames, layout, "landscape"); }

//! The texture scene's stimulus: the relief under the disc, the Speed technique's law and
//! the stripes on the actuator channel.
struct TextureStimulus {
  TextureRelief relief;
  SpeedTechniqueConfig speed;
  StripeParams stripes;
};

struct Scene {
  SceneKind kind = SceneKind::percussion;
  SceneLayout layout = SceneLayout::landscape;  //!< as loaded: landscape
  std::string name;
  std::string file;                  //!< where it was loaded from (for messages)
  std::string instruments_file;      //!< acoustic presets, resolved against the scene's folder
  double mallet_radius_m = 0.015;
  double tuning_a4_hz = 440.0;
  ScreenToWorld screen_to_world;
  Camera camera;
  std::vector<Material> materials;   //!< only those the scene uses
  std::vector<Instrument> instruments;
  std::vector<Target> targets;
  std::optional<TextureStimulus> texture;  //!< kind == texture only
  std::vector<int> wall_materials;         //!< kind == wall: the materials to switch between
  //! Drawn behind everything, sRGB 0..1 (the second paper's scenes: grey). Unset: a dark room.
  std::optional<std::array<double, 3>> background_srgb;
  std::string mallet_model = "mallet_head.glb";  //!< glTF in models/ drawn as the mallet head / cursor
  //! Where each model file was named (file, line, dotted key), so that a broken model is
  //! reported against the setting that chose it. Defaults are named at their table.
  struct ModelRef {
    std::string model;
    FilePlace at;
    std::string key;
  };
  std::vector<ModelRef> model_refs;
  //! The first place that names `model`; nullptr if none is known.
  const ModelRef* model_ref(const std::string& model) const {
    for (const ModelRef& r : model_refs)
      if (r.model == model) return &r;
    return nullptr;
  }

  const Material& material_of(const Target& t) const { return materials.at(t.material); }
};

}  // namespace mallet
