/* The artist's seams in the atlas domain, through the C ABI: no chart holds triangles of two
 * groups (raps_mesh_set_triangle_groups), marked seam edges that cross the surface separate
 * charts (raps_mesh_set_seam_edges), the input's own vertex splits stay chart boundaries with
 * RAPS_PARAM_ATLAS_KEEP_INPUT_SEAMS, the map does not depend on the thread count, and every bad
 * input is refused with its own status and a message naming it. Each test first shows that
 * the same mesh without the seams does put both sides in one chart, so it fails if the seams
 * are ignored. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "raps.h"
#include "support/test_meshes.h"

#define GRID 12 /* cells per side of the test grid; vertex (i, j) is j * (GRID + 1) + i */

typedef struct atlas {
    size_t vertex_count, triangle_count;
    double* uv;
    uint32_t* indices;
    uint32_t* remap;
    uint32_t* chart;
} atlas;

static void atlas_free(atlas* a) {
    free(a->uv);
    free(a->indices);
    free(a->remap);
    free(a->chart);
}

static raps_settings* atlas_settings(int64_t threads, int64_t keep_input_seams) {
    raps_settings* s = NULL;
    assert_int_equal(raps_settings_create(&s), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_THREADS, threads), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_KEEP_INPUT_SEAMS, keep_input_seams),
                     RAPS_OK);
    return s;
}

static atlas run_atlas(const raps_mesh* mesh, const raps_settings* settings) {
    raps_result* r = parameterize_ok(mesh, settings);
    atlas a;
    a.vertex_count = raps_result_vertex_count(r);
    a.triangle_count = raps_result_index_count(r) / 3;
    a.uv = malloc(2 * a.vertex_count * sizeof(double));
    a.indices = malloc(3 * a.triangle_count * sizeof(uint32_t));
    a.remap = malloc(a.vertex_count * sizeof(uint32_t));
    a.chart = malloc(a.triangle_count * sizeof(uint32_t));
    assert_non_null(a.uv);
    assert_non_null(a.indices);
    assert_non_null(a.remap);
    assert_non_null(a.chart);
    assert_int_equal(raps_result_copy_uvs_f64(r, a.uv, a.vertex_count, 0), RAPS_OK);
    assert_int_equal(raps_result_copy_indices_u32(r, a.indices, 3 * a.triangle_count), RAPS_OK);
    assert_int_equal(raps_result_copy_vertex_remap(r, a.remap, a.vertex_count), RAPS_OK);
    assert_int_equal(raps_result_copy_chart_ids(r, a.chart, a.triangle_count), RAPS_OK);
    raps_result_destroy(r);
    return a;
}

/* Whether input triangles s and t share an edge (two input vertices). */
static int share_edge(const test_mesh* m, size_t s, size_t t) {
    int shared = 0;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) shared += m->indices[3 * s + i] == m->indices[3 * t + j];
    }
    return shared == 2;
}

/* Adjacent triangles (sharing an input edge) with different labels that the atlas put in one
 * chart. */
static size_t joined_across(const test_mesh* m, const uint32_t* label, const atlas* a) {
    size_t joined = 0;
    const size_t n = m->index_count / 3;
    for (size_t s = 0; s < n; ++s) {
        for (size_t t = s + 1; t < n; ++t) {
            if (label[s] != label[t] && share_edge(m, s, t) && a->chart[s] == a->chart[t]) ++joined;
        }
    }
    return joined;
}

/* Three regions of a smooth sphere, bounded where nothing in the geometry says so. */
static uint32_t* sphere_groups(const test_mesh* m) {
    const size_t n = m->index_count / 3;
    uint32_t* group = malloc(n * sizeof(uint32_t));
    assert_non_null(group);
    for (size_t t = 0; t < n; ++t) {
        double c[3] = {0, 0, 0};
        for (int k = 0; k < 3; ++k) {
            for (int d = 0; d < 3; ++d) c[d] += m->positions[3 * m->indices[3 * t + k] + d] / 3;
        }
        group[t] = c[2] > 0.3 ? 7u : c[0] > 0.1 ? 3u : 0u;
    }
    return group;
}

static void no_chart_crosses_a_change_of_group(void** state) {
    (void)state;
    test_mesh m = make_uv_sphere(10, 20);
    uint32_t* group = sphere_groups(&m);
    raps_settings* s = atlas_settings(1, 0);
    raps_mesh* mesh = to_raps_mesh(&m);
    atlas plain = run_atlas(mesh, s);
    assert_true(joined_across(&m, group, &plain) > 0);
    assert_int_equal(raps_mesh_set_triangle_groups(mesh, group, m.index_count / 3), RAPS_OK);
    atlas grouped = run_atlas(mesh, s);
    assert_int_equal(joined_across(&m, group, &grouped), 0);

    /* The same in a scene, the grouped sphere beside a mesh without groups. */
    test_mesh grid = make_grid(4, 4, 1.0, 1.0);
    raps_mesh* other = to_raps_mesh(&grid);
    const raps_mesh* meshes[2] = {other, mesh};
    raps_result* r = NULL;
    assert_int_equal(raps_result_create(&r), RAPS_OK);
    if (raps_parameterize_scene(meshes, 2, s, r) != RAPS_OK)
        fail_msg("scene refused: %s", raps_result_last_error(r));
    uint64_t first_index = 0, index_count = 0;
    assert_int_equal(raps_result_mesh_range(r, 1, NULL, NULL, &first_index, &index_count), RAPS_OK);
    assert_int_equal(index_count, m.index_count);
    const size_t all = raps_result_index_count(r) / 3;
    uint32_t* chart = malloc(all * sizeof(uint32_t));
    assert_non_null(chart);
    assert_int_equal(raps_result_copy_chart_ids(r, chart, all), RAPS_OK);
    atlas in_scene = grouped;
    in_scene.chart = chart + first_index / 3;
    assert_int_equal(joined_across(&m, group, &in_scene), 0);

    free(chart);
    raps_result_destroy(r);
    raps_mesh_destroy(other);
    test_mesh_free(&grid);
    atlas_free(&plain);
    atlas_free(&grouped);
    raps_mesh_destroy(mesh);
    raps_settings_destroy(s);
    free(group);
    test_mesh_free(&m);
}

/* Left (0) or right (1) of the grid's column GRID / 2, per triangle. */
static uint32_t* grid_sides(const test_mesh* m) {
    const size_t n = m->index_count / 3;
    uint32_t* side = malloc(n * sizeof(uint32_t));
    assert_non_null(side);
    for (size_t t = 0; t < n; ++t) {
        double x = 0;
        for (int k = 0; k < 3; ++k) x += m->positions[3 * m->indices[3 * t + k]] / 3;
        side[t] = x > 0.5 ? 1u : 0u;
    }
    return side;
}

static void seam_edges_across_the_surface_separate_charts(void** state) {
    (void)state;
    test_mesh m = make_grid(GRID, GRID, 1.0, 1.0);
    uint32_t* side = grid_sides(&m);
    raps_settings* s = atlas_settings(1, 0);
    raps_mesh* mesh = to_raps_mesh(&m);
    atlas plain = run_atlas(mesh, s);
    assert_true(joined_across(&m, side, &plain) > 0);
    /* The column x = 1/2, from the bottom boundary to the top one, its pairs in either order. */
    uint32_t pairs[2 * GRID];
    for (uint32_t j = 0; j < GRID; ++j) {
        const uint32_t below = j * (GRID + 1) + GRID / 2, above = below + GRID + 1;
        pairs[2 * j] = j % 2 ? below : above;
        pairs[2 * j + 1] = j % 2 ? above : below;
    }
    assert_int_equal(raps_mesh_set_seam_edges(mesh, pairs, GRID), RAPS_OK);
    atlas cut = run_atlas(mesh, s);
    assert_int_equal(joined_across(&m, side, &cut), 0);
    /* Removing them restores the plain atlas. */
    assert_int_equal(raps_mesh_set_seam_edges(mesh, NULL, 0), RAPS_OK);
    atlas again = run_atlas(mesh, s);
    assert_int_equal(again.vertex_count, plain.vertex_count);
    assert_memory_equal(again.uv, plain.uv, 2 * plain.vertex_count * sizeof(double));
    atlas_free(&plain);
    atlas_free(&cut);
    atlas_free(&again);
    raps_mesh_destroy(mesh);
    raps_settings_destroy(s);
    free(side);
    test_mesh_free(&m);
}

/* The grid with its middle column of vertices duplicated (same positions) for the triangles on
 * its right, as an exporter writes a uv seam. */
static test_mesh grid_with_split_column(void) {
    test_mesh m = make_grid(GRID, GRID, 1.0, 1.0);
    const size_t n = m.vertex_count, copies = GRID + 1;
    m.positions = realloc(m.positions, 3 * (n + copies) * sizeof(double));
    assert_non_null(m.positions);
    for (size_t j = 0; j < copies; ++j)
        memcpy(&m.positions[3 * (n + j)], &m.positions[3 * (j * (GRID + 1) + GRID / 2)],
               3 * sizeof(double));
    m.vertex_count = n + copies;
    uint32_t* side = grid_sides(&m);
    for (size_t t = 0; t < m.index_count / 3; ++t) {
        for (int k = 0; k < 3 && side[t]; ++k) {
            uint32_t* v = &m.indices[3 * t + k];
            if (*v % (GRID + 1) == GRID / 2) *v = (uint32_t)n + *v / (GRID + 1);
        }
    }
    free(side);
    return m;
}

static void input_vertex_splits_stay_seams_when_kept(void** state) {
    (void)state;
    test_mesh m = grid_with_split_column();
    test_mesh welded = make_grid(GRID, GRID, 1.0, 1.0);
    uint32_t* side = grid_sides(&welded);
    raps_mesh* mesh = to_raps_mesh(&m);
    raps_settings* weld = atlas_settings(1, 0);
    raps_settings* keep = atlas_settings(1, 1);
    /* Adjacency is read on the welded grid: the split mesh's sides share no input edge. */
    atlas plain = run_atlas(mesh, weld);
    assert_true(joined_across(&welded, side, &plain) > 0);
    atlas kept = run_atlas(mesh, keep);
    assert_int_equal(joined_across(&welded, side, &kept), 0);
    atlas_free(&plain);
    atlas_free(&kept);
    raps_settings_destroy(weld);
    raps_settings_destroy(keep);
    raps_mesh_destroy(mesh);
    free(side);
    test_mesh_free(&welded);
    test_mesh_free(&m);
}

static void expect_refused(const raps_mesh* mesh, raps_status status, const char* message) {
    raps_settings* s = atlas_settings(1, 0);
    raps_result* r = NULL;
    assert_int_equal(raps_result_create(&r), RAPS_OK);
    assert_int_equal(raps_parameterize(mesh, s, r), status);
    if (!strstr(raps_result_last_error(r), message))
        fail_msg("message \"%s\" lacks \"%s\"", raps_result_last_error(r), message);
    assert_int_equal(raps_result_vertex_count(r), 0);
    raps_result_destroy(r);
    raps_settings_destroy(s);
}

static void every_bad_seam_input_is_refused_with_its_status(void** state) {
    (void)state;
    test_mesh m = make_grid(2, 2, 1.0, 1.0); /* 9 vertices, 8 triangles */
    raps_mesh* mesh = to_raps_mesh(&m);
    const uint32_t groups[9] = {0, 0, 0, 0, 1, 1, 1, 1, 1};
    assert_int_equal(raps_mesh_set_triangle_groups(NULL, groups, 8), RAPS_ERROR_INVALID_ARGUMENT);
    assert_int_equal(raps_mesh_set_triangle_groups(mesh, NULL, 8), RAPS_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(raps_mesh_last_error(mesh), "groups is NULL"));
    assert_int_equal(raps_mesh_set_seam_edges(mesh, NULL, 1), RAPS_ERROR_INVALID_ARGUMENT);

    assert_int_equal(raps_mesh_set_triangle_groups(mesh, groups, 9), RAPS_OK);
    expect_refused(mesh, RAPS_ERROR_GROUP_COUNT, "groups number 9 but the mesh has 8 triangles");
    /* Right for the mesh, then wrong once the indices change. */
    assert_int_equal(raps_mesh_set_triangle_groups(mesh, groups, 8), RAPS_OK);
    assert_int_equal(raps_mesh_set_indices_u32(mesh, m.indices, 3 * 7), RAPS_OK);
    expect_refused(mesh, RAPS_ERROR_GROUP_COUNT, "groups number 8 but the mesh has 7 triangles");
    assert_int_equal(raps_mesh_set_indices_u32(mesh, m.indices, m.index_count), RAPS_OK);

    const uint32_t out_of_range[4] = {0, 1, 4, 9};
    assert_int_equal(raps_mesh_set_seam_edges(mesh, out_of_range, 2), RAPS_OK);
    expect_refused(mesh, RAPS_ERROR_INDEX_OUT_OF_RANGE,
                   "seam edge 1 (4, 9) names vertex 9 but the mesh has only 9 vertices");
    const uint32_t across[4] = {3, 4, 0, 2}; /* 0 and 2 are the ends of the bottom row */
    assert_int_equal(raps_mesh_set_seam_edges(mesh, across, 2), RAPS_OK);
    expect_refused(mesh, RAPS_ERROR_SEAM_NOT_AN_EDGE,
                   "seam edge 1 (0, 2) is not an edge of any triangle");
    const uint32_t loop[2] = {4, 4};
    assert_int_equal(raps_mesh_set_seam_edges(mesh, loop, 1), RAPS_OK);
    expect_refused(mesh, RAPS_ERROR_SEAM_NOT_AN_EDGE, "seam edge 0 (4, 4)");

    /* In a scene, the message names the mesh. */
    raps_mesh* good = to_raps_mesh(&m);
    const raps_mesh* meshes[2] = {good, mesh};
    raps_settings* s = atlas_settings(1, 0);
    raps_result* r = NULL;
    assert_int_equal(raps_result_create(&r), RAPS_OK);
    assert_int_equal(raps_parameterize_scene(meshes, 2, s, r), RAPS_ERROR_SEAM_NOT_AN_EDGE);
    assert_non_null(strstr(raps_result_last_error(r), "mesh 1: seam edge 0 (4, 4)"));
    assert_string_equal(raps_status_string(RAPS_ERROR_GROUP_COUNT),
                        "triangle group count differs from the triangle count");
    assert_string_equal(raps_status_string(RAPS_ERROR_SEAM_NOT_AN_EDGE),
                        "seam edge is not an edge of the mesh");
    raps_result_destroy(r);
    raps_settings_destroy(s);
    raps_mesh_destroy(good);
    raps_mesh_destroy(mesh);
    test_mesh_free(&m);
}

static void seams_give_the_same_bits_for_any_thread_count(void** state) {
    (void)state;
    test_mesh m = make_uv_sphere(10, 20);
    uint32_t* group = sphere_groups(&m);
    raps_mesh* mesh = to_raps_mesh(&m);
    assert_int_equal(raps_mesh_set_triangle_groups(mesh, group, m.index_count / 3), RAPS_OK);
    const uint32_t pairs[4] = {m.indices[0], m.indices[1], m.indices[30], m.indices[31]};
    assert_int_equal(raps_mesh_set_seam_edges(mesh, pairs, 2), RAPS_OK);
    raps_settings* one = atlas_settings(1, 1);
    raps_settings* two = atlas_settings(2, 1);
    atlas a = run_atlas(mesh, one), b = run_atlas(mesh, two);
    assert_int_equal(a.vertex_count, b.vertex_count);
    assert_memory_equal(a.uv, b.uv, 2 * a.vertex_count * sizeof(double));
    assert_memory_equal(a.indices, b.indices, 3 * a.triangle_count * sizeof(uint32_t));
    assert_memory_equal(a.chart, b.chart, a.triangle_count * sizeof(uint32_t));
    atlas_free(&a);
    atlas_free(&b);
    raps_settings_destroy(one);
    raps_settings_destroy(two);
    raps_mesh_destroy(mesh);
    free(group);
    test_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(no_chart_crosses_a_change_of_group),
        cmocka_unit_test(seam_edges_across_the_surface_separate_charts),
        cmocka_unit_test(input_vertex_splits_stay_seams_when_kept),
        cmocka_unit_test(every_bad_seam_input_is_refused_with_its_status),
        cmocka_unit_test(seams_give_the_same_bits_for_any_thread_count),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
