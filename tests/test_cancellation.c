/* Cancellation: the progress callback returning 0 at any of its calls, in every phase of every
 * domain, makes raps_parameterize return RAPS_ERROR_CANCELLED at once (no further call), leaves
 * the result empty with a message, frees what the run held (the sanitizer build's leak check
 * sees every cancelled run), and leaves the handles usable: the next run gives exactly the
 * output of a run that was never cancelled. Worker threads report too (the atlas maps charts in
 * parallel), so a cancellation also comes from them. */
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "raps.h"
#include "support/test_meshes.h"

/* Cancels at call number cancel_at (0: never), recording every call's phase and whether the
 * cancelling call came from a thread other than the one running the test (a worker). */
typedef struct probe {
    int calls;
    int cancel_at;
    int calls_after_cancel;
    pthread_t runner;
    int cancelled_on_worker;
    raps_phase phases[4096];
} probe;

static int32_t probe_progress(void* user, raps_phase phase, double fraction) {
    probe* p = user;
    assert_true(phase >= 0 && phase < RAPS_PHASE_COUNT);
    assert_true(fraction >= 0.0 && fraction <= 1.0);
    if (p->cancel_at > 0 && p->calls >= p->cancel_at) ++p->calls_after_cancel;
    if (p->calls < 4096) p->phases[p->calls] = phase;
    ++p->calls;
    if (p->calls == p->cancel_at)
        p->cancelled_on_worker = !pthread_equal(pthread_self(), p->runner);
    return p->calls != p->cancel_at;
}

/* A run's output, copied out: uvs (or sphere points) and triangles. */
typedef struct output {
    size_t vertex_count, index_count;
    double* values;
    uint32_t* indices;
} output;

static output output_of(const raps_result* r) {
    output o;
    o.vertex_count = raps_result_vertex_count(r);
    o.index_count = raps_result_index_count(r);
    o.values = calloc(3 * o.vertex_count + 1, sizeof(double));
    o.indices = calloc(o.index_count + 1, sizeof(uint32_t));
    assert_non_null(o.values);
    assert_non_null(o.indices);
    if (raps_result_copy_uvs_f64(r, o.values, o.vertex_count, 0) != RAPS_OK) {
        assert_status(raps_result_copy_sphere_points_f64(r, o.values, o.vertex_count, 0), RAPS_OK);
    }
    assert_status(raps_result_copy_indices_u32(r, o.indices, o.index_count), RAPS_OK);
    return o;
}

static void assert_same_output(const output* a, const output* b) {
    assert_int_equal(a->vertex_count, b->vertex_count);
    assert_int_equal(a->index_count, b->index_count);
    assert_memory_equal(a->values, b->values, 3 * a->vertex_count * sizeof(double));
    assert_memory_equal(a->indices, b->indices, a->index_count * sizeof(uint32_t));
}

static void free_output(output* o) {
    free(o->values);
    free(o->indices);
}

/* Cancels a run of `mesh` with `s` at each of its progress calls in turn. Returns the number of
 * calls of an uncancelled run; *phases_seen gets a bit per phase reported, *on_workers the
 * number of cancellations that came from a worker thread. */
static int cancel_at_every_call(const test_mesh* mesh, raps_settings* s, unsigned* phases_seen,
                                int* on_workers) {
    raps_mesh* m = to_raps_mesh(mesh);
    raps_result* r = NULL;
    assert_status(raps_result_create(&r), RAPS_OK);
    /* The reference: a run nobody cancels, through the same handles. */
    probe* full = calloc(1, sizeof(probe));
    assert_non_null(full);
    assert_status(raps_settings_set_progress(s, probe_progress, full), RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_OK);
    output reference = output_of(r);
    const int calls = full->calls;
    assert_true(calls >= 2 * 5 && calls < 4096);
    *phases_seen = 0;
    for (int c = 0; c < calls; ++c) *phases_seen |= 1u << full->phases[c];
    probe* p = calloc(1, sizeof(probe));
    assert_non_null(p);
    *on_workers = 0;
    for (int at = 1; at <= calls; ++at) {
        memset(p, 0, sizeof(*p));
        p->cancel_at = at;
        p->runner = pthread_self();
        assert_status(raps_settings_set_progress(s, probe_progress, p), RAPS_OK);
        const raps_status status = raps_parameterize(m, s, r);
        if (status != RAPS_ERROR_CANCELLED) {
            fail_msg("cancelling at call %d of %d (phase %d) returned %s: %s", at, calls,
                     (int)full->phases[at - 1], raps_status_string(status),
                     raps_result_last_error(r));
        }
        assert_int_equal(p->calls, at);
        assert_int_equal(p->calls_after_cancel, 0);
        *on_workers += p->cancelled_on_worker;
        assert_non_null(strstr(raps_result_last_error(r), "cancelled"));
        assert_int_equal(raps_result_vertex_count(r), 0);
        assert_int_equal(raps_result_index_count(r), 0);
        assert_true(raps_result_phase_ms(r, RAPS_PHASE_VALIDATE) == 0.0);
    }
    /* The handles are as good as new. */
    assert_status(raps_settings_set_progress(s, NULL, NULL), RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_OK);
    assert_string_equal(raps_result_last_error(r), "");
    output after = output_of(r);
    assert_same_output(&after, &reference);
    free_output(&after);
    free_output(&reference);
    free(p);
    free(full);
    raps_result_destroy(r);
    raps_mesh_destroy(m);
    return calls;
}

static raps_settings* domain_settings(int32_t domain, int64_t threads) {
    raps_settings* s = NULL;
    assert_status(raps_settings_create(&s), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_DOMAIN, domain), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_THREADS, threads), RAPS_OK);
    return s;
}

#define PHASE_BIT(phase) (1u << (phase))

static void disk_cancels_at_every_call(void** state) {
    (void)state;
    test_mesh disk = make_flat_disk(20, 6, 0.2);
    raps_settings* s = domain_settings(RAPS_DOMAIN_DISK, 1);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_ITERATIONS, 2), RAPS_OK);
    unsigned seen = 0;
    int on_workers = 0;
    const int calls = cancel_at_every_call(&disk, s, &seen, &on_workers);
    print_message("disk: cancelled at each of %d calls\n", calls);
    assert_int_equal(on_workers, 0); /* one thread */
    assert_int_equal(seen, PHASE_BIT(RAPS_PHASE_VALIDATE) | PHASE_BIT(RAPS_PHASE_TOPOLOGY) |
                               PHASE_BIT(RAPS_PHASE_INITIAL_MAP) | PHASE_BIT(RAPS_PHASE_ADAPT) |
                               PHASE_BIT(RAPS_PHASE_METRICS));
    raps_settings_destroy(s);
    test_mesh_free(&disk);
}

static void sphere_cancels_at_every_call(void** state) {
    (void)state;
    test_mesh sphere = make_icosphere(2);
    const int32_t methods[] = {RAPS_SPHERE_ROBUST, RAPS_SPHERE_LITERAL};
    for (int i = 0; i < 2; ++i) {
        raps_settings* s = domain_settings(RAPS_DOMAIN_SPHERE, 2);
        assert_status(raps_settings_set_int(s, RAPS_PARAM_SPHERE_METHOD, methods[i]), RAPS_OK);
        assert_status(raps_settings_set_int(s, RAPS_PARAM_SPHERE_MAX_SWEEPS, 30), RAPS_OK);
        assert_status(raps_settings_set_int(s, RAPS_PARAM_SPHERE_UV, RAPS_SPHERE_UV_OCTAHEDRAL),
                      RAPS_OK);
        unsigned seen = 0;
        int on_workers = 0;
        const int calls = cancel_at_every_call(&sphere, s, &seen, &on_workers);
        print_message("sphere (%s): cancelled at each of %d calls\n",
                      methods[i] == RAPS_SPHERE_ROBUST ? "robust" : "literal", calls);
        assert_int_equal(on_workers, 0); /* 162 vertices: below one thread per 4,096 */
        assert_int_equal(seen, PHASE_BIT(RAPS_PHASE_VALIDATE) | PHASE_BIT(RAPS_PHASE_TOPOLOGY) |
                                   PHASE_BIT(RAPS_PHASE_INITIAL_MAP) | PHASE_BIT(RAPS_PHASE_ADAPT) |
                                   PHASE_BIT(RAPS_PHASE_METRICS));
        raps_settings_destroy(s);
    }
    test_mesh_free(&sphere);
}

static void atlas_cancels_at_every_call(void** state) {
    (void)state;
    test_mesh torus = make_closed_torus(24, 12); /* several charts: mapped on 3 threads */
    raps_settings* s = domain_settings(RAPS_DOMAIN_ATLAS, 3);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_ATLAS_RESOLUTION, 128), RAPS_OK);
    unsigned seen = 0;
    int on_workers = 0;
    const int calls = cancel_at_every_call(&torus, s, &seen, &on_workers);
    print_message("atlas: cancelled at each of %d calls, %d of them from a worker thread\n", calls,
                  on_workers);
    assert_int_equal(seen, PHASE_BIT(RAPS_PHASE_VALIDATE) | PHASE_BIT(RAPS_PHASE_TOPOLOGY) |
                               PHASE_BIT(RAPS_PHASE_SEGMENT) | PHASE_BIT(RAPS_PHASE_INITIAL_MAP) |
                               PHASE_BIT(RAPS_PHASE_PACK) | PHASE_BIT(RAPS_PHASE_METRICS));
    raps_settings_destroy(s);
    test_mesh_free(&torus);
}

/* Cancels at the first call that comes from a thread other than `runner`. */
typedef struct worker_cancel {
    pthread_t runner;
    int calls, cancelled, calls_after;
} worker_cancel;

static int32_t cancel_on_a_worker(void* user, raps_phase phase, double fraction) {
    (void)phase;
    (void)fraction;
    worker_cancel* w = user; /* calls never overlap (the header), so plain fields do */
    ++w->calls;
    if (w->cancelled) {
        ++w->calls_after;
        return 0;
    }
    w->cancelled = !pthread_equal(pthread_self(), w->runner);
    return !w->cancelled;
}

/* A cancellation that comes from a worker thread (the atlas maps charts on them and reports
 * after each) stops the run as one from the calling thread does: CANCELLED, no further call,
 * the handles usable. The mesh's charts take long enough to map that workers take some. */
static void a_cancellation_from_a_worker_thread_stops_the_run(void** state) {
    (void)state;
    test_mesh mesh = load_shared_mesh("bunny.off");
    raps_mesh* m = to_raps_mesh(&mesh);
    raps_settings* s = domain_settings(RAPS_DOMAIN_ATLAS, 3);
    worker_cancel w = {pthread_self(), 0, 0, 0};
    assert_status(raps_settings_set_progress(s, cancel_on_a_worker, &w), RAPS_OK);
    raps_result* r = NULL;
    assert_status(raps_result_create(&r), RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_ERROR_CANCELLED);
    print_message("cancelled at call %d, from a worker thread\n", w.calls);
    assert_true(w.cancelled);
    assert_int_equal(w.calls_after, 0);
    assert_int_equal(raps_result_vertex_count(r), 0);
    assert_non_null(strstr(raps_result_last_error(r), "cancelled"));
    assert_status(raps_settings_set_progress(s, NULL, NULL), RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_OK);
    raps_result_destroy(r);
    raps_settings_destroy(s);
    raps_mesh_destroy(m);
    test_mesh_free(&mesh);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(disk_cancels_at_every_call),
        cmocka_unit_test(sphere_cancels_at_every_call),
        cmocka_unit_test(atlas_cancels_at_every_call),
        cmocka_unit_test(a_cancellation_from_a_worker_thread_stops_the_run),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
