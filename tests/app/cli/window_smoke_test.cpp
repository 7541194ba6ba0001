// The windowed path, for real: `mallet render --window` opens its GLFW window and
// swapchain on lavapipe under a virtual X server (xvfb-run, from Debian's xvfb), draws
// frames, and writes the last presented frame; it must match the offscreen render of
// the same state.
#include <algorithm>
#include <atomic>
#include <thread>
#include <cstdlib>
#include <vector>

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "render/render_setup.hpp"
#include "app/strike/replay.hpp"
#include "render/image.hpp"
#include "child_process.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

using test::child_preload;
using test::slurp;
using test::wait_for;

TEST(WindowSmoke, SwapchainUnderXvfbPresentsTheOffscreenPicture) {
  ASSERT_EQ(std::system("command -v xvfb-run >/dev/null"), 0) << "xvfb-run is missing (Debian package xvfb)";
  const auto dir = test::scratch_dir();
  const Target& bar = test::percussion().targets.at(6);
  const double x = (bar.x_min + bar.x_max) / 2, y = 0.03;
  {
    std::ofstream csv(dir / "still.csv");
    csv << "t,x,y\n0," << x << ',' << y << '\n';
  }
  const std::string cmd = child_preload() + "MALLET_VK_VALIDATION=required xvfb-run -a -s '-screen 0 1024x768x24' " +
                          std::string(MALLET_TEST_BINARY) + " render --window --input-space world --input " +
                          (dir / "still.csv").string() + " --at 0 --size 640x360 --msaa 4 --frames 4 --device llvmpipe" +
                          " --screenshot " + (dir / "window.png").string() + " > " + (dir / "log.txt").string() +
                          " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir / "log.txt");
  const render::Image window = render::read_png(dir / "window.png");
  ASSERT_EQ(window.width, 640);
  ASSERT_EQ(window.height, 360);

  render::HeadlessOptions o;
  o.size = {640, 360};
  o.device = "llvmpipe";
  o.validation = render::Validation::required;
  o.cache_dir = "";
  o.settings.samples = VK_SAMPLE_COUNT_4_BIT;
  render::HeadlessRenderer offscreen(test::percussion(), o);
  render::FrameState state;
  state.mallet_centre = {x, y};
  const render::ImageDiff d = render::compare_images(window, offscreen.render(state), 3);
  EXPECT_LT(d.differing_fraction, 0.001) << d.differing_pixels << " pixels differ, max " << d.max_channel_delta;
  EXPECT_EQ(offscreen.context().validation_messages(), 0u);
}

TEST(WindowSmoke, TheKioskRunsItsAttractModeInAWindow) {
  const auto dir = test::scratch_dir();
  const std::string cmd = child_preload() + "MALLET_VK_VALIDATION=required xvfb-run -a -s '-screen 0 1024x768x24' " +
                          std::string(MALLET_TEST_BINARY) +
                          " run --windowed --size 480x270 --idle-after 1 --quit-after 2.5 --device llvmpipe > " +
                          (dir / "log.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir / "log.txt");
  const std::string log = slurp(dir / "log.txt");
  // The ghost player's first strike comes one beat after the phrase starts, then one per beat.
  EXPECT_NE(log.find("strike t="), std::string::npos) << log;
  EXPECT_NE(log.find("480x270"), std::string::npos) << log;
  EXPECT_EQ(log.find("validation"), std::string::npos) << log;
}

TEST(WindowSmoke, ALostVulkanDeviceIsRebuiltAndTheKioskGoesOn) {
  // VK_ERROR_DEVICE_LOST cannot be had on demand: the kiosk's seam makes the 40th and the
  // 120th frame's draw fail with it. Under the validation layer (which names any object
  // left alive when the old device and instance are destroyed) the kiosk rebuilds, twice,
  // and plays on: the ghost strikes after the second rebuild, frames go on past it, and the
  // run ends as usual with status 0.
  const auto dir = test::scratch_dir();
  const std::string cmd = child_preload() +
                          "MALLET_INJECT_DEVICE_LOST=40,120 MALLET_VK_VALIDATION=required xvfb-run -a -s "
                          "'-screen 0 1024x768x24' " +
                          std::string(MALLET_TEST_BINARY) +
                          " run --windowed --size 320x180 --idle-after 1 --quit-after 6 --device llvmpipe > " +
                          (dir / "log.txt").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir / "log.txt");
  const std::string log = slurp(dir / "log.txt");
  const auto count = [&](const std::string& text) {
    int n = 0;
    for (std::size_t at = log.find(text); at != std::string::npos; at = log.find(text, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("the Vulkan device was lost (submitting a frame (an injected fault): VK_ERROR_DEVICE_LOST)"), 2)
      << log;
  EXPECT_EQ(count("<5>render: rebuilt on llvmpipe"), 2) << log;
  EXPECT_EQ(log.find("validation"), std::string::npos) << log;
  const std::size_t rebuilt = log.rfind("render: rebuilt on");
  ASSERT_NE(rebuilt, std::string::npos);
  EXPECT_NE(log.find("strike t=", rebuilt), std::string::npos) << log;
  const std::size_t stopping = log.find("stopping after ");
  ASSERT_NE(stopping, std::string::npos) << log;
  EXPECT_GT(std::stoull(log.substr(stopping + 15)), 120u) << log;
}

//! Waits (polling, up to a minute) until `file` contains `text`.
TEST(WindowSmoke, SighupReloadsTheSettingsAndRefusesABrokenFile) {
  const auto dir = test::scratch_dir();
  const auto cfg = dir / "mallet.toml";
  std::filesystem::copy_file(test::config_dir() / "mallet.toml", cfg);
  const std::string launch = child_preload() + "xvfb-run -a -s '-screen 0 1024x768x24' " +
                             std::string(MALLET_TEST_BINARY) + " run --windowed --size 320x180 --quit-after 8" +
                             " --device llvmpipe --config " + cfg.string() + " > " + (dir / "log.txt").string() +
                             " 2>&1 &";
  ASSERT_EQ(std::system(launch.c_str()), 0);
  ASSERT_TRUE(wait_for(dir / "log.txt", "mallet run:")) << slurp(dir / "log.txt");

  // Only the kiosk itself (its command line starts with the binary), not xvfb-run's shell.
  const std::string hup = "pkill -HUP -f '^" + std::string(MALLET_TEST_BINARY) + " run .*" + cfg.string() + "'";
  std::ofstream(cfg) << "[audio]\nvolume = 7\n";
  std::system(hup.c_str());
  ASSERT_TRUE(wait_for(dir / "log.txt", "reload refused")) << slurp(dir / "log.txt");
  EXPECT_NE(slurp(dir / "log.txt").find(cfg.string() + ":2"), std::string::npos) << "names the file and line";

  std::ofstream(cfg) << "[audio]\nvolume = 0.3\n";
  std::system(hup.c_str());
  ASSERT_TRUE(wait_for(dir / "log.txt", "reloaded the settings")) << slurp(dir / "log.txt");
  // The kiosk kept running through both and quits by itself.
  EXPECT_TRUE(wait_for(dir / "log.txt", "strike t=")) << slurp(dir / "log.txt");
}

// Hostile models met in public glTF test files: tinygltf alone ended the process on each
// (std::bad_alloc for a buffer naming a directory, a stack overflow for deep nesting). On a
// reload they are refused with their file and problem, and the kiosk plays on.
TEST(WindowSmoke, AReloadNamingAHostileModelIsRefusedAndTheKioskPlaysOn) {
  const auto dir = test::scratch_dir();
  std::filesystem::copy(test::config_dir(), dir / "config", std::filesystem::copy_options::recursive);
  const auto cfg = dir / "config" / "mallet.toml";
  const auto scene = dir / "config" / "scenes" / "percussion.toml";
  std::filesystem::create_directories(dir / "data");
  std::ofstream(dir / "dir_buffer.gltf")
      << R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
             "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
             "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
             "bufferViews": [{"buffer": 0, "byteLength": 36}], "buffers": [{"uri": "data", "byteLength": 36}]})";
  std::ofstream(dir / "deep.gltf") << R"({"asset": {"version": "2.0"}, "extras": )" << std::string(100000, '[')
                                   << std::string(100000, ']') << "}";
  const std::string original = slurp(scene);
  const auto use_bar_model = [&](const std::filesystem::path& model) {
    std::string text = original;
    const std::size_t at = text.find("\"wood_bar.glb\"");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, std::string("\"wood_bar.glb\"").size(), "\"" + model.string() + "\"");
    std::ofstream(scene) << text;
  };
  const std::string launch = "(" + child_preload() + "xvfb-run -a -s '-screen 0 1024x768x24' " +
                             std::string(MALLET_TEST_BINARY) + " run --windowed --size 320x180 --quit-after 12" +
                             " --idle-after 1 --device llvmpipe --config " + cfg.string() + " > " +
                             (dir / "log.txt").string() + " 2>&1; echo $? > " + (dir / "status").string() + ") &";
  ASSERT_EQ(std::system(launch.c_str()), 0);
  ASSERT_TRUE(wait_for(dir / "log.txt", "mallet run:")) << slurp(dir / "log.txt");
  const std::string hup = "pkill -HUP -f '^" + std::string(MALLET_TEST_BINARY) + " run .*" + cfg.string() + "'";

  use_bar_model(dir / "dir_buffer.gltf");
  std::system(hup.c_str());
  ASSERT_TRUE(wait_for(dir / "log.txt", "is a directory, not a file")) << slurp(dir / "log.txt");
  use_bar_model(dir / "deep.gltf");
  std::system(hup.c_str());
  ASSERT_TRUE(wait_for(dir / "log.txt", "JSON nested more than 64")) << slurp(dir / "log.txt");

  ASSERT_TRUE(wait_for(dir / "status", "\n")) << slurp(dir / "log.txt");
  const std::string log = slurp(dir / "log.txt");
  EXPECT_EQ(slurp(dir / "status"), "0\n") << log;
  for (const char* model : {"dir_buffer.gltf", "deep.gltf"}) {
    const std::size_t refused = log.find(std::string("reload refused, the running configuration stays: ") +
                                         scene.string());
    EXPECT_NE(refused, std::string::npos) << log;
    EXPECT_NE(log.find(model, refused), std::string::npos) << log;
  }
  // The attract mode still strikes after both refusals.
  EXPECT_NE(log.find("strike t=", log.rfind("JSON nested more than 64")), std::string::npos) << log;
}

TEST(WindowSmoke, SigtermIsACleanStopWithItsLineAndStatusZero) {
  // systemd's `systemctl stop` sends SIGTERM: the kiosk ends as the operator's Q ends it.
  const auto dir = test::scratch_dir();
  const auto cfg = dir / "mallet.toml";
  std::filesystem::copy_file(test::config_dir() / "mallet.toml", cfg);
  const std::string launch = "(" + child_preload() + "xvfb-run -a -s '-screen 0 1024x768x24' " +
                             std::string(MALLET_TEST_BINARY) + " run --windowed --size 320x180 --quit-after 60" +
                             " --device llvmpipe --config " + cfg.string() + " > " + (dir / "log.txt").string() +
                             " 2>&1; echo $? > " + (dir / "status").string() + ") &";
  ASSERT_EQ(std::system(launch.c_str()), 0);
  ASSERT_TRUE(wait_for(dir / "log.txt", "mallet run:")) << slurp(dir / "log.txt");
  const std::string term = "pkill -TERM -f '^" + std::string(MALLET_TEST_BINARY) + " run .*" + cfg.string() + "'";
  std::system(term.c_str());
  ASSERT_TRUE(wait_for(dir / "status", "\n")) << slurp(dir / "log.txt");
  EXPECT_EQ(slurp(dir / "status"), "0\n") << slurp(dir / "log.txt");
  EXPECT_NE(slurp(dir / "log.txt").find("SIGTERM received, stopping"), std::string::npos) << slurp(dir / "log.txt");
  EXPECT_NE(slurp(dir / "log.txt").find("mallet run: stopping after"), std::string::npos) << slurp(dir / "log.txt");
}

TEST(WindowSmoke, UnderSystemdTheKioskSaysReadyFeedsTheWatchdogAndSaysStopping) {
  const auto dir = test::scratch_dir();
  const auto socket_path = dir / "notify.sock";
  const int fd = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::snprintf(addr.sun_path, sizeof addr.sun_path, "%s", socket_path.c_str());
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);

  // A datagram socket queues only a few messages: read them while the kiosk runs.
  timeval timeout{0, 100'000};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  std::vector<std::string> messages;
  std::atomic<bool> done{false};
  std::thread reader([&] {
    char buf[512];
    while (!done.load()) {
      const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
      if (n > 0) messages.emplace_back(buf, static_cast<std::size_t>(n));
    }
    for (ssize_t n; (n = ::recv(fd, buf, sizeof buf, MSG_DONTWAIT)) > 0;) messages.emplace_back(buf, n);
  });
  // Only the kiosk gets the variables: Xvfb, like any systemd-aware X server, would
  // announce its own READY=1 on the same socket.
  const std::string cmd = child_preload() + "xvfb-run -a -s '-screen 0 1024x768x24' env NOTIFY_SOCKET=" +
                          socket_path.string() + " WATCHDOG_USEC=200000 " + std::string(MALLET_TEST_BINARY) +
                          " run --windowed --size 160x90 --quit-after 2" +
                          " --device llvmpipe > " + (dir / "log.txt").string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  done = true;
  reader.join();
  ASSERT_EQ(status, 0) << slurp(dir / "log.txt");
  ::close(fd);
  ASSERT_FALSE(messages.empty()) << slurp(dir / "log.txt");
  EXPECT_EQ(messages.front(), "READY=1");
  EXPECT_EQ(messages.back(), "STOPPING=1") << [&] { std::string all; for (auto& m : messages) all += m + " "; return all; }();
  // Every 0.1 s for about 2 s: well over a handful, all while frames, input and audio ran.
  const auto beats = std::count(messages.begin(), messages.end(), std::string("WATCHDOG=1"));
  EXPECT_GE(beats, 5) << slurp(dir / "log.txt");
}

//! `mallet study` with a display: the window opens on a 2-trial protocol, the first trial's
//! taps are presented and its prompt shown; stopping it (SIGTERM, handled as Esc) leaves a
//! valid results CSV with no row, exits 0 and says how to resume. The keys themselves are tested
//! through the shared trial code (tests/app/study/study_session_test.cpp).
TEST(WindowSmoke, TheStudyOpensItsWindowPromptsSurvivesALostDeviceAndStopsLeavingAValidCsv) {
  const auto dir = test::scratch_dir();
  std::ofstream(dir / "tiny.toml") << "name = \"tiny\"\ntask = \"2afc_harder\"\nconditions = [\"both\"]\n"
                                      "repetitions = 2\nseed = 1\noutput = \"tiny.csv\"\nreference_bar = 0\n"
                                      "[timing]\nlead_s = 0.1\nstimulus_s = 0.2\nstimulus_interval_s = 0.3\n"
                                      "inter_trial_s = 0.1\n[[stimulus]]\nname = \"wood\"\nmaterial = \"wood\"\n"
                                      "[[stimulus]]\nname = \"wood_B130\"\nmaterial = \"wood\"\ndecay_scale = 1.30\n"
                                      "[[pair]]\na = \"wood\"\nb = \"wood_B130\"\n";
  // The study's window loses its Vulkan device at its 10th frame (the seam) and draws on.
  const std::string launch = "(" + child_preload() +
                             "MALLET_INJECT_DEVICE_LOST=10 MALLET_VK_VALIDATION=required xvfb-run -a -s '-screen 0 1024x768x24' " +
                             std::string(MALLET_TEST_BINARY) + " study --windowed --size 320x180 --quit-after 60" +
                             " --device llvmpipe --protocol " + (dir / "tiny.toml").string() +
                             " --participant W1 --out " + (dir / "r.csv").string() + " > " +
                             (dir / "log.txt").string() + " 2>&1; echo exit=$? >> " + (dir / "log.txt").string() +
                             ") &";
  ASSERT_EQ(std::system(launch.c_str()), 0);
  ASSERT_TRUE(wait_for(dir / "log.txt", "trial 1 of 2: Which tap felt harder? Press 1 or 2")) << slurp(dir / "log.txt");
  ASSERT_TRUE(wait_for(dir / "log.txt", "<5>render: rebuilt on llvmpipe")) << slurp(dir / "log.txt");
  // Nobody answers: it waits at the prompt. SIGTERM stops it as Esc, Q or the close button
  // would (--quit-after 60 only guards against a hang).
  const std::string stop = "pkill -f '^" + std::string(MALLET_TEST_BINARY) + " study .*" + (dir / "r.csv").string() + "'";
  EXPECT_EQ(std::system(stop.c_str()), 0) << stop;
  ASSERT_TRUE(wait_for(dir / "log.txt", "exit=")) << slurp(dir / "log.txt");
  const std::string log = slurp(dir / "log.txt");
  EXPECT_NE(log.find("320x180"), std::string::npos) << log;
  EXPECT_EQ(log.find("validation"), std::string::npos) << log;
  EXPECT_NE(log.find("stopped by the participant after 1 trial(s) shown"), std::string::npos) << log;
  EXPECT_NE(log.find("run the same command to resume"), std::string::npos) << log;
  EXPECT_NE(log.find("exit=0"), std::string::npos) << log;
  const std::string csv = slurp(dir / "r.csv");
  EXPECT_EQ(csv.rfind("participant,trial,condition", 0), 0u) << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1) << "the header only: no trial was answered\n" << csv;
}

}  // namespace
}  // namespace mallet::app
