// sim/util/parallel_for.h: every index once, done() counting to n one call
// at a time, the first exception rethrown after the threads stop.
#include "sim/util/parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <stdexcept>
#include <vector>

namespace gyrotherm {
namespace {

TEST(ParallelFor, EveryIndexOnceAndDoneCountsToN) {
  for (int threads : {1, 2, 4}) {
    std::vector<std::atomic<int>> ran(1000);
    std::vector<std::size_t> counts;
    parallel_for(
        ran.size(), threads, [&](std::size_t i) { ++ran[i]; },
        [&](std::size_t done) { counts.push_back(done); });  // serialised: no lock here
    for (const auto& r : ran) EXPECT_EQ(r.load(), 1) << threads;
    ASSERT_EQ(counts.size(), ran.size()) << threads;
    for (std::size_t k = 0; k < counts.size(); ++k) EXPECT_EQ(counts[k], k + 1) << threads;
  }
  parallel_for(0, 2, [](std::size_t) { FAIL() << "no index"; });
}

TEST(ParallelFor, TheFirstErrorIsRethrownAndNoMoreWorkStarts) {
  std::atomic<int> started{0};
  // Each index takes 2 ms: once index 3 has thrown, the other thread starts
  // at most the index it was about to take, far from all 500.
  EXPECT_THROW(parallel_for(500, 2,
                            [&](std::size_t i) {
                              ++started;
                              if (i == 3) throw std::runtime_error("index 3");
                              std::this_thread::sleep_for(std::chrono::milliseconds(2));
                            }),
               std::runtime_error);
  EXPECT_LT(started.load(), 20);
}

}  // namespace
}  // namespace gyrotherm
