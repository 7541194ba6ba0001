#pragma once
// Everything a headless frame needs, in one owner: the Vulkan context, the persisted
// pipeline cache, the scene renderer and an offscreen target. Used by `mallet render`,
// `mallet bench render`, the golden tests and the headless kiosk. And the pieces every
// full-screen window of the product (the kiosk, the study) builds the same way from the
// [render] settings.
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/app_config.hpp"
#include "core/scene.hpp"
#include "core/frame_pacer.hpp"
#include "core/view_aspect.hpp"
#include "render/font_atlas.hpp"
#include "render/offscreen_target.hpp"
#include "render/overlay.hpp"
#include "render/pipeline_cache.hpp"
#include "render/scene_renderer.hpp"
#include "render/vk_context.hpp"
#include "render/window_target.hpp"

namespace mallet::render {

//! MALLET_VK_VALIDATION: "0" off, "1" if available, "required"; unset: on (if
//! available) in Debug builds, off otherwise.
render::Validation validation_from_env();

//! "1280x720" → {1280, 720}; throws FileError naming `option` otherwise.
VkExtent2D parse_size(const std::string& text, const std::string& option);

struct HeadlessOptions {
  VkExtent2D size{1280, 720};
  render::RenderSettings settings;
  bool auto_samples = false;          //!< replace settings' samples by render::use_recommended_antialiasing
  std::string device;                 //!< substring of the Vulkan device name; empty = best
  render::Validation validation = validation_from_env();
  std::filesystem::path cache_dir = render::PipelineCache::default_dir();
  std::filesystem::path models;  //!< where the scene's models are; empty = the shipped models_dir()
};

//! The kiosk's offscreen renderer as its settings choose it ([render] msaa, shadow, device;
//! `device` overrides the device when not empty): the headless run and `mallet doctor`.
HeadlessOptions kiosk_headless_options(const RenderConfig& r, VkExtent2D size, const std::string& device);

class HeadlessRenderer {
 public:
  HeadlessRenderer(const Scene& scene, const HeadlessOptions& options);
  ~HeadlessRenderer();

  render::Image render(const render::FrameState& state) { return target_->render(*renderer_, state); }
  void draw(const render::FrameState& state) { target_->draw(*renderer_, state); }
  render::Image read_back() const { return target_->read_back(); }

  render::Context& context() { return *ctx_; }
  render::SceneRenderer& renderer() { return *renderer_; }
  render::OffscreenTarget& target() { return *target_; }
  const render::PipelineCache& pipeline_cache() const { return *cache_; }

 private:
  std::unique_ptr<render::Context> ctx_;
  std::unique_ptr<render::PipelineCache> cache_;
  std::unique_ptr<render::SceneRenderer> renderer_;
  std::unique_ptr<render::OffscreenTarget> target_;
};

//! The shipped models: DATA/models.
std::filesystem::path models_dir();

// ---- a window on the display ----

//! A Vulkan context that can present to a window (validation from the environment);
//! `device`: a substring of the device's name, empty = the best one.
std::unique_ptr<render::Context> make_window_context(const std::string& device);

//! Fullscreen on [render] monitor with the OS cursor hidden, or a `size` window when
//! `windowed`; [render] present_mode. `size` is "WIDTHxHEIGHT" (FileError naming --size).
render::WindowOptions window_options(const RenderConfig& r, const std::string& size, bool windowed);

//! [render] msaa ("auto": what the device is recommended) and shadow, as renderer settings.
render::RenderSettings render_settings(const render::Context& ctx, const RenderConfig& r);

//! Every text of the kiosk's catalogue (the template's, in the visitor's language) and the
//! digits: what a window's font warms before its first frame.
std::vector<std::string> screen_texts();

//! The overlay's font, sized for a window of this size: a 24th of its shorter side (the height
//! of a landscape screen, the width of a portrait one), at least 14 px; each language in the
//! family [fonts] names for it, else Noto's (render/font_fallback.hpp).
std::unique_ptr<render::FontAtlas> overlay_font(VkExtent2D extent, const std::map<std::string, std::string>& fonts = {});

//! A window of the product (the kiosk's, the study's), made from the [render] settings in
//! the order its parts need and unmade in reverse: GLFW, a Vulkan context that presents
//! (`device`, else [render] device), the persisted pipeline cache, the window (see
//! window_options), the overlay's font and the overlay. A renderer drawing into it must be
//! destroyed before it.
struct ProductWindow {
  ProductWindow(const RenderConfig& r, const std::string& device, const std::string& size, bool windowed,
                const std::string& title);
  //! After VK_ERROR_DEVICE_LOST: a new Vulkan context (instance and device), pipeline cache
  //! and window target, on the same GLFW window (its place, size and callbacks stay) and the
  //! same present model (`clock`, which the strike routes of other threads read meanwhile).
  //! Every renderer drawing into it must be destroyed before. Throws RenderError when the
  //! new device cannot be made; it may then be called again.
  void rebuild();
  //! Draws and presents a frame (WindowTarget::draw); true when one was drawn. When the
  //! device is lost (VK_ERROR_DEVICE_LOST): says so on stderr, calls `drop` (the caller
  //! destroys what it made on the device: its renderer), rebuild()s (five tries, a second
  //! apart), calls `make` (the caller makes it anew), says how long it took and returns
  //! false. Rethrows when no new device can be made. The fault-injecting seam for tests:
  //! MALLET_INJECT_DEVICE_LOST="N[,M…]" makes the draws after the Nth (Mth…) frame fail so.
  bool draw_or_recover(render::SceneRenderer& renderer, const render::FrameState& state,
                       const std::function<void()>& drop, const std::function<void()>& make);
  std::uint64_t devices_lost() const { return devices_lost_; }
  //! The frame budget ([render] max_fps; 0 = the refresh, never above it; < 0, only from
  //! `mallet run --no-frame-cap`: none): called before each frame, it waits until the
  //! frame's slot. A FIFO display that paces the frames itself (the present model's
  //! verdict, from its first frames' own pace, none held back until then) is left to do
  //! so, unless max_fps is below its refresh. Says in the log what it chose and why, once,
  //! and again only when that changes (a reload's max_fps, a display judged again).
  void pace();
  void set_max_fps(double max_fps);
  //! How long the last pace() held the frame back: PresentClock::frame_started's held_ns.
  Nanos held_ns() const { return held_ns_; }

  render::WindowSystem glfw;
  PresentClock clock;  //!< outlives every window target made for this window
  //! The window's proportions, after each frame drawn: the pointers' threads frame the
  //! scene with them as the renderer frames the picture.
  ViewAspect aspect;
  std::string device_name;
  render::WindowOptions options;
  GLFWwindow* kept_window = nullptr;  //!< between a release and a rebuild that succeeded
  std::unique_ptr<render::Context> ctx;
  std::unique_ptr<render::PipelineCache> cache;
  std::unique_ptr<render::WindowTarget> window;
  std::unique_ptr<render::FontAtlas> font;
  std::unique_ptr<render::Overlay> overlay;
  //! How the frames are paced, as the log last said it ("render: frames paced at 60 a
  //! second, ..."); empty until said. The operator page's timing line says the same words.
  const std::string& pace_said() const { return pace_said_; }

 private:
  std::uint64_t frames_ = 0, devices_lost_ = 0;
  double max_fps_ = 0;
  std::string pace_said_;  //!< the pace's line last said in the log
  void say_pace(std::string line);
  //! What pace() chose, and from what: its line is said when this changes.
  struct PaceChoice {
    bool pace = false, display_paces = false;
    double cap = 0, refresh = 0;
    int fast_frames = 0;
    const render::WindowTarget* window = nullptr;
    bool operator==(const PaceChoice&) const = default;
  };
  PaceChoice pace_chosen_;
  void say_pace_choice(const PaceChoice& choice);
  Nanos held_ns_ = 0;
  FramePacer pacer_;
  std::vector<std::uint64_t> inject_lost_at_;  //!< frame counts, ascending
};

}  // namespace mallet::render
