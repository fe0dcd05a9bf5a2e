// prefer_huge_pages: large buffers come from the kept heap, not a mapping
// each (a fresh mapping faults again on every first touch).

#include "sim/util/huge_pages.h"

#include <dlfcn.h>
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdlib>
#include <cstring>

namespace {

TEST(HugePages, LargeBuffersComeFromTheHeapAndStayInIt) {
  // The sanitized build links AddressSanitizer's allocator, which replaces
  // glibc's (the test files themselves are built without instrumentation:
  // asked at run time).
  if (dlsym(RTLD_DEFAULT, "__asan_init") != nullptr) GTEST_SKIP() << "the sanitizer's allocator replaces glibc's";
  gyrotherm::prefer_huge_pages();
  const std::size_t mapped_before = mallinfo2().hblkhd;
  constexpr std::size_t kBytes = std::size_t{4} << 20;  // above glibc's default threshold of 128 KB
  void* p = std::malloc(kBytes);
  ASSERT_NE(p, nullptr);
  std::memset(p, 1, kBytes);
  EXPECT_EQ(mallinfo2().hblkhd, mapped_before) << "a 4 MB buffer was given its own mapping";
  const std::size_t heap_before_free = mallinfo2().arena;
  std::free(p);
  EXPECT_GE(mallinfo2().arena, heap_before_free) << "the heap was returned on free";
  EXPECT_GE(mallinfo2().arena, kBytes);
}

}  // namespace
