/* An allocator that fails on request, for the fault-injection test (test_alloc_failures.c).
 * failing_allocator.cpp replaces the global operator new and delete of the whole process (a
 * replacement in the executable interposes for libraps.so and libstdc++ too) and, outside the
 * sanitizer builds, malloc and its relatives (Eigen allocates through malloc), all counted while
 * armed. The test arms it, calls the library, disarms it, and reads what happened. */
#ifndef RAPS_FAILING_ALLOCATOR_H
#define RAPS_FAILING_ALLOCATOR_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Starts counting allocations (from any thread); the fail_at-th one from now fails (throws
 * std::bad_alloc, or returns NULL from malloc and the nothrow forms), and with `persistent` every
 * one after it too, as when memory has run out. fail_at 0: none fails, and the caller of each
 * allocation is recorded (see failing_allocator_site). */
void failing_allocator_arm(long fail_at, int persistent);
/* Stops counting; returns how many allocations were counted since arming. */
long failing_allocator_disarm(void);
/* Whether the allocation asked to fail was reached (and failed) since the last arm. */
int failing_allocator_failed(void);
/* The code address that made the i-th allocation (1-based) of the last count-only arming, or
 * NULL past what was recorded: allocations from one call site share it. */
const void* failing_allocator_site(long i);
/* Blocks from operator new not yet given back to operator delete, since the program started. */
long failing_allocator_live_blocks(void);
/* Bytes the heap has in use (mallinfo2, or the sanitizer's count under ASan). */
size_t failing_allocator_heap_bytes(void);
/* Whether malloc and its relatives are replaced too (not under the sanitizers, which replace them
 * themselves). */
int failing_allocator_covers_malloc(void);

#ifdef __cplusplus
}
#endif

#endif
