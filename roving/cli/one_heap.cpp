// The command's memory from one heap that is never trimmed. Every block comes from malloc's main
// heap (M_MMAP_MAX 0, M_ARENA_MAX 1: TBB's worker threads would otherwise take blocks from heaps of
// their own), which grows 32 MiB at a time and is never given back before the end, so that a block
// freed between stages (a file's bytes, a sort's spare room, a chunk of REF's samples) serves the
// next on pages already faulted in. Replaces the global operator new of this executable alone;
// memory is still malloc's, so the default operator delete (free) releases it. Sanitizer builds
// keep their own allocator.
//
// Its pages are the kernel's 4 KiB ones. Until 2026-12-07 the heap was advised as transparent huge
// pages as it grew (what glibc's tunable glibc.malloc.hugetlb=1 does); on this project's machines
// (virtual ones, /sys/kernel/mm/transparent_hugepage/enabled: madvise) a fresh 2 MiB page is fast
// only while the kernel has some at hand: writing 1.6 GiB afresh took 0.3 to 20 s on 2 MiB pages
// and 0.7 to 1.4 s on 4 KiB ones, and the runs with huge pages swung between 0.1 and 1.2 s of
// system time. Without the advice, interleaved runs (`/usr/bin/time`, same figures): closest point
// from the n = 8 scaling pair's vertices 2.26-2.48 -> 1.62-1.67 s wall, n = 12 5.03-5.06 -> 3.94-4.04
// s; a million-point --pcc pair 0.30-0.41 -> 0.34-0.36 s, the n = 4 GL pair 2.13-2.87 -> 2.01-2.37 s
// (user time unchanged: no TLB cost seen).
#include <malloc.h>

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <new>

#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)

namespace {

// As the standard's operator new: the new-handler is called until it succeeds or there is none.
template <class Allocate>
void* allocate(std::size_t size, const Allocate& try_allocate) {
  if (size == 0) size = 1;
  for (;;) {
    if (void* p = try_allocate(size)) return p;
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

// Set before main, as the executable's first allocations are made: one heap for every thread,
// never given back to the kernel before the end, growing 32 MiB at a time.
const bool one_heap = mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_ARENA_MAX, 1) == 1 &&
                      mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1 && mallopt(M_TOP_PAD, 32 << 20) == 1;

}  // namespace

void* operator new(std::size_t size) {
  return allocate(size, [](std::size_t n) { return std::malloc(n); });
}

void* operator new(std::size_t size, std::align_val_t alignment) {
  return allocate(size, [alignment](std::size_t n) {
    void* p = nullptr;
    const std::size_t align = std::max(static_cast<std::size_t>(alignment), sizeof(void*));
    return posix_memalign(&p, align, n) == 0 ? p : nullptr;
  });
}

#endif
