#include "progress_record.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stdlib.h>

#include <cmocka.h>

int32_t record_progress(void* user, raps_phase phase, double fraction) {
    progress_record* r = user;
    if (r->count == r->capacity) {
        r->capacity = r->capacity ? 2 * r->capacity : 4096;
        r->calls = realloc(r->calls, (size_t)r->capacity * sizeof(progress_call));
        assert_non_null(r->calls);
    }
    r->calls[r->count].phase = phase;
    r->calls[r->count].fraction = fraction;
    ++r->count;
    return r->count != r->cancel_at;
}

unsigned check_progress_follows_work(const char* name, const progress_record* r, size_t triangles,
                                     int first[RAPS_PHASE_COUNT], int calls[RAPS_PHASE_COUNT]) {
    const int minimum = 2 + (int)(triangles / kTrianglesPerCall);
    unsigned seen = 0;
    for (int p = 0; p < RAPS_PHASE_COUNT; ++p) first[p] = calls[p] = 0;
    assert_true(r->count > 0);
    for (int c = 0; c < r->count; ++c) {
        const progress_call* x = &r->calls[c];
        assert_true(x->phase >= 0 && x->phase < RAPS_PHASE_COUNT);
        assert_true(x->fraction >= 0.0 && x->fraction <= 1.0);
        if (c == 0 || r->calls[c - 1].phase != x->phase) {
            /* A phase's calls are contiguous: it starts once, at 0, after the last one ended
             * at 1. */
            assert_false(seen & (1u << x->phase));
            assert_true(x->fraction == 0.0);
            if (c > 0) assert_true(r->calls[c - 1].fraction == 1.0);
            seen |= 1u << x->phase;
            first[x->phase] = c;
        } else {
            assert_true(x->fraction >= r->calls[c - 1].fraction);
        }
        ++calls[x->phase];
    }
    assert_true(r->calls[r->count - 1].fraction == 1.0);
    for (int p = 0; p < RAPS_PHASE_COUNT; ++p) {
        if (!(seen & (1u << p))) continue;
        print_message("%s, %zu triangles: phase %d, %d calls (at least %d)\n", name, triangles, p,
                      calls[p], minimum);
        if (calls[p] < minimum) {
            fail_msg("%s: phase %d made %d progress calls for %zu triangles, fewer than %d", name,
                     p, calls[p], triangles, minimum);
        }
    }
    return seen;
}
