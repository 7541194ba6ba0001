#include "core/attract_tune.hpp"

#include <algorithm>

#include <gtest/gtest.h>

#include "core/mallet.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

using test::percussion;

TEST(AttractTune, PlaysATunePerInstrumentInTimeOrderWithinOnePeriod) {
  const AttractTune tune;
  const std::vector<ScriptedStrike> s = attract_phrase(percussion(), 1'000'000'000, tune);
  ASSERT_EQ(s.size(), 29u);  // "Ode to Joy" (15 notes), then "Twinkle, Twinkle" (14)
  const Instrument& xylo = percussion().instruments.at(0);
  const Instrument& glock = percussion().instruments.at(1);
  // E E F G G F E D C C D E E D D on the xylophone (bar 0 is its C)...
  const int ode[] = {2, 2, 3, 4, 4, 3, 2, 1, 0, 0, 1, 2, 2, 1, 1};
  for (std::size_t i = 0; i < 15; ++i) EXPECT_EQ(s[i].target, xylo.targets[static_cast<std::size_t>(ode[i])]) << i;
  // ...C C G G A A G F F E E D D C on the glockenspiel.
  const int twinkle[] = {0, 0, 4, 4, 5, 5, 4, 3, 3, 2, 2, 1, 1, 0};
  for (std::size_t i = 0; i < 14; ++i)
    EXPECT_EQ(s[15 + i].target, glock.targets[static_cast<std::size_t>(twinkle[i])]) << i;
  for (std::size_t i = 1; i < s.size(); ++i) EXPECT_GE(s[i].t_ns - s[i - 1].t_ns, 420'000'000) << i;  // a beat at least
  EXPECT_EQ(s[0].t_ns, 1'000'000'000);
  EXPECT_LT(s.back().t_ns - s.front().t_ns, attract_period(percussion(), tune));
}

TEST(AttractTune, IsPhrasedWithSoftAndHardStrikes) {
  const AttractTune tune;
  double softest = 1e9, hardest = 0;
  for (const ScriptedStrike& s : attract_phrase(percussion(), 0, tune)) {
    softest = std::min(softest, s.speed_m_per_s);
    hardest = std::max(hardest, s.speed_m_per_s);
  }
  EXPECT_DOUBLE_EQ(softest, 0.5 * tune.speed_m_per_s);
  EXPECT_DOUBLE_EQ(hardest, 1.6 * tune.speed_m_per_s);
}

TEST(AttractTune, TheGhostPlayerStrikesEveryNoteOfThePhraseExactlyOnce) {
  const std::vector<ScriptedStrike> s = attract_phrase(percussion(), 500'000'000);
  const GhostPath path = ghost_player(percussion(), s, 1000.0);
  Mallet m(percussion(), ContactConfig{});
  std::vector<int> struck;
  for (const PointerSample& p : path.samples)
    if (auto i = m.update(p.t_ns, {p.x, p.y})) struck.push_back(i->target);
  ASSERT_EQ(struck.size(), s.size());
  for (std::size_t i = 0; i < s.size(); ++i) EXPECT_EQ(struck[i], s[i].target) << i;
}

}  // namespace
}  // namespace mallet
