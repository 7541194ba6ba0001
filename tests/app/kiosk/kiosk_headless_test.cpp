// `mallet run` without a display: the attract loop runs offscreen on a simulated clock
// and leaves the three files the README promises.
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "audio/wav_file.hpp"
#include "core/attract_tune.hpp"
#include "render/image.hpp"
#include "run_cli.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

int count_lines_starting(const std::filesystem::path& file, const std::string& prefix) {
  std::ifstream in(file);
  std::string line;
  int n = 0;
  while (std::getline(in, line)) n += line.rfind(prefix, 0) == 0;
  return n;
}

TEST(KioskHeadless, WithoutADisplayTheAttractLoopWritesScreenshotAudioAndLog) {
  const auto dir = test::scratch_dir() / "out";
  unsetenv("DISPLAY");  // as in CI; the child inherits it
  unsetenv("WAYLAND_DISPLAY");
  const test::CliResult r = test::run_mallet("run --seconds 3 --size 320x180 --out " + dir.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("headless"), std::string::npos) << r.output;
  for (const char* f : {"screenshot.png", "audio.wav", "log.txt"})
    EXPECT_NE(r.output.find((dir / f).string()), std::string::npos) << "says it wrote " << f << ":\n" << r.output;

  const render::Image shot = render::read_png(dir / "screenshot.png");
  EXPECT_EQ(shot.width, 320);
  EXPECT_EQ(shot.height, 180);

  // The ghost's strikes in 3 s: one per beat of the phrase after its first beat.
  const AttractTune tune;
  int expected = 0;
  for (const ScriptedStrike& s : attract_phrase(test::percussion(), static_cast<Nanos>(tune.beat_s * 1e9), tune))
    expected += s.t_ns <= 3 * kNanosPerSecond;
  EXPECT_GT(expected, 3);
  EXPECT_EQ(count_lines_starting(dir / "log.txt", "strike "), expected);

  const audio::WavData wav = audio::read_wav(dir / "audio.wav");
  EXPECT_EQ(wav.channels, 2);
  EXPECT_EQ(wav.frames(), 3u * static_cast<std::size_t>(wav.sample_rate_hz));
  double peak = 0;
  for (float v : wav.samples) peak = std::max(peak, static_cast<double>(std::abs(v)));
  EXPECT_GT(peak, 0.01) << "the strikes are heard";
}

TEST(KioskHeadless, ABadSceneIsOneLineAndExitTwo) {
  const auto dir = test::scratch_dir();
  { std::ofstream(dir / "bad.toml") << "name = 3\n"; }
  const test::CliResult r = test::run_mallet("run --headless --scene " + (dir / "bad.toml").string() + " --out " +
                                             (dir / "out").string());
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("bad.toml"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace mallet::app

namespace mallet::app {
namespace {

TEST(KioskHeadless, TheSettingsChooseTheStartSceneAndTheTextureSceneRunsHeadless) {
  // [scenes] start names a file in the scenes/ folder next to the settings file.
  const auto dir = test::scratch_dir();
  std::filesystem::create_directories(dir / "scenes");
  for (const char* f : {"texture.toml", "materials.toml"}) {
    const auto from = std::string(f) == "materials.toml" ? test::config_dir() / f : test::config_dir() / "scenes" / f;
    std::filesystem::copy_file(from, std::string(f) == "materials.toml" ? dir / f : dir / "scenes" / f);
  }
  { std::ofstream(dir / "mallet.toml") << "[scenes]\nstart = \"texture.toml\"\n"; }
  const test::CliResult r = test::run_mallet("run --headless --seconds 4 --size 320x180 --config " +
                                             (dir / "mallet.toml").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream log(dir / "out" / "log.txt");
  std::stringstream text;
  text << log.rdbuf();
  EXPECT_NE(text.str().find("scenes/texture.toml"), std::string::npos) << text.str();
  EXPECT_EQ(count_lines_starting(dir / "out" / "log.txt", "strike "), 0);  // nothing to strike on a texture
  // The attract loop's sweep is felt: the actuator channel carries the stripes.
  const audio::WavData wav = audio::read_wav(dir / "out" / "audio.wav");
  double peak = 0;
  for (std::size_t i = 1; i < wav.samples.size(); i += 2) peak = std::max(peak, static_cast<double>(std::abs(wav.samples[i])));
  EXPECT_GT(peak, 0.05);
}

TEST(KioskHeadless, TheSettingsLanguageIsTheInvitationsAndAnUnknownOneIsRefusedWithItsLineAndEnglishStays) {
  // [kiosk] language from a drop-in: the invitation the headless run shows, from the built
  // catalogue (the log says which, with its words).
  const auto dir = test::scratch_dir();
  std::filesystem::create_directories(dir / "drop-ins");
  { std::ofstream(dir / "drop-ins" / "language.toml") << "[kiosk]\nlanguage = \"fr\"\n"; }
  test::CliResult r = test::run_mallet("run --headless --seconds 1 --size 320x180 --config-dir " +
                                       (dir / "drop-ins").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream log(dir / "out" / "log.txt");
  std::stringstream text;
  text << log.rdbuf();
  EXPECT_NE(text.str().find("language: fr (the invitation: \"Prends la mailloche et frappe une lame\")"),
            std::string::npos)
      << text.str();

  // A drop-in naming a language with no catalogue is refused with its line; the kiosk goes on
  // with the rest of its settings (English).
  { std::ofstream(dir / "drop-ins" / "language.toml") << "[kiosk]\nlanguage = \"klingon\"\n"; }
  r = test::run_mallet("run --headless --seconds 1 --size 320x180 --config-dir " + (dir / "drop-ins").string() +
                       " --out " + (dir / "out2").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream log2(dir / "out2" / "log.txt");
  std::stringstream text2;
  text2 << log2.rdbuf();
  EXPECT_NE(text2.str().find("warning: " + (dir / "drop-ins" / "language.toml").string() + ":2:"), std::string::npos)
      << text2.str();
  EXPECT_NE(text2.str().find("kiosk.language: \"klingon\" has no catalogue; expected one of en, de, fr, ja"),
            std::string::npos)
      << text2.str();
  EXPECT_NE(text2.str().find("language: en (the invitation: \"Pick up the mallet and strike a bar\")"),
            std::string::npos)
      << text2.str();
}

}  // namespace
}  // namespace mallet::app
