// The bars' labels (note names, the study's "Yes"): each centred on its bar as the view shows
// it and no wider than the bar, so that neighbours never run together, at every screen shape
// and in portrait (issue 29, items 17 and 21).
#include <algorithm>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "core/note_name.hpp"
#include "render/overlay.hpp"
#include "render/overlay_text.hpp"
#include "render/render_setup.hpp"
#include "render/scene_view.hpp"
#include "test_paths.hpp"
#include "text_box_check.hpp"

namespace mallet::render {
namespace {

struct Extent {
  float left = std::numeric_limits<float>::max(), right = std::numeric_limits<float>::lowest();
};

TEST(BarLabels, EachLabelIsCentredOnItsBarAndNoWiderThanIt) {
  const Scene& scene = test::percussion();
  for (const auto& [w, h] : test::kWalkShapes) {
    const std::unique_ptr<FontAtlas> font =
        overlay_font({static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)});
    const glm::mat4 vp = view_projection(scene, w / h);
    for (std::size_t i = 0; i < scene.targets.size(); ++i) {
      const Target& t = scene.targets[i];
      for (const std::string& text : {note_name(t.note), std::string("Yes"), std::string("Oui")}) {
        Overlay overlay(*font);
        draw_bar_labels(overlay, scene, vp, w, h, {{static_cast<int>(i), text}});
        Extent drawn;
        for (const OverlayVertex& v : overlay.vertices()) {
          drawn.left = std::min(drawn.left, v.x);
          drawn.right = std::max(drawn.right, v.x);
        }
        const double z = t.length_m / 2 - 0.03;
        const float bar_left = static_cast<float>(project_to_screen(vp, {t.x_min, t.top_y, z}).x) * w;
        const float bar_right = static_cast<float>(project_to_screen(vp, {t.x_max, t.top_y, z}).x) * w;
        const std::string what = std::to_string(int(w)) + "x" + std::to_string(int(h)) + " bar " +
                                 std::to_string(i) + " \"" + text + "\"";
        EXPECT_GE(drawn.left, bar_left - 0.5f) << what;
        EXPECT_LE(drawn.right, bar_right + 0.5f) << what;
        EXPECT_NEAR((drawn.left + drawn.right) / 2, (bar_left + bar_right) / 2, 1.0f) << what;
      }
    }
  }
}

TEST(BarSigns, ASignHangsUnderItsBarsNearEndInTheVisitorsLettersCentredOnItAndOnTheScreen) {
  // The offer's "Yes" was a 14 px label squeezed onto a glockenspiel bar, over its note name
  // (issue 48, items 3 and 4): a sign is under the bar's near end, as large as the banner's
  // letters, centred on the bar (unless the screen's edge is nearer), below the bar's own
  // note name, and never off the screen.
  const Scene& scene = test::percussion();
  for (const auto& [w, h] : test::kWalkShapes) {
    const std::unique_ptr<FontAtlas> font =
        overlay_font({static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)});
    const glm::mat4 vp = view_projection(scene, w / h);
    Overlay banner(*font);
    banner.text(0, 100, "Yes", {1, 1, 1, 1});
    const float letters = banner.text_boxes().at(0).y1 - banner.text_boxes().at(0).y0;
    for (const Target& t : scene.targets) {
      for (const SignStyle style : {SignStyle::plain, SignStyle::called_out}) {
        Overlay overlay(*font);
        draw_note_names(overlay, scene, vp, w, h);
        const std::vector<NoteBox> bands = draw_bar_signs(overlay, scene, vp, w, h, {{t.id, "Yes"}}, style);
        ASSERT_EQ(bands.size(), 1u);
        const TextBox& sign = overlay.text_boxes().back();
        ASSERT_EQ(sign.text, "Yes");
        const std::string what = std::to_string(int(w)) + "x" + std::to_string(int(h)) + " bar " + std::to_string(t.id);
        EXPECT_NEAR(sign.y1 - sign.y0, letters, 0.5f) << what << ": the visitors' size";
        const glm::dvec2 end = project_to_screen(vp, {(t.x_min + t.x_max) / 2, t.top_y - t.thickness_m, t.length_m / 2});
        EXPECT_GE(bands[0].y, static_cast<float>(end.y) * h) << what << ": under the near end";
        const float centre = static_cast<float>(end.x) * w;
        const float em = font->pixel_height();  // the sign keeps half a letter from the edges
        if (centre - bands[0].width / 2 > em && centre + bands[0].width / 2 < w - em) {
          EXPECT_NEAR(bands[0].x + bands[0].width / 2, centre, 1.0f) << what;
        }
        EXPECT_TRUE(sign.x0 >= 0 && sign.x1 <= w && sign.y0 >= 0 && sign.y1 <= h) << what;
        for (std::size_t k = 0; k + 1 < overlay.text_boxes().size(); ++k) {
          EXPECT_FALSE(overlap(overlay.text_boxes()[k], sign))
              << what << ": over the note name " << overlay.text_boxes()[k].text;
        }
      }
    }
  }
}

}  // namespace
}  // namespace mallet::render
