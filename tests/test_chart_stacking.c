/* Stacking congruent charts through the C ABI (RAPS_PARAM_ATLAS_STACK): a mesh given twice to a
 * scene (an instance, moved and turned) costs no extra texels, every chart of the copy taking,
 * texel for texel, the uvs of the chart it is congruent to; a mirrored copy stacks only when
 * mirroring is allowed; a copy bent beyond the tolerance keeps its own place; with repacked
 * uvs an island stacks only on an island laid out the same way; with one page per mesh, charts
 * of different meshes never stack; the same bits for any thread count. */
#include <math.h>
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

typedef struct atlas {
    size_t vertex_count, index_count, chart_count;
    double* uv;
    uint32_t* indices; /* numbering all output vertices */
    uint32_t* chart;
    raps_chart* charts;
    raps_stats stats;
} atlas;

static void atlas_free(atlas* a) {
    free(a->uv);
    free(a->indices);
    free(a->chart);
    free(a->charts);
}

static raps_settings* stack_settings(int64_t stack, int64_t threads) {
    raps_settings* s = NULL;
    assert_int_equal(raps_settings_create(&s), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_THREADS, threads), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_STACK, stack), RAPS_OK);
    return s;
}

/* Runs the scene of `count` meshes; indices come back numbering all output vertices. */
static atlas run_scene(raps_mesh* const* meshes, size_t count, const raps_settings* settings) {
    raps_result* r = NULL;
    assert_int_equal(raps_result_create(&r), RAPS_OK);
    const raps_status status =
        raps_parameterize_scene((const raps_mesh* const*)meshes, count, settings, r);
    if (status != RAPS_OK) fail_msg("scene refused: %s", raps_result_last_error(r));
    atlas a;
    memset(&a, 0, sizeof(a));
    a.vertex_count = raps_result_vertex_count(r);
    a.index_count = raps_result_index_count(r);
    a.stats = stats_of(r);
    a.chart_count = (size_t)a.stats.chart_count;
    a.uv = malloc(2 * a.vertex_count * sizeof(double) + 1);
    a.indices = malloc(a.index_count * sizeof(uint32_t) + 1);
    a.chart = malloc(a.index_count / 3 * sizeof(uint32_t) + 1);
    a.charts = calloc(a.chart_count + 1, sizeof(raps_chart));
    assert_int_equal(raps_result_copy_uvs_f64(r, a.uv, a.vertex_count, 0), RAPS_OK);
    assert_int_equal(raps_result_copy_indices_u32(r, a.indices, a.index_count), RAPS_OK);
    assert_int_equal(raps_result_copy_chart_ids(r, a.chart, a.index_count / 3), RAPS_OK);
    for (size_t m = 0; m < count; ++m) {
        uint64_t first_vertex, first_index, index_count;
        assert_int_equal(
            raps_result_mesh_range(r, m, &first_vertex, NULL, &first_index, &index_count), RAPS_OK);
        for (uint64_t i = first_index; i < first_index + index_count; ++i)
            a.indices[i] += (uint32_t)first_vertex;
    }
    for (size_t c = 0; c < a.chart_count; ++c) {
        a.charts[c].struct_size = sizeof(raps_chart);
        assert_int_equal(raps_result_get_chart(r, c, &a.charts[c]), RAPS_OK);
    }
    raps_result_destroy(r);
    return a;
}

static size_t stacked_count(const atlas* a) {
    size_t stacked = 0;
    for (size_t c = 0; c < a->chart_count; ++c) {
        const raps_chart* chart = &a->charts[c];
        if (!(chart->flags & RAPS_CHART_STACKED)) {
            assert_int_equal(chart->stacked_on, c);
            continue;
        }
        ++stacked;
        assert_true(chart->stacked_on < c);
        const raps_chart* place = &a->charts[chart->stacked_on];
        assert_false(place->flags & RAPS_CHART_STACKED);
        assert_int_equal(chart->page, place->page);
        assert_int_equal(chart->x, place->x);
        assert_int_equal(chart->y, place->y);
        assert_int_equal(chart->width, place->width);
        assert_int_equal(chart->height, place->height);
        assert_int_equal(chart->triangle_count, place->triangle_count);
        assert_near(chart->area_texels, place->area_texels, 1e-9 * place->area_texels);
    }
    return stacked;
}

/* Triangle t of the copy (triangles offset by `offset`) has, corner for corner, the uvs of
 * triangle t of the original, and its chart is stacked on the original's. */
static void check_copy_shares_texels(const atlas* a, size_t triangles, size_t offset) {
    for (size_t t = 0; t < triangles; ++t) {
        const uint32_t original = a->chart[t], copy = a->chart[offset + t];
        assert_int_equal(a->charts[copy].stacked_on, original);
        for (int k = 0; k < 3; ++k) {
            const double* p = &a->uv[2 * a->indices[3 * t + k]];
            const double* q = &a->uv[2 * a->indices[3 * (offset + t) + k]];
            assert_memory_equal(p, q, 2 * sizeof(double));
        }
    }
}

static raps_mesh* placed(const test_mesh* m, const double transform[12]) {
    raps_mesh* mesh = to_raps_mesh(m);
    assert_int_equal(raps_mesh_set_transform(mesh, transform), RAPS_OK);
    return mesh;
}

static const double kIdentity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
/* A quarter turn about z and a move: an instance elsewhere in the scene. */
static const double kTurned[12] = {0, -1, 0, 3.5, 1, 0, 0, -2.25, 0, 0, 1, 0.75};
/* A mirror (x negated) and a move. */
static const double kMirrored[12] = {-1, 0, 0, 4, 0, 1, 0, 0, 0, 0, 1, 0};

static void test_an_instance_costs_no_texels(void** state) {
    (void)state;
    test_mesh spot = load_shared_mesh("spot.obj");
    raps_mesh* meshes[2] = {placed(&spot, kIdentity), placed(&spot, kTurned)};
    const size_t triangles = spot.index_count / 3;
    raps_settings* settings = stack_settings(RAPS_STACK_NONE, 1);
    atlas apart = run_scene(meshes, 2, settings);
    assert_int_equal(stacked_count(&apart), 0);
    raps_settings_destroy(settings);
    atlas serial;
    memset(&serial, 0, sizeof(serial));
    for (int threads = 1; threads <= 3; threads += 2) {
        settings = stack_settings(RAPS_STACK_RIGID, threads);
        atlas a = run_scene(meshes, 2, settings);
        if (threads > 1) { /* the same bits for any thread count */
            assert_int_equal(a.vertex_count, serial.vertex_count);
            assert_memory_equal(a.uv, serial.uv, 2 * a.vertex_count * sizeof(double));
            assert_memory_equal(a.charts, serial.charts, a.chart_count * sizeof(raps_chart));
        }
        /* The instance takes its original's charts (a scene's charts are not made mesh by
         * mesh: apart, the two copies were cut differently), each on its original's place. */
        assert_int_equal(2 * stacked_count(&a), a.chart_count);
        check_copy_shares_texels(&a, triangles, triangles);
        /* The copy's texels are the original's: each shared place counted once. */
        double own = 0, all = 0;
        for (size_t c = 0; c < a.chart_count; ++c) {
            all += a.charts[c].area_texels;
            if (!(a.charts[c].flags & RAPS_CHART_STACKED)) own += a.charts[c].area_texels;
        }
        assert_near(own, all / 2, 1e-9 * all);
        const double page = (double)a.stats.atlas_width * a.stats.atlas_height;
        assert_near(a.stats.utilization, own / page, 1e-6);
        if (threads == 1) {
            serial = a;
        } else {
            atlas_free(&a);
        }
        raps_settings_destroy(settings);
    }
    atlas_free(&serial);
    atlas_free(&apart);
    raps_mesh_destroy(meshes[0]);
    raps_mesh_destroy(meshes[1]);
    test_mesh_free(&spot);
}

static void test_a_mirrored_copy_stacks_only_when_mirroring_is_allowed(void** state) {
    (void)state;
    test_mesh bump = make_open_cone(6, 12, 0.7);
    raps_mesh* meshes[2] = {placed(&bump, kIdentity), placed(&bump, kMirrored)};
    const size_t triangles = bump.index_count / 3;
    raps_settings* settings = stack_settings(RAPS_STACK_RIGID, 1);
    atlas a = run_scene(meshes, 2, settings);
    assert_int_equal(stacked_count(&a), 0);
    atlas_free(&a);
    raps_settings_destroy(settings);
    settings = stack_settings(RAPS_STACK_MIRRORED, 1);
    a = run_scene(meshes, 2, settings);
    assert_int_equal(2 * stacked_count(&a), a.chart_count);
    check_copy_shares_texels(&a, triangles, triangles);
    atlas_free(&a);
    raps_settings_destroy(settings);
    raps_mesh_destroy(meshes[0]);
    raps_mesh_destroy(meshes[1]);
    test_mesh_free(&bump);
}

/* A copy with one vertex moved by 1% of the mesh's size keeps that chart's own place at the
 * default tolerance and stacks with a tolerance of 5%; one page per mesh keeps meshes apart. */
static void test_the_tolerance_and_one_page_per_mesh_keep_charts_apart(void** state) {
    (void)state;
    test_mesh cone = make_open_cone(6, 12, 0.7);
    test_mesh bent = make_open_cone(6, 12, 0.7);
    bent.positions[3 * 10 + 2] += 0.02;
    raps_mesh* meshes[2] = {placed(&cone, kIdentity), placed(&bent, kTurned)};
    raps_settings* settings = stack_settings(RAPS_STACK_RIGID, 1);
    atlas a = run_scene(meshes, 2, settings);
    const size_t strict = stacked_count(&a);
    assert_true(2 * strict < a.chart_count);
    atlas_free(&a);
    assert_int_equal(raps_settings_set_float(settings, RAPS_PARAM_ATLAS_STACK_TOLERANCE, 0.05),
                     RAPS_OK);
    a = run_scene(meshes, 2, settings);
    assert_int_equal(2 * stacked_count(&a), a.chart_count);
    atlas_free(&a);
    /* One page per mesh: a lightmap's pages never share texels across meshes. */
    assert_int_equal(raps_settings_set_float(settings, RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, 64.0),
                     RAPS_OK);
    assert_int_equal(raps_settings_set_int(settings, RAPS_PARAM_ATLAS_MESH_PER_PAGE, 1), RAPS_OK);
    a = run_scene(meshes, 2, settings);
    assert_int_equal(stacked_count(&a), 0);
    atlas_free(&a);
    assert_status(raps_settings_set_int(settings, RAPS_PARAM_ATLAS_STACK, 3),
                  RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_settings_set_float(settings, RAPS_PARAM_ATLAS_STACK_TOLERANCE, NAN),
                  RAPS_ERROR_INVALID_ARGUMENT);
    raps_settings_destroy(settings);
    raps_mesh_destroy(meshes[0]);
    raps_mesh_destroy(meshes[1]);
    test_mesh_free(&bent);
    test_mesh_free(&cone);
}

/* `m` turned by `degrees` about `axis` (through the origin). */
static test_mesh turned_copy(const test_mesh* m, double degrees, const double axis[3]) {
    const double n = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    const double x = axis[0] / n, y = axis[1] / n, z = axis[2] / n;
    const double c = cos(degrees * 3.14159265358979323846 / 180.0);
    const double s = sin(degrees * 3.14159265358979323846 / 180.0), t = 1 - c;
    const double r[9] = {t * x * x + c,     t * x * y - s * z, t * x * z + s * y,
                         t * x * y + s * z, t * y * y + c,     t * y * z - s * x,
                         t * x * z - s * y, t * y * z + s * x, t * z * z + c};
    test_mesh out = join_meshes(m, &(test_mesh){NULL, 0, NULL, 0}, 0, 0, 0);
    for (size_t v = 0; v < out.vertex_count; ++v) {
        const double* p = &m->positions[3 * v];
        for (int k = 0; k < 3; ++k)
            out.positions[3 * v + k] = r[3 * k] * p[0] + r[3 * k + 1] * p[1] + r[3 * k + 2] * p[2];
    }
    return out;
}

/* One mesh holding a shared mesh and a copy of it, turned by a quarter turn or by 37 degrees
 * about a skew axis and moved: the copy's charts are its original's (segmentation alone cuts
 * a turned copy differently), each stacked on its original's place. A copy with one vertex
 * moved by 2% of the mesh's size is no copy: that piece keeps its own places. */
static void test_a_turned_copy_within_one_mesh_stacks_fully(void** state) {
    (void)state;
    test_mesh spot = load_shared_mesh("spot.obj");
    const size_t triangles = spot.index_count / 3;
    const double z_axis[3] = {0, 0, 1}, skew[3] = {1, 2, 3};
    const double turns[2] = {90.0, 37.0};
    raps_settings* settings = stack_settings(RAPS_STACK_RIGID, 1);
    for (int k = 0; k < 3; ++k) {
        test_mesh copy = turned_copy(&spot, turns[k % 2], k == 0 ? z_axis : skew);
        if (k == 2) copy.positions[3 * 100 + 1] += 0.02;
        test_mesh both = join_meshes(&spot, &copy, 2.5, -1.0, 0.5);
        raps_mesh* mesh = to_raps_mesh(&both);
        atlas a = run_scene(&mesh, 1, settings);
        if (k < 2) {
            assert_int_equal(2 * stacked_count(&a), a.chart_count);
            check_copy_shares_texels(&a, triangles, triangles);
        } else {
            assert_true(2 * stacked_count(&a) < a.chart_count);
        }
        atlas_free(&a);
        raps_mesh_destroy(mesh);
        test_mesh_free(&both);
        test_mesh_free(&copy);
    }
    raps_settings_destroy(settings);
    test_mesh_free(&spot);
}

/* Repacking two copies of a grid in one mesh: the copy's island stacks when its uvs are laid
 * out as the original's (moved), not when they are mirrored, unless mirroring is allowed. */
static void test_repacked_islands_stack_when_laid_out_alike(void** state) {
    (void)state;
    test_mesh grid = make_grid(4, 3, 2.0, 1.5);
    test_mesh two = join_meshes(&grid, &grid, 5.0, 0.0, 0.0);
    const size_t triangles = grid.index_count / 3;
    double* uv = malloc(12 * triangles * sizeof(double));
    for (int mirrored = 0; mirrored < 2; ++mirrored) {
        for (size_t t = 0; t < 2 * triangles; ++t) {
            for (int k = 0; k < 3; ++k) {
                const double* p = &two.positions[3 * two.indices[3 * t + k]];
                const int copy = t >= triangles;
                const double x = copy ? p[0] - 5.0 : p[0];
                uv[6 * t + 2 * k] = copy ? 10.0 + (mirrored ? -x : x) : x;
                uv[6 * t + 2 * k + 1] = p[1];
            }
        }
        raps_mesh* mesh = to_raps_mesh(&two);
        assert_status(raps_mesh_set_corner_uvs_f64(mesh, uv, two.index_count, 0), RAPS_OK);
        for (int64_t stack = RAPS_STACK_RIGID; stack <= RAPS_STACK_MIRRORED; ++stack) {
            raps_settings* settings = stack_settings(stack, 1);
            assert_int_equal(raps_settings_set_int(settings, RAPS_PARAM_ATLAS_REPACK, 1), RAPS_OK);
            atlas a = run_scene(&mesh, 1, settings);
            assert_int_equal(a.chart_count, 2);
            const int expect = !mirrored || stack == RAPS_STACK_MIRRORED;
            assert_int_equal(stacked_count(&a), expect ? 1 : 0);
            if (expect) check_copy_shares_texels(&a, triangles, triangles);
            atlas_free(&a);
            raps_settings_destroy(settings);
        }
        raps_mesh_destroy(mesh);
    }
    free(uv);
    test_mesh_free(&two);
    test_mesh_free(&grid);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_an_instance_costs_no_texels),
        cmocka_unit_test(test_a_turned_copy_within_one_mesh_stacks_fully),
        cmocka_unit_test(test_a_mirrored_copy_stacks_only_when_mirroring_is_allowed),
        cmocka_unit_test(test_the_tolerance_and_one_page_per_mesh_keep_charts_apart),
        cmocka_unit_test(test_repacked_islands_stack_when_laid_out_alike),
    };
    return cmocka_run_group_tests_name("chart_stacking", tests, NULL, NULL);
}
