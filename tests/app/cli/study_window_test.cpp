// The study's windows under their own Xvfb, with the X pointer moved by XTest as a mouse's
// events arrive: an answer struck on an answer bar, a texture disc crossed, and the kiosk's
// visitor micro-study from its offer to the row in the day's file.
#include <cmath>
#include <fstream>
#include <optional>
#include <cstdio>

#include <gtest/gtest.h>

#include "app/bench/bench_latency_x11.hpp"
#include "app/study/study_session.hpp"
#include "app/study/study_stimuli.hpp"
#include "app/study/visitor_study.hpp"
#include "core/study/protocol_loader.hpp"
#include "core/study/results_csv.hpp"
#include "core/study/visitor_offer.hpp"
#include "render/scene_view.hpp"
#include "child_process.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

namespace fs = std::filesystem;
constexpr int kW = 640, kH = 360;

//! The X server, the pointer and the child's log.
struct Screen {
  latency::VirtualDisplay display{kW, kH};
  std::optional<latency::FakePointer> pointer;
  latency::PixelBox box;

  //! Runs `args` of the mallet binary on this display in the background, its log in `log`.
  void launch(const std::string& args, const fs::path& log, const std::string& env = "") {
    const std::string cmd = "(" + test::child_preload() + env + " DISPLAY=" + display.name() + " " +
                            std::string(MALLET_TEST_BINARY) + " " + args + " > " + log.string() +
                            " 2>&1; echo exit=$? >> " + log.string() + ") &";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
  }
  //! The window, once it is there.
  bool find_window() {
    pointer.emplace(display.name());
    for (int i = 0; i < 100; ++i, std::system("sleep 0.1"))
      if (auto b = pointer->find_window(kW, kH)) {
        box = *b;
        return true;
      }
    return false;
  }
  //! The pointer from `from` to `to` (world metres on the plane z = 0 of `scene` framed for
  //! the window), in `steps` moves 20 ms apart: about one a frame.
  void move(const Scene& scene, Vec2 from, Vec2 to, int steps = 30) {
    const glm::mat4 vp = render::view_projection(scene, static_cast<double>(kW) / kH);
    for (int k = 0; k <= steps; ++k) {
      const double s = static_cast<double>(k) / steps;
      const glm::dvec2 p = render::project_to_screen(vp, {from.x + (to.x - from.x) * s, from.y + (to.y - from.y) * s, 0});
      pointer->move_to(box.x + static_cast<int>(p.x * kW), box.y + static_cast<int>(p.y * kH));
      std::system("sleep 0.02");
    }
  }
  //! A stroke down through `target`'s top, from 6 cm above it.
  void strike(const Scene& scene, int target) {
    const Target& bar = scene.targets.at(static_cast<std::size_t>(target));
    const double x = (bar.x_min + bar.x_max) / 2;
    move(scene, {x, bar.top_y + scene.mallet_radius_m + 0.06}, {x, bar.top_y});
    move(scene, {x, bar.top_y}, {x, bar.top_y + scene.mallet_radius_m + 0.06}, 5);
  }
};

std::string stop_command(const std::string& pattern) {
  return "pkill -f '^" + std::string(MALLET_TEST_BINARY) + " " + pattern + "'";
}

std::string strike_protocol() {
  return "name = \"strike\"\ntask = \"2afc_harder\"\nconditions = [\"both\", \"none\"]\nrepetitions = 2\nseed = 3\n"
         "impact_speed_m_per_s = 0.5\nsound = false\nreference_bar = 0\nresponse = \"strike\"\n"
         "[timing]\nlead_s = 0.1\nstimulus_s = 0.2\nstimulus_interval_s = 0.3\ninter_trial_s = 0.1\n"
         "[[stimulus]]\nname = \"wood\"\nmaterial = \"wood\"\n[[stimulus]]\nname = \"metal\"\nmaterial = \"metal\"\n"
         "[[pair]]\na = \"wood\"\nb = \"metal\"\n";
}

TEST(StudyWindow, TheMouseStrikesAnAnswerBar) {
  const fs::path dir = test::scratch_dir();
  std::ofstream(dir / "p.toml") << strike_protocol();
  Screen screen;
  screen.launch("study --windowed --size 640x360 --quit-after 60 --device llvmpipe --protocol " +
                    (dir / "p.toml").string() + " --participant P3 --out " + (dir / "r.csv").string(),
                dir / "log.txt");
  ASSERT_TRUE(test::wait_for(dir / "log.txt", "trial 1 of 4: Which tap felt harder? Strike 1 or 2"))
      << test::slurp(dir / "log.txt");
  ASSERT_TRUE(screen.find_window());
  StudyOptions o;
  o.protocol = dir / "p.toml";
  o.participant = "P3";
  o.out = dir / "r.csv";
  o.scene = test::percussion_scene();
  const StudyPlan plan = plan_study(o);
  const Scene scene = study_scene_for(plan.base, plan.protocol, 640.0 / 360.0);  // as the window lays it out
  const AnswerBar two = answer_bars(scene, plan.protocol).at(1);
  screen.strike(scene, two.target);
  ASSERT_TRUE(test::wait_for(dir / "log.txt", "trial 2 of 4")) << test::slurp(dir / "log.txt");
  EXPECT_EQ(std::system(stop_command("study .*" + (dir / "r.csv").string()).c_str()), 0);
  ASSERT_TRUE(test::wait_for(dir / "log.txt", "exit=")) << test::slurp(dir / "log.txt");
  const std::string log = test::slurp(dir / "log.txt");
  EXPECT_NE(log.find("bar=" + std::to_string(two.target) + " answer 2"), std::string::npos) << log;
  EXPECT_NE(log.find("exit=0"), std::string::npos) << log;
  const std::vector<study::ResultRow> rows = study::read_results(dir / "r.csv").rows;
  ASSERT_EQ(rows.size(), 1u) << log;
  EXPECT_EQ(rows[0].answer, "2");
  EXPECT_EQ(rows[0].source, "strike");
  EXPECT_GT(rows[0].response_time_ms, 0.0);
}

TEST(StudyWindow, TheMouseCrossesTheTextureDiscAndTheCursorFollowsTheSpeedTechnique) {
  const fs::path dir = test::scratch_dir();
  std::ofstream(dir / "t.toml")
      << "name = \"t\"\ntask = \"texture_slope\"\nquestion = \"bump_or_hole\"\nconditions = [\"both\"]\n"
         "repetitions = 1\nseed = 2\n[timing]\nlead_s = 0.2\nstimulus_s = 8\ninter_trial_s = 0.1\n"
         "[[stimulus]]\nname = \"bump\"\nrelief = \"bump\"\nheight_m = 0.008\n"
         "[[stimulus]]\nname = \"hole\"\nrelief = \"hole\"\nheight_m = 0.008\n";
  Screen screen;
  screen.launch("study --windowed --size 640x360 --quit-after 60 --device llvmpipe --protocol " +
                    (dir / "t.toml").string() + " --participant T9 --out " + (dir / "r.csv").string(),
                dir / "log.txt");
  ASSERT_TRUE(test::wait_for(dir / "log.txt", "crossing for")) << test::slurp(dir / "log.txt");
  ASSERT_TRUE(screen.find_window());
  const Scene& scene = test::texture();
  const TextureRelief& r = scene.texture->relief;
  // The crossing's samples are its frames: an ASan build on a software GPU draws about three
  // a second (measured here), so the window is 8 s and the hand crosses in about 2 s (90
  // steps), to be seen in a handful of frames on the disc.
  screen.move(scene, {r.center.x - 1.3 * r.radius_m, r.center.y}, {r.center.x + 1.3 * r.radius_m, r.center.y}, 90);
  ASSERT_TRUE(test::wait_for(dir / "log.txt", "A bump or a hole? Press B or H")) << test::slurp(dir / "log.txt");
  EXPECT_EQ(std::system(stop_command("study .*" + (dir / "r.csv").string()).c_str()), 0);
  ASSERT_TRUE(test::wait_for(dir / "log.txt", "exit=")) << test::slurp(dir / "log.txt");
  const std::string log = test::slurp(dir / "log.txt");
  EXPECT_NE(log.find("exit=0"), std::string::npos) << log;
  // What the crossing presented ("both"), measured on its route's output: the Speed
  // technique moved the cursor off the hand, and the stripes played.
  const std::size_t at = log.find("crossed: ");
  ASSERT_NE(at, std::string::npos) << log;
  int samples = 0;
  double offset_mm = 0, stripes = 0;
  ASSERT_EQ(std::sscanf(log.c_str() + at, "crossed: %d samples, the cursor up to %lf mm off the hand, the stripes up to %lf",
                        &samples, &offset_mm, &stripes),
            3)
      << log;
  // The offset's size follows the hand's speed and how many frames fall on the disc: 2.3 to
  // 5.2 mm in three runs here with the crossing above (0 without the technique).
  EXPECT_GT(samples, 20);
  EXPECT_GT(offset_mm, 1.0);
  EXPECT_GT(stripes, 0.01);
}

// A visitor strikes again when nothing happens: a window that draws a few frames a second
// (ASan on a software GPU) can miss one quick stroke. Up to five strokes, 5 s apart.
bool strike_until(Screen& screen, const Scene& scene, int target, const fs::path& log, const std::string& text) {
  for (int stroke = 0; stroke < 5; ++stroke) {
    screen.strike(scene, target);
    if (test::wait_for(log, text, 50)) return true;
  }
  return false;
}

TEST(StudyWindow, TheKioskOffersTheVisitorStudyAndAVisitorCompletesItByStriking) {
  const fs::path dir = test::scratch_dir();
  // visual_only, not both: a kiosk without an audio output (a test machine) offers no study
  // whose actuator cues it cannot deliver (study::undeliverable_cues).
  std::string visual = strike_protocol();
  visual.replace(visual.find("[\"both\", \"none\"]"), 16, "[\"visual_only\", \"none\"]");
  std::ofstream(dir / "v.toml") << visual
                                << "[visitor]\nconsent = \"Strike Yes to take part.\"\ntrials = 1\nanswer_timeout_s = 60\n";
  // A Japanese kiosk, and a protocol with English words only: the study is shown wholly in
  // English (its prompt below, the row's language), never English words beside Japanese ones.
  std::ofstream(dir / "mallet.toml") << "[input]\nsource = \"mouse\"\nmouse = \"window\"\n[kiosk]\nlanguage = \"ja\"\n"
                                     << "[study]\nvisitor_protocol = \"v.toml\"\noffer_every_s = 10\noffer_for_s = 60\n"
                                     << "results_dir = \"visitors\"\n[metrics]\ntextfile = \"m.prom\"\n";
  Screen screen;
  screen.launch("run --windowed --size 640x360 --quit-after 90 --device llvmpipe --config " +
                    (dir / "mallet.toml").string(),
                dir / "log.txt", "MALLET_STATE_DIR=" + (dir / "state").string());
  ASSERT_TRUE(test::wait_for(dir / "log.txt", "visitor study: offered")) << test::slurp(dir / "log.txt");
  ASSERT_TRUE(screen.find_window());
  const Scene& kiosk = test::percussion();
  // "Yes" on the last bar.
  ASSERT_TRUE(strike_until(screen, kiosk, static_cast<int>(kiosk.targets.size()) - 1, dir / "log.txt",
                           "a visitor's consent screen"))
      << test::slurp(dir / "log.txt");
  // The consent's "Yes" is the first answer bar, the trial's "1" too.
  const study::StudyProtocol protocol =
      study::load_study_protocol(dir / "v.toml", kiosk.materials, kiosk.targets.size());
  const Scene scene = study_scene_for(kiosk, protocol, 640.0 / 360.0);  // as the window lays it out
  const std::vector<AnswerBar> bars = answer_bars(scene, protocol);
  ASSERT_TRUE(strike_until(screen, scene, bars.at(0).target, dir / "log.txt",
                           "trial 1 of 1: Which tap felt harder? Strike 1 or 2"))
      << test::slurp(dir / "log.txt");
  ASSERT_TRUE(strike_until(screen, scene, bars.at(0).target, dir / "log.txt", "visitor study: visitor-"))
      << test::slurp(dir / "log.txt");
  EXPECT_EQ(std::system(stop_command("run .*" + (dir / "mallet.toml").string()).c_str()), 0);
  ASSERT_TRUE(test::wait_for(dir / "log.txt", "exit=")) << test::slurp(dir / "log.txt");
  const std::string log = test::slurp(dir / "log.txt");
  EXPECT_NE(log.find("completed, 1 of 1 trials"), std::string::npos) << log;
  EXPECT_NE(log.find("exit=0"), std::string::npos) << log;
  const fs::path day = dir / "visitors" / study::visitor_results_file(study::utc_date(std::time(nullptr)));
  const std::vector<study::ResultRow> rows = study::read_results(day).rows;
  ASSERT_EQ(rows.size(), 1u) << log;
  EXPECT_TRUE(rows[0].participant.starts_with("visitor-") && rows[0].participant.size() == 16) << rows[0].participant;
  EXPECT_EQ(rows[0].session, study::utc_date(std::time(nullptr)));
  EXPECT_EQ(rows[0].answer, "1");
  EXPECT_EQ(rows[0].source, "strike");
  EXPECT_EQ(rows[0].language, "en");
  EXPECT_NE(log.find("visitor study: in en (the protocol has no words in ja)"), std::string::npos) << log;
  // The operators' count of it (written at the stop).
  const std::string prom = test::slurp(dir / "m.prom");
  EXPECT_NE(prom.find("mallet_visitor_study_sessions_total{outcome=\"completed\"} 1\n"), std::string::npos) << prom;
  EXPECT_NE(prom.find("mallet_visitor_study_sessions_total{outcome=\"declined\"} 0\n"), std::string::npos) << prom;
}

TEST(KioskWindow, AWindowTurnedToPortraitLaysTheSceneOutStackedAndPlaysOn) {
  // A screen turned (here: the kiosk's window resized) from 16:9 to 9:16: the stage is built
  // again on the same settings, laid out for portrait, and the attract mode plays on in it.
  const fs::path dir = test::scratch_dir();
  std::ofstream(dir / "mallet.toml") << "[input]\nsource = \"mouse\"\nmouse = \"window\"\n";
  Screen screen;
  screen.launch("run --windowed --size 640x360 --idle-after 1 --quit-after 60 --device llvmpipe --config " +
                    (dir / "mallet.toml").string(),
                dir / "log.txt", "MALLET_STATE_DIR=" + (dir / "state").string());
  ASSERT_TRUE(test::wait_for(dir / "log.txt", "strike t=")) << test::slurp(dir / "log.txt");
  ASSERT_TRUE(screen.find_window());
  EXPECT_EQ(test::slurp(dir / "log.txt").find("laid out portrait"), std::string::npos);
  ASSERT_TRUE(screen.pointer->resize_window(kW, kH, 198, 352));
  ASSERT_TRUE(test::wait_for(dir / "log.txt", "the screen is now 0.56:1: the scene laid out portrait"))
      << test::slurp(dir / "log.txt");
  // The ghost strikes again, now on the stacked bars: the phrase opens on the upper row.
  const std::size_t turned = test::slurp(dir / "log.txt").find("the scene laid out portrait");
  std::size_t strike = std::string::npos;
  for (int i = 0; i < 600 && strike == std::string::npos; ++i, std::system("sleep 0.1"))
    strike = test::slurp(dir / "log.txt").find("strike t=", turned);
  ASSERT_NE(strike, std::string::npos) << "it plays on:\n" << test::slurp(dir / "log.txt");
  const std::string log = test::slurp(dir / "log.txt");
  EXPECT_NE(log.substr(strike, log.find('\n', strike) - strike).find("xylophone"), std::string::npos) << log;
  EXPECT_EQ(std::system(stop_command("run .*" + (dir / "mallet.toml").string()).c_str()), 0);
  ASSERT_TRUE(test::wait_for(dir / "log.txt", "exit=")) << test::slurp(dir / "log.txt");
  EXPECT_NE(test::slurp(dir / "log.txt").find("exit=0"), std::string::npos) << test::slurp(dir / "log.txt");
}

}  // namespace
}  // namespace mallet::app
