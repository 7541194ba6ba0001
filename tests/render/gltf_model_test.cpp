// glTF models: the shipped models load with the shapes and materials the renderer scales
// and shades, and are exactly what their generator writes; node transforms are baked in;
// every kind of malformed file is refused with one line naming the file and the problem.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <sys/stat.h>

#include <gtest/gtest.h>
#include <stb_image_write.h>

#include "render/gltf_model.hpp"
#include "render/gltf_source.hpp"
#include "test_paths.hpp"

namespace mallet::render {
namespace {

namespace fs = std::filesystem;

using Vec3f = std::array<float, 3>;

const std::array<const char*, 9> kShippedModels{"wood_bar",          "metal_bar",    "xylophone_rail",
                                                "glockenspiel_rail", "mallet_head",  "mallet_stick",
                                                "texture_disc",      "wall_panel",   "cursor_head"};

fs::path shipped(const std::string& name) { return test::source_dir() / "models" / (name + ".glb"); }

std::vector<unsigned char> read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& file, const void* data, std::size_t size) {
  std::ofstream(file, std::ios::binary).write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
}

void write_text(const fs::path& file, const std::string& text) { write_bytes(file, text.data(), text.size()); }

std::size_t triangle_count(const Model& model) {
  std::size_t n = 0;
  for (const auto& p : model.primitives) n += p.indices.size() / 3;
  return n;
}

void expect_bounds(const Model& model, Vec3f lo, Vec3f hi) {
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(model.bounds_min[i], lo[i], 1e-6) << "axis " << i;
    EXPECT_NEAR(model.bounds_max[i], hi[i], 1e-6) << "axis " << i;
  }
}

Vec3f sub(const Vec3f& a, const Vec3f& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3f cross(const Vec3f& a, const Vec3f& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
float dot(const Vec3f& a, const Vec3f& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Front faces are counter-clockwise (glTF, and the renderer's culling): every triangle's
// geometric normal agrees with its vertices' normals, which are unit vectors.
void expect_front_faces_wind_counter_clockwise(const Model& model) {
  for (const auto& primitive : model.primitives) {
    for (const auto& v : primitive.vertices) ASSERT_NEAR(std::sqrt(dot(v.normal, v.normal)), 1.0f, 1e-5f);
    for (std::size_t t = 0; t < primitive.indices.size(); t += 3) {
      const Vertex& a = primitive.vertices[primitive.indices[t]];
      const Vertex& b = primitive.vertices[primitive.indices[t + 1]];
      const Vertex& c = primitive.vertices[primitive.indices[t + 2]];
      const Vec3f face = cross(sub(b.position, a.position), sub(c.position, a.position));
      const Vec3f normals{a.normal[0] + b.normal[0] + c.normal[0], a.normal[1] + b.normal[1] + c.normal[1],
                          a.normal[2] + b.normal[2] + c.normal[2]};
      ASSERT_GT(dot(face, normals), 0.0f) << model.file << ": triangle " << t / 3;
    }
  }
}

const PbrMaterial& only_material(const Model& model) {
  EXPECT_EQ(model.materials.size(), 1u);
  for (const auto& p : model.primitives) EXPECT_EQ(p.material, 0);
  return model.materials.at(0);
}

// ---- the shipped models ----

TEST(GltfModel, EveryShippedModelLoadsWithCounterClockwiseFrontFaces) {
  for (const char* name : kShippedModels) {
    SCOPED_TRACE(name);
    const Model model = load_gltf(shipped(name));
    EXPECT_EQ(model.file, shipped(name).string());
    ASSERT_EQ(model.primitives.size(), 1u);
    EXPECT_GT(triangle_count(model), 0u);
    expect_front_faces_wind_counter_clockwise(model);
  }
}

TEST(GltfModel, TextureDiscIsAUnitWhiteDiscFacingTheViewer) {
  const Model model = load_gltf(shipped("texture_disc"));
  expect_bounds(model, {-1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 0.0f});
  for (const auto& v : model.primitives[0].vertices) EXPECT_EQ(v.normal[2], 1.0f);
  const PbrMaterial& white = only_material(model);
  EXPECT_EQ(white.metallic, 0.0f);
  EXPECT_EQ(white.base_color[0], white.base_color[2]);  // neutral
  const Model cursor = load_gltf(shipped("cursor_head"));
  const PbrMaterial& green = only_material(cursor);
  EXPECT_GT(green.base_color[1], 4 * green.base_color[0]);  // the paper's green cursor
}

TEST(GltfModel, WoodBarIsAUnitBarOfRosewoodWithGrainAlongItsLength) {
  const Model model = load_gltf(shipped("wood_bar"));
  expect_bounds(model, {-0.5f, -1.0f, -0.5f}, {0.5f, 0.0f, 0.5f});
  EXPECT_EQ(model.primitives[0].vertices.size(), 24u);  // a flat-shaded box
  EXPECT_EQ(triangle_count(model), 12u);
  const PbrMaterial& wood = only_material(model);
  EXPECT_EQ(wood.name, "rosewood");
  EXPECT_EQ(wood.metallic, 0.0f);
  EXPECT_NEAR(wood.roughness, 0.55f, 1e-6f);
  EXPECT_GT(wood.base_color[0], wood.base_color[1]);  // warm: red over green over blue
  EXPECT_GT(wood.base_color[1], wood.base_color[2]);
  ASSERT_EQ(wood.base_color_texture, 0);
  EXPECT_EQ(wood.metallic_roughness_texture, -1);
  const TextureImage& grain = model.textures.at(0);
  ASSERT_EQ(grain.width, 512);
  ASSERT_EQ(grain.height, 128);
  ASSERT_EQ(grain.rgba.size(), 512u * 128u * 4u);
  // Grain lines run along the image's width: neighbours along a row differ less than
  // neighbours down a column.
  double along = 0;
  double across = 0;
  for (int y = 0; y + 1 < grain.height; ++y) {
    for (int x = 0; x + 1 < grain.width; ++x) {
      const auto red = [&](int px, int py) { return static_cast<double>(grain.rgba[(py * 512u + px) * 4u]); };
      along += std::abs(red(x + 1, y) - red(x, y));
      across += std::abs(red(x, y + 1) - red(x, y));
    }
  }
  EXPECT_LT(along, 0.8 * across);
  // ... and u follows the bar's length (z) on the top face.
  for (const auto& v : model.primitives[0].vertices) {
    if (v.normal[1] > 0.5f) {
      EXPECT_FLOAT_EQ(v.uv[0], v.position[2] + 0.5f);
      EXPECT_FLOAT_EQ(v.uv[1], v.position[0] + 0.5f);
    }
  }
}

TEST(GltfModel, MetalBarIsTheSameBarInLightPolishedMetal) {
  const Model model = load_gltf(shipped("metal_bar"));
  expect_bounds(model, {-0.5f, -1.0f, -0.5f}, {0.5f, 0.0f, 0.5f});
  EXPECT_EQ(model.primitives[0].vertices.size(), 24u);
  const PbrMaterial& metal = only_material(model);
  EXPECT_EQ(metal.metallic, 1.0f);
  EXPECT_NEAR(metal.roughness, 0.25f, 1e-6f);
  EXPECT_NEAR(metal.base_color[0], 0.85f, 1e-6f);
  EXPECT_NEAR(metal.base_color[2], 0.88f, 1e-6f);
  EXPECT_EQ(metal.base_color_texture, -1);
  EXPECT_TRUE(model.textures.empty());
}

TEST(GltfModel, RailsRunAlongXFromZeroToOneAndAreDarkAndRough) {
  for (const char* name : {"xylophone_rail", "glockenspiel_rail"}) {
    SCOPED_TRACE(name);
    const Model model = load_gltf(shipped(name));
    expect_bounds(model, {0.0f, -1.0f, -0.5f}, {1.0f, 0.0f, 0.5f});
    const PbrMaterial& rail = only_material(model);
    EXPECT_EQ(rail.metallic, 0.0f);
    EXPECT_GE(rail.roughness, 0.7f);
    EXPECT_LT(*std::max_element(rail.base_color.begin(), rail.base_color.begin() + 3), 0.15f);
  }
  EXPECT_GE(only_material(load_gltf(shipped("glockenspiel_rail"))).roughness, 0.9f);  // felt
}

TEST(GltfModel, MalletHeadIsASmoothWhiteUnitSphere) {
  const Model model = load_gltf(shipped("mallet_head"));
  expect_bounds(model, {-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f});
  EXPECT_GE(triangle_count(model), 1800u);
  EXPECT_LE(triangle_count(model), 2400u);
  for (const auto& v : model.primitives[0].vertices) {
    ASSERT_NEAR(std::sqrt(dot(v.position, v.position)), 1.0f, 1e-6f);
    for (std::size_t i = 0; i < 3; ++i) ASSERT_NEAR(v.normal[i], v.position[i], 1e-6f);  // smooth
  }
  const PbrMaterial& white = only_material(model);
  EXPECT_NEAR(white.base_color[0], 0.92f, 1e-6f);
  EXPECT_EQ(white.metallic, 0.0f);
  EXPECT_NEAR(white.roughness, 0.4f, 1e-6f);
}

TEST(GltfModel, MalletStickIsACappedUnitCylinderStandingOnTheOrigin) {
  const Model model = load_gltf(shipped("mallet_stick"));
  expect_bounds(model, {-1.0f, 0.0f, -1.0f}, {1.0f, 1.0f, 1.0f});
  EXPECT_EQ(triangle_count(model), 4u * 32u);  // 32 segments: two per side quad, one per cap wedge
  const auto caps = std::count_if(model.primitives[0].vertices.begin(), model.primitives[0].vertices.end(),
                                  [](const Vertex& v) { return std::abs(v.normal[1]) > 0.999f; });
  EXPECT_EQ(caps, 2 * 33);
  EXPECT_EQ(only_material(model).metallic, 0.0f);
}

// The committed models can never drift from their generator.
fs::path generator_binary() {
  const fs::path build = fs::path(MALLET_TEST_BINARY).parent_path();
  for (const fs::path& candidate :
       {build / "mallet_gen_models", build / "tools" / "gen_models" / "mallet_gen_models"}) {
    if (fs::exists(candidate)) return candidate;
  }
  return {};
}

std::set<std::string> glb_files(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() == ".glb") names.insert(entry.path().filename().string());
  }
  return names;
}

TEST(GltfModel, GeneratorReproducesTheCommittedModelsByteForByte) {
  const fs::path generator = generator_binary();
  ASSERT_FALSE(generator.empty()) << "mallet_gen_models is not built next to " << MALLET_TEST_BINARY
                                  << " (render_asset_tests depends on it: build that target)";
  const fs::path out = test::scratch_dir();
  const std::string command = "'" + generator.string() + "' '" + out.string() + "' > /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const fs::path committed = test::source_dir() / "models";
  ASSERT_EQ(glb_files(out), glb_files(committed));
  EXPECT_EQ(glb_files(out).size(), kShippedModels.size());
  for (const std::string& name : glb_files(out)) {
    EXPECT_TRUE(read_bytes(out / name) == read_bytes(committed / name))
        << "models/" << name << " differs from what tools/gen_models writes: regenerate it with "
        << "`cmake --build --preset debug --target models` and commit the result";
  }
}

// ---- small glTF files written by the tests ----

// One primitive in model.gltf + model.bin: positions, optional normals and indices.
struct GltfFile {
  std::vector<Vec3f> positions{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  std::vector<Vec3f> normals;                   // empty: no NORMAL attribute
  std::vector<std::uint16_t> indices{0, 1, 2};  // empty: no indices
  int mode = 4;                                 // TRIANGLES
  std::string nodes = R"([{"mesh": 0}])";
  std::size_t position_count = 0;  // what the POSITION accessor claims; 0: positions.size()
  std::string material;            // a primitive "material" member, e.g. R"("material": 0,)"
  std::string extra;               // more top-level members, each starting with a comma
};

fs::path write_gltf(const fs::path& dir, const GltfFile& f) {
  std::vector<unsigned char> bin;
  std::string views;
  std::string accessors;
  int next = 0;
  const auto add = [&](const void* data, std::size_t size, std::size_t count, int component_type, const char* type) {
    bin.resize((bin.size() + 3) / 4 * 4);
    const std::size_t offset = bin.size();
    bin.insert(bin.end(), static_cast<const unsigned char*>(data), static_cast<const unsigned char*>(data) + size);
    const std::string comma = next == 0 ? "" : ",";
    views += comma + R"({"buffer": 0, "byteOffset": )" + std::to_string(offset) + R"(, "byteLength": )" +
             std::to_string(size) + "}";
    accessors += comma + R"({"bufferView": )" + std::to_string(next) + R"(, "componentType": )" +
                 std::to_string(component_type) + R"(, "count": )" + std::to_string(count) + R"(, "type": ")" + type +
                 "\"}";
    return next++;
  };
  std::string attributes =
      R"("POSITION": )" + std::to_string(add(f.positions.data(), f.positions.size() * 12,
                                             f.position_count ? f.position_count : f.positions.size(), 5126, "VEC3"));
  if (!f.normals.empty()) {
    attributes += R"(, "NORMAL": )" +
                  std::to_string(add(f.normals.data(), f.normals.size() * 12, f.normals.size(), 5126, "VEC3"));
  }
  std::string indices;
  if (!f.indices.empty()) {
    indices = R"("indices": )" +
              std::to_string(add(f.indices.data(), f.indices.size() * 2, f.indices.size(), 5123, "SCALAR")) + ",";
  }
  const std::string json = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": )" +
                           f.nodes + R"(, "meshes": [{"name": "tri", "primitives": [{"attributes": {)" + attributes +
                           "}, " + indices + f.material + R"("mode": )" + std::to_string(f.mode) +
                           R"(}]}], "buffers": [{"uri": "model.bin", "byteLength": )" + std::to_string(bin.size()) +
                           R"(}], "bufferViews": [)" + views + R"(], "accessors": [)" + accessors + "]" + f.extra + "}";
  write_bytes(dir / "model.bin", bin.data(), bin.size());
  write_text(dir / "model.gltf", json);
  return dir / "model.gltf";
}

void expect_position(const Vertex& v, Vec3f expected) {
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(v.position[i], expected[i], 1e-5f) << "axis " << i;
}
void expect_normal(const Vertex& v, Vec3f expected) {
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(v.normal[i], expected[i], 1e-5f) << "axis " << i;
}

TEST(GltfModel, NodeTransformsOfTheHierarchyAreBakedIn) {
  GltfFile f;
  // Parent: translate (1, 2, 3) after scaling by 2; child: a quarter turn about z.
  f.nodes = R"([{"translation": [1, 2, 3], "scale": [2, 2, 2], "children": [1]},
                {"rotation": [0, 0, 0.70710678118654752, 0.70710678118654752], "mesh": 0}])";
  const Model model = load_gltf(write_gltf(test::scratch_dir(), f));
  ASSERT_EQ(model.primitives.size(), 1u);
  const auto& v = model.primitives[0].vertices;
  const auto& idx = model.primitives[0].indices;
  ASSERT_EQ(idx.size(), 3u);
  expect_position(v[idx[0]], {1, 2, 3});   // (0, 0, 0)
  expect_position(v[idx[1]], {1, 4, 3});   // (1, 0, 0) → (0, 1, 0) → (0, 2, 0) → + t
  expect_position(v[idx[2]], {-1, 2, 3});  // (0, 1, 0) → (-1, 0, 0) → (-2, 0, 0) → + t
  expect_bounds(model, {-1, 2, 3}, {1, 4, 3});
  for (const auto& vertex : v) expect_normal(vertex, {0, 0, 1});  // flat normals: none in the file
}

TEST(GltfModel, NodeMatrixIsApplied) {
  GltfFile f;
  f.nodes = R"([{"matrix": [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0,  5, 6, 7, 1], "mesh": 0}])";
  const Model model = load_gltf(write_gltf(test::scratch_dir(), f));
  expect_bounds(model, {5, 6, 7}, {6, 7, 7});
}

TEST(GltfModel, NormalsTurnByTheInverseTransposeOfANonUniformScale) {
  GltfFile f;
  const float r = 1.0f / std::sqrt(2.0f);
  f.positions = {{1, 0, 0}, {0, 1, 0}, {1, 0, 1}};  // in the plane x + y = 1
  f.normals.assign(3, {r, r, 0});
  f.nodes = R"([{"scale": [2, 1, 1], "mesh": 0}])";
  const Model model = load_gltf(write_gltf(test::scratch_dir(), f));
  // Stretched in x, the plane 2·y + x = 2 has normal ∝ (1, 2, 0), not (1, 1, 0).
  const float k = 1.0f / std::sqrt(5.0f);
  for (const auto& v : model.primitives[0].vertices) expect_normal(v, {k, 2 * k, 0});
  expect_position(model.primitives[0].vertices[0], {2, 0, 0});
  expect_front_faces_wind_counter_clockwise(model);
}

TEST(GltfModel, MirroringTransformKeepsFrontFacesCounterClockwise) {
  GltfFile f;
  f.normals.assign(3, {0, 0, 1});
  f.nodes = R"([{"scale": [-1, 1, 1], "mesh": 0}])";
  const Model model = load_gltf(write_gltf(test::scratch_dir(), f));
  expect_bounds(model, {-1, 0, 0}, {0, 1, 0});
  expect_front_faces_wind_counter_clockwise(model);
}

TEST(GltfModel, MissingIndicesAreGeneratedAndMissingNormalsAreFlat) {
  GltfFile f;
  f.indices.clear();
  f.positions = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}};  // counter-clockwise seen from +y
  const Model model = load_gltf(write_gltf(test::scratch_dir(), f));
  ASSERT_EQ(model.primitives[0].indices, (std::vector<std::uint32_t>{0, 1, 2}));
  for (const auto& v : model.primitives[0].vertices) {
    expect_normal(v, {0, 1, 0});
    EXPECT_EQ(v.uv, (std::array<float, 2>{0, 0}));  // no TEXCOORD_0
  }
  EXPECT_EQ(model.primitives[0].material, -1);
  EXPECT_TRUE(model.materials.empty());
}

TEST(GltfModel, TriangleStripsAndFansBecomeTriangleLists) {
  for (const int mode : {5, 6}) {
    SCOPED_TRACE(mode);
    GltfFile f;
    f.mode = mode;
    // strip: (0 1 2) (1 3 2); fan: (0 1 2) (0 2 3) with 3 = (-1, 1)
    f.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {mode == 5 ? 1.0f : -1.0f, 1, 0}};
    f.indices = {0, 1, 2, 3};
    f.normals.assign(4, {0, 0, 1});
    const Model model = load_gltf(write_gltf(test::scratch_dir(), f));
    EXPECT_EQ(model.primitives[0].indices.size(), 6u);
    expect_front_faces_wind_counter_clockwise(model);
  }
}

TEST(GltfModel, ExternalPngTextureIsDecodedToRgba8) {
  const fs::path dir = test::scratch_dir();
  const std::array<unsigned char, 6> rgb{255, 0, 0, 0, 0, 255};  // red, blue
  ASSERT_NE(stbi_write_png((dir / "two.png").c_str(), 2, 1, 3, rgb.data(), 6), 0);
  GltfFile f;
  f.material = R"("material": 0, )";
  f.extra = R"(, "materials": [{"name": "painted", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                 "metallicRoughnessTexture": {"index": 0}, "metallicFactor": 0.5}}],
               "textures": [{"source": 0}], "images": [{"uri": "two.png"}])";
  const Model model = load_gltf(write_gltf(dir, f));
  const PbrMaterial& m = only_material(model);
  EXPECT_EQ(m.name, "painted");
  EXPECT_EQ(m.metallic, 0.5f);
  EXPECT_EQ(m.roughness, 1.0f);
  EXPECT_EQ(m.base_color, (std::array<float, 4>{1, 1, 1, 1}));
  ASSERT_EQ(m.base_color_texture, 0);
  EXPECT_EQ(m.metallic_roughness_texture, 0);  // the same glTF texture, decoded once
  ASSERT_EQ(model.textures.size(), 1u);
  EXPECT_EQ(model.textures[0].width, 2);
  EXPECT_EQ(model.textures[0].height, 1);
  EXPECT_EQ(model.textures[0].rgba, (std::vector<std::uint8_t>{255, 0, 0, 255, 0, 0, 255, 255}));
}

// ---- malformed files: one FileError naming the file and the problem ----

void expect_error(const fs::path& file, const std::string& problem) {
  const FileError e = test::file_error_of([&] { load_gltf(file); });
  EXPECT_EQ(e.file(), file.string());
  const std::string what = e.what();
  EXPECT_EQ(what.rfind(file.string() + ": ", 0), 0u) << what;
  EXPECT_NE(what.find(problem), std::string::npos) << what;
  EXPECT_EQ(what.find('\n'), std::string::npos) << what;
}

fs::path gltf_in_scratch(const GltfFile& f) { return write_gltf(test::scratch_dir(), f); }

TEST(GltfModelErrors, MissingFile) { expect_error(test::scratch_dir() / "absent.glb", "no such file"); }

TEST(GltfModelErrors, TruncatedGlb) {
  const fs::path file = test::scratch_dir() / "truncated.glb";
  const std::vector<unsigned char> whole = read_bytes(shipped("wood_bar"));
  write_bytes(file, whole.data(), whole.size() / 2);
  expect_error(file, "not a valid glTF binary");
}

TEST(GltfModelErrors, InvalidJson) {
  const fs::path file = test::scratch_dir() / "broken.gltf";
  write_text(file, R"({"asset": {"version": "2.0"}, "meshes": [)");
  expect_error(file, "not valid glTF: [json.exception.parse_error");
}

TEST(GltfModelErrors, IndexOutOfRange) {
  GltfFile f;
  f.indices = {0, 1, 5};
  expect_error(gltf_in_scratch(f), "mesh 'tri' primitive 0: index 5 >= 3 vertices");
}

TEST(GltfModelErrors, LinesAreRefused) {
  GltfFile f;
  f.mode = 1;
  f.indices = {0, 1};
  expect_error(gltf_in_scratch(f), "mesh 'tri' primitive 0: mode LINES cannot be drawn");
}

TEST(GltfModelErrors, IndicesThatAreNotWholeTriangles) {
  GltfFile f;
  f.indices = {0, 1, 2, 0};
  expect_error(gltf_in_scratch(f), "4 indices are not a whole number of triangles");
}

TEST(GltfModelErrors, AccessorPastTheEndOfItsBuffer) {
  GltfFile f;
  f.position_count = 4;  // three positions in the buffer
  expect_error(gltf_in_scratch(f), "POSITION (accessor 0): 4 elements of 12 bytes from offset 0 run past the end");
}

TEST(GltfModelErrors, NanPosition) {
  GltfFile f;
  f.positions[1][1] = std::numeric_limits<float>::quiet_NaN();
  expect_error(gltf_in_scratch(f), "mesh 'tri' primitive 0: POSITION 1 is not finite");
}

// The node transform's own problems, each named with the node.
TEST(GltfModelErrors, SingularTransform) {
  GltfFile f;
  f.nodes = R"([{"scale": [1, 0, 1], "mesh": 0}])";
  expect_error(gltf_in_scratch(f),
               "node 0: its transform is singular (a zero scale): mesh 'tri' primitive 0 would collapse");
}

TEST(GltfModelErrors, MatrixThatIsNotAffine) {
  GltfFile f;
  f.nodes = R"([{"matrix": [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 0.5,  0, 0, 0, 1], "mesh": 0}])";
  expect_error(gltf_in_scratch(f), "node 0: matrix is not affine (its last row must be 0 0 0 1)");
}

TEST(GltfModelErrors, TransformThatTakesAPositionToInfinity) {
  GltfFile f;
  f.positions[1] = {1e10f, 0, 0};
  f.nodes = R"([{"scale": [1e300, 1, 1], "mesh": 0}])";
  expect_error(gltf_in_scratch(f), "node 0: its transform takes mesh 'tri' primitive 0 POSITION 1 to infinity");
}

TEST(GltfModelErrors, ZeroNormal) {
  GltfFile f;
  f.normals = {{0, 0, 1}, {0, 0, 0}, {0, 0, 1}};
  expect_error(gltf_in_scratch(f), "mesh 'tri' primitive 0: NORMAL 1 is not a direction (0, 0, 0)");
}

TEST(GltfModelErrors, NoPosition) {
  const fs::path file = test::scratch_dir() / "nothing.gltf";
  write_text(file, R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0}],
                      "meshes": [{"primitives": [{"attributes": {}}]}]})");
  expect_error(file, "mesh 0 primitive 0: no POSITION attribute");
}

TEST(GltfModelErrors, SceneWithoutMeshes) {
  const fs::path file = test::scratch_dir() / "empty.gltf";
  write_text(file, R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"name": "lonely"}]})");
  expect_error(file, "no triangles to draw");
}

TEST(GltfModelErrors, NodeCycle) {
  GltfFile f;
  f.nodes = R"([{"name": "a", "children": [1]}, {"name": "b", "mesh": 0, "children": [0]}])";
  expect_error(gltf_in_scratch(f), "node 'a': reached twice");
}

TEST(GltfModelErrors, RequiredExtension) {
  GltfFile f;
  f.extra = R"(, "extensionsUsed": ["KHR_texture_basisu"], "extensionsRequired": ["KHR_texture_basisu"])";
  expect_error(gltf_in_scratch(f), "requires extension 'KHR_texture_basisu', which the renderer does not support");
}

TEST(GltfModelErrors, MissingTextureImage) {
  GltfFile f;
  f.material = R"("material": 0, )";
  f.extra = R"(, "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
               "textures": [{"source": 0}], "images": [{"uri": "absent.png"}])";
  expect_error(gltf_in_scratch(f), "image 0: cannot read 'absent.png'");
}

TEST(GltfModelErrors, CorruptEmbeddedTexture) {
  const fs::path file = test::scratch_dir() / "corrupt_texture.glb";
  std::vector<unsigned char> bytes = read_bytes(shipped("wood_bar"));
  const unsigned char png_magic[] = {0x89, 'P', 'N', 'G'};
  const auto png = std::search(bytes.begin(), bytes.end(), std::begin(png_magic), std::end(png_magic));
  ASSERT_NE(png, bytes.end());
  std::fill(png, png + 64, 0);
  write_bytes(file, bytes.data(), bytes.size());
  expect_error(file, "image 'rosewood_grain': cannot decode");
}

// ---- hostile files (found with real public glTF test files): refused, never a crash or a hang ----

TEST(GltfModelErrors, ModelPathIsADirectory) {
  const fs::path dir = test::scratch_dir() / "model.glb";
  fs::create_directories(dir);
  expect_error(dir, "is a directory");
}

TEST(GltfModelErrors, ModelPathIsAFifoAndIsNotOpened) {
  const fs::path fifo = test::scratch_dir() / "model.glb";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_error(fifo, "is not a regular file (a FIFO, socket or device)");  // opening it would block forever
}

TEST(GltfModelErrors, ModelLargerThanTheLoaderReads) {
  const fs::path file = test::scratch_dir() / "huge.glb";
  write_text(file, "glTF");
  fs::resize_file(file, kMaxGltfFileBytes + 1);  // sparse: nothing is written to the disk
  expect_error(file, "larger than the 512 MiB Mallet loads");
}

TEST(GltfModelErrors, BufferUriNamingADirectory) {
  const fs::path file = gltf_in_scratch(GltfFile{});
  fs::remove(file.parent_path() / "model.bin");
  fs::create_directories(file.parent_path() / "model.bin");  // tinygltf alone: std::bad_alloc
  expect_error(file, "model.bin : is a directory, not a file");
}

TEST(GltfModelErrors, BufferUriNamingAFifo) {
  const fs::path file = gltf_in_scratch(GltfFile{});
  fs::remove(file.parent_path() / "model.bin");
  ASSERT_EQ(::mkfifo((file.parent_path() / "model.bin").c_str(), 0600), 0);  // tinygltf alone: blocks
  expect_error(file, "model.bin : is not a regular file");
}

TEST(GltfModelErrors, ImageUriNamingADirectory) {
  GltfFile f;
  f.material = R"("material": 0, )";
  f.extra = R"(, "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
               "textures": [{"source": 0}], "images": [{"uri": "grain.png"}])";
  const fs::path file = gltf_in_scratch(f);
  fs::create_directories(file.parent_path() / "grain.png");
  expect_error(file, "image 0: cannot read 'grain.png': is a directory, not a file");
}

std::string nested(int depth) { return std::string(static_cast<std::size_t>(depth), '[') + std::string(static_cast<std::size_t>(depth), ']'); }

TEST(GltfModelErrors, DeeplyNestedExtrasAreRefusedAtTheirLineAndColumn) {
  GltfFile f;
  f.extra = ",\n \"extras\": " + nested(200000);  // tinygltf alone: a stack overflow
  const fs::path file = gltf_in_scratch(f);
  const FileError e = test::file_error_of([&] { load_gltf(file); });
  EXPECT_EQ(e.line(), 2u);
  EXPECT_EQ(e.column(), 12u + 63u);  // the 64th [ (inside the top-level object: depth 65)
  EXPECT_NE(std::string(e.what()).find("JSON nested more than 64 arrays or objects deep"), std::string::npos)
      << e.what();
}

TEST(GltfModelErrors, DeeplyNestedJsonChunkOfAGlb) {
  const std::string json = R"({"asset": {"version": "2.0"}, "extras": )" + nested(100000) + "}";
  std::vector<unsigned char> glb(20);
  const std::uint32_t header[5] = {0x46546C67u, 2u, static_cast<std::uint32_t>(20 + json.size()),
                                   static_cast<std::uint32_t>(json.size()), 0x4E4F534Au};  // "glTF", "JSON"
  std::memcpy(glb.data(), header, sizeof header);
  glb.insert(glb.end(), json.begin(), json.end());
  const fs::path file = test::scratch_dir() / "deep.glb";
  write_bytes(file, glb.data(), glb.size());
  expect_error(file, "JSON chunk line 1 column 104: JSON nested more than 64");
}

TEST(GltfModel, BracketsInsideJsonStringsAreNotNesting) {
  GltfFile f;
  f.extra = R"(, "extras": {"note": ")" + nested(1000) + R"(\" [[["})";
  EXPECT_EQ(triangle_count(load_gltf(gltf_in_scratch(f))), 1u);
}

TEST(GltfModelErrors, DracoCompressedMeshIsNamedAsSuch) {
  // As a Draco exporter writes it: the accessors have no bufferView; the primitive's
  // extension points at the compressed bytes.
  const fs::path dir = test::scratch_dir();
  write_bytes(dir / "draco.bin", "DRACO\0\0\0", 8);
  write_text(dir / "draco.gltf", R"({"asset": {"version": "2.0"},
    "extensionsUsed": ["KHR_draco_mesh_compression"], "extensionsRequired": ["KHR_draco_mesh_compression"],
    "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1,
      "extensions": {"KHR_draco_mesh_compression": {"bufferView": 0, "attributes": {"POSITION": 0}}}}]}],
    "accessors": [{"componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"componentType": 5123, "count": 3, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteLength": 8}], "buffers": [{"uri": "draco.bin", "byteLength": 8}]})");
  expect_error(dir / "draco.gltf",
               "its meshes are compressed with KHR_draco_mesh_compression (Draco), which Mallet cannot decode");
}

}  // namespace
}  // namespace mallet::render
