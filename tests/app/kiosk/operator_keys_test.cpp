// The operator's keys: what each does, and what a held key's auto-repeat does again.
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include "app/kiosk/operator_page.hpp"

namespace mallet::app {
namespace {

constexpr int kChord = GLFW_MOD_CONTROL | GLFW_MOD_ALT;

TEST(OperatorKeys, TheChordOpensAnywhereAndThePagesKeysOnlyOnThePage) {
  EXPECT_EQ(operator_action(GLFW_KEY_O, kChord, false), OperatorAction::open);
  EXPECT_EQ(operator_action(GLFW_KEY_O, kChord, true), OperatorAction::open);
  EXPECT_EQ(operator_action(GLFW_KEY_O, GLFW_MOD_CONTROL, false), OperatorAction::none);
  EXPECT_EQ(operator_action(GLFW_KEY_Q, 0, false), OperatorAction::none);  // a visitor's Q
  EXPECT_EQ(operator_action(GLFW_KEY_Q, 0, true), OperatorAction::quit);
  EXPECT_EQ(operator_action(GLFW_KEY_UP, 0, true), OperatorAction::volume_up);
}

TEST(OperatorKeys, AHeldKeyRepeatsOnlyTheVolumeAndTheGain) {
  // A chord held for seconds (the VM test's keys, a remote desktop) must open the page once,
  // not open and close it with each repeat; a held Q quits once.
  EXPECT_FALSE(operator_action_repeats(OperatorAction::open));
  EXPECT_FALSE(operator_action_repeats(OperatorAction::close));
  EXPECT_FALSE(operator_action_repeats(OperatorAction::quit));
  EXPECT_FALSE(operator_action_repeats(OperatorAction::next_scene));
  EXPECT_FALSE(operator_action_repeats(OperatorAction::doctor));
  for (OperatorAction step : {OperatorAction::volume_up, OperatorAction::volume_down, OperatorAction::gain_up,
                              OperatorAction::gain_down})
    EXPECT_TRUE(operator_action_repeats(step));
}

}  // namespace
}  // namespace mallet::app
