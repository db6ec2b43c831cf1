/* Every progress call of a run, recorded through the C ABI's callback, and the check that a
 * run's progress follows its work: per phase at least 2 + triangles / kTrianglesPerCall calls,
 * so that a phase that reports only at its start and end fails however fast the machine (work
 * is counted, never timed); each phase's calls contiguous, starting at 0, never falling, ending
 * at 1. */
#ifndef RAPS_TEST_PROGRESS_RECORD_H
#define RAPS_TEST_PROGRESS_RECORD_H

#include <stddef.h>
#include <stdint.h>

#include "raps.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Work per progress call a phase may not exceed, in triangles of the mesh (the library reports
 * every 8,192 items of a pass; a phase makes several passes). */
enum { kTrianglesPerCall = 16384 };

typedef struct progress_call {
    raps_phase phase;
    double fraction;
} progress_call;

/* Start from {0}; cancel_at: the call (1-based) at which the callback returns 0 (0: never).
 * free(calls) when done. */
typedef struct progress_record {
    progress_call* calls;
    int count, capacity, cancel_at;
} progress_record;

/* The callback for raps_settings_set_progress, with a progress_record as `user`. */
int32_t record_progress(void* user, raps_phase phase, double fraction);

/* Fails the test unless the recorded run's progress follows its work (above); `name` labels
 * its messages. Returns the phases seen as bits (1 << phase) and, per phase, its first call's
 * index and its number of calls. */
unsigned check_progress_follows_work(const char* name, const progress_record* record,
                                     size_t triangles, int first[RAPS_PHASE_COUNT],
                                     int calls[RAPS_PHASE_COUNT]);

#ifdef __cplusplus
}
#endif

#endif
