#include <cmath>
#include <cstdio>
#include <memory>

#include "app/cli/commands.hpp"
#include "core/scene_layout.hpp"
#include "core/data_paths.hpp"
#include "render/render_setup.hpp"
#include "app/strike/replay.hpp"
#include "app/common/settings_source.hpp"
#include "app/offline/simulate.hpp"
#include "core/config/app_config_loader.hpp"
#include "core/config/scene_config.hpp"
#include "core/file_error.hpp"
#include "render/image.hpp"
#include "render/window_target.hpp"

#include <GLFW/glfw3.h>

#include <fmt/format.h>

namespace mallet::app {
namespace {

struct RenderCliOptions {
  std::filesystem::path scene = default_scene();
  std::filesystem::path input;
  std::optional<std::filesystem::path> config = default_settings();
  std::optional<std::filesystem::path> config_dir;
  std::string input_space = "screen";
  std::string size = "1280x720";
  std::string layout = "auto";  //!< auto: as the kiosk lays the scene out for --size's shape
  std::optional<double> at_s;
  std::filesystem::path out;
  std::optional<double> fps;
  double from_s = 0, to_s = 0;
  std::filesystem::path out_dir;
  std::string msaa = "4";
  bool no_shadow = false;
  std::string device;
  bool window = false;
  int frames = 0;                       //!< window: stop after this many frames (0 = until closed)
  std::filesystem::path screenshot;     //!< window: the last presented frame, as PNG
  PresentPacing present_mode = PresentPacing::fifo;
};

//! A time the flags gave: CLI11 has checked that the clock holds it (seconds()).
Nanos to_nanos(double seconds) { return *from_seconds(seconds); }

VkSampleCountFlagBits sample_count(const std::string& msaa) {
  if (msaa == "1") return VK_SAMPLE_COUNT_1_BIT;
  if (msaa == "2") return VK_SAMPLE_COUNT_2_BIT;
  if (msaa == "4") return VK_SAMPLE_COUNT_4_BIT;
  return VK_SAMPLE_COUNT_8_BIT;  // "8": the flag's check admits no other
}

//! The same frames in a GLFW window (real time for a sequence; held for --at).
void run_window(const RenderCliOptions& o, const Scene& scene, const Replay& replay,
                const render::HeadlessOptions& ho) {
  render::WindowSystem glfw;
  render::ContextOptions co;
  co.validation = ho.validation;
  co.device_name = ho.device;
  co.instance_extensions = render::WindowSystem::instance_extensions();
  co.swapchain = true;
  render::Context ctx(co);
  render::PipelineCache cache(ctx, ho.cache_dir);
  render::WindowOptions wo;
  wo.width = static_cast<int>(ho.size.width);
  wo.height = static_cast<int>(ho.size.height);
  wo.present_mode = o.present_mode;
  wo.title = "Mallet — " + o.input.filename().string();
  wo.skip_unchanged = false;  // --frames counts frames drawn, a trajectory at rest too
  render::WindowTarget window(ctx, wo);
  render::RenderSettings rs = ho.settings;
  if (ho.auto_samples) render::use_recommended_antialiasing(ctx, rs);
  render::SceneRenderer renderer(ctx, scene, render::models_dir(), window.format(), rs, cache.get());
  std::printf("device: %s; window %ux%u\n", ctx.device_name().c_str(), window.extent().width, window.extent().height);

  const Nanos from = o.at_s ? to_nanos(*o.at_s) : to_nanos(o.from_s);
  const Nanos to = o.at_s ? from : to_nanos(o.to_s);
  const Nanos start = monotonic_now();
  render::Image shot;
  int drawn = 0;
  while (!window.close_requested() && (o.frames == 0 || drawn < o.frames)) {
    glfwPollEvents();
    // The trajectory's clock runs with the wall clock from --from; each frame shows the
    // state at its predicted present time.
    const Nanos t = std::min(to, from + (window.predicted_present(monotonic_now()) - start));
    render::FrameState state;
    state.mallet_centre = replay.cursor_at(t).shown;
    const bool last = o.frames > 0 && drawn + 1 == o.frames;
    if (window.draw(renderer, state, last && !o.screenshot.empty() ? &shot : nullptr)) ++drawn;
  }
  vkDeviceWaitIdle(ctx.device());
  if (!o.screenshot.empty() && shot.width > 0) {
    render::write_png(shot, o.screenshot);
    std::printf("wrote %s (the last presented frame, %d frames drawn)\n", o.screenshot.string().c_str(), drawn);
  }
  if (ctx.validation_messages() > 0) {
    std::fprintf(stderr, "error: %llu Vulkan validation message(s); first: %s\n",
                 static_cast<unsigned long long>(ctx.validation_messages()), ctx.first_validation_message().c_str());
    finish_with(1);
  }
}

void run_render(const RenderCliOptions& o) {
  // Everything that can be wrong with the input is found before the GPU is touched.
  const AppConfig config = command_settings(o.config, o.config_dir, "render");
  render::HeadlessOptions ho;
  ho.size = render::parse_size(o.size, "--size");
  const Scene file_scene = config::load_scene(o.scene);
  const SceneLayout layout =
      o.layout == "auto" ? layout_for(file_scene, static_cast<double>(ho.size.width) / static_cast<double>(ho.size.height))
                         : *value_named(kSceneLayoutNames, o.layout);
  const Scene scene = laid_out(file_scene, layout);
  input::Trajectory trajectory = input::read_trajectory_csv(o.input);
  InputSpace space = o.input_space == "world" ? InputSpace::world : InputSpace::screen;
  if (o.layout == "auto" && scene.layout != file_scene.layout) {
    // With the layout chosen for the image, the trajectory is one made over the scene as its
    // file lays it out (as `simulate` replays it by default): each sample is taken where it
    // is over the laid-out scene, so that a stroke onto a bar lands on that bar, not on the
    // rail of a row moved under it. A --layout named is the trajectory's own (`mallet
    // trajectory --layout portrait` aims at the stacked rows).
    for (PointerSample& p : trajectory.samples) {
      const Vec2 world = space == InputSpace::screen ? file_scene.screen_to_world.map(p.x, p.y) : Vec2{p.x, p.y};
      const Vec2 moved = to_layout(file_scene, scene, world);
      p.x = moved.x;
      p.y = moved.y;
    }
    space = InputSpace::world;
  }
  const Replay replay(scene, config, trajectory, space, o.input.string());
  if (o.msaa == "auto")
    ho.auto_samples = true;
  else
    ho.settings.samples = sample_count(o.msaa);
  ho.settings.shadow = !o.no_shadow;
  ho.device = o.device;

  if (o.window) {
    if (o.fps && *o.fps != 0 && !(o.to_s >= o.from_s)) throw FileError("--to", 0, 0, "must not be before --from");
    run_window(o, scene, replay, ho);
    return;
  }
  std::vector<std::pair<Nanos, std::filesystem::path>> frames;
  if (o.at_s) {
    if (o.out.empty()) throw FileError("--out", 0, 0, "is required with --at (the PNG to write)");
    frames.push_back({to_nanos(*o.at_s), o.out});
  } else {
    const Nanos from = to_nanos(o.from_s), to = to_nanos(o.to_s);
    if (to < from) throw FileError("--to", 0, 0, "must not be before --from");
    for (std::int64_t k = 0;; ++k) {
      const Nanos t = from + static_cast<Nanos>(std::llround(static_cast<double>(k) * 1e9 / *o.fps));
      if (t > to) break;
      if (k >= 100000) throw FileError("--fps", 0, 0, "more than 100000 frames requested");
      const std::string name = fmt::format("frame_{:06}.png", static_cast<long long>(k));
      frames.push_back({t, o.out_dir / name});
    }
    if (o.out_dir.empty()) throw FileError("--out-dir", 0, 0, "is required with --fps");
    std::filesystem::create_directories(o.out_dir);
  }

  render::HeadlessRenderer renderer(scene, ho);
  std::printf("device: %s\n", renderer.context().device_name().c_str());
  for (const auto& [t, file] : frames) {
    const CursorState c = replay.cursor_at(t);
    render::FrameState state;
    state.mallet_centre = c.shown;
    render::write_png(renderer.render(state), file);
    std::printf("wrote %s  t=%s  mallet=(%.4f, %.4f) m  offset=%.6f m\n", file.string().c_str(),
                format_seconds(t).c_str(), c.shown.x, c.shown.y, c.offset);
  }
  if (renderer.context().validation_messages() > 0) {
    std::fprintf(stderr, "error: %llu Vulkan validation message(s); first: %s\n",
                 static_cast<unsigned long long>(renderer.context().validation_messages()),
                 renderer.context().first_validation_message().c_str());
    finish_with(1);
  }
}

}  // namespace

void register_render(CLI::App& app) {
  auto o = std::make_shared<RenderCliOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render frames of a trajectory offscreen (Vulkan) to PNG");
  cmd->footer(R"(  mallet render --input TRAJ.csv --at SECONDS --size 1280x720 --out frame.png
  mallet render --input TRAJ.csv --fps 60 --from S --to S --out-dir DIR   (DIR/frame_000000.png ...)
The trajectory is replayed through the contact solver, so the mallet's position, its
contacts and the visual vibration (Eq. 1, evaluated at each frame's time on the int64 ns
clock) are the real ones at that moment. Times are on the trajectory's clock (its t column).
Runs on any Vulkan 1.3 device, lavapipe included (no display needed).
  mallet render --input TRAJ.csv --window [--fps 60 --from S --to S | --at S] [--frames N --screenshot F]
shows the same frames in a window through the swapchain (needs a display).
Exit status: 0 written, 1 renderer failure, 2 bad input (FILE:LINE: problem).)");
  cmd->add_option("--scene", o->scene, "Scene file")->capture_default_str()->check(CLI::ExistingFile);
  cmd->add_option("--input", o->input, "Trajectory CSV (t,x,y)")->required();
  add_settings_options(*cmd, o->config, o->config_dir);
  cmd->add_option("--input-space", o->input_space, "screen: x,y normalised 0..1; world: sphere centre in metres")
      ->check(CLI::IsMember({"screen", "world"}))
      ->capture_default_str();
  cmd->add_option("--size", o->size, "Image size WIDTHxHEIGHT")->capture_default_str()->check(pixel_size());
  cmd->add_option("--layout", o->layout,
                  "auto (as the kiosk lays the scene out for --size: portrait, instruments stacked, on a "
                  "portrait image where that shows them larger; the trajectory, made over the scene file's "
                  "landscape layout, is moved with the instrument it is over), landscape or portrait (the "
                  "trajectory is taken as made in that layout: mallet trajectory --layout)")
      ->check(CLI::IsMember({"auto", "landscape", "portrait"}))
      ->capture_default_str();
  auto* at = cmd->add_option("--at", o->at_s, "One frame at this time (s)")->check(seconds());
  auto* out = cmd->add_option("--out", o->out, "PNG file for --at");
  auto* fps = cmd->add_option("--fps", o->fps, "A sequence at this frame rate")
                  ->check(positive_at_most(1000.0));
  auto* from = cmd->add_option("--from", o->from_s, "Sequence start (s)")->check(seconds());
  auto* to = cmd->add_option("--to", o->to_s, "Sequence end (s, included)")->check(seconds());
  auto* out_dir = cmd->add_option("--out-dir", o->out_dir, "Directory for the sequence's PNG files");
  at->excludes(fps);
  fps->needs(from)->needs(to);
  (void)out;
  (void)out_dir;
  cmd->add_option("--msaa", o->msaa,
                  "Antialiasing: MSAA samples 1, 2, 4 or 8 (as the device offers; lavapipe: 1, 4), or auto "
                  "(what the kiosk uses: on a CPU rasteriser 4 for the cached instruments and 1 for the mallet, "
                  "4 on a GPU)")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "1", "2", "4", "8"}));
  cmd->add_flag("--no-shadow", o->no_shadow, "Leave out the mallet's cast shadow");
  cmd->add_option("--device", o->device, "Vulkan device to use (substring of its name)");
  cmd->add_flag("--window", o->window,
                "Show the frames in a window instead (a sequence plays in real time; --at holds)");
  cmd->add_option("--frames", o->frames, "With --window: stop after this many frames (0 = until closed)")
      ->capture_default_str();
  cmd->add_option("--screenshot", o->screenshot, "With --window: write the last presented frame to this PNG");
  add_choice(*cmd, "--present-mode", o->present_mode, kPresentPacingNames,
             "With --window: fifo (vsync), mailbox or immediate");
  cmd->callback([o, at, fps] {
    if (at->count() == 0 && fps->count() == 0) throw CLI::ValidationError("--at or --fps", "one of them is required");
    run_render(*o);
  });
}

}  // namespace mallet::app
