#pragma once
// Rendering into a GLFW window: the kiosk's screen. Through a Vulkan swapchain, or, where
// the device is a CPU rasteriser (lavapipe) and the window is on X11, into an image in
// memory whose changed pixels alone are put into the window (render/x11_image_put.hpp: a
// whole frame through the X socket each time cost the kiosk more than its drawing).
// Resizes, minimising (an iconified or hidden window, or a 0×0 framebuffer: frames are
// skipped, nothing is recreated until it comes back) and VK_ERROR_OUT_OF_DATE_KHR / VK_SUBOPTIMAL_KHR (the swapchain is
// recreated and the frame retried) are handled here; the caller only calls draw().
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "core/present_clock.hpp"
#include "core/time.hpp"
#include "render/gpu_resources.hpp"
#include "render/image.hpp"
#include "render/offscreen_target.hpp"
#include "render/scene_renderer.hpp"
#include "render/x11_image_put.hpp"

struct GLFWwindow;

namespace mallet::render {

//! The present mode asked for: core's, which also models when its frames are shown.
using PresentMode = PresentPacing;

struct WindowOptions {
  int width = 1280, height = 720;
  bool fullscreen = false;  //!< borderless on `monitor`, at its mode
  int monitor = 0;          //!< index in glfwGetMonitors
  PresentMode present_mode = PresentMode::fifo;  //!< falls back to FIFO when not offered
  std::string title = "Mallet";
  bool hide_cursor = false;
  //! A frame that would change nothing on the screen (SceneRenderer::changes) is not drawn:
  //! draw() returns false and still() says why. Off for a fixed count of frames (`mallet
  //! render --window --frames`).
  bool skip_unchanged = true;
  //! A CPU rasteriser's frames in an X11 window: only the pixels that changed are put
  //! (X11ImagePut), shown as soon as they are put (PresentPacing::immediate). False: the
  //! Vulkan swapchain (Mesa then sends each whole frame). A GPU always uses the swapchain.
  bool put_changes = true;
};

//! GLFW itself: initialised once per process, before the Vulkan instance (which needs its
//! surface extensions). Throws RenderError when there is no display.
class WindowSystem {
 public:
  WindowSystem();
  ~WindowSystem();
  WindowSystem(const WindowSystem&) = delete;
  WindowSystem& operator=(const WindowSystem&) = delete;
  static std::vector<std::string> instance_extensions();
  static bool display_available();  //!< DISPLAY or WAYLAND_DISPLAY is set
};

class WindowTarget {
 public:
  //! A new window, or `adopt`: the window of a target released before (release_window),
  //! kept with its place, size and callbacks when the device under it is rebuilt. `clock`:
  //! a present model owned by the caller, which then outlives this target (the strike
  //! routes of other threads keep reading it while the target is rebuilt); else its own.
  WindowTarget(const Context& ctx, const WindowOptions& options, PresentClock* clock = nullptr,
               GLFWwindow* adopt = nullptr);
  ~WindowTarget();
  WindowTarget(const WindowTarget&) = delete;
  WindowTarget& operator=(const WindowTarget&) = delete;

  GLFWwindow* window() const { return window_; }
  VkFormat format() const { return format_; }
  VkPresentModeKHR present_mode() const { return present_mode_; }
  VkExtent2D extent() const { return extent_; }
  //! How frames reach the window, for the log: "a Vulkan swapchain (fifo)", or "only the
  //! changed pixels, put into the X11 window" (and why not, where it was asked and not had).
  const std::string& presentation() const { return presentation_; }
  //! Pixels put into the X11 window so far (0 through the swapchain).
  std::uint64_t pixels_put() const { return put_ ? put_->pixels_put() : 0; }
  bool close_requested() const;
  std::uint64_t swapchain_recreations() const { return recreations_; }
  //! Hands the GLFW window over: this target's destructor then frees its Vulkan objects
  //! (surface, swapchain) but leaves the window open, for a new target to adopt.
  GLFWwindow* release_window();
  //! The fault-injecting seam for a lost device, which cannot be had on demand: the next
  //! draw() fails as if the queue had returned `result` (a RenderError carrying it).
  void fail_next_draw(VkResult result) { injected_ = result; }

  //! When the frame about to be drawn should reach the screen (present_clock()'s model:
  //! FIFO = now + the frames queued ahead of it times the refresh period). The visual
  //! vibration is evaluated there, not at the time the frame is recorded.
  Nanos predicted_present(Nanos now) const { return clock_->present_of_frame_started(now); }
  //! The swapchain's present model: its pacing (the present mode in use), the display's
  //! refresh, refined by the frame starts the caller reports (frame_started). The strike
  //! route reads it from other threads to align the sound with the picture.
  PresentClock& present_clock() { return *clock_; }
  //! The monitor's refresh rate as the window system reports it (60 when it does not).
  double refresh_hz() const { return refresh_hz_; }
  const PresentClock& present_clock() const { return *clock_; }

  //! Draws and presents one frame; false when nothing was drawn (minimised: it then waits
  //! up to one refresh for window events, so a loop around it does not spin). With
  //! `capture`, the presented pixels are also copied out (RGBA) for a screenshot.
  //! Each frame draws only what changed since the swapchain image last showed (the images
  //! keep their pixels: FrameTarget::kept), and a frame that changes nothing is not drawn
  //! (WindowOptions::skip_unchanged) unless the window must be shown again (an expose, a
  //! new swapchain) or `capture` is asked.
  bool draw(SceneRenderer& renderer, const FrameState& state, Image* capture = nullptr);
  //! The last draw() drew nothing because nothing had changed (not because the window was minimised).
  bool still() const { return still_; }
  //! How long the last frame drawn waited in the swapchain's acquire and present (0 where
  //! it put its image itself): PresentClock::frame_started's display_wait_ns.
  Nanos display_wait_ns() const { return display_wait_ns_; }
  //! The next frame is drawn and shown even if it changes nothing (the window was exposed).
  void show_again() { show_again_ = true; }

 private:
  struct FrameSync {
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    vk::Semaphore acquired;
    vk::Fence done;
  };
  void create_swapchain();
  void create_picture();  //!< put_changes: the image frames are drawn into, at the window's size
  bool draw_and_put(SceneRenderer& renderer, const FrameState& state, Image* capture);
  void recreate_swapchain();  //!< waits for the device, makes a new one, counts it
  bool framebuffer_visible(std::pair<int, int> size) const;
  std::pair<int, int> framebuffer_size() const;

  const Context& ctx_;
  WindowOptions options_;
  GLFWwindow* window_ = nullptr;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  vk::Swapchain swapchain_;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  bool copy_destination_ = false;  //!< the swapchain's images take TRANSFER_DST
  std::pair<int, int> built_for_{};  //!< the framebuffer size the swapchain was made for
  VkPresentModeKHR present_mode_ = VK_PRESENT_MODE_FIFO_KHR;
  VkExtent2D extent_{};
  std::vector<VkImage> images_;
  std::vector<vk::ImageView> views_;
  std::vector<vk::Semaphore> rendered_;  //!< one per swapchain image
  std::vector<bool> kept_;  //!< per swapchain image: it holds a frame the renderer drew (was presented)
  bool still_ = false, show_again_ = true;
  Nanos display_wait_ns_ = 0;
  std::vector<FrameSync> frames_;
  std::uint32_t frame_ = 0;
  std::uint64_t recreations_ = 0;
  double refresh_hz_ = 60.0;
  PresentClock own_clock_;
  PresentClock* clock_ = &own_clock_;
  VkResult injected_ = VK_SUCCESS;
  GpuBuffer capture_buffer_;
  std::unique_ptr<X11ImagePut> put_;         //!< put_changes, had: no surface, no swapchain
  std::unique_ptr<OffscreenTarget> picture_;  //!< what put_ shows, drawn as kept frames
  std::string presentation_;
  std::string put_refused_;  //!< why put_changes was not had ("; not ...: why"), or empty
};

}  // namespace mallet::render
