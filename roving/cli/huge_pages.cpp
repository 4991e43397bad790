// The command's large allocations on transparent huge pages. Where the kernel makes them only on
// request (/sys/kernel/mm/transparent_hugepage/enabled: madvise, Debian's default), every 4 KiB of
// a model's arrays costs a page fault when first written: a fifth of `roving measure --pcc`'s time
// on a million points each side, and more for the loads of a 10^8-triangle REF. Asking for 2 MiB
// pages on each large block (what glibc's tunable glibc.malloc.hugetlb=1 does) takes 512 times
// fewer. Replaces the global operator new of this executable alone; memory is still malloc's, so
// the default operator delete (free) releases it. Sanitizer builds keep their own allocator.
//
// Large blocks also come from malloc's heap rather than a mapping each (M_MMAP_MAX 0): a block
// freed between stages (a file's bytes, a sort's spare room, a chunk of REF's samples) then
// serves the next stage's allocation on pages already faulted in, where a mapping would be
// unmapped and the next one zeroed by the kernel afresh. Measured: a million-point --pcc pair
// 0.72 -> 0.63 s; 10^8 OBJ triangles streamed 67 -> 58 s, peak 2.18 -> 2.19 GB.
#include <malloc.h>
#include <sys/mman.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <new>

#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)

namespace {

constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;
constexpr std::size_t kLarge = 4 * kHugePage;  // smaller blocks are left alone: most of them are in use

// The whole huge pages inside [p, p + size), advised (a hint: failure changes nothing).
void advise_huge_pages(void* p, std::size_t size) {
  if (size < kLarge) return;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(p) + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(p) + size) & ~(kHugePage - 1);
  if (begin < end) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

// As the standard's operator new: the new-handler is called until it succeeds or there is none.
template <class Allocate>
void* allocate(std::size_t size, const Allocate& try_allocate) {
  if (size == 0) size = 1;
  for (;;) {
    if (void* p = try_allocate(size)) {
      advise_huge_pages(p, size);
      return p;
    }
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

// Set before main, as the executable's first allocations are made.
const bool heap_for_large_blocks = mallopt(M_MMAP_MAX, 0) == 1;

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
