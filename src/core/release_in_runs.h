// Large buffers given back to the system in runs before they are freed, with a progress call
// between two. Freeing hundreds of megabytes in one go unmaps every resident page at once: at
// 5.65M triangles the sphere's factorizations took 70 to 126 ms to free with no progress call,
// so a cancel waited that long. madvise(MADV_DONTNEED) gives a run of pages back; the free that
// follows then has (nearly) none left to unmap. The contents are lost. Only where the system has
// MADV_DONTNEED (Linux); elsewhere the free costs what it costs (and the calls are the same).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "core/progress.h"

namespace raps {

// Bytes per run: 4,096 pages of 4 KB. Runs of 64 MB took 30 ms each to give back at 5.65M
// triangles (about 2 us a page on the project's virtual machine).
constexpr size_t kBytesPerReleaseRun = size_t(16) << 20;

// Gives back the whole pages inside [data, data + bytes) in runs of run_bytes (a multiple of
// 4 KB), a progress call between two runs: how many calls, and where, depends on `bytes` only,
// never on where the buffer lies, so every run of a mesh makes the same calls. A buffer of one
// run is left alone: with no call to put between, its free alone is as quick. Otherwise the
// memory stays the caller's (it reads as zeros afterwards) until it frees it.
inline void release_pages_in_runs(void* data, size_t bytes, const ProgressSpan& progress,
                                  size_t run_bytes = kBytesPerReleaseRun) {
    const size_t runs = (bytes + run_bytes - 1) / run_bytes;
    if (runs <= 1) return;
#if defined(__linux__) && defined(MADV_DONTNEED)
    // The whole pages inside the buffer, cut at page-aligned multiples of run_bytes.
    constexpr uintptr_t kPage = 4096;
    const uintptr_t pages_begin = (reinterpret_cast<uintptr_t>(data) + kPage - 1) & ~(kPage - 1);
    const uintptr_t pages_end = (reinterpret_cast<uintptr_t>(data) + bytes) & ~(kPage - 1);
#else
    (void)data;
#endif
    for (size_t r = 0; r < runs; ++r) {
        if (r > 0 && progress.active())
            progress.report(static_cast<double>(r) / static_cast<double>(runs));
#if defined(__linux__) && defined(MADV_DONTNEED)
        const uintptr_t begin = pages_begin + r * run_bytes;
        const uintptr_t end = r + 1 < runs ? std::min(begin + run_bytes, pages_end) : pages_end;
        if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_DONTNEED);
#endif
    }
}

// Frees `v` (capacity included) after giving its pages back in runs.
template <typename T>
void release_in_runs(std::vector<T>& v, const ProgressSpan& progress) {
    release_pages_in_runs(v.data(), v.capacity() * sizeof(T), progress);
    std::vector<T>().swap(v);
}

}  // namespace raps
