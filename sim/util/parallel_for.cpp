#include "sim/util/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace gyrotherm {

void parallel_for(std::size_t n, int threads, const std::function<void(std::size_t)>& work,
                  const std::function<void(std::size_t)>& done) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;  // guards `finished`, `first_error` and the done() calls
  std::size_t finished = 0;
  std::exception_ptr first_error;
  auto take = [&] {
    for (std::size_t i = next++; i < n && !failed; i = next++) {
      try {
        work(i);
      } catch (...) {
        const std::lock_guard lock(mutex);
        if (!first_error) first_error = std::current_exception();
        failed = true;
        return;
      }
      if (done) {
        const std::lock_guard lock(mutex);
        done(++finished);
      }
    }
  };
  const auto helpers = std::min(static_cast<std::size_t>(std::max(1, threads)) - 1, n);
  {
    std::vector<std::jthread> pool;
    for (std::size_t t = 0; t < helpers; ++t) pool.emplace_back(take);
    take();
  }  // joined
  if (first_error) std::rethrow_exception(first_error);
}

int threads_at_most(int wanted) {
  const auto cores = static_cast<int>(std::thread::hardware_concurrency());
  return std::max(1, std::min(wanted, cores > 0 ? cores : 1));
}

}  // namespace gyrotherm
