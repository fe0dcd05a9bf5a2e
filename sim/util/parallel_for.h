#pragma once
// Independent work over indices on a few threads, the one pool of the
// project (score's trials, plan's search families and verification seeds).
//
//   parallel_for(n, threads, work, done)
//
// runs work(i) exactly once for every i in [0, n): the calling thread and up
// to threads − 1 others each take the next index not yet taken. done(k), if
// given, is called after each index with the number finished so far, one
// call at a time. If work throws, no further index is started and the first
// exception is rethrown here once every thread has stopped. The order in
// which indices run is not fixed: callers write results by index, so the
// result does not depend on the threads.

#include <cstddef>
#include <functional>

namespace gyrotherm {

void parallel_for(std::size_t n, int threads, const std::function<void(std::size_t)>& work,
                  const std::function<void(std::size_t)>& done = {});

// min(wanted, the machine's hardware threads), at least 1.
int threads_at_most(int wanted);

}  // namespace gyrotherm
