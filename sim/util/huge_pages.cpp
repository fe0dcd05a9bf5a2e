#include "sim/util/huge_pages.h"

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>

namespace gyrotherm {

void prefer_huge_pages() {
  constexpr std::size_t kHuge = std::size_t{2} << 20, kHeap = std::size_t{64} << 20;
  // Buffers up to 32 MB (glibc's largest threshold) from the heap, not each
  // its own mapping faulted anew; the heap grown 64 MB at a time and kept.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  mallopt(M_TOP_PAD, static_cast<int>(kHeap));
  void* probe = std::malloc(kHuge);  // grows the heap by the pad; touches one page
  if (probe == nullptr) return;
  const auto first = (reinterpret_cast<std::uintptr_t>(probe) + kHuge - 1) / kHuge * kHuge;
  const auto top = reinterpret_cast<std::uintptr_t>(sbrk(0));
  if (top > first + kHuge) madvise(reinterpret_cast<void*>(first), (top - first) / kHuge * kHuge, MADV_HUGEPAGE);
  std::free(probe);
}

}  // namespace gyrotherm
