#pragma once
#include <string>

#include "core/scene.hpp"

namespace mallet::app {

//! `mallet scene describe`: the scene as JSON, in metres, for researchers' scripts:
//! {"mallet_radius": m, "targets": [{"id", "instrument", "material", "note",
//!  "frequency_hz", "x_min", "x_max", "top_y"}, ...], "screen_to_world": {...}}
std::string describe_scene_json(const Scene& scene);

}  // namespace mallet::app
