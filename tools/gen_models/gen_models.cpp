// mallet_gen_models OUT_DIR: writes the shipped glTF models (models/*.glb), the source of
// truth for them. Units are metres, y is up; every model is a unit shape the renderer
// scales from the scene config (see models/README.md). The output is byte-identical on
// every run, and a test checks the committed files against it.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <vector>

#include "glb_writer.hpp"
#include "mesh_shapes.hpp"
#include "wood_grain.hpp"

namespace mallet::gen {
namespace {

constexpr int kGrainWidth = 512;   // along the bar's length
constexpr int kGrainHeight = 128;  // across its width

// Base colours are linear (glTF's factors); the bar's grain texture multiplies the
// rosewood factor.
MaterialSpec rosewood() {
  return {"rosewood", {0.30, 0.10, 0.045, 1.0}, 0.0, 0.55, wood_grain(kGrainWidth, kGrainHeight), "rosewood_grain"};
}
MaterialSpec bar_steel() { return {"bar_steel", {0.85, 0.85, 0.88, 1.0}, 1.0, 0.25, {}, {}}; }
MaterialSpec rail_dark_wood() { return {"rail_dark_wood", {0.08, 0.035, 0.018, 1.0}, 0.0, 0.75, {}, {}}; }
MaterialSpec rail_felt_case() { return {"rail_felt_case", {0.05, 0.05, 0.055, 1.0}, 0.0, 0.95, {}, {}}; }
MaterialSpec mallet_head_white() { return {"mallet_head_white", {0.92, 0.92, 0.92, 1.0}, 0.0, 0.4, {}, {}}; }
// The second paper's scenes: a white disc or wall on grey, a green cursor.
MaterialSpec paper_white() { return {"paper_white", {1.0, 1.0, 1.0, 1.0}, 0.0, 0.9, {}, {}}; }
MaterialSpec cursor_green() { return {"cursor_green", {0.02, 0.55, 0.06, 1.0}, 0.0, 0.5, {}, {}}; }
MaterialSpec stick_light_wood() { return {"stick_light_wood", {0.70, 0.50, 0.30, 1.0}, 0.0, 0.6, {}, {}}; }

// A bar: x ∈ [-0.5, 0.5] width, y ∈ [-1, 0] thickness (top face at y = 0), z ∈ [-0.5, 0.5]
// length, the grain along z.
MeshData unit_bar() { return box({-0.5, -1.0, -0.5}, {0.5, 0.0, 0.5}, LengthAxis::kZ); }

// A rail: x ∈ [0, 1] along its length, y ∈ [-1, 0], z ∈ [-0.5, 0.5].
MeshData unit_rail() { return box({0.0, -1.0, -0.5}, {1.0, 0.0, 0.5}, LengthAxis::kX); }

std::vector<ModelSpec> shipped_models() {
  std::vector<ModelSpec> models;
  models.push_back({"wood_bar", unit_bar(), rosewood()});
  models.push_back({"metal_bar", unit_bar(), bar_steel()});
  models.push_back({"xylophone_rail", unit_rail(), rail_dark_wood()});
  models.push_back({"glockenspiel_rail", unit_rail(), rail_felt_case()});
  models.push_back({"mallet_head", uv_sphere(48, 22), mallet_head_white()});  // 2016 triangles
  models.push_back({"mallet_stick", capped_cylinder(32), stick_light_wood()});
  models.push_back({"texture_disc", disc(128), paper_white()});
  models.push_back({"wall_panel", unit_bar(), paper_white()});
  models.push_back({"cursor_head", uv_sphere(48, 22), cursor_green()});
  return models;
}

}  // namespace
}  // namespace mallet::gen

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: mallet_gen_models OUT_DIR\n  writes the shipped glTF models into OUT_DIR\n");
    return 2;
  }
  try {
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    for (const auto& model : mallet::gen::shipped_models()) {
      mallet::gen::write_glb(model, dir);
      std::printf("wrote %s (%zu vertices, %zu triangles)\n", (dir / (model.name + ".glb")).c_str(),
                  model.mesh.positions.size(), model.mesh.indices.size() / 3);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mallet_gen_models: %s\n", e.what());
    return 1;
  }
  return 0;
}
