// The failing allocator (failing_allocator.h): replacements of the global operator new and
// delete, and outside the sanitizers of malloc, calloc, realloc, free and the aligned forms, that
// count allocations while armed and fail the one asked for.
#include "failing_allocator.h"

#include <errno.h>
#include <malloc.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <new>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define RAPS_UNDER_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
#define RAPS_UNDER_SANITIZER 1
#endif
#endif
#ifdef RAPS_UNDER_SANITIZER
// The sanitizer runtimes' count of heap bytes in use (GCC ships no header declaring it).
extern "C" size_t __sanitizer_get_current_allocated_bytes(void);
#endif

namespace {

std::atomic<bool> g_armed{false};
std::atomic<long> g_counted{0};
std::atomic<long> g_fail_at{0};
std::atomic<bool> g_failed{false};
std::atomic<bool> g_persistent{false};
std::atomic<long> g_live_blocks{0};

constexpr long kSiteCapacity = 1L << 21;
const void* g_sites[kSiteCapacity];  // per counted allocation of a count-only arming

// Counts one allocation made from `site`; returns whether it must fail.
bool must_fail(const void* site) {
    if (!g_armed.load(std::memory_order_relaxed)) return false;
    const long n = g_counted.fetch_add(1, std::memory_order_relaxed) + 1;
    const long fail_at = g_fail_at.load(std::memory_order_relaxed);
    if (fail_at == 0) {
        if (n <= kSiteCapacity) g_sites[n - 1] = site;
        return false;
    }
    if (n < fail_at || (n > fail_at && !g_persistent.load(std::memory_order_relaxed))) {
        return false;
    }
    g_failed.store(true, std::memory_order_relaxed);
    return true;
}

}  // namespace

#ifndef RAPS_UNDER_SANITIZER
// glibc's own entry points: the replacements below hand real work to them (declared noexcept
// like glibc's declarations of the functions they replace).
extern "C" {
void* __libc_malloc(size_t size);
void* __libc_calloc(size_t count, size_t size);
void* __libc_realloc(void* block, size_t size);
void* __libc_memalign(size_t alignment, size_t size);
void __libc_free(void* block);
}
#define RAPS_RAW_MALLOC malloc_uncounted_failure
#define RAPS_RAW_MEMALIGN memalign_uncounted_failure
#define RAPS_RAW_FREE free

namespace {

// Heap bytes handed out through the replacements and not freed (malloc_usable_size of each):
// exact, unlike mallinfo2, which counts blocks cached per thread as in use.
std::atomic<long long> g_heap_bytes{0};

void* counted(void* block) {
    if (block) g_heap_bytes.fetch_add(static_cast<long long>(malloc_usable_size(block)));
    return block;
}

// What operator new allocates with: the heap bytes counted, the failure decided by new itself.
void* malloc_uncounted_failure(size_t size) noexcept {
    return counted(__libc_malloc(size));
}

void* memalign_uncounted_failure(size_t alignment, size_t size) noexcept {
    return counted(__libc_memalign(alignment, size));
}

}  // namespace

extern "C" {

void* malloc(size_t size) noexcept {
    if (must_fail(__builtin_return_address(0))) {
        errno = ENOMEM;
        return nullptr;
    }
    return counted(__libc_malloc(size));
}

void* calloc(size_t count, size_t size) noexcept {
    if (must_fail(__builtin_return_address(0))) {
        errno = ENOMEM;
        return nullptr;
    }
    return counted(__libc_calloc(count, size));
}

void* realloc(void* block, size_t size) noexcept {
    if (must_fail(__builtin_return_address(0))) {
        errno = ENOMEM;
        return nullptr;  // the block stays allocated, as with a real failure
    }
    const long long before = block ? static_cast<long long>(malloc_usable_size(block)) : 0;
    void* moved = __libc_realloc(block, size);
    if (moved || size == 0) g_heap_bytes.fetch_sub(before);
    return counted(moved);
}

void* memalign(size_t alignment, size_t size) noexcept {
    if (must_fail(__builtin_return_address(0))) {
        errno = ENOMEM;
        return nullptr;
    }
    return counted(__libc_memalign(alignment, size));
}

void* aligned_alloc(size_t alignment, size_t size) noexcept {
    return memalign(alignment, size);
}

int posix_memalign(void** out, size_t alignment, size_t size) noexcept {
    if (must_fail(__builtin_return_address(0))) return ENOMEM;
    void* block = counted(__libc_memalign(alignment, size));
    if (!block) return ENOMEM;
    *out = block;
    return 0;
}

void free(void* block) noexcept {
    if (block) g_heap_bytes.fetch_sub(static_cast<long long>(malloc_usable_size(block)));
    __libc_free(block);
}

}  // extern "C"
#else
#define RAPS_RAW_MALLOC std::malloc
#define RAPS_RAW_MEMALIGN(alignment, size) \
    std::aligned_alloc((alignment), ((size) + (alignment)-1) / (alignment) * (alignment))
#define RAPS_RAW_FREE std::free
#endif

namespace {

void* allocate(size_t size, const void* site) {
    if (must_fail(site)) return nullptr;
    void* block = RAPS_RAW_MALLOC(size ? size : 1);
    if (block) g_live_blocks.fetch_add(1, std::memory_order_relaxed);
    return block;
}

void* allocate_aligned(size_t size, std::align_val_t alignment, const void* site) {
    if (must_fail(site)) return nullptr;
    void* block = RAPS_RAW_MEMALIGN(static_cast<size_t>(alignment), size ? size : 1);
    if (block) g_live_blocks.fetch_add(1, std::memory_order_relaxed);
    return block;
}

void release(void* block) {
    if (!block) return;
    g_live_blocks.fetch_sub(1, std::memory_order_relaxed);
    RAPS_RAW_FREE(block);
}

}  // namespace

void* operator new(size_t size) {
    void* block = allocate(size, __builtin_return_address(0));
    if (!block) throw std::bad_alloc();
    return block;
}
void* operator new[](size_t size) {
    void* block = allocate(size, __builtin_return_address(0));
    if (!block) throw std::bad_alloc();
    return block;
}
void* operator new(size_t size, const std::nothrow_t&) noexcept {
    return allocate(size, __builtin_return_address(0));
}
void* operator new[](size_t size, const std::nothrow_t&) noexcept {
    return allocate(size, __builtin_return_address(0));
}
void* operator new(size_t size, std::align_val_t alignment) {
    void* block = allocate_aligned(size, alignment, __builtin_return_address(0));
    if (!block) throw std::bad_alloc();
    return block;
}
void* operator new[](size_t size, std::align_val_t alignment) {
    void* block = allocate_aligned(size, alignment, __builtin_return_address(0));
    if (!block) throw std::bad_alloc();
    return block;
}
void* operator new(size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
    return allocate_aligned(size, alignment, __builtin_return_address(0));
}
void* operator new[](size_t size, std::align_val_t alignment, const std::nothrow_t&) noexcept {
    return allocate_aligned(size, alignment, __builtin_return_address(0));
}

void operator delete(void* block) noexcept {
    release(block);
}
void operator delete[](void* block) noexcept {
    release(block);
}
void operator delete(void* block, size_t) noexcept {
    release(block);
}
void operator delete[](void* block, size_t) noexcept {
    release(block);
}
void operator delete(void* block, const std::nothrow_t&) noexcept {
    release(block);
}
void operator delete[](void* block, const std::nothrow_t&) noexcept {
    release(block);
}
void operator delete(void* block, std::align_val_t) noexcept {
    release(block);
}
void operator delete[](void* block, std::align_val_t) noexcept {
    release(block);
}
void operator delete(void* block, size_t, std::align_val_t) noexcept {
    release(block);
}
void operator delete[](void* block, size_t, std::align_val_t) noexcept {
    release(block);
}
void operator delete(void* block, std::align_val_t, const std::nothrow_t&) noexcept {
    release(block);
}
void operator delete[](void* block, std::align_val_t, const std::nothrow_t&) noexcept {
    release(block);
}

extern "C" {

void failing_allocator_arm(long fail_at, int persistent) {
    g_counted.store(0);
    g_failed.store(false);
    g_persistent.store(persistent != 0);
    g_fail_at.store(fail_at);
    g_armed.store(true);
}

long failing_allocator_disarm(void) {
    g_armed.store(false);
    return g_counted.load();
}

int failing_allocator_failed(void) {
    return g_failed.load() ? 1 : 0;
}

const void* failing_allocator_site(long i) {
    return i >= 1 && i <= kSiteCapacity && i <= g_counted.load() ? g_sites[i - 1] : nullptr;
}

long failing_allocator_live_blocks(void) {
    return g_live_blocks.load();
}

size_t failing_allocator_heap_bytes(void) {
#ifdef RAPS_UNDER_SANITIZER
    return __sanitizer_get_current_allocated_bytes();
#else
    return static_cast<size_t>(g_heap_bytes.load());
#endif
}

int failing_allocator_covers_malloc(void) {
#ifdef RAPS_UNDER_SANITIZER
    return 0;
#else
    return 1;
#endif
}

}  // extern "C"
