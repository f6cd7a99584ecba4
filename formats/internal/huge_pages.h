// formats/internal/huge_pages.h -- private to the libraries (the stream decoder, the
// runtime's watertight plan and CPU evaluation): large allocations advised onto
// transparent huge pages, where the kernel offers them for madvise (Linux).
//
// Advice only: the contents and every result are the same without it. It is for a
// first use of fresh memory, where faulting 4 KiB pages in dominates on a virtual
// machine (about 3 us a page: 32 MiB in 23-29 ms against 4-5 ms as 2 MiB pages;
// bench/README.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace lt::fmt {

inline constexpr size_t kHugePage = size_t(1) << 21;

// Advises the whole huge pages inside [p, p + bytes).
inline void adviseHugePages(void* p, size_t bytes) {
#if defined(__linux__)
    const uintptr_t begin = (uintptr_t(p) + kHugePage - 1) & ~uintptr_t(kHugePage - 1);
    const uintptr_t end = (uintptr_t(p) + bytes) & ~uintptr_t(kHugePage - 1);
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
    (void)p, (void)bytes;
#endif
}

// At least `bytes` bytes (at least 1) for std::free, uninitialized, or null when
// none are left. From one huge page up: aligned to huge pages, rounded up to whole
// ones (shared with no other allocation) and advised onto them.
inline void* allocateHugePages(size_t bytes) {
#if defined(__linux__)
    if (bytes >= kHugePage) {
        const size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
        void* p = std::aligned_alloc(kHugePage, rounded);
        if (p) adviseHugePages(p, rounded);
        return p;
    }
#endif
    return std::malloc(bytes ? bytes : 1);
}

}  // namespace lt::fmt
