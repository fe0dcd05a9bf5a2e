#pragma once

namespace gyrotherm {

// Asks for the heap in huge pages (a program's choice, made once at its
// start, before any thread). On a virtual machine a page fault is a few
// microseconds; a 583 MB log's fit touches about 50 MB of fresh memory
// (13,800 faults of 4 KB, a tenth of its CPU time here). Large buffers then
// come from the heap, which is kept rather than returned between uses, and
// its first 64 MB are advised as transparent huge pages (one fault per 2 MB
// where the kernel allows them: THP "always" or "madvise"). A hint: where the
// kernel or C library refuses, nothing changes.
void prefer_huge_pages();

}  // namespace gyrotherm
