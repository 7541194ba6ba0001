// The window target in this process, under a virtual X server of its own (CTest runs this
// binary through xvfb-run), both ways lavapipe's frames reach the window: only the changed
// pixels put into it (the kiosk's way on a CPU rasteriser) and the Vulkan swapchain (a
// GPU's way). A window resized while frames are drawn gets the frames of its new size, drawn
// over the renderer's cached background (redrawn for the new size); a hidden (minimised)
// window draws nothing and comes back when shown; a frame that changes nothing is not drawn,
// and one that does draws only what changed. Each time the X server is asked what the
// window shows.
#include <GLFW/glfw3.h>

#include <gtest/gtest.h>

#include "render/render_setup.hpp"
#include "render/image.hpp"
#include "render/pipeline_cache.hpp"
#include "render/scene_renderer.hpp"
#include "render/window_target.hpp"
#include "test_paths.hpp"

// Last: Xlib's macros (None, Status, Bool…) must not meet the headers above.
#define GLFW_EXPOSE_NATIVE_X11
#include <GLFW/glfw3native.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>

namespace mallet::render {
namespace {

struct OpenWindow {
  WindowSystem system;
  std::unique_ptr<Context> ctx;
  std::unique_ptr<WindowTarget> target;
  std::unique_ptr<PipelineCache> cache;
  std::unique_ptr<SceneRenderer> renderer;

  OpenWindow(VkSampleCountFlagBits samples, bool put_changes) {
    ContextOptions co;
    co.validation = Validation::required;
    co.device_name = "llvmpipe";
    co.instance_extensions = WindowSystem::instance_extensions();
    co.swapchain = true;
    ctx = std::make_unique<Context>(co);
    WindowOptions wo;
    wo.width = 320;
    wo.height = 180;
    wo.put_changes = put_changes;
    target = std::make_unique<WindowTarget>(*ctx, wo);
    // lavapipe is a CPU rasteriser: the changed pixels are put where asked, on Xvfb.
    EXPECT_EQ(target->presentation().starts_with("only the changed pixels"), put_changes) << target->presentation();
    EXPECT_EQ(target->present_clock().pacing() == PresentPacing::immediate, put_changes);
    cache = std::make_unique<PipelineCache>(*ctx, "");
    RenderSettings rs;
    rs.samples = samples;
    rs.background_samples = VK_SAMPLE_COUNT_4_BIT;  // with 1 sample per frame: what the kiosk does on lavapipe
    renderer = std::make_unique<SceneRenderer>(*ctx, test::percussion(), render::models_dir(), target->format(), rs,
                                               cache->get());
  }
  ~OpenWindow() { vkDeviceWaitIdle(ctx->device()); }
};

FrameState mallet_over_a_bar() {
  const Target& bar = test::percussion().targets.at(5);
  FrameState s;
  s.mallet_centre = {(bar.x_min + bar.x_max) / 2, bar.top_y + 0.02};
  return s;
}

//! The same state rendered offscreen at `size`, the way the goldens are.
Image offscreen(VkExtent2D size, VkSampleCountFlagBits samples, const FrameState& state = mallet_over_a_bar()) {
  render::HeadlessOptions o;
  o.size = size;
  o.settings.samples = samples;
  o.settings.background_samples = VK_SAMPLE_COUNT_4_BIT;
  o.device = "llvmpipe";
  o.validation = Validation::required;
  o.cache_dir = "";
  render::HeadlessRenderer r(test::percussion(), o);
  return r.render(state);
}

//! Lets the X server's configure reach GLFW: events are polled until the framebuffer has
//! `w` × `h` pixels (or 500 polls have gone by).
bool framebuffer_becomes(GLFWwindow* window, int w, int h) {
  for (int i = 0; i < 500; ++i) {
    glfwWaitEventsTimeout(0.01);
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window, &fw, &fh);
    if (fw == w && fh == h) return true;
  }
  return false;
}

//! What the X server shows in the window now, read back with XGetImage: the frames that
//! were really presented, not the swapchain image we drew.
Image what_the_window_shows(GLFWwindow* window) {
  Display* display = glfwGetX11Display();
  const ::Window xid = glfwGetX11Window(window);
  XSync(display, False);
  XWindowAttributes a;
  XGetWindowAttributes(display, xid, &a);
  XImage* x = XGetImage(display, xid, 0, 0, static_cast<unsigned>(a.width), static_cast<unsigned>(a.height),
                        AllPlanes, ZPixmap);
  Image out(a.width, a.height);
  if (!x) return out;
  auto channel = [](unsigned long pixel, unsigned long mask) {
    int shift = 0;
    while (mask && !(mask & 1)) mask >>= 1, ++shift;
    return static_cast<std::uint8_t>((pixel >> shift) & mask);
  };
  for (int y = 0; y < a.height; ++y)
    for (int i = 0; i < a.width; ++i) {
      const unsigned long p = XGetPixel(x, i, y);
      out.at(i, y)[0] = channel(p, x->red_mask);
      out.at(i, y)[1] = channel(p, x->green_mask);
      out.at(i, y)[2] = channel(p, x->blue_mask);
      out.at(i, y)[3] = 255;
    }
  XDestroyImage(x);
  return out;
}

void expect_matches(const Image& shot, const Image& expected) {
  const ImageDiff d = compare_images(shot, expected, 3);
  ASSERT_TRUE(d.same_size) << shot.width << "x" << shot.height << " vs " << expected.width << "x" << expected.height;
  EXPECT_LT(d.differing_fraction, 0.001) << d.differing_pixels << " pixels differ, max " << d.max_channel_delta;
}

void resize_and_check(VkSampleCountFlagBits samples, bool put_changes) {
  OpenWindow w(samples, put_changes);
  const FrameState s = mallet_over_a_bar();
  Image shot;
  ASSERT_TRUE(w.target->draw(*w.renderer, s, &shot));
  expect_matches(shot, offscreen({320, 180}, samples));

  glfwSetWindowSize(w.target->window(), 480, 300);
  ASSERT_TRUE(framebuffer_becomes(w.target->window(), 480, 300));
  // The swapchain learns it is out of date at the next acquire or present (the put image at
  // the next frame); within a few frames every frame has the new size.
  for (int i = 0; i < 4; ++i) w.target->draw(*w.renderer, s);
  ASSERT_TRUE(w.target->draw(*w.renderer, s, &shot));
  EXPECT_GE(w.target->swapchain_recreations(), 1u);
  EXPECT_EQ(w.target->extent().width, 480u);
  EXPECT_EQ(w.target->extent().height, 300u);
  const Image expected = offscreen({480, 300}, samples);
  expect_matches(shot, expected);
  // And the X window itself shows that frame, at its new size (the same state was drawn
  // several times; vkDeviceWaitIdle, then the server is asked).
  w.target->draw(*w.renderer, s);
  vkDeviceWaitIdle(w.ctx->device());
  expect_matches(what_the_window_shows(w.target->window()), expected);
  // Both sizes were drawn over the cached background, one build each.
  EXPECT_EQ(w.renderer->background_builds(), 2u);
  EXPECT_EQ(w.ctx->validation_messages(), 0u) << w.ctx->first_validation_message();
}

//! Moves the X pointer to (x, y) of the root window and waits (bounded) for the window's
//! cursor callback to say so; false if it never does.
bool pointer_reaches(GLFWwindow* window, int x, int y) {
  Display* d = glfwGetX11Display();
  XWarpPointer(d, 0, DefaultRootWindow(d), 0, 0, 0, 0, x, y);
  XSync(d, False);
  for (int i = 0; i < 200; ++i) {
    glfwWaitEventsTimeout(0.01);
    const auto* heard = static_cast<const double*>(glfwGetWindowUserPointer(window));
    if (heard[0] == x && heard[1] == y) return true;
  }
  return false;
}

// A fullscreen kiosk hears the pointer at the screen's exact centre: GLFW, which warped its
// new fullscreen window's cursor there, took a later move to that point for its own and
// dropped it (a touch screen's or a remote desktop's tap at the centre did nothing).
TEST(WindowTarget, AFullscreenWindowHearsThePointerAtTheScreensExactCentre) {
  WindowSystem system;
  ContextOptions co;
  co.device_name = "llvmpipe";
  co.instance_extensions = WindowSystem::instance_extensions();
  co.swapchain = true;
  Context ctx(co);
  WindowOptions wo;
  wo.fullscreen = true;
  WindowTarget target(ctx, wo);
  int w = 0, h = 0;
  glfwGetWindowSize(target.window(), &w, &h);
  ASSERT_GT(w, 2);
  double at[2] = {-1, -1};  // the last position the callback gave
  glfwSetWindowUserPointer(target.window(), at);
  glfwSetCursorPosCallback(target.window(), [](GLFWwindow* win, double x, double y) {
    auto* p = static_cast<double*>(glfwGetWindowUserPointer(win));
    p[0] = x;
    p[1] = y;
  });
  ASSERT_TRUE(pointer_reaches(target.window(), w / 4, h / 4));
  EXPECT_TRUE(pointer_reaches(target.window(), w / 2, h / 2)) << "the move to the centre was not heard";
  glfwSetCursorPosCallback(target.window(), nullptr);
  glfwSetWindowUserPointer(target.window(), nullptr);
}

class BothWays : public testing::TestWithParam<bool> {};
INSTANTIATE_TEST_SUITE_P(WindowTarget, BothWays, testing::Values(true, false),
                         [](const testing::TestParamInfo<bool>& i) { return i.param ? "PutChanges" : "Swapchain"; });

TEST_P(BothWays, AResizedWindowGetsTheFramesOfItsNewSize) { resize_and_check(VK_SAMPLE_COUNT_1_BIT, GetParam()); }

TEST_P(BothWays, AResizedMultisampledWindowGetsTheFramesOfItsNewSize) {
  resize_and_check(VK_SAMPLE_COUNT_4_BIT, GetParam());
}

TEST_P(BothWays, AHiddenWindowDrawsNothingAndComesBackWhenShown) {
  OpenWindow w(VK_SAMPLE_COUNT_1_BIT, GetParam());
  const FrameState s = mallet_over_a_bar();
  ASSERT_TRUE(w.target->draw(*w.renderer, s));
  glfwHideWindow(w.target->window());  // what minimising does to an X11 window: it is unmapped
  glfwPollEvents();
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(w.target->draw(*w.renderer, s));
  glfwShowWindow(w.target->window());
  glfwPollEvents();
  Image shot;
  ASSERT_TRUE(w.target->draw(*w.renderer, s, &shot));
  const Image expected = offscreen({320, 180}, VK_SAMPLE_COUNT_1_BIT);
  expect_matches(shot, expected);
  w.target->draw(*w.renderer, s);
  vkDeviceWaitIdle(w.ctx->device());
  expect_matches(what_the_window_shows(w.target->window()), expected);
  EXPECT_EQ(w.ctx->validation_messages(), 0u) << w.ctx->first_validation_message();
}

TEST_P(BothWays, AStillFrameIsNotDrawnAndAMovingOneDrawsOnlyWhatChanged) {
  OpenWindow w(VK_SAMPLE_COUNT_1_BIT, GetParam());
  FrameState s = mallet_over_a_bar();
  ASSERT_TRUE(w.target->draw(*w.renderer, s));
  EXPECT_FALSE(w.target->still());
  EXPECT_FALSE(w.target->draw(*w.renderer, s)) << "the screen shows this frame already";
  EXPECT_TRUE(w.target->still());
  // The head moves: each swapchain image, holding a frame two or three behind, is brought up
  // to date by drawing only where the head was since and is.
  const int whole = 320 * 180;
  const std::uint64_t put_before = w.target->pixels_put();
  for (int i = 0; i < 7; ++i) {
    s.mallet_centre.x += 0.004;
    s.mallet_centre.y -= 0.002;
    ASSERT_TRUE(w.target->draw(*w.renderer, s));
    const PixelRect a = w.renderer->last_drawn_area();
    if (i >= 3) {
      EXPECT_LT((a.x1 - a.x0) * (a.y1 - a.y0) * 4, whole) << "frame " << i << " drew more than a quarter";
    }
  }
  // Only what changed went to the X server: under a quarter of the window a frame.
  if (GetParam()) {
    EXPECT_GT(w.target->pixels_put() - put_before, 0u);
    EXPECT_LT(w.target->pixels_put() - put_before, 7u * whole / 4);
  } else {
    EXPECT_EQ(w.target->pixels_put(), 0u) << "the swapchain presents whole frames itself";
  }
  // What the X window shows is the whole frame of the last state.
  EXPECT_FALSE(w.target->draw(*w.renderer, s));
  vkDeviceWaitIdle(w.ctx->device());
  expect_matches(what_the_window_shows(w.target->window()), offscreen({320, 180}, VK_SAMPLE_COUNT_1_BIT, s));
  // The window system asks for the picture again (an expose): drawn, though nothing changed.
  w.target->show_again();
  EXPECT_TRUE(w.target->draw(*w.renderer, s));
  EXPECT_FALSE(w.target->draw(*w.renderer, s));
  EXPECT_EQ(w.ctx->validation_messages(), 0u) << w.ctx->first_validation_message();
}

}  // namespace
}  // namespace mallet::render
