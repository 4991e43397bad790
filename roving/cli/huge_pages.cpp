// The command's memory on transparent huge pages. Where the kernel makes them only on request
// (/sys/kernel/mm/transparent_hugepage/enabled: madvise, Debian's default), every 4 KiB written
// for the first time costs a page fault: on this project's machine, writing 64 MiB afresh took
// 230 ms in 4 KiB pages and 6 to 85 ms in 2 MiB ones. Every block comes from one heap (M_MMAP_MAX
// 0, M_ARENA_MAX 1: TBB's worker threads would otherwise take blocks from heaps of their own, on
// 4 KiB pages), and each time it grows, its new whole 2 MiB pages are advised as huge (what glibc's
// tunable glibc.malloc.hugetlb=1 does for its heap). The heap is never trimmed and grows 32 MiB at
// a time, so that a block freed between stages (a file's bytes, a sort's spare room, a chunk of
// REF's samples) serves the next on pages already faulted in. Replaces the global operator new of
// this executable alone; memory is still malloc's, so the default operator delete (free) releases
// it. Sanitizer builds keep their own allocator.
//
// Measured against advising only blocks of 8 MiB or more (which left a thread's smaller blocks on
// 4 KiB pages), medians of interleaved runs, peak memory 0 to 5% more (results/scaling.md at 10 M
// triangles: roving 452 -> 463 MiB, cooperative 24x12 1,059 -> 1,115): a million-point --pcc pair
// 0.64 -> 0.41 s wall (0.86 -> 0.65 s user time: fewer TLB misses too); bench/scaling.py's n = 8
// pair (4.4 M against 0.67 M triangles) with Embree 1.93 -> 1.55 s, CGAL 3.49 -> 3.12 s; the GL
// method at n = 4 1.64 -> 1.45 s; n = 12 (10 M) streamed in blocks of a million faces 3.3 -> 2.65 s.
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <new>

#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)

namespace {

constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;

// The heap's whole huge pages, advised as it grows: up to here (a multiple of 2 MiB).
std::atomic<std::uintptr_t> heap_advised{0};

// The heap's new whole huge pages, advised (a hint: failure changes nothing): one call each time
// the heap has grown by 2 MiB or more, whichever thread allocates then.
void advise_huge_pages() {
  const std::uintptr_t top = reinterpret_cast<std::uintptr_t>(sbrk(0)) & ~(kHugePage - 1);
  std::uintptr_t from = heap_advised.load(std::memory_order_relaxed);
  if (top <= from || !heap_advised.compare_exchange_strong(from, top)) return;
  madvise(reinterpret_cast<void*>(from), top - from, MADV_HUGEPAGE);
}

// As the standard's operator new: the new-handler is called until it succeeds or there is none.
template <class Allocate>
void* allocate(std::size_t size, const Allocate& try_allocate) {
  if (size == 0) size = 1;
  for (;;) {
    if (void* p = try_allocate(size)) {
      advise_huge_pages();
      return p;
    }
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

// Set before main, as the executable's first allocations are made: one heap for every thread,
// never given back to the kernel before the end, growing 32 MiB at a time.
const bool heap_for_large_blocks = [] {
  heap_advised = (reinterpret_cast<std::uintptr_t>(sbrk(0)) + kHugePage - 1) & ~(kHugePage - 1);
  return mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_ARENA_MAX, 1) == 1 &&
         mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1 && mallopt(M_TOP_PAD, 32 << 20) == 1;
}();

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
