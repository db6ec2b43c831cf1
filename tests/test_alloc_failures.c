/* Faults: an allocation failure injected at every allocation site a run reaches (the failing
 * allocator, faults/failing_allocator.h, replaces operator new and, outside the sanitizer build,
 * malloc). For each domain a counting run records which code made each allocation; then, for the
 * first allocation of every distinct site (and once past the last allocation), a whole session
 * through the C ABI (create the handles, set the arrays and settings, parameterize, copy the
 * output out) runs with that one allocation failing, and again with it and every later one
 * failing (memory that has run out). Every call must return its usual status or
 * RAPS_ERROR_OUT_OF_MEMORY, never crash; after a single failure the failing call's handle must
 * say "out of memory"; the same handles must then finish the session with exactly the output of
 * a run without faults (nothing was corrupted), and after destroying them as many blocks and
 * heap bytes are in use as before. A failure the library absorbs (a worker thread that cannot
 * start) must still give that output. Runs use one thread, so that allocations come in the same
 * order every time; the threaded cases then fail each allocation site only threads reach. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "faults/failing_allocator.h"
#include "raps.h"
#include "support/test_meshes.h"

/* One session to run with faults. */
typedef struct fault_case {
    const char* name;
    test_mesh mesh;
    int32_t domain;
    int64_t threads;
    int64_t monitor;
    int64_t sphere_uv;
    int64_t sphere_max_sweeps;
    int cancel_at; /* > 0: the progress callback cancels at this call */
} fault_case;

/* The handles of a session and where its output goes (allocated before arming). */
typedef struct session {
    raps_mesh* mesh;
    raps_settings* settings;
    raps_result* result;
    size_t capacity; /* output vertices the buffers hold */
    double* values;  /* uvs, or sphere points when the map has no uvs */
    uint32_t* indices;
    uint32_t* remap;
    size_t vertex_count, index_count;
    raps_stats stats;
    int progress_calls;
    int cancel_at;
} session;

static int32_t cancel_at_call(void* user, raps_phase phase, double fraction) {
    (void)phase;
    (void)fraction;
    session* s = user;
    return ++s->progress_calls != s->cancel_at;
}

enum { kStepCount = 9 };

/* The message of the handle step `s` stores its failure in, or NULL (creation steps). */
static const char* message_of_step(const session* s, int step) {
    switch (step) {
        case 3:
        case 4:
            return raps_mesh_last_error(s->mesh);
        case 5:
            return raps_settings_last_error(s->settings);
        case 6:
        case 7:
        case 8:
            return raps_result_last_error(s->result);
        default:
            return NULL;
    }
}

/* Step `step` of the session; returns its status. Steps 0-2 skip a handle that exists. */
static raps_status run_step(const fault_case* c, session* s, int step) {
    switch (step) {
        case 0:
            return s->mesh ? RAPS_OK : raps_mesh_create(&s->mesh);
        case 1:
            return s->settings ? RAPS_OK : raps_settings_create(&s->settings);
        case 2:
            return s->result ? RAPS_OK : raps_result_create(&s->result);
        case 3:
            return raps_mesh_set_positions_f64(s->mesh, c->mesh.positions, c->mesh.vertex_count, 0);
        case 4:
            return raps_mesh_set_indices_u32(s->mesh, c->mesh.indices, c->mesh.index_count);
        case 5: {
            const struct {
                raps_param param;
                int64_t value;
            } values[] = {{RAPS_PARAM_DOMAIN, c->domain},
                          {RAPS_PARAM_THREADS, c->threads},
                          {RAPS_PARAM_MONITOR, c->monitor},
                          {RAPS_PARAM_SPHERE_UV, c->sphere_uv},
                          {RAPS_PARAM_SPHERE_MAX_SWEEPS, c->sphere_max_sweeps},
                          {RAPS_PARAM_ATLAS_RESOLUTION, 64}};
            for (size_t i = 0; i < sizeof(values) / sizeof(values[0]); ++i) {
                const raps_status status =
                    raps_settings_set_int(s->settings, values[i].param, values[i].value);
                if (status != RAPS_OK) return status;
            }
            s->cancel_at = c->cancel_at;
            return c->cancel_at > 0 ? raps_settings_set_progress(s->settings, cancel_at_call, s)
                                    : RAPS_OK;
        }
        case 6:
            s->progress_calls = 0;
            return raps_parameterize(s->mesh, s->settings, s->result);
        case 7: {
            s->vertex_count = raps_result_vertex_count(s->result);
            s->index_count = raps_result_index_count(s->result);
            if (s->vertex_count > s->capacity || s->index_count > 3 * s->capacity) {
                return RAPS_ERROR_INTERNAL; /* the buffers are too small: a test bug */
            }
            raps_status status = raps_result_copy_uvs_f64(s->result, s->values, s->capacity, 0);
            if (status == RAPS_ERROR_INVALID_OPERATION) {
                status = raps_result_copy_sphere_points_f64(s->result, s->values, s->capacity, 0);
            }
            if (status == RAPS_OK) {
                status = raps_result_copy_indices_u32(s->result, s->indices, 3 * s->capacity);
            }
            if (status == RAPS_OK) {
                status = raps_result_copy_vertex_remap(s->result, s->remap, s->capacity);
            }
            return status;
        }
        default:
            memset(&s->stats, 0, sizeof(s->stats));
            s->stats.struct_size = sizeof(s->stats);
            return raps_result_get_stats(s->result, &s->stats);
    }
}

/* What parameterize returns without faults: cancelled, for a case that cancels. */
static raps_status expected_run_status(const fault_case* c) {
    return c->cancel_at > 0 ? RAPS_ERROR_CANCELLED : RAPS_OK;
}

/* Runs the steps from `step` on; returns the step that failed (kStepCount when the session is
 * done: all steps ran, or a cancelling case stopped at its expected status) and its status. */
static int run_steps(const fault_case* c, session* s, int step, raps_status* status) {
    for (; step < kStepCount; ++step) {
        *status = run_step(c, s, step);
        if (step == 6 && *status == expected_run_status(c) && *status != RAPS_OK) {
            return kStepCount; /* cancelled as expected: nothing to copy out */
        }
        if (*status != RAPS_OK) return step;
    }
    *status = RAPS_OK;
    return kStepCount;
}

static session new_session(size_t capacity) {
    session s;
    memset(&s, 0, sizeof(s));
    s.capacity = capacity;
    s.values = calloc(3 * capacity, sizeof(double));
    s.indices = calloc(3 * capacity, sizeof(uint32_t));
    s.remap = calloc(capacity, sizeof(uint32_t));
    assert_non_null(s.values);
    assert_non_null(s.indices);
    assert_non_null(s.remap);
    return s;
}

static void end_session(session* s) {
    raps_result_destroy(s->result);
    raps_settings_destroy(s->settings);
    raps_mesh_destroy(s->mesh);
    free(s->values);
    free(s->indices);
    free(s->remap);
    memset(s, 0, sizeof(*s));
}

/* Whether two finished sessions hold the same output, bit for bit. The statistics' thread count
 * describes the run, not the output (a threaded session is compared with a one-thread one, and
 * a worker that cannot start lowers it): it is left out. */
static int same_output(const session* a, const session* b) {
    raps_stats sa = a->stats, sb = b->stats;
    sa.threads_used = sb.threads_used = 0;
    return a->vertex_count == b->vertex_count && a->index_count == b->index_count &&
           memcmp(a->values, b->values, 3 * a->capacity * sizeof(double)) == 0 &&
           memcmp(a->indices, b->indices, a->index_count * sizeof(uint32_t)) == 0 &&
           memcmp(a->remap, b->remap, a->vertex_count * sizeof(uint32_t)) == 0 &&
           memcmp(&sa, &sb, sizeof(sa)) == 0;
}

/* Totals over one case's injections, printed at the end. */
typedef struct tally {
    long tried, out_of_memory, absorbed;
} tally;

/* Runs the session with the fail_at-th allocation failing (and every later one, if
 * `persistent`), then finishes it without faults and checks the output and that nothing is left
 * allocated. */
static void run_with_fault(const fault_case* c, const session* reference, long fail_at,
                           int persistent, tally* t) {
    const long blocks_before = failing_allocator_live_blocks();
    const size_t heap_before = failing_allocator_heap_bytes();
    session s = new_session(reference->capacity);
    raps_status status = RAPS_OK;
    failing_allocator_arm(fail_at, persistent);
    int step = run_steps(c, &s, 0, &status);
    failing_allocator_disarm();
    const int failed = failing_allocator_failed();
    ++t->tried;
    if (step < kStepCount) {
        const char* message = message_of_step(&s, step);
        if (status != RAPS_ERROR_OUT_OF_MEMORY || !failed) {
            fail_msg("%s, allocation %ld%s: step %d returned %s (%s)", c->name, fail_at,
                     persistent ? " on" : "", step, raps_status_string(status),
                     message ? message : "");
        }
        if (message && strcmp(message, "out of memory") != 0) {
            fail_msg("%s, allocation %ld%s: step %d says '%s'", c->name, fail_at,
                     persistent ? " on" : "", step, message);
        }
        ++t->out_of_memory;
        /* The same handles finish the session. */
        step = run_steps(c, &s, step, &status);
        if (step < kStepCount) {
            fail_msg("%s, after failing allocation %ld%s: step %d returned %s", c->name, fail_at,
                     persistent ? " on" : "", step, raps_status_string(status));
        }
    } else if (failed) {
        ++t->absorbed;
    }
    if (!same_output(&s, reference)) {
        fail_msg("%s, allocation %ld%s: the output differs from a run without faults", c->name,
                 fail_at, persistent ? " on" : "");
    }
    end_session(&s);
    const long blocks_after = failing_allocator_live_blocks();
    const size_t heap_after = failing_allocator_heap_bytes();
    if (blocks_after != blocks_before || heap_after != heap_before) {
        fail_msg("%s, allocation %ld%s: %ld blocks and %zu heap bytes in use, %ld and %zu before",
                 c->name, fail_at, persistent ? " on" : "", blocks_after, heap_after, blocks_before,
                 heap_before);
    }
}

/* The allocation sites of one session: counts them and returns, in *first_of_site, the index
 * of the first allocation of each distinct site (1-based), in order; returns how many. */
static long first_allocation_of_each_site(const fault_case* c, const session* reference,
                                          long** first_of_site, long* allocations) {
    session s = new_session(reference->capacity);
    raps_status status;
    failing_allocator_arm(0, 0);
    assert_int_equal(run_steps(c, &s, 0, &status), kStepCount);
    *allocations = failing_allocator_disarm();
    end_session(&s);
    *first_of_site = calloc((size_t)*allocations + 1, sizeof(long));
    const void** seen = calloc((size_t)*allocations + 1, sizeof(void*));
    assert_non_null(*first_of_site);
    assert_non_null(seen);
    long sites = 0;
    for (long i = 1; i <= *allocations; ++i) {
        const void* site = failing_allocator_site(i);
        assert_non_null(site);
        long k = 0;
        while (k < sites && seen[k] != site) ++k;
        if (k == sites) {
            seen[sites] = site;
            (*first_of_site)[sites++] = i;
        }
    }
    free(seen);
    return sites;
}

static session reference_session(const fault_case* c) {
    size_t capacity = 2 * c->mesh.vertex_count + 64; /* seams add output vertices */
    session s = new_session(capacity);
    raps_status status;
    const int step = run_steps(c, &s, 0, &status);
    if (step < kStepCount) {
        fail_msg("%s: step %d returned %s without faults", c->name, step,
                 raps_status_string(status));
    }
    /* Handles are not part of the output: keep only the copies. */
    raps_result_destroy(s.result);
    raps_settings_destroy(s.settings);
    raps_mesh_destroy(s.mesh);
    s.result = NULL;
    s.settings = NULL;
    s.mesh = NULL;
    return s;
}

static void fail_every_site(fault_case* c) {
    session reference = reference_session(c);
    run_with_fault(c, &reference, 1L << 40, 0, &(tally){0, 0, 0}); /* warms lazy state up */
    long* first_of_site = NULL;
    long allocations = 0;
    const long sites = first_allocation_of_each_site(c, &reference, &first_of_site, &allocations);
    tally once = {0, 0, 0}, on = {0, 0, 0};
    for (long k = 0; k < sites; ++k) {
        run_with_fault(c, &reference, first_of_site[k], 0, &once);
        run_with_fault(c, &reference, first_of_site[k], 1, &on);
    }
    /* Past the last allocation nothing fails, and the session is the reference. */
    run_with_fault(c, &reference, allocations + 1, 1, &on);
    assert_int_equal(once.out_of_memory + once.absorbed, sites);
    assert_int_equal(on.out_of_memory + on.absorbed, sites);
    print_message(
        "%s: %ld allocations from %ld sites%s; each failed in turn: %ld out of memory, "
        "%ld absorbed; failing from each on: %ld out of memory, %ld absorbed\n",
        c->name, allocations, sites,
        failing_allocator_covers_malloc() ? "" : " (operator new only)", once.out_of_memory,
        once.absorbed, on.out_of_memory, on.absorbed);
    free(first_of_site);
    end_session(&reference);
    test_mesh_free(&c->mesh);
}

static void disk_fails_cleanly_at_every_allocation_site(void** state) {
    (void)state;
    fault_case c = {"disk", make_flat_disk(3, 6, 0.2), RAPS_DOMAIN_DISK, 1, RAPS_MONITOR_AREA, 0, 0,
                    0};
    fail_every_site(&c);
}

static void sphere_fails_cleanly_at_every_allocation_site(void** state) {
    (void)state;
    fault_case c = {"sphere",
                    make_icosphere(1),
                    RAPS_DOMAIN_SPHERE,
                    1,
                    RAPS_MONITOR_AREA,
                    RAPS_SPHERE_UV_OCTAHEDRAL,
                    10,
                    0};
    fail_every_site(&c);
}

static void atlas_fails_cleanly_at_every_allocation_site(void** state) {
    (void)state;
    fault_case c = {
        "atlas", make_punctured_torus(8, 4), RAPS_DOMAIN_ATLAS, 1, RAPS_MONITOR_AREA, 0, 0, 0};
    fail_every_site(&c);
}

/* A run the progress callback cancels: the cancellation's message is made before memory runs
 * out and stored after, so storing it must not need memory the library cannot get. */
static void a_cancelled_run_fails_cleanly_at_every_allocation_site(void** state) {
    (void)state;
    fault_case c = {"disk, cancelled",
                    make_flat_disk(3, 6, 0.2),
                    RAPS_DOMAIN_DISK,
                    1,
                    RAPS_MONITOR_AREA,
                    0,
                    0,
                    6};
    fail_every_site(&c);
}

/* With threads, the allocations only threads make: starting them (std::thread's state, the
 * stack and thread-local storage pthread_create allocates) and what workers allocate apart from
 * the work itself. Each of them fails in turn, not only the first of its site, so that a thread
 * fails to start after another one did. Allocation order varies from run to run with threads,
 * so an index is only where such an allocation usually is; every promise is checked whatever
 * allocation fails. */
static void fail_sites_only_threads_reach(fault_case* single, fault_case* threaded) {
    session reference = reference_session(single);
    long *single_sites = NULL, *threaded_sites = NULL;
    long single_count = 0, threaded_count = 0;
    const long singles =
        first_allocation_of_each_site(single, &reference, &single_sites, &single_count);
    const void** known = calloc((size_t)singles + 1, sizeof(void*));
    assert_non_null(known);
    for (long k = 0; k < singles; ++k) known[k] = failing_allocator_site(single_sites[k]);
    /* failing_allocator_site reads the last count: count the threaded session now. */
    first_allocation_of_each_site(threaded, &reference, &threaded_sites, &threaded_count);
    long* thread_only = calloc((size_t)threaded_count + 1, sizeof(long));
    assert_non_null(thread_only);
    long thread_only_count = 0;
    for (long i = 1; i <= threaded_count; ++i) {
        const void* site = failing_allocator_site(i);
        long j = 0;
        while (j < singles && known[j] != site) ++j;
        if (j == singles) thread_only[thread_only_count++] = i;
    }
    assert_true(thread_only_count > 0); /* threads did start */
    tally t = {0, 0, 0};
    for (long k = 0; k < thread_only_count; ++k) {
        run_with_fault(threaded, &reference, thread_only[k], 0, &t);
    }
    print_message(
        "%s: %ld of %ld allocations only threads make; each failed in turn: %ld out of "
        "memory, %ld absorbed\n",
        threaded->name, thread_only_count, threaded_count, t.out_of_memory, t.absorbed);
    free(known);
    free(thread_only);
    free(single_sites);
    free(threaded_sites);
    end_session(&reference);
}

static void atlas_threads_fail_cleanly(void** state) {
    (void)state;
    test_mesh torus = make_closed_torus(24, 12); /* several charts, mapped in parallel */
    fault_case single = {
        "atlas, 1 thread", torus, RAPS_DOMAIN_ATLAS, 1, RAPS_MONITOR_AREA, 0, 0, 0};
    fault_case threaded = single;
    threaded.name = "atlas, 3 threads";
    threaded.threads = 3;
    fail_sites_only_threads_reach(&single, &threaded);
    test_mesh_free(&torus);
}

static void sphere_threads_fail_cleanly(void** state) {
    (void)state;
    /* The sphere starts a thread per 4096 vertices: 12872 vertices give it 3, two of them
     * workers, so that one can fail to start after the other did. */
    test_mesh sphere = make_uv_sphere(100, 130);
    fault_case single = {
        "sphere, 1 thread", sphere, RAPS_DOMAIN_SPHERE, 1, RAPS_MONITOR_NONE, 0, 2, 0};
    fault_case threaded = single;
    threaded.name = "sphere, 3 threads";
    threaded.threads = 3;
    fail_sites_only_threads_reach(&single, &threaded);
    test_mesh_free(&sphere);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(disk_fails_cleanly_at_every_allocation_site),
        cmocka_unit_test(sphere_fails_cleanly_at_every_allocation_site),
        cmocka_unit_test(atlas_fails_cleanly_at_every_allocation_site),
        cmocka_unit_test(a_cancelled_run_fails_cleanly_at_every_allocation_site),
        cmocka_unit_test(atlas_threads_fail_cleanly),
        cmocka_unit_test(sphere_threads_fail_cleanly),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
