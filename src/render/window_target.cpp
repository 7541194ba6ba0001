#include "render/window_target.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <map>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include "render/gpu_resources.hpp"
#include "render/vk_error.hpp"

namespace mallet::render {

namespace {
//! The target drawing into each window, for the window system's "draw it again" (an expose:
//! the window was covered and is shown again, and nothing on screen holds its pixels).
//! GLFW calls back on the thread that polls its events, the one that draws.
std::map<GLFWwindow*, WindowTarget*>& targets_of_windows() {
  static std::map<GLFWwindow*, WindowTarget*> targets;
  return targets;
}

//! How the present model paces a swapchain's frames.
PresentPacing clock_pacing(VkPresentModeKHR mode) {
  return mode == VK_PRESENT_MODE_MAILBOX_KHR     ? PresentPacing::mailbox
         : mode == VK_PRESENT_MODE_IMMEDIATE_KHR ? PresentPacing::immediate
                                                 : PresentPacing::fifo;
}
}  // namespace

WindowSystem::WindowSystem() {
  if (!glfwInit()) {
    const char* why = nullptr;
    glfwGetError(&why);
    throw RenderError(std::string("cannot open the display (GLFW: ") + (why ? why : "unknown") + ")");
  }
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    throw RenderError("GLFW found no Vulkan loader (Debian: libvulkan1)");
  }
}

WindowSystem::~WindowSystem() { glfwTerminate(); }

std::vector<std::string> WindowSystem::instance_extensions() {
  std::uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  return std::vector<std::string>(names, names + count);
}

bool WindowSystem::display_available() {
  const char* x = std::getenv("DISPLAY");
  const char* w = std::getenv("WAYLAND_DISPLAY");
  return (x && *x) || (w && *w);
}

WindowTarget::WindowTarget(const Context& ctx, const WindowOptions& options, PresentClock* clock, GLFWwindow* adopt)
    : ctx_(ctx), options_(options), clock_(clock ? clock : &own_clock_) {
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  // GLFW centres the cursor in a new fullscreen window by warping it there, and from then on
  // takes any motion that ends exactly where it warped for its own: a visitor's (or a touch
  // screen's, a remote desktop's) move to the screen's very centre was never seen. The
  // cursor is left where it is (the kiosk asks where: seed_window_cursor).
  glfwWindowHint(GLFW_CENTER_CURSOR, GLFW_FALSE);
  GLFWmonitor* monitor = nullptr;
  int width = options.width, height = options.height;
  int monitor_count = 0;
  GLFWmonitor** monitors = glfwGetMonitors(&monitor_count);
  if (monitor_count > 0) {
    GLFWmonitor* m = monitors[std::clamp(options.monitor, 0, monitor_count - 1)];
    if (const GLFWvidmode* mode = glfwGetVideoMode(m)) {
      if (mode->refreshRate > 0) refresh_hz_ = mode->refreshRate;
      clock_->set_refresh_hz(refresh_hz_);
      if (options.fullscreen) {  // borderless: the monitor's own mode, no mode switch
        glfwWindowHint(GLFW_RED_BITS, mode->redBits);
        glfwWindowHint(GLFW_GREEN_BITS, mode->greenBits);
        glfwWindowHint(GLFW_BLUE_BITS, mode->blueBits);
        glfwWindowHint(GLFW_REFRESH_RATE, mode->refreshRate);
        width = mode->width;
        height = mode->height;
        monitor = m;
      }
    }
  }
  window_ = adopt ? adopt : glfwCreateWindow(width, height, options.title.c_str(), monitor, nullptr);
  if (!window_) {
    const char* why = nullptr;
    glfwGetError(&why);
    throw RenderError(std::string("cannot create the window (GLFW: ") + (why ? why : "unknown") + ")");
  }
  if (options.hide_cursor) glfwSetInputMode(window_, GLFW_CURSOR, GLFW_CURSOR_HIDDEN);
  targets_of_windows()[window_] = this;
  glfwSetWindowRefreshCallback(window_, [](GLFWwindow* w) {
    if (const auto t = targets_of_windows().find(w); t != targets_of_windows().end()) t->second->show_again();
  });
  if (options.put_changes && ctx.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) {
    auto put = X11ImagePut::open(window_);
    if (put) {
      put_ = std::move(*put);
      presentation_ = "only the changed pixels, put into the X11 window";
      format_ = VK_FORMAT_B8G8R8A8_SRGB;  // the X server's byte order
      present_mode_ = VK_PRESENT_MODE_IMMEDIATE_KHR;
      clock_->set_pacing(PresentPacing::immediate);  // on the server as soon as it is put
      create_picture();
      return;
    }
    put_refused_ = "; not the changed pixels alone: " + put.error();
  }
  check(glfwCreateWindowSurface(ctx.instance(), window_, nullptr, &surface_), "creating the window surface");
  VkBool32 supported = VK_FALSE;
  vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physical_device(), ctx.queue_family(), surface_, &supported);
  if (!supported) throw RenderError("the Vulkan device cannot present to this window");

  frames_.resize(SceneRenderer::kSlots);
  for (FrameSync& f : frames_) {
    f.cmd = ctx.allocate_command_buffer();
    f.acquired = ctx.make_semaphore();
    f.done = ctx.make_fence(/*signaled=*/true);
  }
  create_swapchain();
}

WindowTarget::~WindowTarget() {
  vkDeviceWaitIdle(ctx_.device());
  for (FrameSync& f : frames_) ctx_.free_command_buffer(f.cmd);
  frames_.clear();
  views_.clear();
  rendered_.clear();
  swapchain_.reset();
  if (surface_) vkDestroySurfaceKHR(ctx_.instance(), surface_, nullptr);
  picture_.reset();
  put_.reset();
  if (window_) {
    targets_of_windows().erase(window_);
    glfwDestroyWindow(window_);
  }
}

GLFWwindow* WindowTarget::release_window() {
  targets_of_windows().erase(window_);
  return std::exchange(window_, nullptr);
}

bool WindowTarget::close_requested() const { return glfwWindowShouldClose(window_); }

std::pair<int, int> WindowTarget::framebuffer_size() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return {w, h};
}

bool WindowTarget::framebuffer_visible(std::pair<int, int> size) const {
  // Minimised: iconified, or on X11 unmapped (hidden); elsewhere a 0×0 framebuffer.
  if (glfwGetWindowAttrib(window_, GLFW_ICONIFIED) || !glfwGetWindowAttrib(window_, GLFW_VISIBLE)) return false;
  return size.first > 0 && size.second > 0;
}

void WindowTarget::create_picture() {
  built_for_ = framebuffer_size();
  extent_ = {static_cast<std::uint32_t>(std::max(built_for_.first, 1)),
             static_cast<std::uint32_t>(std::max(built_for_.second, 1))};
  picture_.reset();  // waits for the device
  picture_ = std::make_unique<OffscreenTarget>(ctx_, extent_, format_);
  picture_->keep_frames(true);
  show_again();  // a new image, never shown
}

bool WindowTarget::draw_and_put(SceneRenderer& renderer, const FrameState& state, Image* capture) {
  if (show_again_) picture_->draw_whole();
  picture_->draw(renderer, state);  // waits for it
  put_->put(picture_->pixels(), static_cast<int>(extent_.width), static_cast<int>(extent_.height),
            static_cast<std::size_t>(picture_->row_pitch()), picture_->changed());
  show_again_ = false;
  if (capture) *capture = picture_->read_back();
  return true;
}

void WindowTarget::recreate_swapchain() {
  vkDeviceWaitIdle(ctx_.device());  // the old swapchain's images may be in use
  create_swapchain();
  ++recreations_;
}

void WindowTarget::create_swapchain() {
  VkPhysicalDevice pd = ctx_.physical_device();
  built_for_ = framebuffer_size();
  VkSurfaceCapabilitiesKHR caps;
  check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(pd, surface_, &caps), "querying the window surface");
  std::uint32_t n = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface_, &n, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(n);
  vkGetPhysicalDeviceSurfaceFormatsKHR(pd, surface_, &n, formats.data());
  if (formats.empty()) throw RenderError("the window surface offers no format");
  VkSurfaceFormatKHR chosen = formats[0];
  for (const VkSurfaceFormatKHR& f : formats)
    if ((f.format == VK_FORMAT_B8G8R8A8_SRGB || f.format == VK_FORMAT_R8G8B8A8_SRGB) &&
        f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
      chosen = f;
      break;
    }
  if (format_ != VK_FORMAT_UNDEFINED && chosen.format != format_)
    throw RenderError("the window surface changed its pixel format");
  format_ = chosen.format;

  vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface_, &n, nullptr);
  std::vector<VkPresentModeKHR> modes(n);
  vkGetPhysicalDeviceSurfacePresentModesKHR(pd, surface_, &n, modes.data());
  const VkPresentModeKHR wanted = options_.present_mode == PresentMode::mailbox     ? VK_PRESENT_MODE_MAILBOX_KHR
                                  : options_.present_mode == PresentMode::immediate ? VK_PRESENT_MODE_IMMEDIATE_KHR
                                                                                     : VK_PRESENT_MODE_FIFO_KHR;
  present_mode_ = std::find(modes.begin(), modes.end(), wanted) != modes.end() ? wanted : VK_PRESENT_MODE_FIFO_KHR;
  presentation_ = std::string("a Vulkan swapchain (") + to_string(clock_pacing(present_mode_)) + ")" + put_refused_;
  clock_->set_pacing(clock_pacing(present_mode_));

  if (caps.currentExtent.width != UINT32_MAX) {
    extent_ = caps.currentExtent;
  } else {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    extent_ = {std::clamp(static_cast<std::uint32_t>(w), caps.minImageExtent.width, caps.maxImageExtent.width),
               std::clamp(static_cast<std::uint32_t>(h), caps.minImageExtent.height, caps.maxImageExtent.height)};
  }
  std::uint32_t count = caps.minImageCount + 1;
  if (caps.maxImageCount > 0) count = std::min(count, caps.maxImageCount);

  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = surface_;
  ci.minImageCount = count;
  ci.imageFormat = chosen.format;
  ci.imageColorSpace = chosen.colorSpace;
  ci.imageExtent = extent_;
  ci.imageArrayLayers = 1;
  // TRANSFER_SRC for screenshots; TRANSFER_DST to copy the renderer's cached background in
  // (without it every frame draws the whole scene).
  ci.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                  (caps.supportedUsageFlags & (VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT));
  copy_destination_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT) != 0;
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                          ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                          : static_cast<VkCompositeAlphaFlagBitsKHR>(caps.supportedCompositeAlpha &
                                                                     (~caps.supportedCompositeAlpha + 1));
  ci.presentMode = present_mode_;
  ci.clipped = VK_TRUE;
  ci.oldSwapchain = swapchain_.get();
  VkSwapchainKHR raw;
  check(vkCreateSwapchainKHR(ctx_.device(), &ci, nullptr, &raw), "creating the swapchain");
  views_.clear();
  rendered_.clear();
  swapchain_ = vk::Swapchain(ctx_.device(), raw);  // destroys the old one (the device is idle)
  show_again();  // new images, never shown

  vkGetSwapchainImagesKHR(ctx_.device(), raw, &n, nullptr);
  images_.resize(n);
  vkGetSwapchainImagesKHR(ctx_.device(), raw, &n, images_.data());
  for (VkImage image : images_) {
    views_.push_back(
        make_image_view(ctx_.device(), image, format_, VK_IMAGE_ASPECT_COLOR_BIT, "creating a swapchain image view"));
    rendered_.push_back(ctx_.make_semaphore());
  }
  kept_.assign(images_.size(), false);  // nothing drawn into them yet
}

bool WindowTarget::draw(SceneRenderer& renderer, const FrameState& state, Image* capture) {
  still_ = false;
  const std::pair<int, int> size = framebuffer_size();  // asked of the window system once a frame
  if (!framebuffer_visible(size)) {
    // Minimised: nothing to draw into. Waiting up to a refresh for the window's events keeps
    // the callers' loops from spinning a core until it comes back, shown whole (an unmapped
    // X11 window keeps no pixels; its expose may come after the next frame).
    glfwWaitEventsTimeout(1.0 / refresh_hz_);
    show_again();
    return false;
  }
  if (const VkResult injected = std::exchange(injected_, VK_SUCCESS); injected != VK_SUCCESS)
    check(injected, "submitting a frame (an injected fault)");
  VkDevice dev = ctx_.device();
  // Not every driver says OUT_OF_DATE when the window changes size (lavapipe on X11 goes
  // on presenting the old size, measured): the window's own size is checked too.
  if (size != built_for_) {
    if (put_) {
      create_picture();
      ++recreations_;
    } else {
      recreate_swapchain();
    }
  }
  // A frame that would change nothing is not drawn: the screen shows it already.
  still_ = options_.skip_unchanged && !capture && !show_again_ && !renderer.changes(state, extent_);
  if (still_) return false;
  if (put_) {
    display_wait_ns_ = 0;  // its own put: no swapchain to wait on
    return draw_and_put(renderer, state, capture);
  }
  FrameSync& f = frames_[frame_];
  VkFence fence = f.done.get();
  check(vkWaitForFences(dev, 1, &fence, VK_TRUE, UINT64_MAX), "waiting for a frame");

  std::uint32_t index = 0;
  const Nanos acquire_from = monotonic_now();
  for (int attempt = 0;; ++attempt) {
    const VkResult r = vkAcquireNextImageKHR(dev, swapchain_.get(), UINT64_MAX, f.acquired.get(), VK_NULL_HANDLE,
                                             &index);
    if (r == VK_SUCCESS || r == VK_SUBOPTIMAL_KHR) break;
    if (r == VK_ERROR_OUT_OF_DATE_KHR && attempt < 3) {
      if (!framebuffer_visible(framebuffer_size())) return false;
      recreate_swapchain();
      continue;
    }
    check(r, "acquiring a swapchain image");
  }
  display_wait_ns_ = monotonic_now() - acquire_from;
  check(vkResetFences(dev, 1, &fence), "resetting a fence");

  check(vkResetCommandBuffer(f.cmd, 0), "resetting a command buffer");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(f.cmd, &bi), "beginning a command buffer");
  const VkDeviceSize capture_bytes = VkDeviceSize{extent_.width} * extent_.height * 4;
  if (capture) {
    if (capture_buffer_.size < capture_bytes)
      capture_buffer_ = make_host_buffer(ctx_, capture_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    renderer.record(f.cmd,
                    {images_[index], views_[index].get(), extent_, copy_destination_,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                     kept_[index], VK_IMAGE_LAYOUT_PRESENT_SRC_KHR},
                    state, frame_);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {extent_.width, extent_.height, 1};
    vkCmdCopyImageToBuffer(f.cmd, images_[index], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, capture_buffer_.buffer.get(),
                           1, &region);
    transition(f.cmd, images_[index], VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
               VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
               VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE);
  } else {
    renderer.record(f.cmd,
                    {images_[index], views_[index].get(), extent_, copy_destination_, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                     VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, kept_[index], VK_IMAGE_LAYOUT_PRESENT_SRC_KHR},
                    state, frame_);
  }
  check(vkEndCommandBuffer(f.cmd), "ending a command buffer");

  VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  wait.semaphore = f.acquired.get();
  wait.stageMask = kTargetFirstUse;
  VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  signal.semaphore = rendered_[index].get();
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkCommandBufferSubmitInfo cbi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cbi.commandBuffer = f.cmd;
  VkSubmitInfo2 si{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  si.waitSemaphoreInfoCount = 1;
  si.pWaitSemaphoreInfos = &wait;
  si.commandBufferInfoCount = 1;
  si.pCommandBufferInfos = &cbi;
  si.signalSemaphoreInfoCount = 1;
  si.pSignalSemaphoreInfos = &signal;
  check(vkQueueSubmit2(ctx_.queue(), 1, &si, fence), "submitting a frame");

  VkSemaphore rendered = rendered_[index].get();
  VkSwapchainKHR sc = swapchain_.get();
  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &rendered;
  pi.swapchainCount = 1;
  pi.pSwapchains = &sc;
  pi.pImageIndices = &index;
  const Nanos present_from = monotonic_now();
  const VkResult pr = vkQueuePresentKHR(ctx_.queue(), &pi);
  display_wait_ns_ += monotonic_now() - present_from;
  // The image keeps this frame for the next time it comes round (the presentation engine
  // only reads it); the window shows a whole picture again.
  kept_[index] = true;
  show_again_ = false;
  if (capture) {
    check(vkWaitForFences(dev, 1, &fence, VK_TRUE, UINT64_MAX), "waiting for a frame");
    *capture = Image(static_cast<int>(extent_.width), static_cast<int>(extent_.height));
    std::memcpy(capture->rgba.data(), capture_buffer_.mapped, capture_bytes);
    if (format_ == VK_FORMAT_B8G8R8A8_SRGB || format_ == VK_FORMAT_B8G8R8A8_UNORM)
      for (std::size_t i = 0; i < capture->rgba.size(); i += 4) std::swap(capture->rgba[i], capture->rgba[i + 2]);
  }
  frame_ = (frame_ + 1) % SceneRenderer::kSlots;
  if (pr == VK_ERROR_OUT_OF_DATE_KHR || pr == VK_SUBOPTIMAL_KHR) {
    if (framebuffer_visible(framebuffer_size())) recreate_swapchain();
  } else {
    check(pr, "presenting a frame");
  }
  return true;
}

}  // namespace mallet::render
