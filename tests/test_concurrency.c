/* The threading contract: one mesh and one settings handle shared read-only by concurrent
 * runs, each with its own result, give exactly the serial result; so do many threads each
 * running their own meshes of every domain at once, sharing one settings handle per domain (and
 * its progress callback), while some of the runs compute on a worker thread of their own (the
 * statistics' threads_used says which). ThreadSanitizer runs this file (quickstart). */
#include <math.h>
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

#define THREADS 4
#define RUNS_PER_THREAD 3

typedef struct job {
    const raps_mesh* mesh;
    const raps_settings* settings;
    const double* expected;
    size_t vertex_count;
    int mismatches;
    int failures;
} job;

static void* worker(void* arg) {
    job* j = arg;
    raps_result* r = NULL;
    if (raps_result_create(&r) != RAPS_OK) {
        j->failures++;
        return NULL;
    }
    double* uv = malloc(2 * j->vertex_count * sizeof(double));
    for (int run = 0; run < RUNS_PER_THREAD; ++run) {
        if (raps_parameterize(j->mesh, j->settings, r) != RAPS_OK ||
            raps_result_copy_uvs_f64(r, uv, j->vertex_count, 0) != RAPS_OK) {
            j->failures++;
            continue;
        }
        if (memcmp(uv, j->expected, 2 * j->vertex_count * sizeof(double)) != 0) j->mismatches++;
    }
    free(uv);
    raps_result_destroy(r);
    return NULL;
}

static double ripple(double x, double y) {
    return 0.3 * sin(4 * x + y) + 0.2 * x * x;
}

static void shared_mesh_and_settings_give_the_serial_result(void** state) {
    (void)state;
    test_mesh disk = make_lifted_disk(30, 6, ripple);
    raps_mesh* mesh = to_raps_mesh(&disk);
    raps_settings* settings = make_settings(RAPS_WEIGHTS_MEAN_VALUE, RAPS_MONITOR_AREA, 2, 2);
    raps_result* serial = parameterize_ok(mesh, settings);
    double* expected = uvs_of(serial);
    job jobs[THREADS];
    pthread_t threads[THREADS];
    for (int t = 0; t < THREADS; ++t) {
        jobs[t] = (job){mesh, settings, expected, disk.vertex_count, 0, 0};
        assert_int_equal(pthread_create(&threads[t], NULL, worker, &jobs[t]), 0);
    }
    for (int t = 0; t < THREADS; ++t) {
        assert_int_equal(pthread_join(threads[t], NULL), 0);
        assert_int_equal(jobs[t].failures, 0);
        assert_int_equal(jobs[t].mismatches, 0);
    }
    free(expected);
    raps_result_destroy(serial);
    raps_settings_destroy(settings);
    raps_mesh_destroy(mesh);
    test_mesh_free(&disk);
}

/* One run of the many-meshes test: its own mesh, a shared settings handle, and the output a
 * serial run gave. */
typedef struct own_mesh_job {
    raps_mesh* mesh;
    const raps_settings* settings;
    size_t vertex_count, index_count; /* of the serial output */
    double* values;                   /* serial uvs, or sphere points */
    uint32_t* indices;
    int mismatches, failures;
    uint64_t most_threads; /* the largest threads_used of its concurrent runs */
} own_mesh_job;

/* The output of `r` (uvs, or sphere points when it has none), malloc'ed. */
static double* values_of(const raps_result* r) {
    const size_t n = raps_result_vertex_count(r);
    double* values = calloc(3 * n + 1, sizeof(double));
    if (!values) return NULL;
    if (raps_result_copy_uvs_f64(r, values, n, 0) != RAPS_OK &&
        raps_result_copy_sphere_points_f64(r, values, n, 0) != RAPS_OK) {
        free(values);
        return NULL;
    }
    return values;
}

static void* run_own_mesh(void* arg) {
    own_mesh_job* j = arg;
    raps_result* r = NULL;
    if (raps_result_create(&r) != RAPS_OK) {
        j->failures++;
        return NULL;
    }
    uint32_t* indices = malloc(j->index_count * sizeof(uint32_t) + 1);
    for (int run = 0; run < RUNS_PER_THREAD && indices; ++run) {
        if (raps_parameterize(j->mesh, j->settings, r) != RAPS_OK ||
            raps_result_vertex_count(r) != j->vertex_count ||
            raps_result_copy_indices_u32(r, indices, j->index_count) != RAPS_OK) {
            j->failures++;
            continue;
        }
        double* values = values_of(r);
        raps_stats stats;
        memset(&stats, 0, sizeof(stats));
        stats.struct_size = sizeof(stats);
        if (!values || raps_result_get_stats(r, &stats) != RAPS_OK) {
            free(values);
            j->failures++;
            continue;
        }
        if (stats.threads_used > j->most_threads) j->most_threads = stats.threads_used;
        if (memcmp(values, j->values, 3 * j->vertex_count * sizeof(double)) != 0 ||
            memcmp(indices, j->indices, j->index_count * sizeof(uint32_t)) != 0) {
            j->mismatches++;
        }
        free(values);
    }
    free(indices);
    raps_result_destroy(r);
    return NULL;
}

static int32_t count_progress(void* user, raps_phase phase, double fraction) {
    (void)phase;
    (void)fraction;
    __atomic_add_fetch((int*)user, 1, __ATOMIC_RELAXED);
    return 1;
}

#define OWN_MESH_JOBS 9

/* Nine threads, three per domain, each with a mesh of its own; the runs of a domain share one
 * settings handle (2 threads per run, a progress callback counting every call). 2 threads
 * means the calling one and at most one worker, which a run starts only for a mesh large
 * enough to share: of these, the 8,972-vertex sphere (one thread per 4,096 vertices) and the
 * atlases (one pool for the whole run; its worker computes when it takes a chart or a block
 * before the calling thread does). The disks, below the 32,768 triangles at which their
 * statistics share out, and the smaller spheres start none. */
static void many_threads_with_their_own_meshes_give_the_serial_results(void** state) {
    (void)state;
    test_mesh meshes[OWN_MESH_JOBS] = {
        make_flat_disk(12, 6, 0.2),
        make_lifted_disk(16, 5, ripple),
        make_grid(20, 14, 2, 1),
        make_icosphere(2),
        make_icosphere(3),
        make_uv_sphere(70, 130), /* 8972 vertices: the sphere starts a worker for it */
        make_closed_torus(24, 12),
        make_punctured_torus(20, 10),
        make_open_cone(8, 6, 1.5)};
    const int32_t domains[3] = {RAPS_DOMAIN_DISK, RAPS_DOMAIN_SPHERE, RAPS_DOMAIN_ATLAS};
    raps_settings* settings[3];
    int progress_calls = 0;
    for (int d = 0; d < 3; ++d) {
        assert_status(raps_settings_create(&settings[d]), RAPS_OK);
        assert_status(raps_settings_set_int(settings[d], RAPS_PARAM_DOMAIN, domains[d]), RAPS_OK);
        assert_status(raps_settings_set_int(settings[d], RAPS_PARAM_THREADS, 2), RAPS_OK);
        assert_status(raps_settings_set_int(settings[d], RAPS_PARAM_SPHERE_MAX_SWEEPS, 20),
                      RAPS_OK);
        assert_status(raps_settings_set_int(settings[d], RAPS_PARAM_ATLAS_RESOLUTION, 256),
                      RAPS_OK);
        assert_status(raps_settings_set_progress(settings[d], count_progress, &progress_calls),
                      RAPS_OK);
    }
    assert_status(
        raps_settings_set_int(settings[1], RAPS_PARAM_SPHERE_UV, RAPS_SPHERE_UV_OCTAHEDRAL),
        RAPS_OK);
    /* threads_used of the serial runs: 1 where the run starts no worker, 2 for the sphere that
     * gives its worker a share of every sweep; an atlas's worker may or may not have taken work
     * (0: not checked beyond <= 2). */
    const uint64_t serial_threads[OWN_MESH_JOBS] = {1, 1, 1, 1, 1, 2, 0, 0, 0};
    own_mesh_job jobs[OWN_MESH_JOBS];
    int serial_calls = 0;
    for (int i = 0; i < OWN_MESH_JOBS; ++i) {
        own_mesh_job* j = &jobs[i];
        memset(j, 0, sizeof(*j));
        j->mesh = to_raps_mesh(&meshes[i]);
        j->settings = settings[i / 3];
        const int before = progress_calls;
        raps_result* serial = parameterize_ok(j->mesh, j->settings);
        serial_calls += progress_calls - before;
        j->vertex_count = raps_result_vertex_count(serial);
        j->index_count = raps_result_index_count(serial);
        j->values = values_of(serial);
        j->indices = malloc(j->index_count * sizeof(uint32_t));
        assert_non_null(j->values);
        assert_non_null(j->indices);
        assert_status(raps_result_copy_indices_u32(serial, j->indices, j->index_count), RAPS_OK);
        const uint64_t used = stats_of(serial).threads_used;
        print_message("job %d (domain %d): %llu thread(s) computed\n", i, (int)domains[i / 3],
                      (unsigned long long)used);
        assert_true(used >= 1 && used <= 2);
        if (serial_threads[i]) assert_int_equal(used, serial_threads[i]);
        raps_result_destroy(serial);
    }
    progress_calls = 0;
    pthread_t threads[OWN_MESH_JOBS];
    for (int i = 0; i < OWN_MESH_JOBS; ++i) {
        assert_int_equal(pthread_create(&threads[i], NULL, run_own_mesh, &jobs[i]), 0);
    }
    for (int i = 0; i < OWN_MESH_JOBS; ++i) assert_int_equal(pthread_join(threads[i], NULL), 0);
    for (int i = 0; i < OWN_MESH_JOBS; ++i) {
        if (jobs[i].failures || jobs[i].mismatches) {
            fail_msg("job %d (domain %d): %d failed runs, %d differing from the serial run", i,
                     (int)domains[i / 3], jobs[i].failures, jobs[i].mismatches);
        }
        assert_true(jobs[i].most_threads >= 1 && jobs[i].most_threads <= 2);
        /* The sphere's worker computes in the concurrent runs too: their nested pools ran. */
        if (serial_threads[i]) assert_int_equal(jobs[i].most_threads, serial_threads[i]);
    }
    /* Every call reached the shared callback: as many as the serial runs made, per round. */
    assert_int_equal(progress_calls, RUNS_PER_THREAD * serial_calls);
    for (int i = 0; i < OWN_MESH_JOBS; ++i) {
        free(jobs[i].values);
        free(jobs[i].indices);
        raps_mesh_destroy(jobs[i].mesh);
        test_mesh_free(&meshes[i]);
    }
    for (int d = 0; d < 3; ++d) raps_settings_destroy(settings[d]);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shared_mesh_and_settings_give_the_serial_result),
        cmocka_unit_test(many_threads_with_their_own_meshes_give_the_serial_results),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
