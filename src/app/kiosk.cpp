#include "app/kiosk.hpp"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <memory>
#include <span>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "app/audio_setup.hpp"
#include "app/data_paths.hpp"
#include "app/render_setup.hpp"
#include "app/simulate.hpp"
#include "app/strike_loop.hpp"
#include "audio/portaudio_output.hpp"
#include "audio/wav_file.hpp"
#include "core/config/app_config_loader.hpp"
#include "core/config/scene_config.hpp"
#include "core/file_error.hpp"
#include "core/sample_clock.hpp"
#include "render/font_atlas.hpp"
#include "render/overlay.hpp"
#include "render/window_target.hpp"

namespace mallet::app {
namespace fs = std::filesystem;
namespace {

constexpr const char* kInvitation = "Pick up the mallet and strike a bar";

//! The invitation of the attract mode, centred near the top, on a translucent band.
void draw_invitation(render::Overlay& overlay, float width, float height) {
  const render::FontAtlas& font = overlay.atlas();
  const float w = font.measure(kInvitation) + 48, h = font.pixel_height() * 1.8f;
  const float x = (width - w) / 2, y = height * 0.08f;
  overlay.fill_rect(x, y, w, h, {0.0f, 0.0f, 0.0f, 0.55f});
  overlay.text(width / 2, y + h / 2 + font.pixel_height() * 0.35f, kInvitation, {1.0f, 1.0f, 1.0f, 1.0f},
               render::TextAlign::center);
}

std::string describe(const Scene& scene, const Impact& i) {
  const Target& t = scene.targets.at(i.target);
  char buf[160];
  std::snprintf(buf, sizeof buf, "strike t=%s bar=%d %s note=%d speed=%.3f m/s", format_seconds(i.t_ns).c_str(), t.id,
                t.instrument.c_str(), t.note, i.speed_m_per_s);
  return buf;
}

fs::path new_out_dir() {
  const std::time_t now = std::time(nullptr);
  char name[64];
  std::strftime(name, sizeof name, "mallet-run-%Y%m%d-%H%M%S", std::localtime(&now));
  return fs::current_path() / name;
}

int run_headless(const KioskOptions& o, const Scene& scene, const AppConfig& config, const std::string& why) {
  if (!(o.seconds > 0 && o.seconds <= 24 * 3600)) throw FileError("--seconds", 0, 0, "must be in (0, 86400]");
  const fs::path out = o.out_dir.empty() ? new_out_dir() : o.out_dir;
  fs::create_directories(out);
  std::ofstream log(out / "log.txt");
  auto say = [&](const std::string& line) { log << line << '\n'; };
  say("mallet run (headless: " + why + ")");
  say("scene: " + scene.file);

  const int rate = config.audio.sample_rate_hz;
  AudioRig rig = make_audio_rig(scene, config, rate);
  const int channels = config.audio.routing.channels;
  audio::WavWriter wav(out / "audio.wav", channels, rate);

  HeadlessOptions ho;
  ho.size = parse_size(o.size, "--size");
  ho.auto_samples = config.render.msaa == "auto";
  if (!ho.auto_samples) ho.settings.samples = static_cast<VkSampleCountFlagBits>(std::stoi(config.render.msaa));
  ho.device = o.device.empty() ? config.render.device : o.device;
  HeadlessRenderer renderer(scene, ho);
  say("render: " + renderer.context().device_name() + ", " + o.size);
  const render::FontAtlas font(render::FontAtlas::default_font(), static_cast<float>(ho.size.height) / 24.0f);
  render::Overlay overlay(font);

  // Nobody is there: the attract loop plays from the start, on a simulated 60 Hz clock.
  StrikeLoop loop(scene, config);
  AttractLoop ghost(scene, 0);
  const Nanos frame = kNanosPerSecond / 60;
  const Nanos end = static_cast<Nanos>(std::llround(o.seconds * 1e9));
  std::vector<float> block;
  std::int64_t audio_pos = 0;
  std::uint64_t strikes = 0, frames = 0;
  for (Nanos t = 0; t <= end; t += frame) {
    for (const PointerSample& s : ghost.samples_until(t)) {
      if (auto impact = loop.feed(s.t_ns, {s.x, s.y})) {
        rig.engine->post(*impact);  // posted before the audio block it falls in
        say(describe(scene, *impact));
        ++strikes;
      }
    }
    const std::int64_t audio_end = align_to_sample(t, rate).index;
    if (audio_end > audio_pos) {
      const int n = static_cast<int>(audio_end - audio_pos);
      block.resize(static_cast<std::size_t>(n * channels));
      rig.engine->process(block.data(), n);
      wav.write(std::span<const float>(block));
      audio_pos = audio_end;
    }
    overlay.clear();
    draw_invitation(overlay, static_cast<float>(ho.size.width), static_cast<float>(ho.size.height));
    render::FrameState state;
    state.mallet_centre = loop.displayed(t);
    state.overlay = &overlay;
    renderer.draw(state);
    ++frames;
  }
  wav.close();
  render::write_png(renderer.read_back(), out / "screenshot.png");
  const std::uint64_t vk_messages = renderer.context().validation_messages();
  char summary[200];
  std::snprintf(summary, sizeof summary, "ran %.3f s: %llu frames, %llu strikes, %lld audio frames at %d Hz", o.seconds,
                static_cast<unsigned long long>(frames), static_cast<unsigned long long>(strikes),
                static_cast<long long>(audio_pos), rate);
  say(summary);
  if (vk_messages) say("error: " + std::to_string(vk_messages) + " Vulkan validation message(s)");
  log.close();
  std::printf("mallet run: headless (%s)\n%s\n", why.c_str(), summary);
  for (const char* f : {"screenshot.png", "audio.wav", "log.txt"}) std::printf("wrote %s\n", (out / f).c_str());
  return vk_messages ? 1 : 0;
}

int run_window(const KioskOptions& o, const Scene& scene, const AppConfig& config) {
  render::WindowSystem glfw;
  render::ContextOptions co;
  co.validation = validation_from_env();
  co.device_name = o.device.empty() ? config.render.device : o.device;
  co.instance_extensions = render::WindowSystem::instance_extensions();
  co.swapchain = true;
  render::Context ctx(co);
  render::PipelineCache cache(ctx, render::PipelineCache::default_dir());
  render::WindowOptions wo;
  const VkExtent2D size = parse_size(o.size, "--size");
  wo.width = static_cast<int>(size.width);
  wo.height = static_cast<int>(size.height);
  wo.fullscreen = !o.windowed;
  wo.hide_cursor = !o.windowed;
  wo.monitor = config.render.monitor;
  wo.present_mode = config.render.present_mode == "mailbox"     ? render::PresentMode::mailbox
                    : config.render.present_mode == "immediate" ? render::PresentMode::immediate
                                                                : render::PresentMode::fifo;
  render::WindowTarget window(ctx, wo);
  render::RenderSettings rs;
  rs.samples = config.render.msaa == "auto" ? render::recommended_samples(ctx)
                                             : static_cast<VkSampleCountFlagBits>(std::stoi(config.render.msaa));
  render::SceneRenderer renderer(ctx, scene, models_dir(), window.format(), rs, cache.get());
  std::fprintf(stderr, "<6>mallet run: %s, %ux%u\n", ctx.device_name().c_str(), window.extent().width,
               window.extent().height);

  AudioRig rig = make_audio_rig(scene, config, config.audio.sample_rate_hz);
  std::unique_ptr<audio::PortAudioOutput> output;
  try {
    output = std::make_unique<audio::PortAudioOutput>(*rig.engine, config.audio);
    output->start();
  } catch (const std::exception& e) {  // the scene still plays, silently
    std::fprintf(stderr, "<3>audio: %s; running without sound\n", e.what());
    output.reset();
  }

  const float font_px = static_cast<float>(window.extent().height) / 24.0f;
  const render::FontAtlas font(render::FontAtlas::default_font(), font_px);
  render::Overlay overlay(font);
  StrikeLoop loop(scene, config);
  const Nanos idle_after = static_cast<Nanos>(std::llround(o.idle_after_s * 1e9));
  Nanos last_input = monotonic_now() - idle_after;  // nobody there yet: attract at once
  std::optional<AttractLoop> ghost;
  double last_x = -1, last_y = -1;
  const Nanos started = monotonic_now();
  const Nanos quit_after = static_cast<Nanos>(std::llround(o.quit_after_s * 1e9));
  auto strike = [&](const Impact& impact) {
    rig.engine->post(impact);
    std::fprintf(stderr, "<6>%s\n", describe(scene, impact).c_str());
  };
  for (;;) {
    glfwPollEvents();
    if (window.close_requested()) {
      if (o.windowed) break;
      glfwSetWindowShouldClose(window.window(), GLFW_FALSE);  // visitors cannot close the kiosk
    }
    const bool chord = glfwGetKey(window.window(), GLFW_KEY_O) == GLFW_PRESS &&
                       (glfwGetKey(window.window(), GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
                        glfwGetKey(window.window(), GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS) &&
                       (glfwGetKey(window.window(), GLFW_KEY_LEFT_ALT) == GLFW_PRESS ||
                        glfwGetKey(window.window(), GLFW_KEY_RIGHT_ALT) == GLFW_PRESS);
    if (chord) break;  // the operator's way out
    const Nanos now = monotonic_now();
    if (quit_after > 0 && now - started >= quit_after) break;
    double x = 0, y = 0;
    int w = 1, h = 1;
    glfwGetCursorPos(window.window(), &x, &y);
    glfwGetWindowSize(window.window(), &w, &h);
    const bool moved = last_x >= 0 && (x != last_x || y != last_y);
    last_x = x;
    last_y = y;
    if (moved) {
      if (ghost) {  // a visitor takes over from the ghost within this frame
        ghost.reset();
        loop.reset();
      }
      last_input = now;
      const Vec2 hand = scene.screen_to_world.map(x / std::max(w, 1), y / std::max(h, 1));
      if (auto impact = loop.feed(now, hand)) strike(*impact);
    } else if (now - last_input >= idle_after) {
      if (!ghost) {
        ghost.emplace(scene, now);
        loop.reset();
      }
      for (const PointerSample& s : ghost->samples_until(now))
        if (auto impact = loop.feed(s.t_ns, {s.x, s.y})) strike(*impact);
    }
    overlay.clear();
    if (ghost)
      draw_invitation(overlay, static_cast<float>(window.extent().width), static_cast<float>(window.extent().height));
    render::FrameState state;
    state.mallet_centre = loop.displayed(window.predicted_present(now));
    state.overlay = &overlay;
    window.draw(renderer, state);
  }
  vkDeviceWaitIdle(ctx.device());
  if (output) output->stop();
  if (ctx.validation_messages() > 0) {
    std::fprintf(stderr, "<3>%llu Vulkan validation message(s); first: %s\n",
                 static_cast<unsigned long long>(ctx.validation_messages()), ctx.first_validation_message().c_str());
    return 1;
  }
  return 0;
}

}  // namespace

int run_kiosk(const KioskOptions& o) {
  const AppConfig config = o.config ? config::load_app_config(*o.config) : AppConfig{};
  const Scene scene = config::load_scene(o.scene);
  if (o.headless) return run_headless(o, scene, config, "--headless");
  if (!render::WindowSystem::display_available())
    return run_headless(o, scene, config, "no display: DISPLAY and WAYLAND_DISPLAY are unset");
  return run_window(o, scene, config);
}

}  // namespace mallet::app
