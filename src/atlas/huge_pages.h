// Large arrays the atlas fills once and reads many times (the surface's, the segmentation's)
// are asked for transparent huge pages before their first touch. On the project's 2-core
// virtual machine a page touched for the first time costs tens of microseconds (20 MB touched
// in 4 KB pages: 200 ms; the same in 2 MB pages after madvise: 14 to 49 ms), which was most of
// the topology and segmentation phases' time on a million triangles. Only advice: where the
// system has no such pages (or is not Linux), nothing changes; the contents never depend on it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace raps {

// Reserves room for `count` elements in the empty `array` and advises huge pages over the
// whole 2 MB stretches inside it; the caller then fills it (resize, assign, push_back).
template <typename T>
void reserve_huge_pages(std::vector<T>& array, size_t count) {
    array.reserve(count);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    constexpr uintptr_t kHugePage = uintptr_t{2} << 20;
    const uintptr_t first = reinterpret_cast<uintptr_t>(array.data());
    const uintptr_t begin = (first + kHugePage - 1) & ~(kHugePage - 1);
    const uintptr_t end = (first + count * sizeof(T)) & ~(kHugePage - 1);
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#endif
}

}  // namespace raps
