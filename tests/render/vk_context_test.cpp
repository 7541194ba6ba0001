// The Vulkan context frees what it made when a later step fails: the instance, the
// validation layer's messenger, the device and the command pool are each owned from the
// moment they exist. A failure is injected after each step in turn; the validation layer
// (which reports a device left alive when its instance is destroyed) says nothing, and no
// instance or device is left behind.
#include <string>

#include <gtest/gtest.h>

#include "render/vk_context.hpp"
#include "render/vk_error.hpp"

namespace mallet::render {
namespace {

ContextOptions lavapipe() {
  ContextOptions o;
  o.validation = Validation::required;
  o.device_name = "llvmpipe";
  return o;
}

class ContextFailingAfter : public ::testing::TestWithParam<const char*> {};

TEST_P(ContextFailingAfter, FreesEverythingItMadeBefore) {
  const std::int64_t before = live_instances_and_devices();
  ContextOptions o = lavapipe();
  o.fail_after = GetParam();
  ::testing::internal::CaptureStderr();
  try {
    Context ctx(o);
    ADD_FAILURE() << "no failure injected after the " << GetParam();
  } catch (const RenderError& e) {
    EXPECT_EQ(std::string(e.what()).find("injected failure after the " + std::string(GetParam())), 0u) << e.what();
  }
  const std::string said = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(said.find("vulkan validation"), std::string::npos) << said;
  EXPECT_EQ(live_instances_and_devices(), before);
}

INSTANTIATE_TEST_SUITE_P(Steps, ContextFailingAfter,
                         ::testing::Values("instance", "messenger", "device", "command pool"),
                         [](const ::testing::TestParamInfo<const char*>& i) {
                           std::string name = i.param;
                           for (char& c : name)
                             if (c == ' ') c = '_';
                           return name;
                         });

TEST(Context, AWholeOneHoldsAnInstanceAndADeviceUntilItGoes) {
  const std::int64_t before = live_instances_and_devices();
  {
    Context ctx(lavapipe());
    EXPECT_TRUE(ctx.validation_enabled());
    EXPECT_EQ(live_instances_and_devices(), before + 2);
    EXPECT_EQ(ctx.validation_messages(), 0u) << ctx.first_validation_message();
  }
  EXPECT_EQ(live_instances_and_devices(), before);
}

TEST(Context, NoDeviceOfThatNameFreesTheInstance) {
  const std::int64_t before = live_instances_and_devices();
  ContextOptions o = lavapipe();
  o.device_name = "no such device";
  EXPECT_THROW(Context{o}, RenderError);
  EXPECT_EQ(live_instances_and_devices(), before);
}

}  // namespace
}  // namespace mallet::render
