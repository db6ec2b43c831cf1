/* Progress as work goes on: every phase a run enters, in every domain, reports between its start
 * and its end in proportion to the work it does - at least once per kTrianglesPerCall triangles
 * of the mesh besides its start and end - so a phase that reports only at its start and end
 * fails here, however fast the machine. Work is counted, never timed. Within a phase the
 * fractions start at 0, never fall and end at 1, and a phase's calls are contiguous. A cancel
 * issued at a call in the middle of each phase stops the run there: RAPS_ERROR_CANCELLED and no
 * further call. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "raps.h"
#include "support/test_meshes.h"

/* Work per progress call a phase may not exceed, in triangles of the mesh (the library reports
 * every 8,192 items of a pass; a phase makes several passes). */
enum { kTrianglesPerCall = 16384 };

typedef struct call {
    raps_phase phase;
    double fraction;
} call;

/* Every call of a run, and the call at which to cancel (0: never). */
typedef struct recorder {
    call* calls;
    int count, capacity, cancel_at;
} recorder;

static int32_t record(void* user, raps_phase phase, double fraction) {
    recorder* r = user;
    if (r->count == r->capacity) {
        r->capacity = r->capacity ? 2 * r->capacity : 4096;
        r->calls = realloc(r->calls, (size_t)r->capacity * sizeof(call));
        assert_non_null(r->calls);
    }
    r->calls[r->count].phase = phase;
    r->calls[r->count].fraction = fraction;
    ++r->count;
    return r->count != r->cancel_at;
}

static raps_status run(const test_mesh* mesh, raps_settings* s, recorder* r) {
    raps_mesh* m = to_raps_mesh(mesh);
    raps_result* result = NULL;
    assert_status(raps_result_create(&result), RAPS_OK);
    assert_status(raps_settings_set_progress(s, record, r), RAPS_OK);
    const raps_status status = raps_parameterize(m, s, result);
    if (status == RAPS_ERROR_CANCELLED) {
        assert_int_equal(raps_result_vertex_count(result), 0);
    }
    raps_result_destroy(result);
    raps_mesh_destroy(m);
    return status;
}

/* The uncancelled run: per phase its calls (contiguous, rising from 0 to 1), at least
 * 2 + triangles / kTrianglesPerCall of them; then a cancel at the middle call of each phase. */
static void assert_progress_follows_work(const char* name, const test_mesh* mesh, raps_settings* s,
                                         unsigned expected_phases) {
    const size_t triangles = mesh->index_count / 3;
    const int minimum = 2 + (int)(triangles / kTrianglesPerCall);
    recorder full = {NULL, 0, 0, 0};
    assert_status(run(mesh, s, &full), RAPS_OK);
    int first[RAPS_PHASE_COUNT], calls[RAPS_PHASE_COUNT];
    unsigned seen = 0;
    for (int p = 0; p < RAPS_PHASE_COUNT; ++p) first[p] = calls[p] = 0;
    for (int c = 0; c < full.count; ++c) {
        const call* x = &full.calls[c];
        assert_true(x->phase >= 0 && x->phase < RAPS_PHASE_COUNT);
        assert_true(x->fraction >= 0.0 && x->fraction <= 1.0);
        const int starts = c == 0 || full.calls[c - 1].phase != x->phase;
        if (starts) {
            /* A phase's calls are contiguous: it starts once, at 0, after the last one ended
             * at 1. */
            assert_false(seen & (1u << x->phase));
            assert_true(x->fraction == 0.0);
            if (c > 0) assert_true(full.calls[c - 1].fraction == 1.0);
            seen |= 1u << x->phase;
            first[x->phase] = c;
        } else {
            assert_true(x->fraction >= full.calls[c - 1].fraction);
        }
        ++calls[x->phase];
    }
    assert_true(full.calls[full.count - 1].fraction == 1.0);
    assert_int_equal(seen, expected_phases);
    for (int p = 0; p < RAPS_PHASE_COUNT; ++p) {
        if (!(seen & (1u << p))) continue;
        print_message("%s, %zu triangles: phase %d, %d calls (at least %d)\n", name, triangles, p,
                      calls[p], minimum);
        if (calls[p] < minimum) {
            fail_msg("%s: phase %d made %d progress calls for %zu triangles, fewer than %d", name,
                     p, calls[p], triangles, minimum);
        }
        /* Cancelled at the middle call of the phase: that call is the run's last. */
        recorder cancelled = {NULL, 0, 0, first[p] + calls[p] / 2 + 1};
        assert_status(run(mesh, s, &cancelled), RAPS_ERROR_CANCELLED);
        assert_int_equal(cancelled.count, cancelled.cancel_at);
        assert_int_equal(cancelled.calls[cancelled.count - 1].phase, p);
        free(cancelled.calls);
    }
    free(full.calls);
}

#define PHASE_BIT(phase) (1u << (phase))

static raps_settings* domain_settings(int32_t domain) {
    raps_settings* s = NULL;
    assert_status(raps_settings_create(&s), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_DOMAIN, domain), RAPS_OK);
    /* One thread: the calls come in the same order every run, so a cancel at call k falls in
     * the phase it aims at (test_cancellation covers the workers' calls). */
    assert_status(raps_settings_set_int(s, RAPS_PARAM_THREADS, 1), RAPS_OK);
    return s;
}

static const unsigned kCommon = PHASE_BIT(RAPS_PHASE_VALIDATE) | PHASE_BIT(RAPS_PHASE_TOPOLOGY) |
                                PHASE_BIT(RAPS_PHASE_INITIAL_MAP) | PHASE_BIT(RAPS_PHASE_METRICS);

static void disk_phases_report_as_they_work(void** state) {
    (void)state;
    test_mesh grid = make_grid(128, 128, 1.0, 1.0); /* 32,768 triangles */
    raps_settings* s = domain_settings(RAPS_DOMAIN_DISK);
    assert_progress_follows_work("disk", &grid, s, kCommon | PHASE_BIT(RAPS_PHASE_ADAPT));
    raps_settings_destroy(s);
    test_mesh_free(&grid);
}

static void atlas_phases_report_as_they_work(void** state) {
    (void)state;
    test_mesh torus = make_closed_torus(128, 128); /* 32,768 triangles, several charts */
    raps_settings* s = domain_settings(RAPS_DOMAIN_ATLAS);
    assert_progress_follows_work(
        "atlas", &torus, s, kCommon | PHASE_BIT(RAPS_PHASE_SEGMENT) | PHASE_BIT(RAPS_PHASE_PACK));
    raps_settings_destroy(s);
    test_mesh_free(&torus);
}

static void sphere_phases_report_as_they_work(void** state) {
    (void)state;
    test_mesh sphere = make_uv_sphere(129, 128); /* 32,768 triangles */
    raps_settings* s = domain_settings(RAPS_DOMAIN_SPHERE);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_SPHERE_UV, RAPS_SPHERE_UV_OCTAHEDRAL),
                  RAPS_OK);
    assert_progress_follows_work("sphere", &sphere, s, kCommon | PHASE_BIT(RAPS_PHASE_ADAPT));
    raps_settings_destroy(s);
    test_mesh_free(&sphere);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(disk_phases_report_as_they_work),
        cmocka_unit_test(atlas_phases_report_as_they_work),
        cmocka_unit_test(sphere_phases_report_as_they_work),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
