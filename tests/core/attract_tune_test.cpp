#include "core/attract_tune.hpp"

#include <gtest/gtest.h>

#include "core/mallet.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

using test::percussion;

TEST(AttractTune, WalksUpEachInstrumentInTimeOrderWithinOnePeriod) {
  const AttractTune tune;
  const std::vector<ScriptedStrike> s = attract_phrase(percussion(), 1'000'000'000, tune);
  ASSERT_EQ(s.size(), 10u);  // C E G C' G on each of the two instruments
  const Instrument& xylo = percussion().instruments.at(0);
  const Instrument& glock = percussion().instruments.at(1);
  EXPECT_EQ(s[0].target, xylo.targets[0]);
  EXPECT_EQ(s[3].target, xylo.targets[7]);
  EXPECT_EQ(s[5].target, glock.targets[0]);
  for (std::size_t i = 1; i < s.size(); ++i) EXPECT_GT(s[i].t_ns, s[i - 1].t_ns);
  EXPECT_EQ(s[0].t_ns, 1'000'000'000);
  EXPECT_LT(s.back().t_ns - s.front().t_ns, attract_period(percussion(), tune));
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
