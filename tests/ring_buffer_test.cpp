// Tests for fit/data/ring_buffer.h: the same answers as std::deque under
// random pushes and pops at both ends, across its growth and wrap-around.

#include "fit/data/ring_buffer.h"

#include <gtest/gtest.h>

#include <deque>
#include <random>
#include <utility>

namespace gyrotherm::fit {
namespace {

TEST(RingBuffer, ActsAsADequeAcrossGrowthAndWrapAround) {
  std::mt19937_64 rng(1);
  RingBuffer<std::pair<int, double>> ring;
  std::deque<std::pair<int, double>> deque;
  std::uniform_int_distribution<int> action(0, 9);
  for (int step = 0; step < 200000; ++step) {
    // Phases that grow, hold steady (the sliding window) and shrink.
    const int phase = (step / 20000) % 3;
    const int a = action(rng);
    const bool push = deque.empty() || (phase == 0 ? a < 7 : phase == 1 ? a < 5 : a < 3);
    if (push) {
      ring.push_back({step, 0.5 * step});
      deque.push_back({step, 0.5 * step});
    } else if (a % 2 == 0) {
      ring.pop_front();
      deque.pop_front();
    } else {
      ring.pop_back();
      deque.pop_back();
    }
    ASSERT_EQ(ring.size(), deque.size());
    ASSERT_EQ(ring.empty(), deque.empty());
    if (!deque.empty()) {
      ASSERT_EQ(ring.front(), deque.front());
      ASSERT_EQ(ring.back(), deque.back());
    }
    if (step % 1000 == 0) {
      for (std::size_t i = 0; i < deque.size(); ++i) ASSERT_EQ(ring[i], deque[i]) << step;
    }
  }
  ring.clear();
  EXPECT_TRUE(ring.empty());
  ring.push_back({1, 2.0});
  EXPECT_EQ(ring.front(), (std::pair<int, double>{1, 2.0}));
}

}  // namespace
}  // namespace gyrotherm::fit
