// The glyph atlas fills as text is first shown (render/font_atlas.hpp); the renderer copies
// the glyphs added since the last frame into the texture the frames already sample, inside the
// frame's own commands, instead of making a new texture (a texture replaced under lavapipe's
// rasterizer crashed the kiosk in the VM test). A frame whose text brought new glyphs must show
// exactly what a renderer whose atlas held every glyph from its first frame shows.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/font_atlas.hpp"
#include "render/image.hpp"
#include "render/offscreen_target.hpp"
#include "render/overlay.hpp"
#include "render/render_setup.hpp"
#include "render/scene_renderer.hpp"
#include "test_paths.hpp"

namespace mallet::render {
namespace {

HeadlessOptions options() {
  HeadlessOptions o;
  o.size = {480, 270};
  o.validation = Validation::required;
  o.cache_dir = "";
  o.device = "llvmpipe";
  return o;
}

TEST(AtlasTexture, GlyphsFirstShownLaterAreCopiedIntoTheTextureTheFramesSample) {
  const Scene& scene = test::percussion();
  // One text a frame, most bringing letters the frames before had not shown; the last ones
  // only letters already there.
  const std::vector<std::string> texts = {"Strike",     "Strike a bar", "Frappez une lame", "Zwölf Boxkämpfer 0123",
                                          "Strike a bar", "lame Boxer"};
  HeadlessRenderer lazy(scene, options());
  HeadlessRenderer warmed(scene, options());
  const FontAtlas lazy_font(16.0f);
  const FontAtlas warmed_font(16.0f);
  warmed_font.warm("en", texts);  // every glyph drawn before the first frame, in the same order
  Overlay lazy_overlay(lazy_font), warmed_overlay(warmed_font);
  int new_glyph_frames = 0;
  for (std::size_t i = 0; i < texts.size(); ++i) {
    const std::uint64_t before = lazy_font.generation();
    for (Overlay* o : {&lazy_overlay, &warmed_overlay}) {
      o->clear();
      o->text(24, 60, texts[i], {1, 1, 1, 1});
    }
    if (i > 0 && lazy_font.generation() != before) ++new_glyph_frames;
    FrameState s;
    s.draw_mallet = false;
    s.overlay = &lazy_overlay;
    const Image shown = lazy.render(s);
    s.overlay = &warmed_overlay;
    const ImageDiff d = compare_images(shown, warmed.render(s), 0);
    ASSERT_TRUE(d.same_size);
    EXPECT_EQ(d.max_channel_delta, 0) << "\"" << texts[i] << "\": " << d.differing_pixels << " pixels differ";
  }
  EXPECT_GE(new_glyph_frames, 3) << "the texts must bring new glyphs after the first frame";
  // Copied in place once per frame that brought glyphs, never for the warmed atlas.
  EXPECT_EQ(lazy.renderer().atlas_updates(), static_cast<std::uint64_t>(new_glyph_frames));
  EXPECT_EQ(warmed.renderer().atlas_updates(), 0u);
  EXPECT_EQ(lazy.context().validation_messages(), 0u) << lazy.context().first_validation_message();
}

}  // namespace
}  // namespace mallet::render
