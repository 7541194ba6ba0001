// The operator page's arrows move the volume and the gain one step toward their end of the
// settings' range, never the other way (Up at 200 % used to set 100 %).
#include <gtest/gtest.h>

#include "core/operator_knobs.hpp"

namespace mallet {
namespace {

TEST(OperatorKnobs, UpNeverLowersTheVolumeTheSettingsAllow) {
  EXPECT_DOUBLE_EQ(knob_step(2.0, kVolumeKnob, true), 2.05);
  EXPECT_DOUBLE_EQ(knob_step(4.0, kVolumeKnob, true), 4.0);
  EXPECT_DOUBLE_EQ(knob_step(3.98, kVolumeKnob, true), 4.0);
  for (double v = 0.0; v <= 4.0; v += 0.13) EXPECT_GE(knob_step(v, kVolumeKnob, true), v) << v;
}

TEST(OperatorKnobs, DownNeverRaisesAndStopsAtZero) {
  EXPECT_DOUBLE_EQ(knob_step(0.02, kVolumeKnob, false), 0.0);
  EXPECT_DOUBLE_EQ(knob_step(0.0, kVolumeKnob, false), 0.0);
  for (double v = 0.0; v <= 4.0; v += 0.13) EXPECT_LE(knob_step(v, kVolumeKnob, false), v) << v;
}

TEST(OperatorKnobs, TheGainReachesItsSettingsRange) {
  EXPECT_DOUBLE_EQ(knob_step(2.0, kGainKnob, true), 2.02);  // above the old 1.0 cap
  EXPECT_DOUBLE_EQ(knob_step(10.0, kGainKnob, true), 10.0);
  EXPECT_DOUBLE_EQ(knob_step(2.0, kGainKnob, false), 1.98);
}

}  // namespace
}  // namespace mallet
