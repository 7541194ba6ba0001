// The device memory count a soak watches (render::device_memory_bytes, the kiosk's
// mallet_vulkan_device_memory_bytes): a renderer's buffers and images raise it by what they
// allocated, and freeing them brings it back to where it was, byte for byte.
#include <gtest/gtest.h>

#include "render/render_setup.hpp"
#include "render/vk_handle.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

render::HeadlessRenderer make(std::uint32_t width, std::uint32_t height) {
  render::HeadlessOptions o;
  o.size = {width, height};
  o.cache_dir = "";
  o.device = "llvmpipe";
  return render::HeadlessRenderer(test::percussion(), o);
}

TEST(DeviceMemory, ARendererIsCountedWhileItLivesAndGivesEverythingBack) {
  const std::uint64_t before = render::device_memory_bytes();
  std::uint64_t small = 0, large = 0;
  {
    render::HeadlessRenderer r = make(160, 90);
    r.render(render::FrameState{});  // the first frame makes what it needs (the read-back buffer)
    small = render::device_memory_bytes() - before;
    for (int i = 0; i < 3; ++i) r.render(render::FrameState{});
    EXPECT_EQ(render::device_memory_bytes() - before, small) << "a later frame allocates nothing that stays";
  }
  EXPECT_EQ(render::device_memory_bytes(), before);
  {
    render::HeadlessRenderer r = make(1280, 720);
    large = render::device_memory_bytes() - before;
  }
  EXPECT_EQ(render::device_memory_bytes(), before);
  EXPECT_GT(small, 0u);
  // The colour, depth and read-back images grow with the pixels (64 times as many here).
  EXPECT_GT(large, small + 1280u * 720u * 4u);
}

}  // namespace
}  // namespace mallet::app
