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

namespace mallet::render {
namespace {

struct Extent {
  float left = std::numeric_limits<float>::max(), right = std::numeric_limits<float>::lowest();
};

TEST(BarLabels, EachLabelIsCentredOnItsBarAndNoWiderThanIt) {
  const Scene& scene = test::percussion();
  for (const auto& [w, h] : {std::pair{1920.0f, 1080.0f}, std::pair{1280.0f, 1024.0f}, std::pair{1080.0f, 1920.0f},
                             std::pair{2560.0f, 1080.0f}}) {
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

}  // namespace
}  // namespace mallet::render
