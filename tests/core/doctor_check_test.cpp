// `mallet doctor`'s judgements: the thresholds, the line format and the exit status.
#include <gtest/gtest.h>

#include "core/doctor_check.hpp"

namespace mallet {
namespace {

constexpr std::uint64_t kMiB = 1024 * 1024;

TEST(DoctorCheck, OneLineWithLevelNameFoundAndFix) {
  const std::string line = format_check({"audio", CheckLevel::fail, "no output device", "connect the sound card"});
  EXPECT_EQ(line, "fail  audio        no output device -> fix: connect the sound card");
  EXPECT_EQ(format_check({"disk", CheckLevel::ok, "5.0 GiB free", ""}).find("fix"), std::string::npos);
}

TEST(DoctorCheck, ExitStatusIsOneOnlyWhenSomethingFails) {
  EXPECT_EQ(doctor_exit_status({{"a", CheckLevel::ok, "", ""}, {"b", CheckLevel::warn, "", ""}}), 0);
  EXPECT_EQ(doctor_exit_status({{"a", CheckLevel::ok, "", ""}, {"b", CheckLevel::fail, "", ""}}), 1);
}

TEST(DoctorCheck, FreeSpaceThresholds) {
  EXPECT_EQ(judge_free_space("/var", 50 * kMiB).level, CheckLevel::fail);
  EXPECT_EQ(judge_free_space("/var", 500 * kMiB).level, CheckLevel::warn);
  const DoctorCheck ok = judge_free_space("/var", 5 * 1024 * kMiB);
  EXPECT_EQ(ok.level, CheckLevel::ok);
  EXPECT_NE(ok.found.find("5.0 GiB free in /var"), std::string::npos) << ok.found;
}

TEST(DoctorCheck, AStateFolderThatCannotBeWrittenFailsNamingTheFolderAndItsFreeSpace) {
  const DoctorCheck fine = judge_state_folder("/var/lib/mallet", 5 * 1024 * kMiB, "");
  EXPECT_EQ(fine.name, "disk");
  EXPECT_EQ(fine.level, CheckLevel::ok);
  EXPECT_EQ(fine.found, "state folder: 5.0 GiB free in /var/lib/mallet, writable");
  const DoctorCheck full = judge_state_folder("/var/lib/mallet", 0, "No space left on device");
  EXPECT_EQ(full.level, CheckLevel::fail);
  EXPECT_EQ(full.found, "state folder: 0.0 GiB free in /var/lib/mallet, cannot be written: No space left on device");
  EXPECT_NE(full.fix.find("the kiosk plays on"), std::string::npos) << full.fix;
  // Space enough, but a read-only file system: it fails all the same.
  EXPECT_EQ(judge_state_folder("/var/lib/mallet", 5 * 1024 * kMiB, "Read-only file system").level, CheckLevel::fail);
}

TEST(CompositorRenderer, NoRenderNodeIsPixmanAGpuIsGles2AndASetWlrRendererWins) {
  const std::vector<RenderNode> none;
  const std::vector<RenderNode> gpu{{"renderD128", "i915"}};
  const CompositorRenderer software = compositor_renderer(none, std::nullopt);
  EXPECT_EQ(software.renderer, "pixman");
  EXPECT_FALSE(software.from_environment);
  EXPECT_EQ(format_check(judge_compositor(software, none)),
            "ok    compositor   pixman (no GPU render node in /dev/dri: software)");
  const CompositorRenderer hardware = compositor_renderer(gpu, std::nullopt);
  EXPECT_EQ(hardware.renderer, "gles2");
  EXPECT_EQ(format_check(judge_compositor(hardware, gpu)),
            "ok    compositor   gles2 (the GPU's: renderD128, driver i915)");
  // A render node that only Mesa's software driver serves (virtio-gpu without 3D): Vulkan
  // finds no GPU, so pixman; a GPU that Vulkan finds keeps gles2.
  const std::vector<RenderNode> virtual_gpu{{"renderD128", "virtio_gpu"}};
  const CompositorRenderer no_3d = compositor_renderer(virtual_gpu, std::nullopt, false);
  EXPECT_EQ(no_3d.renderer, "pixman");
  EXPECT_EQ(format_check(judge_compositor(no_3d, virtual_gpu)),
            "ok    compositor   pixman (Vulkan finds no GPU, only a software driver, although /dev/dri has "
            "renderD128, driver virtio_gpu: software)");
  EXPECT_EQ(compositor_renderer(gpu, std::nullopt, true).renderer, "gles2");
  EXPECT_EQ(compositor_renderer(virtual_gpu, std::string("gles2"), false).renderer, "gles2");
  // An empty WLR_RENDERER is unset, as the start script's `-z` test reads it.
  EXPECT_EQ(compositor_renderer(none, std::string()).renderer, "pixman");
  EXPECT_EQ(compositor_renderer({{"renderD128", ""}}, std::string()).renderer, "gles2");
  // An operator's drop-in wins both ways, and the doctor says so.
  const CompositorRenderer forced = compositor_renderer(gpu, std::string("pixman"));
  EXPECT_EQ(forced.renderer, "pixman");
  EXPECT_TRUE(forced.from_environment);
  const DoctorCheck said = judge_compositor(forced, gpu);
  EXPECT_EQ(said.level, CheckLevel::ok);
  EXPECT_NE(said.found.find("WLR_RENDERER set by the unit's environment"), std::string::npos) << said.found;
  // Asking for the GPU where there is none is the crash the rule avoids: a warning with the fix.
  const DoctorCheck risky = judge_compositor(compositor_renderer(none, std::string("gles2")), none);
  EXPECT_EQ(risky.level, CheckLevel::warn);
  EXPECT_NE(risky.fix.find("remove WLR_RENDERER"), std::string::npos) << risky.fix;
}

TEST(DoctorCheck, SoftwareRendererOnALargeDisplayWarnsWithItsFrameTime) {
  const DoctorCheck big = judge_renderer("llvmpipe", true, 1920, 1080, 2.4);
  EXPECT_EQ(big.level, CheckLevel::warn);
  EXPECT_NE(big.found.find("1920x1080 frame takes 2.4 ms"), std::string::npos) << big.found;
  EXPECT_EQ(judge_renderer("llvmpipe", true, 1280, 720, 1.2).level, CheckLevel::ok);
  EXPECT_EQ(judge_renderer("Intel UHD", false, 3840, 2160, 3.0).level, CheckLevel::ok);
  EXPECT_EQ(judge_renderer("llvmpipe", true, 3840, 2160, 20.0).level, CheckLevel::fail);
}

TEST(DoctorCheck, ParsesTheCalibrationsUtcStamp) {
  EXPECT_EQ(parse_utc("1970-01-02T00:00:00Z"), 86400);
  EXPECT_EQ(parse_utc("2025-05-01T09:30:00Z"), 1746091800);
  EXPECT_FALSE(parse_utc("yesterday"));
  EXPECT_FALSE(parse_utc("2025-13-01T09:30:00Z"));
}

TEST(DoctorCheck, Calibration) {
  const std::int64_t now = *parse_utc("2026-01-31T00:00:00Z");
  EXPECT_EQ(judge_calibration("c.toml", std::nullopt, "", now, std::nullopt).level, CheckLevel::warn);
  EXPECT_EQ(judge_calibration("c.toml", std::nullopt, "c.toml:3: bad", now, std::nullopt).found, "c.toml:3: bad");
  Calibration c;
  c.created_utc = "2026-01-01T00:00:00Z";
  c.max_error_screen_px = 4.0;
  c.remote = "00:19:1d:aa:bb:cc";
  const DoctorCheck fresh = judge_calibration("c.toml", c, "", now, c.remote);
  EXPECT_EQ(fresh.level, CheckLevel::ok) << fresh.found;
  EXPECT_NE(fresh.found.find("30 days ago"), std::string::npos) << fresh.found;
  EXPECT_NE(fresh.found.find("max error 4.0 px"), std::string::npos) << fresh.found;
  EXPECT_EQ(judge_calibration("c.toml", c, "", now, std::string("00:19:1d:00:00:01")).level, CheckLevel::warn);
  Calibration rough = c;
  rough.max_error_screen_px = 40;
  EXPECT_EQ(judge_calibration("c.toml", rough, "", now, std::nullopt).level, CheckLevel::warn);
  Calibration old = c;
  old.created_utc = "2025-06-01T00:00:00Z";
  EXPECT_EQ(judge_calibration("c.toml", old, "", now, std::nullopt).level, CheckLevel::warn);
}

TEST(DoctorCheck, ActuatorCalibration) {
  const std::int64_t now = *parse_utc("2026-12-16T00:00:00Z");
  const DoctorCheck none = judge_actuator_eq("a.toml", std::nullopt, "", now, true, 48000);
  EXPECT_EQ(none.level, CheckLevel::ok);
  EXPECT_NE(none.found.find("not measured"), std::string::npos) << none.found;
  const DoctorCheck bad = judge_actuator_eq("a.toml", std::nullopt, "a.toml:3:1: taps: bad", now, true, 48000);
  EXPECT_EQ(bad.level, CheckLevel::warn);
  EXPECT_NE(bad.found.find("a.toml:3:1"), std::string::npos) << bad.found;
  ActuatorEq eq;
  eq.created_utc = "2026-12-06T00:00:00Z";
  eq.sensor = "piezo";
  eq.sample_rate_hz = 48000;
  eq.taps = std::vector<double>(16, 0.1);
  const DoctorCheck applied = judge_actuator_eq("a.toml", eq, "", now, true, 48000);
  EXPECT_EQ(applied.level, CheckLevel::ok);
  EXPECT_NE(applied.found.find("10 days ago"), std::string::npos) << applied.found;
  EXPECT_NE(applied.found.find(eq.hash()), std::string::npos) << applied.found;
  EXPECT_NE(applied.found.find("applied to the actuator channel"), std::string::npos) << applied.found;
  EXPECT_NE(judge_actuator_eq("a.toml", eq, "", now, false, 48000).found.find("not applied"), std::string::npos);
  EXPECT_EQ(judge_actuator_eq("a.toml", eq, "", now, true, 44100).level, CheckLevel::warn);
}

TEST(DoctorCheck, Latency) {
  const std::int64_t now = *parse_utc("2026-12-08T00:00:00Z");
  const DoctorCheck never = judge_latency("l.toml", std::nullopt, "", now, -1);
  EXPECT_EQ(never.level, CheckLevel::ok);
  EXPECT_NE(never.found.find("never measured"), std::string::npos) << never.found;
  EXPECT_EQ(judge_latency("l.toml", std::nullopt, "l.toml:2:1: bad", now, -1).level, CheckLevel::warn);
  LatencyMeasurement m;
  m.measured_utc = "2026-12-06T00:00:00Z";
  m.sample_rate_hz = 48000;
  m.round_trip_samples = 496;  // 10.333 ms
  m.portaudio_input_latency_ms = 0.5;
  m.portaudio_output_latency_ms = 5.333;
  const DoctorCheck saved = judge_latency("l.toml", m, "", now, m.output_latency_ms());
  EXPECT_EQ(saved.level, CheckLevel::ok) << saved.found;
  EXPECT_NE(saved.found.find("2 days ago"), std::string::npos) << saved.found;
  EXPECT_NE(saved.found.find("round trip 10.333 ms, output 9.833 ms"), std::string::npos) << saved.found;
  // PortAudio's figure in force, 4.5 ms off what was measured: said.
  EXPECT_EQ(judge_latency("l.toml", m, "", now, -1).level, CheckLevel::warn);
}

TEST(DoctorCheck, DisplayLatency) {
  const std::int64_t now = *parse_utc("2026-12-08T00:00:00Z");
  const DoctorCheck never = judge_display_latency("d.toml", std::nullopt, "", now, 0);
  EXPECT_EQ(never.level, CheckLevel::ok);
  EXPECT_NE(never.found.find("never measured"), std::string::npos) << never.found;
  EXPECT_EQ(judge_display_latency("d.toml", std::nullopt, "d.toml:3:1: bad", now, 0).level, CheckLevel::warn);
  DisplayLatencyMeasurement m;
  m.measured_utc = "2026-12-07T00:00:00Z";
  m.display_latency_ms = 23.4;
  m.min_ms = 22.9;
  m.max_ms = 24.1;
  m.squares_seen = 9;
  m.squares = 10;
  m.saved = true;
  const DoctorCheck saved = judge_display_latency("d.toml", m, "", now, 23.4);
  EXPECT_EQ(saved.level, CheckLevel::ok) << saved.found;
  EXPECT_NE(saved.found.find("1 days ago): 23.4 ms (22.9 to 24.1 over 9 of 10 squares)"), std::string::npos)
      << saved.found;
  // Measured but never confirmed, and the setting still 0: said, with how to.
  m.saved = false;
  const DoctorCheck unset = judge_display_latency("d.toml", m, "", now, 0);
  EXPECT_EQ(unset.level, CheckLevel::warn);
  EXPECT_NE(unset.found.find("not confirmed"), std::string::npos) << unset.found;
  EXPECT_NE(unset.fix.find("--photodiode"), std::string::npos) << unset.fix;
}

}  // namespace
}  // namespace mallet
