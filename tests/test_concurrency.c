/* The threading contract: one mesh and one settings handle shared read-only by concurrent
 * runs, each with its own result, give exactly the serial result. */
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

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shared_mesh_and_settings_give_the_serial_result),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
