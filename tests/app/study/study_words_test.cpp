// The overlap contract on the study's screens (issue 48, item 4): the consent, a trial's
// prompt and taps, the thanks, each with the signs under its bars and the trial count, in
// every shipped language at the four screen shapes, the study scene laid out for each as the
// window lays it out. No text over another, none off the screen; the consent's "Taps" sign
// no longer hangs over its bar's edge, as a label squeezed onto the bar did.
#include <string>
#include <utility>
#include <vector>

#include <fmt/printf.h>
#include <gtest/gtest.h>

#include "app/study/study_session.hpp"
#include "app/study/study_stimuli.hpp"
#include "app/study/study_words.hpp"
#include "core/study/protocol_loader.hpp"
#include "core/visitor_catalogues.hpp"
#include "core/visitor_language.hpp"
#include "render/render_setup.hpp"
#include "render/text_shaping.hpp"
#include "test_paths.hpp"
#include "text_box_check.hpp"

namespace mallet::app {
namespace {

TEST(StudyWords, NoWordOfTheConsentTrialsOrThanksIsDrawnOverAnotherOrOffTheScreen) {
  const Scene& base = test::percussion();
  int screens = 0;
  for (const char* file : {"visitor.toml", "strike.toml"}) {
    const study::StudyProtocol protocol =
        study::load_study_protocol(test::config_dir() / "study" / file, base.materials, base.targets.size());
    for (const auto& [w, h] : test::kWalkShapes) {
      const std::unique_ptr<render::FontAtlas> font =
          render::overlay_font({static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)});
      for (const std::string& language : visitor_languages()) {
        // As the window lays it out: for the shape, read in the language's direction.
        const Scene scene = study_scene_for(base, protocol, w / h, render::right_to_left(language));
        const std::vector<AnswerBar> bars = answer_bars(scene, protocol);
        ASSERT_GE(bars.size(), 2u);
        int stimulus = -1;
        for (const Target& t : scene.targets)
          if (!t.hand_strikes && stimulus < 0) stimulus = t.id;
        std::vector<std::string> refused;
        start_visitor_language(language, refused);
        ASSERT_TRUE(refused.empty()) << refused.front();
        std::vector<render::BarLabel> answers;
        for (const AnswerBar& b : bars) answers.push_back({b.target, b.answer});
        answers.push_back({stimulus, tr("Taps")});
        const std::string count = fmt::sprintf(tr("Trial %d of %zu"), 6, std::size_t{6});
        std::vector<std::pair<std::string, StudyWords>> states{
            {"a trial's prompt", {answer_prompt(protocol), answers, count}},
            {"a tap", {fmt::sprintf(tr("Tap %d"), 2), answers, count}},
            {"the thanks", {tr("Thank you"), {}, {}}},
        };
        if (protocol.visitor) {
          std::vector<render::BarLabel> consent{{bars[0].target, tr("Yes")}, {bars[1].target, tr("No")},
                                                {stimulus, tr("Taps")}};
          states.push_back({"the consent", {protocol.visitor->text_in(language).consent, consent, {}}});
        }
        for (const auto& [what, words] : states) {
          render::Overlay overlay(*font);
          draw_study_words(overlay, scene, words, w, h);
          ASSERT_FALSE(overlay.text_boxes().empty());
          for (const std::string& p : test::text_box_problems(overlay, w, h))
            ADD_FAILURE() << file << " " << language << " " << w << "x" << h << ", " << what << ": " << p;
          ++screens;
        }
      }
    }
  }
  use_visitor_language("en");
  std::printf("%d study screens, each text against every other\n", screens);
}

}  // namespace
}  // namespace mallet::app
