// The IR sensitivity auto-adjust: in constructed scenes (an LED that flickers at low
// sensitivity, a dot too small or too large, a reflection that appears as sensitivity grows)
// the tuner steps up through the presets and picks the lowest clean one, and never one that
// showed a spurious dot.
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/sensitivity_tuner.hpp"

namespace mallet {
namespace {

// What the camera shows in frame `i` while running preset number `preset`.
using IrScene = std::function<IrFrame(std::size_t preset, int i)>;

IrFrame frame_of(std::vector<IrDot> dots) {
  IrFrame f;
  for (std::size_t k = 0; k < dots.size() && k < 4; ++k) f.slots[k] = dots[k];
  return f;
}

const IrDot kLed{512, 300, 3};
const IrDot kReflection{100, 700, 2};

struct TunerRun {
  SensitivityTuner tuner;
  std::vector<std::string_view> switched_to;  //!< the presets it asked for, in order
  TunerStep last = TunerStep::observing;
};

TunerRun run(const IrScene& scene, SensitivityTunerConfig config = {}) {
  TunerRun r{SensitivityTuner(config), {}, TunerStep::observing};
  for (int i = 0; i < 100000 && !r.tuner.done(); ++i) {
    std::size_t preset = 0;
    while (kSensitivityPresets[preset].name != r.tuner.preset()) ++preset;
    r.last = r.tuner.observe(scene(preset, i));
    if (r.last == TunerStep::next_preset) r.switched_to.push_back(r.tuner.preset());
  }
  return r;
}

TEST(SensitivityTuner, StartsAtTheLeastSensitivePreset) {
  const SensitivityTuner t;
  EXPECT_EQ(t.preset(), "wii1");
  EXPECT_FALSE(t.done());
}

TEST(SensitivityTuner, ACleanSteadyDotAtTheLowestPresetIsChosenAtOnce) {
  const TunerRun r = run([](std::size_t, int) { return frame_of({kLed}); });
  EXPECT_EQ(r.last, TunerStep::chosen);
  EXPECT_EQ(r.tuner.chosen(), "wii1");
  EXPECT_EQ(r.tuner.preset(), "wii1");
  EXPECT_TRUE(r.switched_to.empty());
  ASSERT_EQ(r.tuner.verdicts().size(), 1u);
  EXPECT_EQ(r.tuner.verdicts()[0].verdict.median_size, 3);
}

TEST(SensitivityTuner, AFlickeringLedStepsUpToASteadyOne) {
  // wii1 sees the LED in half the frames; wii2 steadily.
  const TunerRun r = run([](std::size_t p, int i) { return p == 0 && i % 2 ? frame_of({}) : frame_of({kLed}); });
  EXPECT_EQ(r.tuner.chosen(), "wii2");
  EXPECT_EQ(r.switched_to, (std::vector<std::string_view>{"wii2"}));
  ASSERT_EQ(r.tuner.verdicts().size(), 2u);
  EXPECT_EQ(r.tuner.verdicts()[0].verdict.reason, "the LED was seen in only 50 % of the frames");
}

TEST(SensitivityTuner, TheDotSizeMustBeInRange) {
  // Nothing at wii1 and wii2, a speck (size 1) at wii3, a good dot at wii4.
  const TunerRun r = run([](std::size_t p, int) {
    if (p < 2) return frame_of({});
    if (p == 2) return frame_of({{512, 300, 1}});
    return frame_of({{512, 300, 4}});
  });
  EXPECT_EQ(r.tuner.chosen(), "wii4");
  EXPECT_EQ(r.switched_to, (std::vector<std::string_view>{"wii2", "wii3", "wii4"}));
  EXPECT_EQ(r.tuner.verdicts()[2].verdict.reason, "dot size 1 outside 2..8");
  // A blooming LED (size 12 everywhere) is never right.
  const TunerRun big = run([](std::size_t, int) { return frame_of({{512, 300, 12}}); });
  EXPECT_EQ(big.last, TunerStep::failed);
  EXPECT_FALSE(big.tuner.chosen());
  EXPECT_EQ(big.tuner.preset(), "");
  EXPECT_EQ(big.tuner.verdicts().size(), kSensitivityPresets.size());
}

TEST(SensitivityTuner, APresetWithSpuriousDotsIsNeverChosen) {
  // The LED is steady and in range from wii2 up, but from wii3 on a reflection shows in one
  // frame of a hundred; at wii2 the LED is a speck. No preset is clean.
  const TunerRun r = run([](std::size_t p, int i) {
    if (p == 0) return frame_of({});
    if (p == 1) return frame_of({{512, 300, 1}});
    return i % 100 == 37 ? frame_of({kLed, kReflection}) : frame_of({kLed});
  });
  EXPECT_EQ(r.last, TunerStep::failed);
  EXPECT_FALSE(r.tuner.chosen());
  EXPECT_EQ(r.tuner.verdicts()[2].verdict.reason, "spurious dots in 1 % of the frames");
  // With the reflection only from wii5 up, wii4 would be clean... but the speck at wii2
  // steps on to wii3, which is clean: the lowest clean one.
  const TunerRun s = run([](std::size_t p, int) {
    if (p <= 1) return frame_of({{512, 300, 1}});
    if (p >= 4) return frame_of({kLed, kReflection});
    return frame_of({kLed});
  });
  EXPECT_EQ(s.tuner.chosen(), "wii3");
}

TEST(SensitivityTuner, TheZeroDotAndOffSensorSlotsAreNotDots) {
  const TunerRun r = run([](std::size_t, int) { return frame_of({{0, 0, 1}, kLed, {1023, 1023, 15}}); });
  EXPECT_EQ(r.tuner.chosen(), "wii1");
}

TEST(SensitivityTuner, BasicModeHasNoSizeToJudge) {
  const TunerRun r = run([](std::size_t p, int) { return p == 0 ? frame_of({}) : frame_of({{512, 300, -1}}); });
  EXPECT_EQ(r.tuner.chosen(), "wii2");
  EXPECT_EQ(r.tuner.verdicts()[1].verdict.median_size, -1);
}

TEST(SensitivityTuner, FramesRightAfterASwitchAreNotJudged) {
  // While the camera takes its new blocks it may show anything: 10 settle frames are skipped.
  SensitivityTunerConfig c;
  c.frames_per_preset = 50;
  int since_switch = 0;
  std::size_t last_preset = 0;
  const TunerRun r = run(
      [&](std::size_t p, int) {
        if (p != last_preset) {
          last_preset = p;
          since_switch = 0;
        }
        const bool settling = since_switch++ < 10;
        if (p == 0) return frame_of({});
        return settling ? frame_of({kLed, kReflection}) : frame_of({kLed});
      },
      c);
  EXPECT_EQ(r.tuner.chosen(), "wii2");
}

TEST(SensitivityTuner, AWholeObservationCanBeGivenAtOnce) {
  SensitivityTuner t;
  SensitivityObservation dark;
  dark.frames = 100;
  EXPECT_EQ(t.observe(dark), TunerStep::next_preset);
  EXPECT_EQ(t.preset(), "wii2");
  SensitivityObservation good;
  for (int i = 0; i < 100; ++i) observe_frame(good, frame_of({kLed}));
  EXPECT_EQ(good.frames_seen, 100);
  EXPECT_EQ(good.frames_spurious, 0);
  EXPECT_EQ(t.observe(good), TunerStep::chosen);
  EXPECT_EQ(t.chosen(), "wii2");
  EXPECT_EQ(t.observe(dark), TunerStep::chosen);  // done: nothing changes
  EXPECT_EQ(t.chosen(), "wii2");
}

// Random scenes: whatever is chosen showed no spurious dot and is the first clean preset.
TEST(SensitivityTuner, RandomScenesNeverChooseASpuriousPreset) {
  std::mt19937 rng(3);
  int chosen = 0, failed = 0;
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<double> seen(kSensitivityPresets.size()), spurious(kSensitivityPresets.size());
    std::vector<int> size(kSensitivityPresets.size());
    std::uniform_real_distribution<double> u(0, 1);
    for (std::size_t p = 0; p < seen.size(); ++p) {
      seen[p] = u(rng) < 0.5 ? 1.0 : u(rng);
      spurious[p] = u(rng) < 0.5 ? 0.0 : u(rng) * 0.05;
      size[p] = std::uniform_int_distribution<int>(0, 15)(rng);
    }
    std::vector<int> spurious_frames(seen.size(), 0);
    std::mt19937 frames(static_cast<unsigned>(trial));
    SensitivityTunerConfig every_frame_judged;
    every_frame_judged.settle_frames = 0;
    const TunerRun r = run(
        [&](std::size_t p, int) {
          std::vector<IrDot> dots;
          if (u(frames) < seen[p]) dots.push_back({512, 300, size[p]});
          if (u(frames) < spurious[p]) dots.push_back(kReflection);
          if (dots.size() >= 2) ++spurious_frames[p];
          return frame_of(dots);
        },
        every_frame_judged);
    ASSERT_TRUE(r.tuner.done());
    if (!r.tuner.chosen()) {
      ++failed;
      continue;
    }
    ++chosen;
    std::size_t p = 0;
    while (kSensitivityPresets[p].name != *r.tuner.chosen()) ++p;
    EXPECT_EQ(spurious_frames[p], 0) << "trial " << trial;
    EXPECT_GE(size[p], 2);
    EXPECT_LE(size[p], 8);
    EXPECT_EQ(r.tuner.verdicts().size(), p + 1);
    for (std::size_t q = 0; q < p; ++q) EXPECT_FALSE(r.tuner.verdicts()[q].verdict.clean);
  }
  EXPECT_GT(chosen, 50);  // the scenes do exercise both outcomes
  EXPECT_GT(failed, 5);
}

TEST(SensitivityTuner, ABadConfigIsRefused) {
  SensitivityTunerConfig c;
  EXPECT_TRUE(validate(c));
  c.min_size = 9;
  EXPECT_NE(why_not(validate(c)).find("min_size"), std::string::npos);
  EXPECT_THROW(SensitivityTuner{c}, std::invalid_argument);
  c = {};
  c.frames_per_preset = 0;
  EXPECT_NE(why_not(validate(c)).find("frames_per_preset"), std::string::npos);
  c = {};
  c.max_spurious_fraction = 1;
  EXPECT_NE(why_not(validate(c)).find("max_spurious_fraction"), std::string::npos);
}

}  // namespace
}  // namespace mallet
