// A malformed config names the file, the line and the key; the shipped files load.
#include <fstream>

#include <gtest/gtest.h>

#include "core/config/app_config_loader.hpp"
#include "core/config/materials_config.hpp"
#include "core/config/scene_config.hpp"
#include "core/file_error.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

using test::file_error_of;

const char* kGoodMaterial = R"(
[material.wood]
visual   = { amplitude_s = 0.009, decay_per_s = 8.0, freq_hz = 5.0 }
actuator = { amplitude = 1.0, decay_per_s = 80.0, freq_hz = 100.0 }
)";

TEST(MaterialsConfig, SyntaxErrorGivesFileLineAndColumn) {
  const FileError e = file_error_of([] { config::parse_materials("[material.wood]\nvisual = { amplitude_s = }\n", "m.toml"); });
  EXPECT_EQ(e.file(), "m.toml");
  EXPECT_EQ(e.line(), 2u);
  EXPECT_GT(e.column(), 0u);
  EXPECT_EQ(std::string(e.what()).rfind("m.toml:2:", 0), 0u) << e.what();
}

TEST(MaterialsConfig, NegativeDecayNamesTheKeyAndItsLine) {
  const std::string text = std::string(kGoodMaterial) + R"(
[material.metal]
visual   = { amplitude_s = 0.02, decay_per_s = -9.0, freq_hz = 15.0 }
actuator = { amplitude = 2.0, decay_per_s = 90.0, freq_hz = 300.0 }
)";
  const FileError e = file_error_of([&] { config::parse_materials(text, "m.toml"); });
  EXPECT_EQ(e.line(), 7u);
  EXPECT_NE(std::string(e.what()).find("material.metal.visual.decay_per_s"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("-9"), std::string::npos) << e.what();
}

TEST(MaterialsConfig, MissingKeyWrongTypeAndMisspeltKeyAreRefused) {
  const FileError missing = file_error_of([] {
    config::parse_materials("[material.wood]\nvisual = { amplitude_s = 0.009, freq_hz = 5.0 }\n"
                            "actuator = { amplitude = 1.0, decay_per_s = 80.0, freq_hz = 100.0 }\n",
                            "m.toml");
  });
  EXPECT_EQ(missing.line(), 2u);
  EXPECT_NE(std::string(missing.what()).find("decay_per_s: missing"), std::string::npos) << missing.what();

  const FileError type = file_error_of([] {
    config::parse_materials("[material.wood]\nvisual = { amplitude_s = \"big\", decay_per_s = 8.0, freq_hz = 5.0 }\n"
                            "actuator = { amplitude = 1.0, decay_per_s = 80.0, freq_hz = 100.0 }\n",
                            "m.toml");
  });
  EXPECT_NE(std::string(type.what()).find("expected a number"), std::string::npos) << type.what();

  const FileError typo = file_error_of([] {
    config::parse_materials(std::string(kGoodMaterial) + "decay_per_sec = 3\n", "m.toml");
  });
  EXPECT_EQ(typo.line(), 5u);
  EXPECT_NE(std::string(typo.what()).find("unknown key"), std::string::npos) << typo.what();
}

TEST(SceneConfig, ShippedSceneHasTwoOctavesInEqualTemperament) {
  const Scene s = config::load_scene(test::percussion_scene());
  ASSERT_EQ(s.targets.size(), 16u);
  const int xylophone[] = {72, 74, 76, 77, 79, 81, 83, 84};
  const int glockenspiel[] = {84, 86, 88, 89, 91, 93, 95, 96};
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(s.targets[i].instrument, "xylophone");
    EXPECT_EQ(s.targets[i].note, xylophone[i]);
    EXPECT_EQ(s.material_of(s.targets[i]).name, "wood");
    EXPECT_EQ(s.targets[8 + i].instrument, "glockenspiel");
    EXPECT_EQ(s.targets[8 + i].note, glockenspiel[i]);
    EXPECT_EQ(s.material_of(s.targets[8 + i]).name, "metal");
  }
  EXPECT_NEAR(s.targets[0].frequency_hz, 523.2511306011972, 1e-9);   // C5
  EXPECT_NEAR(s.targets[15].frequency_hz, 2093.004522404789, 1e-9);  // C7
  for (std::size_t i = 1; i < s.targets.size(); ++i) {
    EXPECT_GE(s.targets[i].x_min, s.targets[i - 1].x_max);  // left to right, no overlap
    if (s.targets[i].instrument == s.targets[i - 1].instrument) {
      EXPECT_LT(s.targets[i].length_m, s.targets[i - 1].length_m);  // graded: higher is shorter
    }
  }
  // Xylophone on the left, glockenspiel on the right, both on screen.
  EXPECT_LT(s.targets[7].x_max, s.targets[8].x_min);
  EXPECT_GT(s.targets[0].x_min, s.screen_to_world.left_m);
  EXPECT_LT(s.targets[15].x_max, s.screen_to_world.right_m);
}

TEST(SceneConfig, UnknownMaterialListsTheKnownOnes) {
  const MaterialLibrary lib = config::parse_materials(kGoodMaterial, "m.toml");
  const FileError e = file_error_of([&] {
    config::parse_scene(R"(name = "x"
mallet_radius_m = 0.015
[screen_to_world]
left_m = -1
right_m = 1
top_m = 1
bottom_m = 0
[[instrument]]
name = "a"
material = "glass"
x_start_m = 0
top_y_m = 0
bar_width_m = 0.04
gap_m = 0.01
notes = [60]
bar_lengths_m = [0.3]
)",
                        "s.toml", lib);
  });
  EXPECT_EQ(e.line(), 10u);
  EXPECT_NE(std::string(e.what()).find("glass"), std::string::npos);
  EXPECT_NE(std::string(e.what()).find("known: wood"), std::string::npos) << e.what();
}

TEST(SceneConfig, LengthsMustMatchNotesAndBarsMustNotOverlap) {
  const MaterialLibrary lib = config::parse_materials(kGoodMaterial, "m.toml");
  const std::string head = "name = \"x\"\nmallet_radius_m = 0.015\n[screen_to_world]\nleft_m = -1\nright_m = 1\n"
                           "top_m = 1\nbottom_m = 0\n";
  const FileError lengths = file_error_of([&] {
    config::parse_scene(head + "[[instrument]]\nname = \"a\"\nmaterial = \"wood\"\nx_start_m = 0\ntop_y_m = 0\n"
                               "bar_width_m = 0.04\ngap_m = 0.01\nnotes = [60, 62]\nbar_lengths_m = [0.3]\n",
                        "s.toml", lib);
  });
  EXPECT_EQ(lengths.line(), 16u);
  EXPECT_NE(std::string(lengths.what()).find("1 lengths for 2 notes"), std::string::npos) << lengths.what();

  const std::string bar = "material = \"wood\"\ntop_y_m = 0\nbar_width_m = 0.04\ngap_m = 0.01\nnotes = [60, 62]\n"
                          "bar_lengths_m = [0.3, 0.29]\n";
  const FileError overlap = file_error_of([&] {
    config::parse_scene(head + "[[instrument]]\nname = \"a\"\nx_start_m = 0\n" + bar +
                            "[[instrument]]\nname = \"b\"\nx_start_m = 0.05\n" + bar,
                        "s.toml", lib);
  });
  EXPECT_NE(std::string(overlap.what()).find("bars overlap"), std::string::npos) << overlap.what();
}

TEST(SceneConfig, MissingMaterialsFileIsReportedAtTheSceneLine) {
  const auto dir = test::scratch_dir();
  std::ofstream(dir / "s.toml") << "name = \"x\"\nmaterials_file = \"nowhere.toml\"\nmallet_radius_m = 0.015\n";
  const FileError e = file_error_of([&] { config::load_scene(dir / "s.toml"); });
  EXPECT_EQ(e.line(), 2u);
  EXPECT_NE(std::string(e.what()).find("nowhere.toml: file not found"), std::string::npos) << e.what();
}

TEST(AppConfig, ShippedFileEqualsTheBuiltInDefaults) {
  const AppConfig shipped = config::load_app_config(test::config_dir() / "mallet.toml");
  const AppConfig defaults;
  EXPECT_EQ(shipped.contact.rearm_height_m, defaults.contact.rearm_height_m);
  EXPECT_EQ(shipped.contact.min_impact_speed_m_per_s, defaults.contact.min_impact_speed_m_per_s);
  EXPECT_EQ(shipped.contact.max_impact_speed_m_per_s, defaults.contact.max_impact_speed_m_per_s);
  EXPECT_EQ(shipped.bounce, defaults.bounce);
  EXPECT_EQ(shipped.actuator.gain, defaults.actuator.gain);
  EXPECT_EQ(shipped.actuator.soft_clip_knee, defaults.actuator.soft_clip_knee);
  EXPECT_EQ(shipped.audio.sample_rate_hz, defaults.audio.sample_rate_hz);
  EXPECT_EQ(shipped.audio.device, defaults.audio.device);
  EXPECT_EQ(shipped.audio.frames_per_buffer, defaults.audio.frames_per_buffer);
  EXPECT_EQ(shipped.audio.suggested_latency_ms, defaults.audio.suggested_latency_ms);
  EXPECT_EQ(shipped.audio.schedule_ahead_ms, defaults.audio.schedule_ahead_ms);
  EXPECT_EQ(shipped.audio.max_voices, defaults.audio.max_voices);
  EXPECT_EQ(shipped.audio.volume, defaults.audio.volume);
  EXPECT_EQ(shipped.audio.acoustic, defaults.audio.acoustic);
  EXPECT_EQ(shipped.audio.soundfont, defaults.audio.soundfont);
  EXPECT_EQ(shipped.audio.routing.channels, defaults.audio.routing.channels);
  EXPECT_EQ(shipped.audio.routing.acoustic, defaults.audio.routing.acoustic);
  EXPECT_EQ(shipped.audio.routing.actuator, defaults.audio.routing.actuator);
}

TEST(AppConfig, BadValuesAreRefusedWithTheirLine) {
  const FileError bounce = file_error_of([] { config::parse_app_config("[visual]\nbounce = \"wobbly\"\n", "c.toml"); });
  EXPECT_EQ(bounce.line(), 2u);
  EXPECT_NE(std::string(bounce.what()).find("visual.bounce"), std::string::npos);

  const FileError routing = file_error_of(
      [] { config::parse_app_config("[audio.routing]\nchannels = 2\nactuator = 2\n", "c.toml"); });
  EXPECT_EQ(routing.line(), 3u);
  EXPECT_NE(std::string(routing.what()).find("audio.routing.actuator: must be in [0, 1]"), std::string::npos)
      << routing.what();

  const FileError typo = file_error_of([] { config::parse_app_config("[actuator]\ngian = 0.3\n", "c.toml"); });
  EXPECT_NE(std::string(typo.what()).find("actuator.gian: unknown key"), std::string::npos) << typo.what();

  EXPECT_EQ(config::parse_app_config("[visual]\nbounce = \"rectified\"\n", "c.toml").bounce, BounceMode::rectified);
  const AppConfig mono = config::parse_app_config("[audio.routing]\nchannels = 1\nacoustic = 0\nactuator = 0\n", "c");
  EXPECT_EQ(mono.audio.routing.channels, 1);
}

}  // namespace
}  // namespace mallet
