/* The progress state (raps_progress_state): a run writes every report the progress callback
 * would get into it, another thread reads it at any time, and a cancel made there stops the
 * run at its next report with RAPS_ERROR_CANCELLED, the handles usable afterwards. Pinned:
 * the state holds exactly the report the callback is about to see (phase, fraction, count);
 * a run with a state gives the same bits as one without; a cancel from a polling thread
 * (the way a Python or C# caller uses it) stops disk and atlas runs, stays until reset, and
 * a reset state serves the next run; one cancel stops every run sharing the state; bad
 * arguments are refused. */
#define _POSIX_C_SOURCE 200809L /* nanosleep */
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cmocka.h>

#include "raps.h"
#include "support/test_meshes.h"

static raps_settings* domain_settings(int32_t domain, int64_t threads) {
    raps_settings* s = NULL;
    assert_status(raps_settings_create(&s), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_DOMAIN, domain), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_THREADS, threads), RAPS_OK);
    if (domain == RAPS_DOMAIN_ATLAS)
        assert_status(raps_settings_set_int(s, RAPS_PARAM_ATLAS_RESOLUTION, 128), RAPS_OK);
    return s;
}

/* At each callback call: the state read then must be the report the callback gets. */
typedef struct mirror {
    const raps_progress_state* state;
    int64_t calls;
    int mismatches;
    raps_phase last_phase;
    double last_fraction;
} mirror;

static int32_t compare_with_state(void* user, raps_phase phase, double fraction) {
    mirror* m = user; /* calls never overlap (the header) */
    ++m->calls;
    raps_phase read_phase = -2;
    double read_fraction = -1.0;
    int64_t reports = -1;
    if (raps_progress_state_read(m->state, &read_phase, &read_fraction, &reports) != RAPS_OK ||
        read_phase != phase || read_fraction != fraction || reports != m->calls)
        ++m->mismatches;
    m->last_phase = phase;
    m->last_fraction = fraction;
    return 1;
}

static void a_state_holds_each_report_the_callback_gets(void** state) {
    (void)state;
    test_mesh torus = make_closed_torus(24, 12); /* several charts, mapped on 3 threads */
    raps_mesh* m = to_raps_mesh(&torus);
    raps_settings* s = domain_settings(RAPS_DOMAIN_ATLAS, 3);
    raps_progress_state* p = NULL;
    assert_status(raps_progress_state_create(&p), RAPS_OK);
    raps_phase phase = 0;
    double fraction = -1.0;
    int64_t reports = -1;
    assert_status(raps_progress_state_read(p, &phase, &fraction, &reports), RAPS_OK);
    assert_int_equal(phase, -1);
    assert_true(fraction == 0.0);
    assert_int_equal(reports, 0);

    mirror seen = {p, 0, 0, -1, 0.0};
    assert_status(raps_settings_set_progress_state(s, p), RAPS_OK);
    assert_status(raps_settings_set_progress(s, compare_with_state, &seen), RAPS_OK);
    raps_result* r = NULL;
    assert_status(raps_result_create(&r), RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_OK);
    print_message("%lld reports, each read back from the state\n", (long long)seen.calls);
    assert_true(seen.calls > 20);
    assert_int_equal(seen.mismatches, 0);
    assert_status(raps_progress_state_read(p, &phase, &fraction, &reports), RAPS_OK);
    assert_int_equal(reports, seen.calls);
    assert_int_equal(phase, seen.last_phase);
    assert_true(fraction == 1.0 && seen.last_fraction == 1.0); /* a phase ends at 1 */

    /* A state alone (no callback) records as many reports and changes no bit of the output. */
    const size_t count_with = raps_result_vertex_count(r);
    double* with = uvs_of(r);
    assert_status(raps_settings_set_progress(s, NULL, NULL), RAPS_OK);
    assert_status(raps_progress_state_reset(p), RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_OK);
    assert_status(raps_progress_state_read(p, NULL, NULL, &reports), RAPS_OK);
    assert_int_equal(reports, seen.calls);
    assert_status(raps_settings_set_progress_state(s, NULL), RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_OK);
    double* without = uvs_of(r);
    assert_int_equal(raps_result_vertex_count(r), count_with);
    assert_memory_equal(with, without, 2 * count_with * sizeof(double));
    free(with);
    free(without);
    raps_result_destroy(r);
    raps_progress_state_destroy(p);
    raps_settings_destroy(s);
    raps_mesh_destroy(m);
    test_mesh_free(&torus);
}

/* A thread that polls the state, as a caller's interface thread would, and cancels it once the
 * run has made `cancel_after` reports. The run's callback holds the run at that report until
 * the cancel has been made, so the cancel lands mid-run on any machine. */
typedef struct poller {
    raps_progress_state* state;
    int64_t cancel_after;
    int64_t callback_calls, calls_after_cancel;
    int cancelled;
    pthread_mutex_t lock;
    pthread_cond_t changed;
} poller;

static void* poll_and_cancel(void* user) {
    poller* p = user;
    for (;;) {
        int64_t reports = 0;
        assert_status(raps_progress_state_read(p->state, NULL, NULL, &reports), RAPS_OK);
        if (reports >= p->cancel_after) break;
        struct timespec pause = {0, 100000};
        nanosleep(&pause, NULL);
    }
    assert_status(raps_progress_state_cancel(p->state), RAPS_OK);
    pthread_mutex_lock(&p->lock);
    p->cancelled = 1;
    pthread_cond_broadcast(&p->changed);
    pthread_mutex_unlock(&p->lock);
    return NULL;
}

static int32_t hold_until_cancelled(void* user, raps_phase phase, double fraction) {
    (void)phase;
    (void)fraction;
    poller* p = user;
    pthread_mutex_lock(&p->lock);
    if (p->cancelled) ++p->calls_after_cancel;
    ++p->callback_calls;
    if (p->callback_calls == p->cancel_after) {
        while (!p->cancelled) pthread_cond_wait(&p->changed, &p->lock);
    }
    pthread_mutex_unlock(&p->lock);
    return 1; /* never the callback's own cancel */
}

static void assert_cancel_from_a_polling_thread(const test_mesh* mesh, raps_settings* s,
                                                int64_t cancel_after) {
    raps_mesh* m = to_raps_mesh(mesh);
    raps_result* r = NULL;
    assert_status(raps_result_create(&r), RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_OK);
    const size_t reference_count = raps_result_vertex_count(r);
    double* reference = uvs_of(r);

    poller p;
    memset(&p, 0, sizeof(p));
    assert_status(raps_progress_state_create(&p.state), RAPS_OK);
    p.cancel_after = cancel_after;
    pthread_mutex_init(&p.lock, NULL);
    pthread_cond_init(&p.changed, NULL);
    assert_status(raps_settings_set_progress_state(s, p.state), RAPS_OK);
    assert_status(raps_settings_set_progress(s, hold_until_cancelled, &p), RAPS_OK);
    pthread_t thread;
    assert_int_equal(pthread_create(&thread, NULL, poll_and_cancel, &p), 0);
    assert_status(raps_parameterize(m, s, r), RAPS_ERROR_CANCELLED);
    pthread_join(thread, NULL);
    assert_non_null(strstr(raps_result_last_error(r), "progress state"));
    assert_int_equal(raps_result_vertex_count(r), 0);
    /* Stopped at the report after the cancel, which the callback never saw. */
    int64_t reports = 0;
    assert_status(raps_progress_state_read(p.state, NULL, NULL, &reports), RAPS_OK);
    assert_int_equal(reports, cancel_after + 1);
    assert_int_equal(p.callback_calls, cancel_after);
    assert_int_equal(p.calls_after_cancel, 0);

    /* Cancelled until reset: a new run stops at its first report. */
    assert_status(raps_parameterize(m, s, r), RAPS_ERROR_CANCELLED);
    assert_status(raps_progress_state_read(p.state, NULL, NULL, &reports), RAPS_OK);
    assert_int_equal(reports, cancel_after + 2);
    assert_int_equal(p.callback_calls, cancel_after);

    /* Reset, it serves the next run, whose output is the uncancelled one. */
    assert_status(raps_settings_set_progress(s, NULL, NULL), RAPS_OK);
    assert_status(raps_progress_state_reset(p.state), RAPS_OK);
    raps_phase phase = 0;
    assert_status(raps_progress_state_read(p.state, &phase, NULL, &reports), RAPS_OK);
    assert_int_equal(phase, -1);
    assert_int_equal(reports, 0);
    assert_status(raps_parameterize(m, s, r), RAPS_OK);
    double* again = uvs_of(r);
    assert_int_equal(raps_result_vertex_count(r), reference_count);
    assert_memory_equal(again, reference, 2 * reference_count * sizeof(double));

    assert_status(raps_settings_set_progress_state(s, NULL), RAPS_OK);
    free(again);
    free(reference);
    pthread_cond_destroy(&p.changed);
    pthread_mutex_destroy(&p.lock);
    raps_progress_state_destroy(p.state);
    raps_result_destroy(r);
    raps_mesh_destroy(m);
}

static void a_cancel_from_a_polling_thread_stops_a_disk_run(void** state) {
    (void)state;
    test_mesh disk = make_flat_disk(40, 12, 0.2);
    raps_settings* s = domain_settings(RAPS_DOMAIN_DISK, 1);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_ITERATIONS, 2), RAPS_OK);
    assert_cancel_from_a_polling_thread(&disk, s, 5);
    raps_settings_destroy(s);
    test_mesh_free(&disk);
}

static void a_cancel_from_a_polling_thread_stops_an_atlas_run(void** state) {
    (void)state;
    test_mesh mesh = load_shared_mesh("bunny.off");
    raps_settings* s = domain_settings(RAPS_DOMAIN_ATLAS, 3);
    assert_cancel_from_a_polling_thread(&mesh, s, 40); /* among the charts' maps */
    raps_settings_destroy(s);
    test_mesh_free(&mesh);
}

/* Two runs sharing one state, each held by its callback at its `hold_at`-th report until the
 * main thread has cancelled the state: one cancel stops both. */
typedef struct shared_run {
    const test_mesh* mesh;
    raps_settings* settings;
    int64_t hold_at, callback_calls, calls_after_cancel;
    raps_status status;
    struct shared_hold* hold;
} shared_run;

typedef struct shared_hold {
    pthread_mutex_t lock;
    pthread_cond_t changed;
    int held, cancelled;
} shared_hold;

static int32_t hold_until_shared_cancel(void* user, raps_phase phase, double fraction) {
    (void)phase;
    (void)fraction;
    shared_run* run = user;
    shared_hold* h = run->hold;
    pthread_mutex_lock(&h->lock);
    if (h->cancelled) ++run->calls_after_cancel;
    if (++run->callback_calls == run->hold_at) {
        ++h->held;
        pthread_cond_broadcast(&h->changed);
        while (!h->cancelled) pthread_cond_wait(&h->changed, &h->lock);
    }
    pthread_mutex_unlock(&h->lock);
    return 1;
}

static void* run_shared(void* user) {
    shared_run* run = user;
    raps_mesh* m = to_raps_mesh(run->mesh);
    raps_result* r = NULL;
    if (raps_result_create(&r) == RAPS_OK) run->status = raps_parameterize(m, run->settings, r);
    raps_result_destroy(r);
    raps_mesh_destroy(m);
    return NULL;
}

static void one_cancel_stops_every_run_sharing_the_state(void** state) {
    (void)state;
    test_mesh disk = make_flat_disk(40, 12, 0.2);
    test_mesh bunny = load_shared_mesh("bunny.off");
    raps_progress_state* p = NULL;
    assert_status(raps_progress_state_create(&p), RAPS_OK);
    shared_hold hold;
    memset(&hold, 0, sizeof(hold));
    pthread_mutex_init(&hold.lock, NULL);
    pthread_cond_init(&hold.changed, NULL);
    shared_run runs[2];
    memset(runs, 0, sizeof(runs));
    runs[0].mesh = &disk;
    runs[0].settings = domain_settings(RAPS_DOMAIN_DISK, 1);
    assert_status(raps_settings_set_int(runs[0].settings, RAPS_PARAM_ITERATIONS, 2), RAPS_OK);
    runs[0].hold_at = 5;
    runs[1].mesh = &bunny;
    runs[1].settings = domain_settings(RAPS_DOMAIN_ATLAS, 2);
    runs[1].hold_at = 40; /* among the charts' maps, reported from the worker threads */
    pthread_t threads[2];
    for (int k = 0; k < 2; ++k) {
        runs[k].hold = &hold;
        runs[k].status = RAPS_OK;
        assert_status(raps_settings_set_progress_state(runs[k].settings, p), RAPS_OK);
        assert_status(
            raps_settings_set_progress(runs[k].settings, hold_until_shared_cancel, &runs[k]),
            RAPS_OK);
        assert_int_equal(pthread_create(&threads[k], NULL, run_shared, &runs[k]), 0);
    }
    pthread_mutex_lock(&hold.lock);
    while (hold.held < 2) pthread_cond_wait(&hold.changed, &hold.lock);
    int64_t reports = 0;
    assert_status(raps_progress_state_read(p, NULL, NULL, &reports), RAPS_OK);
    assert_int_equal(reports, runs[0].hold_at + runs[1].hold_at); /* both runs' reports */
    assert_status(raps_progress_state_cancel(p), RAPS_OK);
    hold.cancelled = 1;
    pthread_cond_broadcast(&hold.changed);
    pthread_mutex_unlock(&hold.lock);
    for (int k = 0; k < 2; ++k) pthread_join(threads[k], NULL);

    /* Each stopped at its report after the cancel, which its callback never saw. */
    for (int k = 0; k < 2; ++k) {
        assert_status(runs[k].status, RAPS_ERROR_CANCELLED);
        assert_int_equal(runs[k].callback_calls, runs[k].hold_at);
        assert_int_equal(runs[k].calls_after_cancel, 0);
        raps_settings_destroy(runs[k].settings);
    }
    assert_status(raps_progress_state_read(p, NULL, NULL, &reports), RAPS_OK);
    assert_int_equal(reports, runs[0].hold_at + runs[1].hold_at + 2);
    pthread_cond_destroy(&hold.changed);
    pthread_mutex_destroy(&hold.lock);
    raps_progress_state_destroy(p);
    test_mesh_free(&bunny);
    test_mesh_free(&disk);
}

static void bad_arguments_are_refused_and_clones_share_the_state(void** state) {
    (void)state;
    assert_status(raps_progress_state_create(NULL), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_progress_state_read(NULL, NULL, NULL, NULL), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_progress_state_cancel(NULL), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_progress_state_reset(NULL), RAPS_ERROR_INVALID_ARGUMENT);
    raps_progress_state_destroy(NULL);
    raps_progress_state* p = NULL;
    assert_status(raps_progress_state_create(&p), RAPS_OK);
    assert_status(raps_settings_set_progress_state(NULL, p), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_progress_state_read(p, NULL, NULL, NULL), RAPS_OK);

    /* A clone of the settings reports into the same state: cancelled there, its run stops. */
    raps_settings* s = domain_settings(RAPS_DOMAIN_DISK, 1);
    assert_status(raps_settings_set_progress_state(s, p), RAPS_OK);
    raps_settings* clone = NULL;
    assert_status(raps_settings_clone(s, &clone), RAPS_OK);
    assert_status(raps_progress_state_cancel(p), RAPS_OK);
    test_mesh disk = make_flat_disk(10, 4, 0.2);
    raps_mesh* m = to_raps_mesh(&disk);
    raps_result* r = NULL;
    assert_status(raps_result_create(&r), RAPS_OK);
    assert_status(raps_parameterize(m, clone, r), RAPS_ERROR_CANCELLED);
    int64_t reports = 0;
    assert_status(raps_progress_state_read(p, NULL, NULL, &reports), RAPS_OK);
    assert_int_equal(reports, 1);
    raps_result_destroy(r);
    raps_mesh_destroy(m);
    test_mesh_free(&disk);
    raps_settings_destroy(clone);
    raps_settings_destroy(s);
    raps_progress_state_destroy(p);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_state_holds_each_report_the_callback_gets),
        cmocka_unit_test(a_cancel_from_a_polling_thread_stops_a_disk_run),
        cmocka_unit_test(a_cancel_from_a_polling_thread_stops_an_atlas_run),
        cmocka_unit_test(one_cancel_stops_every_run_sharing_the_state),
        cmocka_unit_test(bad_arguments_are_refused_and_clones_share_the_state),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
