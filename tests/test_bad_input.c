/* Bad input: every kind gets its own status and a message naming the problem, leaves the
 * handles usable, and never crashes. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "raps.h"
#include "support/test_meshes.h"

static const double kQuad[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};

/* Runs raps_parameterize on (positions, indices) and checks the status and that the message
 * contains `fragment`. */
static void expect_refusal(const double* xyz, size_t vertex_count, const uint32_t* indices,
                           size_t index_count, raps_status expected, const char* fragment) {
    raps_mesh* m = NULL;
    raps_result* r = NULL;
    assert_status(raps_mesh_create(&m), RAPS_OK);
    assert_status(raps_result_create(&r), RAPS_OK);
    assert_status(raps_mesh_set_positions_f64(m, xyz, vertex_count, 0), RAPS_OK);
    assert_status(raps_mesh_set_indices_u32(m, indices, index_count), RAPS_OK);
    const raps_status status = raps_parameterize(m, NULL, r);
    if (status != expected) {
        fail_msg("got %s (%s), expected %s", raps_status_string(status), raps_result_last_error(r),
                 raps_status_string(expected));
    }
    const char* message = raps_result_last_error(r);
    if (!strstr(message, fragment)) fail_msg("message '%s' lacks '%s'", message, fragment);
    /* Nothing is left in the result. */
    assert_int_equal(raps_result_vertex_count(r), 0);
    float uv[2];
    assert_status(raps_result_copy_uvs_f32(r, uv, 1, 0), RAPS_ERROR_INVALID_OPERATION);
    /* The handles are usable: given a good mesh, the same ones map it. */
    const uint32_t quad[] = {0, 1, 2, 0, 2, 3};
    assert_status(raps_mesh_set_positions_f64(m, kQuad, 4, 0), RAPS_OK);
    assert_status(raps_mesh_set_indices_u32(m, quad, 6), RAPS_OK);
    assert_status(raps_parameterize(m, NULL, r), RAPS_OK);
    assert_string_equal(raps_result_last_error(r), "");
    assert_int_equal(raps_result_vertex_count(r), 4);
    raps_result_destroy(r);
    raps_mesh_destroy(m);
}

static void expect_mesh_refusal(const test_mesh* mesh, raps_status expected, const char* fragment) {
    expect_refusal(mesh->positions, mesh->vertex_count, mesh->indices, mesh->index_count, expected,
                   fragment);
}

/* A steep adaptive step (alpha 50, five steps) on camelhead raises the error monitor past what
 * doubles hold: weights underflow to 0 and the system is singular. The message says so and
 * names alpha (it blamed cotangent weights on obtuse triangles, which this run does not use). */
static void adaptive_weights_past_doubles_name_alpha(void** state) {
    (void)state;
    test_mesh mesh = load_shared_mesh("camelhead.off");
    raps_mesh* m = to_raps_mesh(&mesh);
    raps_settings* s = NULL;
    raps_result* r = NULL;
    assert_status(raps_settings_create(&s), RAPS_OK);
    assert_status(raps_result_create(&r), RAPS_OK);
    assert_status(raps_settings_set_float(s, RAPS_PARAM_ALPHA, 50.0), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_ITERATIONS, 5), RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_ERROR_SOLVER_FAILED);
    const char* message = raps_result_last_error(r);
    if (!strstr(message, "alpha 50") || !strstr(message, "underflow") ||
        strstr(message, "cotangent"))
        fail_msg("message '%s' does not name alpha's overflow", message);
    assert_status(raps_settings_set_float(s, RAPS_PARAM_ALPHA, 1.0), RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_OK);
    raps_result_destroy(r);
    raps_settings_destroy(s);
    raps_mesh_destroy(m);
    test_mesh_free(&mesh);
}

static void null_pointers_are_refused(void** state) {
    (void)state;
    raps_mesh* m = NULL;
    raps_result* r = NULL;
    assert_status(raps_mesh_create(&m), RAPS_OK);
    assert_status(raps_result_create(&r), RAPS_OK);
    const uint32_t tri[] = {0, 1, 2};
    assert_status(raps_mesh_set_positions_f64(NULL, kQuad, 4, 0), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_mesh_set_positions_f64(m, NULL, 4, 0), RAPS_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(raps_mesh_last_error(m), "NULL"));
    assert_status(raps_mesh_set_positions_f32(m, NULL, 4, 0), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_mesh_set_indices_u32(m, NULL, 3), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_mesh_set_indices_u16(m, NULL, 3), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_mesh_set_indices_u32(NULL, tri, 3), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_parameterize(NULL, NULL, r), RAPS_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(raps_result_last_error(r), "mesh is NULL"));
    assert_status(raps_parameterize(m, NULL, NULL), RAPS_ERROR_INVALID_ARGUMENT);
    raps_result_destroy(r);
    raps_mesh_destroy(m);
}

static void zero_and_mismatched_counts_are_refused(void** state) {
    (void)state;
    raps_mesh* m = NULL;
    raps_result* r = NULL;
    assert_status(raps_mesh_create(&m), RAPS_OK);
    assert_status(raps_result_create(&r), RAPS_OK);
    const uint32_t tri[] = {0, 1, 2, 0, 2};
    assert_status(raps_mesh_set_positions_f64(m, kQuad, 0, 0), RAPS_ERROR_EMPTY_MESH);
    assert_status(raps_mesh_set_indices_u32(m, tri, 0), RAPS_ERROR_EMPTY_MESH);
    assert_status(raps_mesh_set_indices_u32(m, tri, 5), RAPS_ERROR_INDEX_COUNT);
    assert_non_null(strstr(raps_mesh_last_error(m), "multiple of 3"));
    assert_status(raps_mesh_set_positions_f64(m, kQuad, 4, 8), RAPS_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(raps_mesh_last_error(m), "stride"));
    /* Nothing set yet: the run says what is missing. */
    assert_status(raps_parameterize(m, NULL, r), RAPS_ERROR_EMPTY_MESH);
    assert_non_null(strstr(raps_result_last_error(r), "no vertices"));
    assert_status(raps_mesh_set_positions_f64(m, kQuad, 4, 0), RAPS_OK);
    assert_status(raps_parameterize(m, NULL, r), RAPS_ERROR_EMPTY_MESH);
    assert_non_null(strstr(raps_result_last_error(r), "no triangles"));
    raps_result_destroy(r);
    raps_mesh_destroy(m);
}

static void indices_out_of_range_are_refused(void** state) {
    (void)state;
    const uint32_t past_end[] = {0, 1, 2, 0, 2, 4};
    expect_refusal(kQuad, 4, past_end, 6, RAPS_ERROR_INDEX_OUT_OF_RANGE, "triangle 1");
    /* An index no mesh can reach is refused when it is set. */
    raps_mesh* m = NULL;
    assert_status(raps_mesh_create(&m), RAPS_OK);
    const uint32_t huge[] = {0, 1, 0xffffffffu};
    assert_status(raps_mesh_set_indices_u32(m, huge, 3), RAPS_ERROR_INDEX_OUT_OF_RANGE);
    assert_non_null(strstr(raps_mesh_last_error(m), "4294967295"));
    raps_mesh_destroy(m);
}

static void non_finite_positions_are_refused(void** state) {
    (void)state;
    raps_mesh* m = NULL;
    assert_status(raps_mesh_create(&m), RAPS_OK);
    const double nan_at_2[] = {0, 0, 0, 1, 0, 0, 1, NAN, 0};
    const float inf_at_1[] = {0, 0, 0, INFINITY, 0, 0, 0, 1, 0};
    assert_status(raps_mesh_set_positions_f64(m, nan_at_2, 3, 0), RAPS_ERROR_NON_FINITE_POSITION);
    assert_non_null(strstr(raps_mesh_last_error(m), "vertex 2"));
    assert_status(raps_mesh_set_positions_f32(m, inf_at_1, 3, 0), RAPS_ERROR_NON_FINITE_POSITION);
    assert_non_null(strstr(raps_mesh_last_error(m), "vertex 1"));
    /* Finite but beyond 1e30: products of such coordinates overflow inside the algorithms. */
    const double huge_at_1[] = {0, 0, 0, 1, -2e30, 0, 0, 1, 0};
    const float float_max_at_0[] = {3.4e38f, 0, 0, 1, 0, 0, 0, 1, 0};
    assert_status(raps_mesh_set_positions_f64(m, huge_at_1, 3, 0), RAPS_ERROR_NON_FINITE_POSITION);
    assert_non_null(strstr(raps_mesh_last_error(m), "vertex 1 has a coordinate beyond 1e30"));
    assert_status(raps_mesh_set_positions_f32(m, float_max_at_0, 3, 0),
                  RAPS_ERROR_NON_FINITE_POSITION);
    assert_non_null(strstr(raps_mesh_last_error(m), "vertex 0"));
    /* The refused arrays did not replace anything. */
    assert_int_equal(raps_mesh_vertex_count(m), 0);
    /* 1e30 itself is in. */
    const double at_bound[] = {0, 0, 0, 1e30, 0, 0, 0, -1e30, 0};
    assert_status(raps_mesh_set_positions_f64(m, at_bound, 3, 0), RAPS_OK);
    raps_mesh_destroy(m);
}

static void repeated_vertex_triangles_are_refused(void** state) {
    (void)state;
    const uint32_t tri[] = {0, 1, 2, 0, 2, 2};
    expect_refusal(kQuad, 4, tri, 6, RAPS_ERROR_REPEATED_VERTEX, "triangle 1");
}

static void zero_area_triangles_are_refused(void** state) {
    (void)state;
    /* Vertex 4 lies on the segment 0-1: triangle (0, 4, 1) is collinear. */
    const double xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5, 0, 0};
    const uint32_t tri[] = {0, 1, 2, 0, 2, 3, 0, 4, 1};
    expect_refusal(xyz, 5, tri, 9, RAPS_ERROR_ZERO_AREA_TRIANGLE, "triangle 2");
    /* Two coincident vertices make a zero-area triangle too. */
    const double coincident[] = {0, 0, 0, 1, 0, 0, 1, 0, 0};
    const uint32_t one[] = {0, 1, 2};
    expect_refusal(coincident, 3, one, 3, RAPS_ERROR_ZERO_AREA_TRIANGLE, "triangle 0");
}

static void non_manifold_edges_are_refused(void** state) {
    (void)state;
    /* Three triangles on edge (0, 1). */
    const double xyz[] = {0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0, 0.5, 0, 1};
    const uint32_t tri[] = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    expect_refusal(xyz, 5, tri, 9, RAPS_ERROR_NON_MANIFOLD_EDGE, "more than two triangles");
    /* A duplicated triangle is named as such. */
    const uint32_t duplicate[] = {0, 1, 2, 1, 0, 3, 0, 1, 2};
    expect_refusal(xyz, 4, duplicate, 9, RAPS_ERROR_NON_MANIFOLD_EDGE, "duplicates");
}

static void non_manifold_vertices_are_refused(void** state) {
    (void)state;
    /* A bow tie: two triangles that share only vertex 0. */
    const double xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0};
    const uint32_t tri[] = {0, 1, 2, 0, 3, 4};
    expect_refusal(xyz, 5, tri, 6, RAPS_ERROR_NON_MANIFOLD_VERTEX, "vertex 0");
}

static void inconsistent_orientation_is_refused(void** state) {
    (void)state;
    /* The second triangle of the quad is wound the other way. */
    const uint32_t tri[] = {0, 1, 2, 0, 3, 2};
    expect_refusal(kQuad, 4, tri, 6, RAPS_ERROR_INCONSISTENT_ORIENTATION, "same direction");
}

static void isolated_vertices_are_refused(void** state) {
    (void)state;
    const double xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 5, 5, 5};
    const uint32_t tri[] = {0, 1, 2, 0, 2, 3};
    expect_refusal(xyz, 5, tri, 6, RAPS_ERROR_ISOLATED_VERTEX, "vertex 4");
}

static void several_components_are_refused(void** state) {
    (void)state;
    const double xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 0, 0, 6, 0, 0, 5, 1, 0};
    const uint32_t tri[] = {0, 1, 2, 3, 4, 5};
    expect_refusal(xyz, 6, tri, 6, RAPS_ERROR_MULTIPLE_COMPONENTS, "2 separate pieces");
}

static void closed_meshes_are_refused(void** state) {
    (void)state;
    test_mesh sphere = make_icosphere(1);
    expect_mesh_refusal(&sphere, RAPS_ERROR_NO_BOUNDARY, "closed");
    test_mesh_free(&sphere);
}

static void meshes_with_holes_are_refused(void** state) {
    (void)state;
    test_mesh annulus = make_annulus(3, 6);
    expect_mesh_refusal(&annulus, RAPS_ERROR_MULTIPLE_BOUNDARIES, "2 boundary loops");
    test_mesh_free(&annulus);
}

static void meshes_with_handles_are_refused(void** state) {
    (void)state;
    test_mesh torus = make_punctured_torus(8, 6);
    expect_mesh_refusal(&torus, RAPS_ERROR_NONZERO_GENUS, "genus 1");
    test_mesh_free(&torus);
}

static void meshes_too_large_for_their_index_type_are_refused(void** state) {
    (void)state;
    /* 70000 vertices cannot all be reached by uint16 indices. */
    const size_t n = 70000;
    float* xyz = calloc(3 * n, sizeof(float));
    for (size_t i = 0; i < n; ++i) {
        xyz[3 * i] = (float)(i % 300);
        xyz[3 * i + 1] = (float)(i / 300);
    }
    const uint16_t tri[] = {0, 1, 300};
    raps_mesh* m = NULL;
    raps_result* r = NULL;
    assert_status(raps_mesh_create(&m), RAPS_OK);
    assert_status(raps_result_create(&r), RAPS_OK);
    assert_status(raps_mesh_set_positions_f32(m, xyz, n, 0), RAPS_OK);
    assert_status(raps_mesh_set_indices_u16(m, tri, 3), RAPS_OK);
    assert_status(raps_parameterize(m, NULL, r), RAPS_ERROR_TOO_LARGE);
    assert_non_null(strstr(raps_result_last_error(r), "uint16"));
    /* A vertex count beyond what the library indexes is refused before anything is read. */
    assert_status(raps_mesh_set_positions_f32(m, xyz, (size_t)1 << 31, 0), RAPS_ERROR_TOO_LARGE);
    assert_status(raps_mesh_set_positions_f32(m, xyz, SIZE_MAX, 0), RAPS_ERROR_TOO_LARGE);
    free(xyz);
    raps_result_destroy(r);
    raps_mesh_destroy(m);
}

static int32_t count_calls(void* user, raps_phase phase, double fraction) {
    (void)phase;
    (void)fraction;
    ++*(int*)user;
    return 1;
}

static void triangle_limit_is_enforced_before_any_work(void** state) {
    (void)state;
    test_mesh disk = make_flat_disk(4, 6, 0.0);
    raps_mesh* m = to_raps_mesh(&disk);
    raps_settings* s = NULL;
    raps_result* r = NULL;
    int calls = 0;
    assert_status(raps_settings_create(&s), RAPS_OK);
    assert_status(raps_settings_set_progress(s, count_calls, &calls), RAPS_OK);
    assert_status(raps_result_create(&r), RAPS_OK);
    assert_status(
        raps_settings_set_int(s, RAPS_PARAM_MAX_TRIANGLES, (int64_t)disk.index_count / 3 - 1),
        RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_ERROR_TOO_LARGE);
    assert_non_null(strstr(raps_result_last_error(r), "RAPS_PARAM_MAX_TRIANGLES"));
    assert_int_equal(calls, 0); /* no phase was started */
    assert_status(raps_settings_set_int(s, RAPS_PARAM_MAX_TRIANGLES, (int64_t)disk.index_count / 3),
                  RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_OK);
    raps_result_destroy(r);
    raps_settings_destroy(s);
    raps_mesh_destroy(m);
    test_mesh_free(&disk);
}

/* The uvs of a run of `m`, malloc'ed. */
static double* uvs_of_mesh(const raps_mesh* m) {
    raps_result* r = parameterize_ok(m, NULL);
    double* uv = uvs_of(r);
    raps_result_destroy(r);
    return uv;
}

/* A failing setter leaves its mesh as it was (the header): after each kind of refusal the mesh
 * holds the same counts and maps to the same bits as before. */
static void failed_setters_leave_the_mesh_as_it_was(void** state) {
    (void)state;
    test_mesh disk = make_flat_disk(3, 6, 0.2);
    raps_mesh* m = to_raps_mesh(&disk);
    double* before = uvs_of_mesh(m);
    const double nan_at_1[] = {0, 0, 0, NAN, 0, 0, 0, 1, 0};
    const uint32_t five[] = {0, 1, 2, 0, 2};
    const uint32_t huge[] = {0, 1, 0xffffffffu};
    assert_status(raps_mesh_set_positions_f64(m, nan_at_1, 3, 0), RAPS_ERROR_NON_FINITE_POSITION);
    assert_status(raps_mesh_set_positions_f64(m, kQuad, 4, 8), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_mesh_set_positions_f64(m, kQuad, 0, 0), RAPS_ERROR_EMPTY_MESH);
    assert_status(raps_mesh_set_positions_f32(m, NULL, 4, 0), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_mesh_set_indices_u32(m, five, 5), RAPS_ERROR_INDEX_COUNT);
    assert_status(raps_mesh_set_indices_u32(m, huge, 3), RAPS_ERROR_INDEX_OUT_OF_RANGE);
    assert_status(raps_mesh_set_indices_u32(m, five, 0), RAPS_ERROR_EMPTY_MESH);
    assert_status(raps_mesh_set_indices_u16(m, NULL, 3), RAPS_ERROR_INVALID_ARGUMENT);
    assert_true(strlen(raps_mesh_last_error(m)) > 0);
    assert_int_equal(raps_mesh_vertex_count(m), disk.vertex_count);
    assert_int_equal(raps_mesh_triangle_count(m), disk.index_count / 3);
    double* after = uvs_of_mesh(m);
    assert_memory_equal(after, before, 2 * disk.vertex_count * sizeof(double));
    free(before);
    free(after);
    raps_mesh_destroy(m);
    test_mesh_free(&disk);
}

static void a_failed_run_clears_the_previous_result(void** state) {
    (void)state;
    test_mesh disk = make_flat_disk(3, 6, 0.0);
    test_mesh sphere = make_icosphere(0);
    raps_mesh* good = to_raps_mesh(&disk);
    raps_mesh* bad = to_raps_mesh(&sphere);
    raps_result* r = parameterize_ok(good, NULL);
    assert_int_equal(raps_result_vertex_count(r), disk.vertex_count);
    assert_status(raps_parameterize(bad, NULL, r), RAPS_ERROR_NO_BOUNDARY);
    assert_int_equal(raps_result_vertex_count(r), 0);
    assert_status(raps_parameterize(good, NULL, r), RAPS_OK);
    assert_string_equal(raps_result_last_error(r), "");
    raps_result_destroy(r);
    raps_mesh_destroy(good);
    raps_mesh_destroy(bad);
    test_mesh_free(&disk);
    test_mesh_free(&sphere);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(null_pointers_are_refused),
        cmocka_unit_test(zero_and_mismatched_counts_are_refused),
        cmocka_unit_test(indices_out_of_range_are_refused),
        cmocka_unit_test(non_finite_positions_are_refused),
        cmocka_unit_test(repeated_vertex_triangles_are_refused),
        cmocka_unit_test(zero_area_triangles_are_refused),
        cmocka_unit_test(non_manifold_edges_are_refused),
        cmocka_unit_test(non_manifold_vertices_are_refused),
        cmocka_unit_test(inconsistent_orientation_is_refused),
        cmocka_unit_test(isolated_vertices_are_refused),
        cmocka_unit_test(several_components_are_refused),
        cmocka_unit_test(closed_meshes_are_refused),
        cmocka_unit_test(meshes_with_holes_are_refused),
        cmocka_unit_test(meshes_with_handles_are_refused),
        cmocka_unit_test(meshes_too_large_for_their_index_type_are_refused),
        cmocka_unit_test(triangle_limit_is_enforced_before_any_work),
        cmocka_unit_test(failed_setters_leave_the_mesh_as_it_was),
        cmocka_unit_test(a_failed_run_clears_the_previous_result),
        cmocka_unit_test(adaptive_weights_past_doubles_name_alpha),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
