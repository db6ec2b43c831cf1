/* A million triangles through the atlas, at a size the test suite affords in its
 * sanitizer-free build (issue 20): lion.off subdivided three times, 1,067,136 triangles. Pinned
 * down, through the C ABI:
 * - the atlas is as valid as on the small meshes (test_atlas.c's structure and overlap checks:
 *   no flipped triangle, no texel shared by two charts or covered twice within one);
 * - it keeps the small mesh's quality: L2 stretch within the default target, Linf at most 3, at
 *   most twice the charts of lion.off itself and its coverage to within 0.05;
 * - progress follows the work: every phase reports at least 2 + triangles / 16,384 times,
 *   its fractions rising from 0 to 1 and its calls contiguous, so a phase that reports only at
 *   its start and end fails however fast the machine (work is counted, never timed);
 * - the same bits on one thread and on two.
 * Time is raps-bench-atlas's to print (docs/bench-atlas-large.md), never asserted here. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "raps.h"
#include "support/atlas_checks.h"
#include "support/progress_record.h"
#include "support/test_meshes.h"

/* The atlas at the default settings on `threads` threads; `progress` records every call, and
 * `uv` (malloc'ed) gets the uvs as doubles, the bits the library computed. */
static atlas run_atlas(const test_mesh* mesh, int64_t threads, progress_record* progress,
                       double** uv) {
    raps_mesh* m = to_raps_mesh(mesh);
    raps_settings* s = NULL;
    assert_status(raps_settings_create(&s), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_THREADS, threads), RAPS_OK);
    if (progress) assert_status(raps_settings_set_progress(s, record_progress, progress), RAPS_OK);
    raps_result* r = parameterize_ok(m, s);
    atlas a = atlas_of(r);
    if (uv) {
        *uv = malloc(2 * a.vertex_count * sizeof(double) + 1);
        assert_non_null(*uv);
        assert_status(raps_result_copy_uvs_f64(r, *uv, a.vertex_count, 0), RAPS_OK);
    }
    raps_result_destroy(r);
    raps_settings_destroy(s);
    raps_mesh_destroy(m);
    return a;
}

static void a_million_triangle_atlas_keeps_the_small_meshs_quality(void** state) {
    (void)state;
    test_mesh small = load_shared_mesh("lion.off");
    atlas reference = run_atlas(&small, 2, NULL, NULL);
    test_mesh_free(&small);

    test_mesh mesh = subdivided_mesh(load_shared_mesh("lion.off"), 3, 0);
    const size_t triangles = mesh.index_count / 3;
    assert_int_equal(triangles, 1067136);
    progress_record progress = {NULL, 0, 0, 0};
    double *uv_two = NULL, *uv_one = NULL;
    atlas two = run_atlas(&mesh, 2, &progress, &uv_two);
    print_message(
        "lion.off: %llu charts, coverage %.3f; subdivided: %zu triangles, %llu charts, "
        "coverage %.3f, L2 %.4f, Linf %.2f\n",
        (unsigned long long)reference.stats.chart_count, reference.stats.utilization, triangles,
        (unsigned long long)two.stats.chart_count, two.stats.utilization, two.stats.stretch_l2,
        two.stats.stretch_linf);
    check_atlas_structure(&mesh, &two);
    check_atlas_overlap(&mesh, &two, 1);
    assert_int_equal(two.stats.flipped_triangles, 0);
    assert_int_equal(two.stats.zero_area_triangles, 0);
    assert_true(two.stats.stretch_l2 <= 1.0101);
    assert_true(two.stats.stretch_linf <= 3.0);
    assert_true(two.stats.chart_count <= 2 * reference.stats.chart_count);
    assert_true(two.stats.utilization >= reference.stats.utilization - 0.05);
    int first[RAPS_PHASE_COUNT], calls[RAPS_PHASE_COUNT];
    check_progress_follows_work("lion.off x64", &progress, triangles, first, calls);
    free(progress.calls);

    atlas one = run_atlas(&mesh, 1, NULL, &uv_one);
    assert_int_equal(one.vertex_count, two.vertex_count);
    assert_int_equal(one.index_count, two.index_count);
    assert_memory_equal(uv_one, uv_two, 2 * one.vertex_count * sizeof(double));
    assert_memory_equal(one.indices, two.indices, one.index_count * sizeof(uint32_t));
    assert_memory_equal(one.chart, two.chart, one.index_count / 3 * sizeof(uint32_t));
    free(uv_one);
    free(uv_two);
    atlas_free(&one);
    atlas_free(&two);
    atlas_free(&reference);
    test_mesh_free(&mesh);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(a_million_triangle_atlas_keeps_the_small_meshs_quality),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
