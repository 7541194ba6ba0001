// A malformed config names the file, the line and the key; the shipped files load.
#include <array>
#include <fstream>
#include <string>

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

TEST(MaterialsConfig, GlowColourIsReadOrDefaultsAndAWrongOneNamesItsLine) {
  EXPECT_EQ(config::parse_materials(kGoodMaterial, "m.toml").all().at(0).glow_srgb, Material::kDefaultGlowSrgb);
  const MaterialLibrary lib =
      config::parse_materials(std::string(kGoodMaterial) + "glow_srgb = [1.0, 0.5, 0.25]\n", "m.toml");
  EXPECT_EQ(lib.all().at(0).glow_srgb, (std::array<double, 3>{1.0, 0.5, 0.25}));
  for (const char* bad : {"glow_srgb = [1.0, 0.5]\n", "glow_srgb = [1.0, 0.5, 1.5]\n"}) {
    const FileError e = file_error_of([&] { config::parse_materials(std::string(kGoodMaterial) + bad, "m.toml"); });
    EXPECT_EQ(e.line(), 5u) << bad;
    EXPECT_NE(std::string(e.what()).find("material.wood.glow_srgb"), std::string::npos) << e.what();
  }
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
  EXPECT_EQ(shipped.note_names, defaults.note_names);
  EXPECT_EQ(shipped.render.max_fps, defaults.render.max_fps);
  EXPECT_EQ(shipped.actuator.gain, defaults.actuator.gain);
  EXPECT_EQ(shipped.actuator.soft_clip_knee, defaults.actuator.soft_clip_knee);
  EXPECT_EQ(shipped.audio.sample_rate_hz, defaults.audio.sample_rate_hz);
  EXPECT_EQ(shipped.audio.device, defaults.audio.device);
  EXPECT_EQ(shipped.audio.frames_per_buffer, defaults.audio.frames_per_buffer);
  EXPECT_EQ(shipped.audio.suggested_latency_ms, defaults.audio.suggested_latency_ms);
  EXPECT_EQ(shipped.audio.schedule_ahead_ms, defaults.audio.schedule_ahead_ms);
  EXPECT_EQ(shipped.audio.max_voices, defaults.audio.max_voices);
  EXPECT_EQ(shipped.audio.max_modes, defaults.audio.max_modes);
  EXPECT_EQ(shipped.quality, defaults.quality);
  EXPECT_EQ(shipped.render.shadow, defaults.render.shadow);
  EXPECT_EQ(shipped.audio.volume, defaults.audio.volume);
  EXPECT_EQ(shipped.audio.acoustic, defaults.audio.acoustic);
  EXPECT_EQ(shipped.audio.soundfont, defaults.audio.soundfont);
  EXPECT_EQ(shipped.audio.routing.channels, defaults.audio.routing.channels);
  EXPECT_EQ(shipped.audio.routing.acoustic, defaults.audio.routing.acoustic);
  EXPECT_EQ(shipped.audio.routing.actuator, defaults.audio.routing.actuator);
  EXPECT_EQ(shipped.pointer.min_cutoff_hz, defaults.pointer.min_cutoff_hz);
  EXPECT_EQ(shipped.pointer.beta_per_m, defaults.pointer.beta_per_m);
  EXPECT_EQ(shipped.pointer.d_cutoff_hz, defaults.pointer.d_cutoff_hz);
  EXPECT_EQ(shipped.pointer.derivative_from_raw, defaults.pointer.derivative_from_raw);
  EXPECT_EQ(shipped.tracking.max_speed_px_per_s, defaults.tracking.max_speed_px_per_s);
  EXPECT_EQ(shipped.tracking.jump_slack_px, defaults.tracking.jump_slack_px);
  EXPECT_EQ(shipped.tracking.reacquire_after_frames, defaults.tracking.reacquire_after_frames);
  EXPECT_EQ(shipped.tracking.lost_after_ms, defaults.tracking.lost_after_ms);
  EXPECT_EQ(shipped.attract.idle_after_s, defaults.attract.idle_after_s);
  EXPECT_EQ(shipped.attract.volume, defaults.attract.volume);
  EXPECT_EQ(shipped.render.present_mode, defaults.render.present_mode);
  EXPECT_EQ(shipped.render.msaa, defaults.render.msaa);
  EXPECT_EQ(shipped.render.device, defaults.render.device);
  EXPECT_EQ(shipped.render.monitor, defaults.render.monitor);
  EXPECT_EQ(shipped.input.source, defaults.input.source);
  EXPECT_EQ(shipped.input.replay_file, defaults.input.replay_file);
  EXPECT_EQ(shipped.wiimote.device, defaults.wiimote.device);
  EXPECT_EQ(shipped.wiimote.ir_mode, defaults.wiimote.ir_mode);
  EXPECT_EQ(shipped.wiimote.sensitivity, defaults.wiimote.sensitivity);
  EXPECT_EQ(shipped.wiimote.rumble_on_impact, defaults.wiimote.rumble_on_impact);
  EXPECT_EQ(shipped.wiimote.rumble_ms, defaults.wiimote.rumble_ms);
  EXPECT_EQ(shipped.wiimote.silence_timeout_ms, defaults.wiimote.silence_timeout_ms);
  EXPECT_EQ(shipped.wiimote.reconnect_min_ms, defaults.wiimote.reconnect_min_ms);
  EXPECT_EQ(shipped.wiimote.reconnect_max_ms, defaults.wiimote.reconnect_max_ms);
  EXPECT_EQ(shipped.scenes.start, defaults.scenes.start);
  EXPECT_EQ(shipped.scenes.choices, defaults.scenes.choices);
}

TEST(AppConfig, InputDefaultsAreTheIssuesChoices) {
  // The numbers `mallet bench input` and the tracker's design settled on; the shipped file
  // must carry exactly these (the test above), so a change here is deliberate.
  const AppConfig c;
  EXPECT_EQ(c.pointer.min_cutoff_hz, 1.0);
  EXPECT_EQ(c.pointer.beta_per_m, 500.0);
  EXPECT_EQ(c.pointer.d_cutoff_hz, 1.0);
  EXPECT_FALSE(c.pointer.derivative_from_raw);
  EXPECT_EQ(c.tracking.max_speed_px_per_s, 10000.0);
  EXPECT_EQ(c.tracking.jump_slack_px, 8.0);
  EXPECT_EQ(c.tracking.reacquire_after_frames, 3);
  EXPECT_EQ(c.tracking.lost_after_ms, 150.0);
  EXPECT_EQ(c.wiimote.ir_mode, IrMode::extended);
  EXPECT_EQ(c.wiimote.sensitivity, "wii3");
  EXPECT_FALSE(c.wiimote.rumble_on_impact);
  EXPECT_EQ(c.wiimote.rumble_ms, 40.0);
  EXPECT_EQ(c.wiimote.silence_timeout_ms, 3000.0);
  EXPECT_EQ(c.wiimote.reconnect_min_ms, 500.0);
  EXPECT_EQ(c.wiimote.reconnect_max_ms, 5000.0);
}

TEST(AppConfig, InputSectionsAreRead) {
  const AppConfig c = config::parse_app_config(
      "[pointer]\nmin_cutoff_hz = 2.5\nbeta_per_m = 100\nd_cutoff_hz = 0.5\nderivative_from_raw = true\n"
      "[tracking]\nmax_speed_px_per_s = 5000\njump_slack_px = 0\nreacquire_after_frames = 5\nlost_after_ms = 80\n"
      "[wiimote]\ndevice = \"00:1f:32\"\nir_mode = \"basic\"\nsensitivity = \"max\"\nrumble_on_impact = true\n"
      "rumble_ms = 25\nsilence_timeout_ms = 1500\nreconnect_min_ms = 250\nreconnect_max_ms = 2000\n"
      "[input]\nsource = \"replay\"\nreplay_file = \"visit.replay\"\n",
      "/etc/mallet/c.toml");
  EXPECT_EQ(c.input.source, "replay");
  EXPECT_EQ(c.input.replay_file, "/etc/mallet/visit.replay");
  EXPECT_EQ(c.pointer.min_cutoff_hz, 2.5);
  EXPECT_EQ(c.pointer.beta_per_m, 100.0);
  EXPECT_EQ(c.pointer.d_cutoff_hz, 0.5);
  EXPECT_TRUE(c.pointer.derivative_from_raw);
  EXPECT_EQ(c.tracking.max_speed_px_per_s, 5000.0);
  EXPECT_EQ(c.tracking.jump_slack_px, 0.0);
  EXPECT_EQ(c.tracking.reacquire_after_frames, 5);
  EXPECT_EQ(c.tracking.lost_after_ms, 80.0);
  EXPECT_EQ(c.wiimote.device, "00:1f:32");
  EXPECT_EQ(c.wiimote.ir_mode, IrMode::basic);
  EXPECT_EQ(c.wiimote.sensitivity, "max");
  EXPECT_TRUE(c.wiimote.rumble_on_impact);
  EXPECT_EQ(c.wiimote.rumble_ms, 25.0);
  EXPECT_EQ(c.wiimote.silence_timeout_ms, 1500.0);
  EXPECT_EQ(c.wiimote.reconnect_min_ms, 250.0);
  EXPECT_EQ(c.wiimote.reconnect_max_ms, 2000.0);
  // What the loader accepts, the filter and the tracker accept too.
  EXPECT_TRUE(validate(c.pointer));
  EXPECT_TRUE(validate(c.tracking));
}

TEST(AppConfig, TheCameraSectionIsRead) {
  const AppConfig d;
  EXPECT_EQ(d.camera.device, "auto");
  EXPECT_EQ(d.camera.width, 640);
  EXPECT_EQ(d.camera.height, 480);
  EXPECT_EQ(d.camera.exposure_us, 500);
  EXPECT_EQ(d.camera.gain, -1);
  EXPECT_EQ(d.camera.format, "auto");
  const AppConfig c = config::parse_app_config(
      "[input]\nsource = \"camera\"\n[camera]\ndevice = \"/dev/v4l/by-id/usb-Cam-video-index0\"\nwidth = 320\n"
      "height = 240\nrate_hz = 240.0\nexposure_us = 300\ngain = 8\nformat = \"yuyv\"\n",
      "c.toml");
  EXPECT_EQ(c.input.source, "camera");
  EXPECT_EQ(c.camera.device, "/dev/v4l/by-id/usb-Cam-video-index0");
  EXPECT_EQ(c.camera.width, 320);
  EXPECT_EQ(c.camera.height, 240);
  EXPECT_EQ(c.camera.rate_hz, 240.0);
  EXPECT_EQ(c.camera.exposure_us, 300);
  EXPECT_EQ(c.camera.gain, 8);
  EXPECT_EQ(c.camera.format, "yuyv");
  // Automatic exposure has no frame-length bound.
  EXPECT_EQ(config::parse_app_config("[camera]\nexposure_us = 0\nrate_hz = 1000\n", "c.toml").camera.exposure_us, 0);
  // The shipped file documents every key with its default.
  const AppConfig shipped = config::load_app_config(test::config_dir() / "mallet.toml");
  EXPECT_EQ(shipped.camera.rate_hz, d.camera.rate_hz);
  EXPECT_EQ(shipped.camera.exposure_us, d.camera.exposure_us);
}

TEST(AppConfig, BadInputValuesNameTheirKeyAndLine) {
  struct Case {
    const char* text;
    std::uint32_t line;
    const char* message;
  };
  const Case cases[] = {
      {"[pointer]\nmin_cutoff_hz = 0\n", 2, "pointer.min_cutoff_hz: must be in [0.01, 100], got 0"},
      {"[pointer]\nbeta_per_m = -1\n", 2, "pointer.beta_per_m: must be in [0, 1e+06], got -1"},
      {"[pointer]\n\nd_cutoff_hz = nan\n", 3, "pointer.d_cutoff_hz: must be finite, got nan"},
      {"[pointer]\nderivative_from_raw = 1\n", 2, "pointer.derivative_from_raw: expected true or false"},
      {"[tracking]\nmax_speed_px_per_s = 0\n", 2, "tracking.max_speed_px_per_s: must be in [1, 1e+06], got 0"},
      {"[tracking]\njump_slack_px = -2\n", 2, "tracking.jump_slack_px: must be in [0, 1024], got -2"},
      {"[tracking]\nreacquire_after_frames = 0\n", 2, "tracking.reacquire_after_frames: must be in [1, 1000], got 0"},
      {"[tracking]\nlost_after_ms = 0.5\n", 2, "tracking.lost_after_ms: must be in [1, 60000], got 0.5"},
      {"[tracking]\nlost_after_s = 1\n", 2, "tracking.lost_after_s: unknown key"},
      {"[wiimote]\nir_mode = \"full\"\n", 2, "wiimote.ir_mode: expected \"extended\" or \"basic\", got \"full\""},
      {"[wiimote]\nsensitivity = \"wii6\"\n", 2,
       "wiimote.sensitivity: unknown preset \"wii6\" (known: wii1, wii2, wii3, wii4, wii5, marcan, max)"},
      {"[wiimote]\nrumble_ms = 0\n", 2, "wiimote.rumble_ms: must be in [1, 1000], got 0"},
      {"[wiimote]\nsilence_timeout_ms = 50\n", 2, "wiimote.silence_timeout_ms: must be in [100, 60000], got 50"},
      {"[wiimote]\nreconnect_min_ms = 1000\nreconnect_max_ms = 900\n", 3,
       "wiimote.reconnect_max_ms: must be in [1000, 600000], got 900"},
      {"[wiimote]\nrumble_on_impact = \"yes\"\n", 2, "wiimote.rumble_on_impact: expected true or false"},
      {"[input]\nsource = \"joystick\"\n", 2,
       "input.source: expected \"auto\", \"wiimote\", \"camera\", \"mouse\" or \"replay\", got \"joystick\""},
      {"[camera]\nwidth = 8\n", 2, "camera.width: must be in [16, 8192], got 8"},
      {"[camera]\nheight = 9000\n", 2, "camera.height: must be in [16, 8192], got 9000"},
      {"[camera]\nrate_hz = 0\n", 2, "camera.rate_hz: must be in [1, 1000], got 0"},
      {"[camera]\n\nexposure_us = -1\n", 3, "camera.exposure_us: must be in [0, 1e+06], got -1"},
      {"[camera]\nrate_hz = 240\nexposure_us = 5000\n", 3,
       "camera.exposure_us: exposure_us 5000 is longer than one frame at rate_hz 240 (4167 µs)"},
      {"[camera]\nexposure_us = 20000\n", 2,
       "camera.exposure_us: exposure_us 20000 is longer than one frame at rate_hz 120 (8333 µs)"},
      {"[camera]\ngain = -2\n", 2, "camera.gain: must be in [-1, 1e+06], got -2"},
      {"[camera]\nformat = \"rgb\"\n", 2,
       "camera.format: expected \"auto\", \"grey\", \"yuyv\" or \"mjpeg\", got \"rgb\""},
      {"[camera]\ndevice = \"\"\n", 2, "camera.device: empty"},
      {"[camera]\nwidth_px = 640\n", 2, "camera.width_px: unknown key"},
      {"[input]\nsource = \"replay\"\n", 2, "input.source: \"replay\" needs replay_file"},
      {"[render]\npresent_mode = \"vsync\"\n", 2,
       "render.present_mode: expected \"fifo\", \"mailbox\" or \"immediate\", got \"vsync\""},
      {"[render]\nmsaa = \"3\"\n", 2, "render.msaa: expected \"auto\", \"1\", \"2\", \"4\" or \"8\", got \"3\""},
      {"[render]\n\nmonitor = 99\n", 3, "render.monitor: must be in [0, 15], got 99"},
      {"[attract]\nidle_after_s = 0\n", 2, "attract.idle_after_s: must be in [1, 86400], got 0"},
      {"[attract]\nvolume = 1.5\n", 2, "attract.volume: must be in [0, 1], got 1.5"},
      {"[kiosk]\nlanguage = \"xx\"\n", 2,
       "kiosk.language: \"xx\" has no catalogue; expected one of en, de, fr, ja"},
      {"[kiosk]\nlanguage = \"\"\n", 2, "kiosk.language: \"\" has no catalogue"},
      {"[attract]\n\nlanguages = [\"en\", \"DE\"]\n", 3,
       "attract.languages: \"DE\" has no catalogue; expected some of en, de, fr, ja"},
      {"[attract]\nlanguage_every_s = 0.5\n", 2, "attract.language_every_s: must be in [1, 3600], got 0.5"},
  };
  for (const Case& k : cases) {
    const FileError e = file_error_of([&] { config::parse_app_config(k.text, "c.toml"); });
    EXPECT_EQ(e.file(), "c.toml") << k.text;
    EXPECT_EQ(e.line(), k.line) << k.text << " → " << e.what();
    EXPECT_NE(std::string(e.what()).find(k.message), std::string::npos) << k.text << " → " << e.what();
  }
}

TEST(AppConfig, BadValuesAreRefusedWithTheirLine) {
  const FileError bounce = file_error_of([] { config::parse_app_config("[visual]\nbounce = \"wobbly\"\n", "c.toml"); });
  EXPECT_EQ(bounce.line(), 2u);
  EXPECT_NE(std::string(bounce.what()).find("visual.bounce"), std::string::npos);
  const FileError names = file_error_of([] { config::parse_app_config("[visual]\nnote_names = 3\n", "c.toml"); });
  EXPECT_EQ(names.line(), 2u);
  EXPECT_NE(std::string(names.what()).find("visual.note_names"), std::string::npos) << names.what();
  const FileError fps = file_error_of([] { config::parse_app_config("[render]\n\nmax_fps = 2000\n", "c.toml"); });
  EXPECT_EQ(fps.line(), 3u);
  EXPECT_NE(std::string(fps.what()).find("render.max_fps"), std::string::npos) << fps.what();
  EXPECT_TRUE(config::parse_app_config("[visual]\nnote_names = true\n", "c.toml").note_names);
  EXPECT_EQ(config::parse_app_config("[render]\nmax_fps = 30\n", "c.toml").render.max_fps, 30.0);

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
