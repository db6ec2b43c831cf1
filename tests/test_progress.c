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
#include "support/progress_record.h"
#include "support/test_meshes.h"

static raps_status run(const test_mesh* mesh, raps_settings* s, progress_record* r) {
    raps_mesh* m = to_raps_mesh(mesh);
    raps_result* result = NULL;
    assert_status(raps_result_create(&result), RAPS_OK);
    assert_status(raps_settings_set_progress(s, record_progress, r), RAPS_OK);
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
    progress_record full = {NULL, 0, 0, 0};
    assert_status(run(mesh, s, &full), RAPS_OK);
    int first[RAPS_PHASE_COUNT], calls[RAPS_PHASE_COUNT];
    const unsigned seen =
        check_progress_follows_work(name, &full, mesh->index_count / 3, first, calls);
    assert_int_equal(seen, expected_phases);
    for (int p = 0; p < RAPS_PHASE_COUNT; ++p) {
        if (!(seen & (1u << p))) continue;
        /* Cancelled at the middle call of the phase: that call is the run's last. */
        progress_record cancelled = {NULL, 0, 0, first[p] + calls[p] / 2 + 1};
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
