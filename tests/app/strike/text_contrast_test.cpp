// The words on the visitors' screen meet WCAG 2.1 AA (4.5:1) on every scene, measured on
// rendered frames (lavapipe): the invitation's band and the staff's corner notes over the dark
// percussion room, the grey texture scene and the wall (issue 29, items 10 and 16). A text's
// contrast is its brightest ink against the median of its band (most of a band is not ink).
// And the staff's corner notes stay clear of every instrument, at every shape, in every language.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/scene_layout.hpp"
#include "core/kiosk_states.hpp"
#include "core/visitor_catalogues.hpp"
#include "core/visitor_language.hpp"
#include "render/image.hpp"
#include "render/overlay.hpp"
#include "render/overlay_text.hpp"
#include "render/render_setup.hpp"
#include "render/scene_view.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

double luminance(const std::uint8_t* p) {
  auto linear = [](std::uint8_t c) { return render::srgb_to_linear(c / 255.0); };
  return 0.2126 * linear(p[0]) + 0.7152 * linear(p[1]) + 0.0722 * linear(p[2]);
}

//! WCAG 2.1's contrast ratio of the brightest pixel inside `box` (1 px in from its edge)
//! against the box's median pixel.
double contrast_in(const render::Image& image, const render::NoteBox& box) {
  std::vector<double> l;
  const int x0 = static_cast<int>(std::ceil(box.x)) + 1, x1 = static_cast<int>(std::floor(box.x + box.width)) - 1;
  const int y0 = static_cast<int>(std::ceil(box.y)) + 1, y1 = static_cast<int>(std::floor(box.y + box.height)) - 1;
  for (int y = std::max(y0, 0); y < std::min(y1, image.height); ++y)
    for (int x = std::max(x0, 0); x < std::min(x1, image.width); ++x) l.push_back(luminance(image.at(x, y)));
  if (l.empty()) return 0;
  std::sort(l.begin(), l.end());
  return (l.back() + 0.05) / (l[l.size() / 2] + 0.05);
}

struct Case {
  const char* name;
  const Scene& (*scene)();
};

TEST(TextContrast, TheInvitationAndTheCornerNotesReadOnEveryScene) {
  for (const Case c : {Case{"percussion", &test::percussion}, Case{"texture", &test::texture},
                       Case{"wall", &test::wall}}) {
    render::HeadlessOptions o;
    o.size = {1280, 720};
    o.cache_dir = "";
    o.device = "llvmpipe";
    render::HeadlessRenderer r(c.scene(), o);
    const std::unique_ptr<render::FontAtlas> font = render::overlay_font(o.size);
    render::Overlay overlay(*font);
    const float w = 1280, h = 720;
    const render::NoteBox banner =
        render::draw_banner(overlay, hint_text(KioskHint::invitation, c.scene().kind, true), w, h);
    const render::NoteBox mouse =
        render::draw_corner_note(overlay, "This kiosk closes from the operator page only", render::Corner::bottom_left, w, h);
    const render::NoteBox silent = render::draw_corner_note(overlay, "No sound", render::Corner::bottom_right, w, h);
    const render::NoteBox wall_name = render::draw_wall_name(
        overlay, c.scene(), render::view_projection(c.scene(), w / h), w, h, "Aluminium");
    render::FrameState state;
    state.draw_mallet = false;
    state.overlay = &overlay;
    const render::Image frame = r.render(state);
    std::printf("%-10s invitation %.1f:1, mouse note %.1f:1, no-sound note %.1f:1\n", c.name,
                contrast_in(frame, banner), contrast_in(frame, mouse), contrast_in(frame, silent));
    EXPECT_GE(contrast_in(frame, banner), 4.5) << c.name << ": the invitation";
    EXPECT_GE(contrast_in(frame, mouse), 4.5) << c.name << ": the staff's left note (a refused close, the longest)";
    EXPECT_GE(contrast_in(frame, silent), 4.5) << c.name << ": the no-sound note";
    if (c.scene().kind == SceneKind::wall) {
      EXPECT_GE(contrast_in(frame, wall_name), 4.5) << c.name << ": the wall's name";
      EXPECT_LE(wall_name.y + wall_name.height, mouse.y) << "clear of the corner notes";
    } else {
      EXPECT_EQ(wall_name.width, 0.0f) << c.name << ": only the wall has a name under it";
    }
    // The notes stay in their corners, on the screen, clear of each other.
    EXPECT_GE(mouse.x, 0);
    EXPECT_LE(silent.x + silent.width, w);
    EXPECT_LE(mouse.x + mouse.width, silent.x);
    EXPECT_LE(mouse.y + mouse.height, h);
    EXPECT_GT(mouse.y, h * 0.8f);
  }
}

//! Two boxes share a pixel.
bool overlap(const render::NoteBox& a, float x0, float y0, float x1, float y1) {
  return a.x < x1 && x0 < a.x + a.width && a.y < y1 && y0 < a.y + a.height;
}

TEST(TextOnScreen, TheCornerNotesAndTheInvitationNeverOverlapAnInstrumentAtAnyShapeInAnyLanguage) {
  // Each bar's and the wall's box as the view shows them (its top face's corners and its
  // front's foot), the scene laid out for the shape as the kiosk lays it out (portrait:
  // stacked), against the notes' bands and the invitation's in the longest wording of each
  // language (the walkthrough found the Japanese note touching the wall).
  for (const std::string& language : visitor_languages()) {
    std::vector<std::string> problems;
    start_visitor_language(language, problems);
    ASSERT_TRUE(problems.empty()) << problems.front();
    for (const auto& [w, h] : {std::pair{1920.0f, 1080.0f}, std::pair{1280.0f, 1024.0f}, std::pair{1080.0f, 1920.0f},
                               std::pair{2560.0f, 1080.0f}, std::pair{1024.0f, 768.0f}}) {
      const std::unique_ptr<render::FontAtlas> font =
          render::overlay_font({static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)});
      render::Overlay overlay(*font);
      const render::NoteBox mouse =
          render::draw_corner_note(overlay, hint_text(KioskHint::close_needs_chord), render::Corner::bottom_left, w, h);
      const render::NoteBox silent =
          render::draw_corner_note(overlay, tr("No sound"), render::Corner::bottom_right, w, h);
      for (const Scene* file_scene : {&test::percussion(), &test::wall()}) {
        const Scene laid = laid_out(*file_scene, layout_for(*file_scene, w / h));
        const Scene* scene = &laid;
        const glm::mat4 vp = render::view_projection(*scene, w / h);
        std::vector<render::NoteBox> invitations;
        for (const bool with_mouse : {false, true})
          invitations.push_back(render::draw_banner(overlay, hint_text(KioskHint::invitation, scene->kind, with_mouse), w, h));
        for (const Target& t : scene->targets) {
          float x0 = w, y0 = h, x1 = 0, y1 = 0;
          for (const double x : {t.x_min, t.x_max})
            for (const double y : {t.top_y, t.top_y - t.thickness_m})
              for (const double z : {-t.length_m / 2, t.length_m / 2}) {
                const glm::dvec2 p = render::project_to_screen(vp, {x, y, z});
                x0 = std::min(x0, static_cast<float>(p.x) * w), x1 = std::max(x1, static_cast<float>(p.x) * w);
                y0 = std::min(y0, static_cast<float>(p.y) * h), y1 = std::max(y1, static_cast<float>(p.y) * h);
              }
          const std::string what = language + " " + std::to_string(int(w)) + "x" + std::to_string(int(h)) + " " +
                                   scene->name + " target " + std::to_string(t.id);
          EXPECT_FALSE(overlap(mouse, x0, y0, x1, y1)) << what << ": the staff's left note (a refused close, the longest)";
          EXPECT_FALSE(overlap(silent, x0, y0, x1, y1)) << what << ": the no-sound note";
          for (const render::NoteBox& invitation : invitations)
            EXPECT_FALSE(overlap(invitation, x0, y0, x1, y1)) << what << ": the invitation";
        }
      }
    }
  }
  use_visitor_language("en");
}

}  // namespace
}  // namespace mallet::app
