/* Polygons in the atlas domain, through the C ABI (raps_mesh_set_triangle_polygons): a mesh of
 * quads and n-gons triangulated for raps keeps every polygon in one chart with no cut through
 * it, so each polygon corner has one output vertex whichever of its triangles it is read from
 * (what an editor that stores uvs per polygon corner needs), with no flipped triangle; alone
 * and in a scene beside a mesh without polygons. The same mesh without its polygons is shown
 * to cut some, so the test fails if they are ignored. A bad count is refused. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <math.h>

#include "raps.h"
#include "support/test_meshes.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define RINGS 12
#define SECTORS 24

/* A sphere of quads between its latitude rings (each two triangles) and two n-gon caps (each
 * fanned from one of its vertices), polygon ids in `polygon`. The northern ring has a vertex in
 * the middle of each of its edges, shared by the cap and the quad below, which are thus n-gons
 * with collinear corners: fanned, each has a zero-area triangle, which raps sets aside. */
static test_mesh quad_sphere(uint32_t** polygon) {
    test_mesh_builder b;
    memset(&b, 0, sizeof(b));
    for (int i = 1; i < RINGS; ++i) {
        const double polar = M_PI * i / RINGS;
        for (int j = 0; j < SECTORS; ++j) {
            const double azimuth = 2.0 * M_PI * j / SECTORS;
            /* Squashed, so that its charts have to bend. */
            test_mesh_add_vertex(&b, sin(polar) * cos(azimuth), 0.6 * sin(polar) * sin(azimuth),
                                 cos(polar));
        }
    }
    const size_t middle = (size_t)(RINGS - 1) * SECTORS; /* middle of edge (j, j + 1) */
    for (int j = 0; j < SECTORS; ++j) {
        const double* p = b.mesh.positions + 3 * j;
        const double* q = b.mesh.positions + 3 * ((j + 1) % SECTORS);
        test_mesh_add_vertex(&b, 0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]), 0.5 * (p[2] + q[2]));
    }
    const size_t triangles =
        2 * (size_t)SECTORS * (RINGS - 2) + SECTORS + 2 * SECTORS - 2 + SECTORS - 2;
    *polygon = malloc(triangles * sizeof(uint32_t));
    assert_non_null(*polygon);
    size_t t = 0;
    uint32_t id = 0;
    for (int i = 0; i + 2 < RINGS; ++i) {
        const size_t row = (size_t)i * SECTORS, below = row + SECTORS;
        for (int j = 0; j < SECTORS; ++j, ++id) {
            const size_t next = (size_t)(j + 1) % SECTORS;
            test_mesh_add_triangle(&b, row + (size_t)j, below + (size_t)j, below + next);
            test_mesh_add_triangle(&b, row + (size_t)j, below + next, row + next);
            (*polygon)[t++] = id;
            (*polygon)[t++] = id;
            if (i == 0) { /* the pentagon's third triangle: zero area */
                test_mesh_add_triangle(&b, (size_t)j, next, middle + (size_t)j);
                (*polygon)[t++] = id;
            }
        }
    }
    /* The caps, counter-clockwise seen from outside: the north one over its ring and the
     * middles (2 SECTORS corners), the south one over its ring. */
    for (size_t k = 1; k + 1 < 2 * (size_t)SECTORS; ++k, ++t) {
        const size_t c = k % 2 ? middle + k / 2 : k / 2, d = k % 2 ? (k + 1) / 2 : middle + k / 2;
        test_mesh_add_triangle(&b, 0, c, d);
        (*polygon)[t] = id;
    }
    ++id;
    const size_t last = (size_t)(RINGS - 2) * SECTORS;
    for (size_t j = 1; j + 1 < SECTORS; ++j) {
        test_mesh_add_triangle(&b, last, last + j + 1, last + j);
        (*polygon)[t++] = id;
    }
    assert_int_equal(t, triangles);
    return b.mesh;
}

/* Polygons whose triangles lie in different charts or give one input vertex different output
 * vertices; out_indices and chart are the mesh's share of a result. */
static size_t cut_polygons(const test_mesh* m, const uint32_t* polygon, const uint32_t* out_indices,
                           const uint32_t* chart) {
    const size_t n = m->index_count / 3;
    size_t cut = 0;
    uint32_t last_cut = UINT32_MAX;
    for (size_t s = 0; s < n; ++s) {
        for (size_t t = s + 1; t < n; ++t) {
            if (polygon[s] != polygon[t] || polygon[s] == last_cut) continue;
            int split = chart[s] != chart[t];
            for (int i = 0; i < 3; ++i) {
                for (int j = 0; j < 3; ++j) {
                    split |= m->indices[3 * s + i] == m->indices[3 * t + j] &&
                             out_indices[3 * s + i] != out_indices[3 * t + j];
                }
            }
            if (split) {
                ++cut;
                last_cut = polygon[s];
            }
        }
    }
    return cut;
}

static raps_settings* atlas_settings(void) {
    raps_settings* s = NULL;
    assert_int_equal(raps_settings_create(&s), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS), RAPS_OK);
    return s;
}

/* The cut polygons of the run, and that no triangle is flipped. */
static size_t run_and_count_cuts(const raps_mesh* mesh, const test_mesh* m, const uint32_t* polygon,
                                 const raps_settings* s) {
    raps_result* r = parameterize_ok(mesh, s);
    const size_t n = raps_result_index_count(r) / 3;
    uint32_t* out = malloc(3 * n * sizeof(uint32_t));
    uint32_t* chart = malloc(n * sizeof(uint32_t));
    assert_non_null(out);
    assert_non_null(chart);
    assert_int_equal(raps_result_copy_indices_u32(r, out, 3 * n), RAPS_OK);
    assert_int_equal(raps_result_copy_chart_ids(r, chart, n), RAPS_OK);
    raps_stats stats;
    stats.struct_size = sizeof(stats);
    assert_int_equal(raps_result_get_stats(r, &stats), RAPS_OK);
    assert_int_equal(stats.flipped_triangles, 0);
    assert_true(stats.chart_count > 1);
    const size_t cut = cut_polygons(m, polygon, out, chart);
    free(out);
    free(chart);
    raps_result_destroy(r);
    return cut;
}

static void every_polygon_stays_whole_in_one_chart(void** state) {
    (void)state;
    uint32_t* polygon = NULL;
    test_mesh m = quad_sphere(&polygon);
    raps_mesh* mesh = to_raps_mesh(&m);
    raps_settings* s = atlas_settings();
    assert_true(run_and_count_cuts(mesh, &m, polygon, s) > 0);
    assert_int_equal(raps_mesh_set_triangle_polygons(mesh, polygon, m.index_count / 3), RAPS_OK);
    assert_int_equal(run_and_count_cuts(mesh, &m, polygon, s), 0);
    /* Lightmap-like packing and a bent crease limit do not cut them either. */
    assert_int_equal(raps_settings_set_float(s, RAPS_PARAM_HARD_EDGE_ANGLE, 5.0), RAPS_OK);
    assert_int_equal(run_and_count_cuts(mesh, &m, polygon, s), 0);
    raps_settings_destroy(s);
    raps_mesh_destroy(mesh);
    free(polygon);
    test_mesh_free(&m);
}

static void polygons_stay_whole_in_a_scene(void** state) {
    (void)state;
    uint32_t* polygon = NULL;
    test_mesh m = quad_sphere(&polygon);
    test_mesh grid = make_grid(4, 4, 1.0, 1.0);
    raps_mesh* mesh = to_raps_mesh(&m);
    raps_mesh* other = to_raps_mesh(&grid);
    assert_int_equal(raps_mesh_set_triangle_polygons(mesh, polygon, m.index_count / 3), RAPS_OK);
    const raps_mesh* meshes[2] = {other, mesh};
    raps_settings* s = atlas_settings();
    raps_result* r = NULL;
    assert_int_equal(raps_result_create(&r), RAPS_OK);
    if (raps_parameterize_scene(meshes, 2, s, r) != RAPS_OK)
        fail_msg("scene refused: %s", raps_result_last_error(r));
    uint64_t first_vertex = 0, vertex_count = 0, first_index = 0, index_count = 0;
    assert_int_equal(
        raps_result_mesh_range(r, 1, &first_vertex, &vertex_count, &first_index, &index_count),
        RAPS_OK);
    assert_int_equal(index_count, m.index_count);
    const size_t all = raps_result_index_count(r) / 3;
    uint32_t* out = malloc(3 * all * sizeof(uint32_t));
    uint32_t* chart = malloc(all * sizeof(uint32_t));
    assert_non_null(out);
    assert_non_null(chart);
    assert_int_equal(raps_result_copy_indices_u32(r, out, 3 * all), RAPS_OK);
    assert_int_equal(raps_result_copy_chart_ids(r, chart, all), RAPS_OK);
    assert_int_equal(cut_polygons(&m, polygon, out + first_index, chart + first_index / 3), 0);
    free(out);
    free(chart);
    raps_result_destroy(r);
    raps_settings_destroy(s);
    raps_mesh_destroy(other);
    raps_mesh_destroy(mesh);
    test_mesh_free(&grid);
    free(polygon);
    test_mesh_free(&m);
}

/* Ids are the caller's: any ids make a valid atlas (whole surface regions as one "polygon",
 * ids repeated across the mesh), never a hang or a refusal. */
static void any_polygon_ids_make_a_valid_atlas(void** state) {
    (void)state;
    uint32_t* polygon = NULL;
    test_mesh m = quad_sphere(&polygon);
    const size_t n = m.index_count / 3;
    raps_mesh* mesh = to_raps_mesh(&m);
    raps_settings* s = atlas_settings();
    uint32_t seed = 12345;
    for (int pattern = 0; pattern < 3; ++pattern) {
        for (size_t t = 0; t < n; ++t) {
            seed = seed * 1664525u + 1013904223u;
            polygon[t] = pattern == 0 ? 0u : pattern == 1 ? (seed >> 16) % 3u : (uint32_t)(t / 7);
        }
        assert_int_equal(raps_mesh_set_triangle_polygons(mesh, polygon, n), RAPS_OK);
        raps_result* r = parameterize_ok(mesh, s);
        raps_stats stats;
        stats.struct_size = sizeof(stats);
        assert_int_equal(raps_result_get_stats(r, &stats), RAPS_OK);
        assert_int_equal(stats.flipped_triangles, 0);
        raps_result_destroy(r);
    }
    raps_settings_destroy(s);
    raps_mesh_destroy(mesh);
    free(polygon);
    test_mesh_free(&m);
}

static void a_bad_polygon_count_is_refused(void** state) {
    (void)state;
    test_mesh m = make_grid(2, 2, 1.0, 1.0); /* 8 triangles */
    raps_mesh* mesh = to_raps_mesh(&m);
    const uint32_t polygons[9] = {0, 0, 1, 1, 2, 2, 3, 3, 4};
    assert_int_equal(raps_mesh_set_triangle_polygons(NULL, polygons, 8),
                     RAPS_ERROR_INVALID_ARGUMENT);
    assert_int_equal(raps_mesh_set_triangle_polygons(mesh, NULL, 8), RAPS_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(raps_mesh_last_error(mesh), "polygons is NULL"));
    assert_int_equal(raps_mesh_set_triangle_polygons(mesh, polygons, 9), RAPS_OK);
    raps_settings* s = atlas_settings();
    raps_result* r = NULL;
    assert_int_equal(raps_result_create(&r), RAPS_OK);
    assert_int_equal(raps_parameterize(mesh, s, r), RAPS_ERROR_GROUP_COUNT);
    assert_non_null(strstr(raps_result_last_error(r), "polygons number 9 but the mesh has 8"));
    assert_int_equal(raps_mesh_set_triangle_polygons(mesh, NULL, 0), RAPS_OK); /* removed */
    assert_int_equal(raps_parameterize(mesh, s, r), RAPS_OK);
    raps_result_destroy(r);
    raps_settings_destroy(s);
    raps_mesh_destroy(mesh);
    test_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_polygon_stays_whole_in_one_chart),
        cmocka_unit_test(polygons_stay_whole_in_a_scene),
        cmocka_unit_test(any_polygon_ids_make_a_valid_atlas),
        cmocka_unit_test(a_bad_polygon_count_is_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
