// The overlap contract, on the visitors' screen: no text is drawn over another or leaves the
// screen, in any of the kiosk's visitor states (the invitation with the mouse or the remote,
// a lost pointer, a missing remote, the study's offer with its "Yes" sign, the staff's
// corner notes, a refused close), on every scene laid out as the kiosk lays it out, at the
// four screen shapes the walkthrough used, in every shipped language (issue 48, item 4: the
// offer's "Yes" was drawn over the bar's note name "C7"). Checked where the boxes are known:
// the overlay's own record of every text's ink (render::Overlay::text_boxes).
#include <array>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "app/kiosk/calibration_screen.hpp"
#include "app/kiosk/visitor_words.hpp"
#include "core/kiosk_states.hpp"
#include "core/scene_layout.hpp"
#include "core/study/protocol_loader.hpp"
#include "core/visitor_catalogues.hpp"
#include "core/visitor_language.hpp"
#include "render/render_setup.hpp"
#include "test_paths.hpp"
#include "text_box_check.hpp"

namespace mallet::app {
namespace {

using test::kWalkShapes;
using test::text_box_problems;

TEST(TextBoxes, NoVisitorWordIsDrawnOverAnotherOrOffTheScreenInAnyStateShapeOrLanguage) {
  const Scene& percussion = test::percussion();
  const study::StudyProtocol visitor_study = study::load_study_protocol(
      test::config_dir() / "study" / "visitor.toml", percussion.materials, percussion.targets.size());
  ASSERT_TRUE(visitor_study.visitor);
  int screens = 0;
  for (const auto& [w, h] : kWalkShapes) {
    const std::unique_ptr<render::FontAtlas> font =
        render::overlay_font({static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)});
    for (const std::string& language : visitor_languages()) {
      std::vector<std::string> refused;
      start_visitor_language(language, refused);
      ASSERT_TRUE(refused.empty()) << refused.front();
      for (const Scene* file_scene : {&percussion, &test::texture(), &test::wall()}) {
        const Scene scene = laid_out(*file_scene, layout_for(*file_scene, w / h));
        // The states' words, each screen as the kiosk composes it (WindowKiosk::visitor_words).
        std::vector<std::pair<std::string, VisitorWords>> states;
        for (const KioskHint hint : {KioskHint::invitation, KioskHint::point_at_screen, KioskHint::remote_missing})
          for (const bool mouse : {false, true}) {
            VisitorWords words;
            words.banner = hint_text(hint, scene.kind, mouse);
            states.push_back({"hint " + words.banner, words});
          }
        VisitorWords staff;  // a refused close, a kiosk without sound
        staff.banner = hint_text(KioskHint::invitation, scene.kind, true);
        staff.staff_left = hint_text(KioskHint::close_needs_chord);
        staff.staff_right = tr("No sound");
        states.push_back({"a refused close", staff});
        staff.staff_left = tr("Mouse");
        states.push_back({"the mouse's note", staff});
        if (scene.kind == SceneKind::percussion) {
          VisitorWords offer;  // the offer, in the study's language (the kiosk's: the protocol has all nine)
          offer.banner = visitor_study.visitor->text_in(language).offer + " " + tr("(strike Yes)");
          offer.called_out = render::BarLabel{static_cast<int>(scene.targets.size()) - 1, tr("Yes")};
          offer.staff_left = tr("Mouse");
          offer.staff_right = tr("No sound");
          states.push_back({"the study's offer", offer});
        }
        for (auto& [what, words] : states) {
          words.note_names = scene.kind == SceneKind::percussion;
          if (scene.kind == SceneKind::wall) words.wall_name = tr("Aluminium");
          render::Overlay overlay(*font);
          draw_visitor_words(overlay, scene, words, w, h);
          ASSERT_FALSE(overlay.text_boxes().empty());
          for (const std::string& p : text_box_problems(overlay, w, h))
            ADD_FAILURE() << language << " " << w << "x" << h << " " << scene.name << ", " << what << ": " << p;
          ++screens;
        }
      }
    }
  }
  use_visitor_language("en");
  std::printf("%d screens, each text against every other\n", screens);
}

TEST(TextBoxes, TheCalibrationScreenSaysOneStepAtATimeAndNothingDrawnOverItsWords) {
  // Item 8 of issue 48: without a remote the screen waited for a light that could not come,
  // in German showed both steps' instructions at once, and its ring sat over the words; a
  // preset's internal name ("wii1") was on it. In every language at the four shapes: without
  // a link it says what is wrong; while the sensitivity is chosen, that step's words alone,
  // the ring below them; no text over another or off the screen; no preset's name.
  const std::array<float, 4> ring{1.0f, 0.78f, 0.2f, 1.0f};
  for (const auto& [w, h] : kWalkShapes) {
    const std::unique_ptr<render::FontAtlas> font =
        render::overlay_font({static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)});
    for (const std::string& language : visitor_languages()) {
      std::vector<std::string> refused;
      start_visitor_language(language, refused);
      ASSERT_TRUE(refused.empty()) << refused.front();
      CalibrationSessionConfig cc;
      cc.screen = {w, h};
      for (const bool up : {false, true}) {
        CalibrationScreen screen(cc, std::nullopt, "00:1f:32:aa:bb:cc");
        screen.tune_sensitivity({}, "wii3");
        screen.link(up, false);
        render::Overlay overlay(*font);
        screen.draw(overlay, w, h);
        const std::string what = language + " " + std::to_string(int(w)) + "x" + std::to_string(int(h)) +
                                 (up ? ", choosing the sensitivity" : ", no remote");
        for (const std::string& p : text_box_problems(overlay, w, h)) ADD_FAILURE() << what << ": " << p;
        // The words as drawn, a wrapped text's lines joined again (spaces aside).
        const auto unspaced = [](std::string text) {
          std::erase(text, ' ');
          return text;
        };
        std::string all;
        for (const render::TextBox& b : overlay.text_boxes()) all += unspaced(b.text);
        EXPECT_EQ(all.find("wii"), std::string::npos) << what << ": " << all;
        EXPECT_EQ(all.find(unspaced(tr("Hold the mallet's light still on the ring until it fills"))), std::string::npos)
            << what << ": the next step's instruction";
        EXPECT_EQ(all.find(unspaced(tr("The Wii Remote is not connected: press its 1 and 2 buttons together"))) !=
                      std::string::npos,
                  !up)
            << what << ": " << all;
        // The ring (its colour is its own) clear of every word.
        float x0 = w, y0 = h, x1 = 0, y1 = 0;
        for (const render::OverlayVertex& v : overlay.vertices())
          if (v.color == ring) x0 = std::min(x0, v.x), y0 = std::min(y0, v.y), x1 = std::max(x1, v.x), y1 = std::max(y1, v.y);
        EXPECT_EQ(x1 > x0, up) << what << ": the ring shows while the sensitivity is chosen";
        if (x1 > x0) {
          for (const render::TextBox& b : overlay.text_boxes())
            EXPECT_FALSE(render::overlap(b, render::TextBox{x0, y0, x1, y1, "the ring"}))
                << what << ": \"" << b.text << "\" under the ring";
        }
      }
    }
  }
  use_visitor_language("en");
}

TEST(TextBoxes, TheMouseMeasuresATargetOnlyOnItsRingAndSaysSo) {
  // Item 9 of issue 48: the mouse resting anywhere measured the first target there.
  CalibrationSessionConfig cc;
  cc.screen = {1280, 720};
  CalibrationScreen screen(cc, std::nullopt, "mouse");
  Nanos t = 1'000 * kNanosPerSecond;
  screen.feed_pointer(t, {0.5, 0.5});  // where it rested
  for (int i = 0; i < 500; ++i) screen.feed_pointer(t += 10'000'000, {0.4, 0.6});  // still, off the ring
  EXPECT_EQ(screen.session().current_target(), 0);
  EXPECT_NE(screen.status_line().find("move the pointer onto the ring"), std::string::npos) << screen.status_line();
  const Vec2 first = screen.session().targets().at(0);
  CalibrationStep step = CalibrationStep::dwelling;
  for (int i = 0; i < 500 && step != CalibrationStep::target_measured; ++i)
    step = screen.feed_pointer(t += 10'000'000, first);
  EXPECT_EQ(step, CalibrationStep::target_measured);
  EXPECT_NE(screen.status_line().find("pointer on the ring"), std::string::npos) << screen.status_line();
  EXPECT_EQ(screen.status_line().find("light"), std::string::npos) << "a mouse has no light: " << screen.status_line();
}

TEST(TextBoxes, TheOverlayRecordsEachTextsInkAndAnOverlapIsSeen) {
  // The check above could pass on boxes that were never recorded: two texts drawn on one
  // line must be seen as one over the other, and a text off the screen's edge as leaving it.
  const std::unique_ptr<render::FontAtlas> font = render::overlay_font({1280, 720});
  render::Overlay overlay(*font);
  overlay.text(100, 100, "Pick up the mallet", {1, 1, 1, 1});
  overlay.text(140, 100, "C7", {1, 1, 1, 1});
  overlay.text(1270, 300, "Yes", {1, 1, 1, 1});
  overlay.text(600, 500, " ", {1, 1, 1, 1});  // no ink: no box
  ASSERT_EQ(overlay.text_boxes().size(), 3u);
  EXPECT_EQ(overlay.text_boxes()[1].text, "C7");
  EXPECT_GT(overlay.text_boxes()[0].x1 - overlay.text_boxes()[0].x0, 100.0f);
  const std::vector<std::string> p = text_box_problems(overlay, 1280, 720);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0], "\"Pick up the mallet\" over \"C7\"");
  EXPECT_EQ(p[1], "\"Yes\" leaves the screen");
  overlay.clear();
  EXPECT_TRUE(overlay.text_boxes().empty());
}

}  // namespace
}  // namespace mallet::app
