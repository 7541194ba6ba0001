// `mallet bench render`'s detailed bar, read back through the project's own glTF loader.
#include "render/detailed_model.hpp"

#include <array>
#include <filesystem>

#include <gtest/gtest.h>

#include "render/gltf_model.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

TEST(BenchDetailedModel, TheBenchsDetailedBarLoadsWholeThroughTheProjectsLoader) {
  // `mallet bench render`'s detailed bar: the unit bar, each face a 10 × 10 grid.
  const std::filesystem::path file = test::scratch_dir() / "detailed_bar.glb";
  const std::size_t triangles = render::write_detailed_bar(file, 10, {0.85, 0.85, 0.88, 1.0}, 1.0, 0.25);
  EXPECT_EQ(triangles, 12u * 10 * 10);
  const render::Model model = render::load_gltf(file);
  ASSERT_EQ(model.primitives.size(), 1u);
  EXPECT_EQ(model.primitives[0].indices.size(), 3 * triangles);
  EXPECT_EQ(model.primitives[0].vertices.size(), 6u * 11 * 11);
  EXPECT_EQ(model.bounds_min, (std::array<float, 3>{-0.5f, -1.0f, -0.5f}));
  EXPECT_EQ(model.bounds_max, (std::array<float, 3>{0.5f, 0.0f, 0.5f}));
  ASSERT_EQ(model.materials.size(), 1u);
  EXPECT_FLOAT_EQ(model.materials[0].metallic, 1.0f);
  EXPECT_FLOAT_EQ(model.materials[0].roughness, 0.25f);
}

}  // namespace
}  // namespace mallet::app
