#include <thread>

#include <gtest/gtest.h>

#include "audio/spsc_ring.hpp"

namespace mallet::audio {
namespace {

TEST(SpscRing, FifoAndFullAndEmpty) {
  SpscRing<int, 4> ring;
  EXPECT_FALSE(ring.pop().has_value());
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(ring.push(i));
  EXPECT_FALSE(ring.push(99));  // full: refused, not overwritten
  for (int i = 0; i < 4; ++i) EXPECT_EQ(ring.pop().value(), i);
  EXPECT_FALSE(ring.pop().has_value());
}

TEST(SpscRing, TwoThreadsSeeEveryValueOnceInOrder) {
  SpscRing<std::uint64_t, 64> ring;
  constexpr std::uint64_t kCount = 200'000;
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < kCount;)
      if (ring.push(i)) ++i;
      else std::this_thread::yield();
  });
  std::uint64_t expected = 0;
  while (expected < kCount) {
    if (auto v = ring.pop()) {
      ASSERT_EQ(*v, expected);
      ++expected;
    } else {
      std::this_thread::yield();
    }
  }
  producer.join();
  EXPECT_FALSE(ring.pop().has_value());
}

}  // namespace
}  // namespace mallet::audio
