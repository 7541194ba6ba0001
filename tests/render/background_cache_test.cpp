// The renderer's cached background (the instruments drawn once per image size, with their
// light per pixel; each frame copies them in, shades the mallet's shadow on the screen where
// it can fall, and draws the mallet over them) must give the pixels of drawing the whole
// scene every frame.
// Frames follow one another in one renderer, so a shadow left behind by the frame before
// would show as a difference too.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/detailed_model.hpp"
#include "render/render_setup.hpp"
#include "render/font_atlas.hpp"
#include "render/image.hpp"
#include "render/overlay.hpp"
#include "render/offscreen_target.hpp"
#include "render/pipeline_cache.hpp"
#include "render/scene_renderer.hpp"
#include "test_paths.hpp"

namespace mallet::render {
namespace {

std::unique_ptr<render::HeadlessRenderer> renderer(const Scene& scene, bool cache,
                                                VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT,
                                                VkSampleCountFlagBits background_samples = VK_SAMPLE_COUNT_1_BIT,
                                                const std::filesystem::path& models = {}) {
  render::HeadlessOptions o;
  o.models = models;
  o.size = {480, 270};
  o.settings.background_cache = cache;
  o.settings.samples = samples;
  o.settings.background_samples = background_samples;
  o.validation = Validation::required;
  o.cache_dir = "";
  o.device = "llvmpipe";
  return std::make_unique<render::HeadlessRenderer>(scene, o);
}

//! Mallet centres that visit every kind of place: high above, resting on and straddling
//! bars, between the instruments, below the bars' tops, at and beyond the screen's edges.
std::vector<Vec2> places(const Scene& scene) {
  std::vector<Vec2> out;
  const ScreenToWorld& w = scene.screen_to_world;
  for (double sx : {-0.05, 0.0, 0.13, 0.31, 0.5, 0.62, 0.77, 0.95, 1.04})
    for (double sy : {0.05, 0.35, 0.62, 0.8, 0.97}) out.push_back(w.map(sx, sy));
  for (const Target& t : scene.targets) {
    out.push_back({(t.x_min + t.x_max) / 2, t.top_y + scene.mallet_radius_m});  // resting on it
    out.push_back({t.x_max, t.top_y + 0.03});                                     // over its edge
    out.push_back({t.x_min, t.top_y - 0.02});                                     // beside it, lower
  }
  return out;
}

//! Single-sampled frames shade the shadow on the screen from the cached light (half floats)
//! and depth: a few of its pixels round to the next 8-bit level (measured: at most 22 of a
//! 480×270 frame, 1/255 each). Everything else is exact.
constexpr int kShadowRounding = 1;

void expect_same_frames(const Scene& scene, VkSampleCountFlagBits samples, const std::filesystem::path& models = {}) {
  auto cached = renderer(scene, true, samples, VK_SAMPLE_COUNT_1_BIT, models);
  auto whole = renderer(scene, false, samples, VK_SAMPLE_COUNT_1_BIT, models);
  int frames = 0;
  for (const Vec2 c : places(scene)) {
    for (bool shadow_on_frame : {true, false}) {
      FrameState s;
      s.mallet_centre = c;
      s.draw_mallet = shadow_on_frame;  // a frame without the mallet: no shadow may remain
      // Lit bars (under the mallet, struck) redrawn over the cache, every other frame.
      if (!scene.targets.empty() && frames % 2 == 0)
        s.bar_lights = {BarLight{scene.targets.front().id, 0.2f},
                        BarLight{scene.targets.at(scene.targets.size() / 2).id, 0.8f}};
      const ImageDiff d = compare_images(cached->render(s), whole->render(s), 0);
      ASSERT_TRUE(d.same_size);
      EXPECT_LE(d.max_channel_delta, kShadowRounding) << "mallet at (" << c.x << ", " << c.y << "), drawn "
                                                      << shadow_on_frame << ": " << d.differing_pixels
                                                      << " pixels differ";
      if (samples != VK_SAMPLE_COUNT_1_BIT) {
        EXPECT_EQ(d.max_channel_delta, 0) << "multisampled frames redraw the bars: exactly the whole scene";
      }
      ++frames;
    }
  }
  EXPECT_GT(frames, 60);
  // The frames really were drawn over the cache, built once for the one size.
  EXPECT_EQ(cached->renderer().background_builds(), 1u);
  EXPECT_EQ(whole->renderer().background_builds(), 0u);
  EXPECT_EQ(cached->context().validation_messages(), 0u) << cached->context().first_validation_message();
}

TEST(BackgroundCache, TheShadowIsOneScreenPassWhereItFallsAndNoneElsewhere) {
  // A detailed model costs nothing more for the shadow: it is shaded on the screen from the
  // cached light and depth, one pass over the shadow's rectangle, whatever the triangles.
  auto cached = renderer(test::percussion(), true);
  ASSERT_TRUE(cached->renderer().screen_space_shadow());
  const Target& t = test::percussion().targets.at(3);
  FrameState s;
  s.mallet_centre = {(t.x_min + t.x_max) / 2, t.top_y + test::percussion().mallet_radius_m};
  cached->render(s);
  EXPECT_EQ(cached->renderer().shadow_passes(), 1u);
  // A lit shipped bar (12 triangles) is redrawn whole, cheaper than a pass over its rectangle.
  s.bar_lights = {BarLight{t.id, 0.2f}, BarLight{}};
  cached->render(s);
  EXPECT_EQ(cached->renderer().shadow_passes(), 1u);
  s.bar_lights = {};
  s.mallet_centre = {2.0, 0.05};  // far beside the instruments: its shadow falls on nothing drawn
  cached->render(s);
  EXPECT_EQ(cached->renderer().shadow_passes(), 0u);
}

TEST(BackgroundCache, MultisampledFramesRedrawOnlyTheBarsTheShadowsScreenBoxMeets) {
  // A GPU's multisampled frames need each sample's coverage at the bars' edges: the shadow
  // redraws the bars it meets, its neighbours and the rails under them, not the whole set.
  auto cached = renderer(test::percussion(), true, VK_SAMPLE_COUNT_4_BIT, VK_SAMPLE_COUNT_4_BIT);
  ASSERT_FALSE(cached->renderer().screen_space_shadow());
  const Target& t = test::percussion().targets.at(3);
  FrameState s;
  s.mallet_centre = {(t.x_min + t.x_max) / 2, t.top_y + test::percussion().mallet_radius_m};
  cached->render(s);
  EXPECT_GE(cached->renderer().shadow_passes(), 1u);
  EXPECT_LE(cached->renderer().shadow_passes(), 6u) << "of " << cached->renderer().instrument_count();
  EXPECT_GE(cached->renderer().instrument_count(), 20u);
}

//! The shipped models with both bars cut into 1200 triangles each (bench_detailed_model.hpp):
//! more than a lit bar is redrawn with, so their glow is shaded on the screen too.
std::filesystem::path detailed_models() {
  const std::filesystem::path dir = test::scratch_dir();
  for (const auto& entry : std::filesystem::directory_iterator(render::models_dir()))
    if (entry.path().extension() == ".glb") std::filesystem::copy_file(entry.path(), dir / entry.path().filename());
  EXPECT_EQ(render::write_detailed_bar(dir / "wood_bar.glb", 10, {0.30, 0.10, 0.045, 1.0}, 0.0, 0.55), 1200u);
  render::write_detailed_bar(dir / "metal_bar.glb", 10, {0.85, 0.85, 0.88, 1.0}, 1.0, 0.25);
  return dir;
}

TEST(BackgroundCache, DetailedBarsShadowedAndLitOnTheScreenAreTheWholeScenesPixels) {
  const std::filesystem::path models = detailed_models();
  expect_same_frames(test::percussion(), VK_SAMPLE_COUNT_1_BIT, models);
  // Their glow is a pass over each lit bar's rectangle, not a redraw of its triangles.
  auto cached = renderer(test::percussion(), true, VK_SAMPLE_COUNT_1_BIT, VK_SAMPLE_COUNT_1_BIT, models);
  const Target& t = test::percussion().targets.at(3);
  FrameState s;
  s.mallet_centre = {(t.x_min + t.x_max) / 2, t.top_y + test::percussion().mallet_radius_m};
  s.bar_lights = {BarLight{t.id, 0.2f}, BarLight{test::percussion().targets.at(9).id, 0.9f}};
  cached->render(s);
  EXPECT_EQ(cached->renderer().shadow_passes(), 3u);  // the shadow's and two bars'
}

TEST(BackgroundCache, PercussionFramesAreTheWholeScenesPixels) {
  expect_same_frames(test::percussion(), VK_SAMPLE_COUNT_1_BIT);
}

TEST(BackgroundCache, TextureAndWallFramesAreTheWholeScenesPixels) {
  expect_same_frames(test::texture(), VK_SAMPLE_COUNT_1_BIT);
  expect_same_frames(test::wall(), VK_SAMPLE_COUNT_1_BIT);
}

TEST(BackgroundCache, WithMultisamplingTooTheFramesAreTheWholeScenesPixels) {
  auto probe = renderer(test::percussion(), true);
  if (!supports_samples(probe->context(), VK_SAMPLE_COUNT_4_BIT)) GTEST_SKIP() << "no 4x MSAA on this device";
  expect_same_frames(test::percussion(), VK_SAMPLE_COUNT_4_BIT);
}

TEST(BackgroundCache, AnAntialiasedBackgroundIsTheMultisampledSceneBesideTheMallet) {
  // Frames of 1 sample over a background of 4 (what the kiosk does on lavapipe): against
  // the whole scene drawn with 4x MSAA every frame, only the mallet and the pixels its
  // shadow darkens (drawn with 1 sample) may differ; and the image is nearer to it than
  // the frames of 1 sample without the antialiased background.
  auto probe = renderer(test::percussion(), true);
  if (!supports_samples(probe->context(), VK_SAMPLE_COUNT_4_BIT)) GTEST_SKIP() << "no 4x MSAA on this device";
  auto cached = renderer(test::percussion(), true, VK_SAMPLE_COUNT_1_BIT, VK_SAMPLE_COUNT_4_BIT);
  auto whole4 = renderer(test::percussion(), false, VK_SAMPLE_COUNT_4_BIT);
  auto whole1 = renderer(test::percussion(), false);
  const Scene& s = test::percussion();
  for (int id : {1, 6, 12}) {
    const Target& bar = s.targets.at(id);
    FrameState f;
    f.mallet_centre = {bar.x_max, bar.top_y + 0.02};
    const Image reference = whole4->render(f);
    const ImageDiff ours = compare_images(cached->render(f), reference, 3);
    const ImageDiff plain = compare_images(whole1->render(f), reference, 3);
    EXPECT_LT(ours.differing_fraction, 0.002) << "bar " << id << ": " << ours.differing_pixels << " pixels";
    EXPECT_LT(ours.rms, 0.3 * plain.rms) << "bar " << id;
  }
  EXPECT_EQ(cached->renderer().background_builds(), 1u);
  EXPECT_EQ(cached->context().validation_messages(), 0u) << cached->context().first_validation_message();
}

TEST(BackgroundCache, IsRedrawnWhenTheImageSizeChanges) {
  // One renderer, targets of three sizes in turn (a window being resized): each frame
  // equals the whole scene drawn at its size.
  ContextOptions co;
  co.validation = Validation::required;
  co.device_name = "llvmpipe";
  Context ctx(co);
  PipelineCache cache(ctx, "");
  RenderSettings cached_settings, whole_settings;
  whole_settings.background_cache = false;
  SceneRenderer cached(ctx, test::percussion(), render::models_dir(), OffscreenTarget::kFormat, cached_settings,
                       cache.get());
  SceneRenderer whole(ctx, test::percussion(), render::models_dir(), OffscreenTarget::kFormat, whole_settings,
                      cache.get());
  const Target& bar = test::percussion().targets.at(5);
  FrameState s;
  s.mallet_centre = {(bar.x_min + bar.x_max) / 2, bar.top_y + 0.02};
  for (VkExtent2D size : {VkExtent2D{320, 180}, VkExtent2D{500, 400}, VkExtent2D{320, 180}}) {
    OffscreenTarget target(ctx, size);
    const Image a = target.render(cached, s);
    const Image b = target.render(whole, s);
    const ImageDiff d = compare_images(a, b, 0);
    ASSERT_TRUE(d.same_size);
    EXPECT_EQ(a.width, static_cast<int>(size.width));
    EXPECT_LE(d.max_channel_delta, kShadowRounding) << size.width << "x" << size.height << ": " << d.differing_pixels;
  }
  EXPECT_EQ(cached.background_builds(), 3u);
  EXPECT_EQ(ctx.validation_messages(), 0u) << ctx.first_validation_message();
}

TEST(BackgroundCache, KeptFramesDrawOnlyWhatChangedAndAreTheWholeFramesPixels) {
  // A window's swapchain image keeps its last frame: each frame over it draws only what
  // changed since (the head where it was and is, the bars whose light changed, the text
  // where it changed), and must show exactly the frame drawn whole.
  const Scene& scene = test::percussion();
  auto kept = renderer(scene, true);
  kept->target().keep_frames(true);
  auto whole = renderer(scene, true);
  const FontAtlas font(16.0f);
  Overlay overlay(font);
  const std::vector<Vec2> at = places(scene);
  const int pixels = 480 * 270;
  int frames = 0, small = 0;
  for (std::size_t i = 0; i < at.size(); ++i) {
    FrameState s;
    s.mallet_centre = at[i];
    s.draw_mallet = i % 7 != 3;  // now and then no head: its last place restored
    if (i % 3 == 0)
      s.bar_lights = {BarLight{scene.targets.at(i % scene.targets.size()).id, 0.2f},
                      BarLight{scene.targets.front().id, 0.05f * static_cast<float>(i % 5)}};
    overlay.clear();
    if (i % 4 < 2) overlay.text(20, 40, i % 8 < 4 ? "Strike a bar" : "Frappez une lame", {1, 1, 1, 1});
    s.overlay = &overlay;
    for (int again = 0; again < (i % 5 == 0 ? 2 : 1); ++again) {  // and a frame that changes nothing
      const ImageDiff d = compare_images(kept->render(s), whole->render(s), 0);
      ASSERT_TRUE(d.same_size);
      EXPECT_EQ(d.max_channel_delta, 0) << "frame " << frames << " (head at " << s.mallet_centre.x << ", "
                                        << s.mallet_centre.y << "): " << d.differing_pixels << " pixels differ";
      const PixelRect a = kept->renderer().last_drawn_area();
      if (frames > 0 && (a.x1 - a.x0) * (a.y1 - a.y0) * 4 < pixels) ++small;
      if (again == 1) {
        EXPECT_EQ((a.x1 - a.x0) * (a.y1 - a.y0), 1) << "nothing changed: one pixel drawn again";
      }
      ++frames;
    }
  }
  EXPECT_EQ(whole->renderer().last_drawn_area().x1, 480);  // not kept: always whole
  EXPECT_GT(small, frames / 3) << "most frames draw under a quarter of the image";
  EXPECT_EQ(kept->renderer().background_builds(), 1u);
  EXPECT_EQ(kept->context().validation_messages(), 0u) << kept->context().first_validation_message();
}

}  // namespace
}  // namespace mallet::render
