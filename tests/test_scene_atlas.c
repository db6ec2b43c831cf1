/* Scene atlases through the C ABI (raps_parameterize_scene): several meshes, each placed in
 * world units by its transform, packed into one atlas at one texel density. Each mesh's share of
 * the output reads as a one-mesh result, no two charts overlap or come closer than the padding
 * (rasterised at the page's texels), every chart gets the same texels per world-unit area, the
 * output does not depend on the thread count, and every bad input is refused with its status
 * and a message naming the problem. */
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

#define MAX_MESHES 10

typedef struct scene {
    size_t mesh_count;
    const test_mesh* meshes[MAX_MESHES];
    double transforms[MAX_MESHES][12];
} scene;

typedef struct scene_atlas {
    size_t vertex_count, index_count, chart_count;
    double* uv;
    uint32_t* indices; /* as copied: each mesh's own output vertices */
    uint32_t* global;  /* the same, numbering all output vertices */
    uint32_t* remap;
    uint32_t* chart;
    raps_chart* charts;
    uint64_t range[MAX_MESHES][4]; /* first vertex, vertex count, first index, index count */
    raps_stats stats;
} scene_atlas;

static void scene_atlas_free(scene_atlas* a) {
    free(a->uv);
    free(a->indices);
    free(a->global);
    free(a->remap);
    free(a->chart);
    free(a->charts);
}

static void set_identity(double m[12]) {
    memset(m, 0, 12 * sizeof(double));
    m[0] = m[5] = m[10] = 1.0;
}

/* Uniform scale s, then a move by (dx, dy, dz). */
static void set_scale_move(double m[12], double s, double dx, double dy, double dz) {
    set_identity(m);
    m[0] = m[5] = m[10] = s;
    m[3] = dx;
    m[7] = dy;
    m[11] = dz;
}

/* One mesh twice, both in place (a test moves or scales a copy by its transform). */
static scene two_copies(const test_mesh* mesh) {
    scene sc;
    sc.mesh_count = 2;
    sc.meshes[0] = sc.meshes[1] = mesh;
    set_identity(sc.transforms[0]);
    set_identity(sc.transforms[1]);
    return sc;
}

static raps_settings* atlas_settings(int64_t threads, int64_t padding) {
    raps_settings* s = NULL;
    assert_int_equal(raps_settings_create(&s), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_THREADS, threads), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_PADDING, padding), RAPS_OK);
    return s;
}

static scene_atlas run_scene(const scene* sc, const raps_settings* settings) {
    raps_mesh* handles[MAX_MESHES];
    for (size_t i = 0; i < sc->mesh_count; ++i) {
        handles[i] = to_raps_mesh(sc->meshes[i]);
        assert_int_equal(raps_mesh_set_transform(handles[i], sc->transforms[i]), RAPS_OK);
    }
    raps_result* r = NULL;
    assert_int_equal(raps_result_create(&r), RAPS_OK);
    const raps_status status =
        raps_parameterize_scene((const raps_mesh* const*)handles, sc->mesh_count, settings, r);
    if (status != RAPS_OK) fail_msg("scene refused: %s", raps_result_last_error(r));
    scene_atlas a;
    memset(&a, 0, sizeof(a));
    a.vertex_count = raps_result_vertex_count(r);
    a.index_count = raps_result_index_count(r);
    a.uv = malloc(2 * a.vertex_count * sizeof(double) + 1);
    a.indices = malloc(a.index_count * sizeof(uint32_t) + 1);
    a.remap = malloc(a.vertex_count * sizeof(uint32_t) + 1);
    a.chart = malloc(a.index_count / 3 * sizeof(uint32_t) + 1);
    assert_int_equal(raps_result_copy_uvs_f64(r, a.uv, a.vertex_count, 0), RAPS_OK);
    assert_int_equal(raps_result_copy_indices_u32(r, a.indices, a.index_count), RAPS_OK);
    assert_int_equal(raps_result_copy_vertex_remap(r, a.remap, a.vertex_count), RAPS_OK);
    assert_int_equal(raps_result_copy_chart_ids(r, a.chart, a.index_count / 3), RAPS_OK);
    a.stats = stats_of(r);
    a.chart_count = (size_t)a.stats.chart_count;
    a.charts = calloc(a.chart_count + 1, sizeof(raps_chart));
    for (size_t c = 0; c < a.chart_count; ++c) {
        a.charts[c].struct_size = sizeof(raps_chart);
        assert_int_equal(raps_result_get_chart(r, c, &a.charts[c]), RAPS_OK);
    }
    assert_int_equal(raps_result_mesh_count(r), sc->mesh_count);
    for (size_t i = 0; i < sc->mesh_count; ++i) {
        assert_int_equal(raps_result_mesh_range(r, i, &a.range[i][0], &a.range[i][1],
                                                &a.range[i][2], &a.range[i][3]),
                         RAPS_OK);
    }
    a.global = malloc(a.index_count * sizeof(uint32_t) + 1);
    for (size_t m = 0; m < sc->mesh_count; ++m) {
        for (uint64_t i = a.range[m][2]; i < a.range[m][2] + a.range[m][3]; ++i)
            a.global[i] = a.indices[i] + (uint32_t)a.range[m][0];
    }
    raps_result_destroy(r);
    for (size_t i = 0; i < sc->mesh_count; ++i) raps_mesh_destroy(handles[i]);
    return a;
}

/* Each mesh's range reads as its own one-mesh result: ranges follow one another and cover the
 * output, a mesh's indices name its own output vertices whose remap gives its own input
 * vertices, and every chart holds triangles of one mesh only (the mesh its record names). */
static void check_ranges(const scene* sc, const scene_atlas* a) {
    uint64_t next_vertex = 0, next_index = 0;
    for (size_t m = 0; m < sc->mesh_count; ++m) {
        const test_mesh* mesh = sc->meshes[m];
        const uint64_t* range = a->range[m];
        assert_int_equal(range[0], next_vertex);
        assert_int_equal(range[2], next_index);
        assert_int_equal(range[3], mesh->index_count);
        for (size_t i = 0; i < mesh->index_count; ++i) {
            const uint32_t local = a->indices[range[2] + i];
            assert_true(local < range[1]);
            const uint32_t input = a->remap[range[0] + local];
            if (input != mesh->indices[i])
                fail_msg("mesh %zu, corner %zu: input vertex %u, expected %u", m, i, input,
                         mesh->indices[i]);
            const uint32_t chart = a->chart[(range[2] + i) / 3];
            assert_true(chart < a->chart_count);
            assert_int_equal(a->charts[chart].mesh, m);
        }
        for (uint64_t v = range[0]; v < range[0] + range[1]; ++v)
            assert_true(a->remap[v] < mesh->vertex_count);
        next_vertex += range[1];
        next_index += range[3];
    }
    assert_int_equal(next_vertex, a->vertex_count);
    assert_int_equal(next_index, a->index_count);
    for (size_t v = 0; v < 2 * a->vertex_count; ++v)
        assert_true(a->uv[v] >= 0.0 && a->uv[v] <= 1.0);
}

/* Marks in `owner` every cell (of `cell` x `cell` texels) of its page that uv triangle t
 * touches, rasterised at the page's texels; fails when a cell within Chebyshev distance `reach`
 * of one belongs to another chart (so at least `reach` free cells lie between any two charts). A
 * texel counts as touched when the triangle's row band reaches more than 1e-6 texel into it: a
 * chart placed on a whole texel touches the texel below its edge only by rounding. */
static void mark_triangle(const scene_atlas* a, size_t t, int32_t* owner, int reach, int cell) {
    const int w = (int)a->stats.atlas_width, h = (int)a->stats.atlas_height;
    const int cw = w / cell, ch = h / cell;
    const uint32_t chart = a->chart[t];
    double x[3], y[3];
    for (int k = 0; k < 3; ++k) {
        x[k] = a->uv[2 * a->global[3 * t + k]] * w;
        y[k] = a->uv[2 * a->global[3 * t + k] + 1] * h;
    }
    const double eps = 1e-6;
    double lo_y = fmin(y[0], fmin(y[1], y[2])), hi_y = fmax(y[0], fmax(y[1], y[2]));
    for (int row = (int)floor(lo_y + eps); row <= (int)floor(hi_y - eps) && row < h; ++row) {
        /* The triangle's x-range over the band [row, row + 1]: its corners inside the band and
         * its edges' crossings of the band's two lines. */
        double lo_x = 1e300, hi_x = -1e300;
        const double band[2] = {fmax(row, lo_y), fmin(row + 1.0, hi_y)};
        for (int k = 0; k < 3; ++k) {
            const int j = (k + 1) % 3;
            if (y[k] >= band[0] && y[k] <= band[1]) {
                lo_x = fmin(lo_x, x[k]);
                hi_x = fmax(hi_x, x[k]);
            }
            for (int b = 0; b < 2; ++b) {
                if ((y[k] - band[b]) * (y[j] - band[b]) <= 0 && y[k] != y[j]) {
                    const double cx = x[k] + (band[b] - y[k]) * (x[j] - x[k]) / (y[j] - y[k]);
                    lo_x = fmin(lo_x, cx);
                    hi_x = fmax(hi_x, cx);
                }
            }
        }
        if (lo_x > hi_x) continue;
        for (int col = (int)floor(lo_x + eps); col <= (int)floor(hi_x - eps) && col < w; ++col) {
            if (row < 0 || col < 0) fail_msg("chart %u reaches texel (%d, %d)", chart, col, row);
            for (int dy = -reach; dy <= reach; ++dy) {
                for (int dx = -reach; dx <= reach; ++dx) {
                    const int cx = col / cell + dx, cy = row / cell + dy;
                    if (cx < 0 || cy < 0 || cx >= cw || cy >= ch) continue;
                    const int32_t other = owner[(size_t)cy * cw + cx];
                    if (other >= 0 && (uint32_t)other != chart)
                        fail_msg(
                            "charts %u and %d have fewer than %d free cell(s) between them at "
                            "texel "
                            "(%d, %d)",
                            chart, other, reach, col, row);
                }
            }
            owner[(size_t)(row / cell) * cw + col / cell] = (int32_t)chart;
        }
    }
}

/* At least `reach` free cells of `cell` x `cell` texels between any two charts on one page. */
static void check_gaps(const scene_atlas* a, int reach, int cell) {
    const int w = (int)a->stats.atlas_width, h = (int)a->stats.atlas_height;
    assert_true(w >= 1 && h >= 1 && a->stats.page_count >= 1);
    assert_true(w % cell == 0 && h % cell == 0);
    const size_t cells = (size_t)(w / cell) * (h / cell);
    int32_t* owner = malloc(cells * sizeof(int32_t));
    for (uint64_t page = 0; page < a->stats.page_count; ++page) {
        for (size_t i = 0; i < cells; ++i) owner[i] = -1;
        for (size_t t = 0; t < a->index_count / 3; ++t) {
            if (a->charts[a->chart[t]].page == page) mark_triangle(a, t, owner, reach, cell);
        }
    }
    free(owner);
}

/* Texels per world-unit area of every chart not scaled down: within 2% of the atlas's
 * density squared. */
static void check_density(const scene_atlas* a) {
    const double expected = a->stats.texels_per_unit * a->stats.texels_per_unit;
    assert_true(expected > 0);
    for (size_t c = 0; c < a->chart_count; ++c) {
        const raps_chart* chart = &a->charts[c];
        if (chart->area_3d <= 0 || (chart->flags & RAPS_CHART_SCALED_DOWN)) continue;
        const double density = chart->area_texels / chart->area_3d;
        if (fabs(density / expected - 1.0) > 0.02)
            fail_msg("chart %zu (mesh %u): %g texels per unit area, the atlas %g", c, chart->mesh,
                     density, expected);
    }
}

/* Settings for a density: texels per unit, pages of at most max_w x max_h texels. */
static raps_settings* density_settings(int64_t threads, int64_t padding, double texels_per_unit,
                                       int64_t max_w, int64_t max_h) {
    raps_settings* s = atlas_settings(threads, padding);
    assert_int_equal(raps_settings_set_float(s, RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, texels_per_unit),
                     RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_MAX_WIDTH, max_w), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_MAX_HEIGHT, max_h), RAPS_OK);
    return s;
}

/* Pages within the maximum, every chart's texel rectangle on its page, the density asked for,
 * scaled-down charts counted. */
static void check_pages(const scene_atlas* a, double texels_per_unit, int64_t max_w,
                        int64_t max_h) {
    assert_true(a->stats.atlas_width >= 1 && (int64_t)a->stats.atlas_width <= max_w);
    assert_true(a->stats.atlas_height >= 1 && (int64_t)a->stats.atlas_height <= max_h);
    assert_true(a->stats.texels_per_unit == texels_per_unit);
    uint64_t scaled = 0;
    for (size_t c = 0; c < a->chart_count; ++c) {
        const raps_chart* chart = &a->charts[c];
        assert_true(chart->page < a->stats.page_count);
        assert_true(chart->x + chart->width <= a->stats.atlas_width);
        assert_true(chart->y + chart->height <= a->stats.atlas_height);
        scaled += (chart->flags & RAPS_CHART_SCALED_DOWN) ? 1 : 0;
    }
    assert_int_equal(scaled, a->stats.scaled_down_charts);
    check_density(a);
}

/* A scene of an open cone, a grid scaled by 3 and moved, and a small sphere moved onto the
 * cone's apex (touching it: no chart may join them). */
typedef struct three_meshes {
    test_mesh cone, grid, sphere;
    scene sc;
} three_meshes;

static void make_three_meshes(three_meshes* t) {
    t->cone = make_open_cone(8, 24, 1.0);
    t->grid = make_grid(12, 6, 1.0, 0.5);
    t->sphere = make_uv_sphere(10, 20);
    t->sc.mesh_count = 3;
    t->sc.meshes[0] = &t->cone;
    t->sc.meshes[1] = &t->grid;
    t->sc.meshes[2] = &t->sphere;
    set_identity(t->sc.transforms[0]);
    set_scale_move(t->sc.transforms[1], 3.0, 5.0, 0.0, 0.0);
    set_scale_move(t->sc.transforms[2], 0.5, 0.0, 0.0, 1.5);
}

static void free_three_meshes(three_meshes* t) {
    test_mesh_free(&t->cone);
    test_mesh_free(&t->grid);
    test_mesh_free(&t->sphere);
}

static void several_meshes_share_one_atlas_without_overlap(void** state) {
    (void)state;
    three_meshes t;
    make_three_meshes(&t);
    raps_settings* s = atlas_settings(0, 2);
    scene_atlas a = run_scene(&t.sc, s);
    print_message("%llu charts, %llux%llu texels, utilization %.3f, %.2f texels per unit\n",
                  (unsigned long long)a.stats.chart_count, (unsigned long long)a.stats.atlas_width,
                  (unsigned long long)a.stats.atlas_height, a.stats.utilization,
                  a.stats.texels_per_unit);
    check_ranges(&t.sc, &a);
    /* The resolution-driven packing keeps `padding` texels in continuous units, which whole
     * texels may round down by one. */
    check_gaps(&a, 1, 1);
    check_density(&a);
    assert_int_equal(a.stats.page_count, 1);
    assert_int_equal(a.stats.flipped_triangles, 0);
    /* Each mesh has charts of its own. */
    int has_chart[3] = {0, 0, 0};
    for (size_t c = 0; c < a.chart_count; ++c) has_chart[a.charts[c].mesh] = 1;
    assert_true(has_chart[0] && has_chart[1] && has_chart[2]);
    scene_atlas_free(&a);
    raps_settings_destroy(s);
    free_three_meshes(&t);
}

/* A flat strip `length` x 1 beside a unit sphere and a flat square `side` x `side`. */
typedef struct strip_scene {
    test_mesh strip, sphere, square;
    scene sc;
} strip_scene;

static void make_strip_scene(strip_scene* t, int length, double side) {
    t->strip = make_grid(10 * length, 10, length, 1.0);
    t->sphere = make_uv_sphere(16, 32);
    t->square = make_grid(12, 12, side, side);
    t->sc.mesh_count = 3;
    t->sc.meshes[0] = &t->strip;
    t->sc.meshes[1] = &t->sphere;
    t->sc.meshes[2] = &t->square;
    set_identity(t->sc.transforms[0]);
    set_scale_move(t->sc.transforms[1], 1.0, 0.0, 3.0, 0.0);
    set_scale_move(t->sc.transforms[2], 1.0, 0.0, 6.0, 0.0);
}

static void free_strip_scene(strip_scene* t) {
    test_mesh_free(&t->strip);
    test_mesh_free(&t->sphere);
    test_mesh_free(&t->square);
}

/* Runs the scene and checks that the strip, under half of the area, was cut (2 charts or more)
 * and that the atlas covers more than 0.6 of the square, with `reach` texels of padding. */
static void expect_strip_cut(const strip_scene* t, const raps_settings* s, int reach) {
    scene_atlas a = run_scene(&t->sc, s);
    size_t strip_charts = 0;
    double strip_area = 0, area = 0;
    for (size_t c = 0; c < a.chart_count; ++c) {
        area += a.charts[c].area_3d;
        if (a.charts[c].mesh != 0) continue;
        ++strip_charts;
        strip_area += a.charts[c].area_3d;
    }
    print_message("%llu charts (%zu of the strip, %.2f of the area), utilization %.3f\n",
                  (unsigned long long)a.stats.chart_count, strip_charts, strip_area / area,
                  a.stats.utilization);
    assert_true(strip_area / area < 0.5);
    check_ranges(&t->sc, &a);
    check_gaps(&a, reach, 1);
    check_density(&a);
    assert_int_equal(a.stats.flipped_triangles, 0);
    assert_true(strip_charts >= 2);
    assert_true(a.stats.utilization > 0.6);
    scene_atlas_free(&a);
}

/* A flat 10:1 strip beside a sphere and a square (a third of the area): at the density at
 * which the charts would fill 0.7 of the square, the strip is 1.5 times the square's side. Kept
 * whole it lowers every chart's density (placed across the square, the atlas covered 0.516 of
 * it); it is cut across instead, and the square is covered as compact meshes cover it. */
static void a_long_mesh_among_compact_ones_is_cut_across(void** state) {
    (void)state;
    strip_scene t;
    make_strip_scene(&t, 10, 3.0);
    raps_settings* s = atlas_settings(0, 2);
    expect_strip_cut(&t, s, 1);
    raps_settings_destroy(s);
    free_strip_scene(&t);
}

/* A flat 7:1 strip beside a sphere and a square (0.3 of the area) is 1.2 times the square's side
 * at the density that would fill 0.7 of it: cut or whole may pack better, so both are packed.
 * On whole texels, where no chart lies across the square, the cut packs denser and is kept. */
static void a_chart_a_little_too_long_is_cut_where_that_packs_denser(void** state) {
    (void)state;
    strip_scene t;
    make_strip_scene(&t, 7, 1.9);
    raps_settings* s = atlas_settings(0, 2);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_WHOLE_TEXELS, 1), RAPS_OK);
    expect_strip_cut(&t, s, 2);
    raps_settings_destroy(s);
    free_strip_scene(&t);
}

/* One mesh twice, the second scaled by 2: it gets four times the texels. */
static void a_scaled_mesh_gets_texels_in_proportion(void** state) {
    (void)state;
    test_mesh cone = make_open_cone(8, 24, 1.0);
    scene sc = two_copies(&cone);
    set_scale_move(sc.transforms[1], 2.0, 0.0, 0.0, 0.0);
    raps_settings* s = atlas_settings(0, 1);
    scene_atlas a = run_scene(&sc, s);
    check_ranges(&sc, &a);
    check_density(&a);
    double texels[2] = {0, 0}, area[2] = {0, 0};
    for (size_t c = 0; c < a.chart_count; ++c) {
        texels[a.charts[c].mesh] += a.charts[c].area_texels;
        area[a.charts[c].mesh] += a.charts[c].area_3d;
    }
    assert_true(fabs(area[1] / area[0] - 4.0) < 1e-9);
    assert_true(fabs(texels[1] / texels[0] / 4.0 - 1.0) < 0.02);
    scene_atlas_free(&a);
    raps_settings_destroy(s);
    test_mesh_free(&cone);
}

/* Runs the scene with 1 and with 2 threads: the same bits. The 2-thread run is repeated (up to 5
 * times, each compared) until its worker has computed a share: on a busy machine the calling
 * thread may finish a small scene's parallel steps before the worker wakes. */
static void check_same_bits_for_two_threads(const scene* sc, raps_settings* one_thread,
                                            raps_settings* two_threads) {
    scene_atlas one = run_scene(sc, one_thread);
    assert_int_equal(one.stats.threads_used, 1);
    uint64_t most_threads = 0;
    for (int run = 0; run < 5 && most_threads < 2; ++run) {
        scene_atlas two = run_scene(sc, two_threads);
        most_threads = two.stats.threads_used;
        assert_int_equal(one.vertex_count, two.vertex_count);
        assert_int_equal(one.chart_count, two.chart_count);
        assert_memory_equal(one.uv, two.uv, 2 * one.vertex_count * sizeof(double));
        assert_memory_equal(one.indices, two.indices, one.index_count * sizeof(uint32_t));
        assert_memory_equal(one.remap, two.remap, one.vertex_count * sizeof(uint32_t));
        assert_memory_equal(one.charts, two.charts, one.chart_count * sizeof(raps_chart));
        scene_atlas_free(&two);
    }
    assert_int_equal(most_threads, 2); /* the worker did compute */
    scene_atlas_free(&one);
}

static void scene_output_is_identical_for_any_thread_count(void** state) {
    (void)state;
    three_meshes t;
    make_three_meshes(&t);
    raps_settings* one_thread = atlas_settings(1, 2);
    raps_settings* two_threads = atlas_settings(2, 2);
    check_same_bits_for_two_threads(&t.sc, one_thread, two_threads);
    raps_settings_destroy(one_thread);
    raps_settings_destroy(two_threads);
    /* And at a density, on pages, one mesh to a page. */
    one_thread = density_settings(1, 2, 40.0, 176, 100);
    two_threads = density_settings(2, 2, 40.0, 176, 100);
    assert_int_equal(raps_settings_set_int(one_thread, RAPS_PARAM_ATLAS_MESH_PER_PAGE, 1), RAPS_OK);
    assert_int_equal(raps_settings_set_int(two_threads, RAPS_PARAM_ATLAS_MESH_PER_PAGE, 1),
                     RAPS_OK);
    check_same_bits_for_two_threads(&t.sc, one_thread, two_threads);
    raps_settings_destroy(one_thread);
    raps_settings_destroy(two_threads);
    free_three_meshes(&t);
}

/* The ten shared meshes of raps-bench-scene (issue 23's scene, 157 charts) in one square of 2048
 * texels at padding 2 cover at least 0.72 of it. On whole texels no order of the charts fits a
 * density from 3.49 texels per unit up; the orders repaired where they fail by a chart or two
 * (repair_orders, src/atlas/page_packing.cpp) fit 3.51, 0.726 (0.716 before). The repaired
 * search gives the same bits with one thread and two. */
static void ten_shared_meshes_cover_072_of_a_2048_square(void** state) {
    (void)state;
    static const char* const names[] = {
        "bunny.off",       "spot.obj",          "suzanne.obj",    "teapot.obj", "fandisk.obj",
        "cheburashka.off", "decimated-max.obj", "halftunnel.off", "3holes.off", "fertility.off"};
    test_mesh meshes[MAX_MESHES];
    scene sc;
    sc.mesh_count = MAX_MESHES;
    for (size_t i = 0; i < MAX_MESHES; ++i) {
        meshes[i] = load_shared_mesh(names[i]);
        sc.meshes[i] = &meshes[i];
        set_identity(sc.transforms[i]);
    }
    raps_settings* one_thread = atlas_settings(1, 2);
    raps_settings* two_threads = atlas_settings(2, 2);
    assert_int_equal(raps_settings_set_int(one_thread, RAPS_PARAM_ATLAS_RESOLUTION, 2048), RAPS_OK);
    assert_int_equal(raps_settings_set_int(two_threads, RAPS_PARAM_ATLAS_RESOLUTION, 2048),
                     RAPS_OK);
    scene_atlas a = run_scene(&sc, two_threads);
    print_message("%llu charts, utilization %.4f, %.3f texels per unit\n",
                  (unsigned long long)a.chart_count, a.stats.utilization, a.stats.texels_per_unit);
    assert_int_equal(a.stats.atlas_width, 2048);
    assert_int_equal(a.stats.atlas_height, 2048);
    assert_true(a.stats.utilization >= 0.72);
    scene_atlas_free(&a);
    check_same_bits_for_two_threads(&sc, one_thread, two_threads);
    raps_settings_destroy(one_thread);
    raps_settings_destroy(two_threads);
    for (size_t i = 0; i < MAX_MESHES; ++i) test_mesh_free(&meshes[i]);
}

/* raps_parameterize's atlas also has its mesh range and chart records, and is the square of
 * the resolution asked for, which its charts reach on two opposite sides. */
static void a_one_mesh_atlas_has_records_and_fits_its_resolution(void** state) {
    (void)state;
    test_mesh meshes[3] = {make_open_cone(8, 24, 1.0), make_grid(30, 7, 3.0, 0.7),
                           make_uv_sphere(12, 24)};
    const int64_t resolutions[3] = {16, 300, 1024};
    for (int m = 0; m < 3; ++m) {
        raps_mesh* mesh = to_raps_mesh(&meshes[m]);
        raps_settings* s = atlas_settings(0, 1);
        assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_RESOLUTION, resolutions[m]),
                         RAPS_OK);
        raps_result* r = parameterize_ok(mesh, s);
        const raps_stats stats = stats_of(r);
        assert_int_equal(stats.atlas_width, resolutions[m]);
        assert_int_equal(stats.atlas_height, resolutions[m]);
        double* uv = malloc(2 * raps_result_vertex_count(r) * sizeof(double));
        assert_non_null(uv);
        assert_int_equal(raps_result_copy_uvs_f64(r, uv, raps_result_vertex_count(r), 0), RAPS_OK);
        double high[2] = {0, 0};
        for (uint64_t k = 0; k < 2 * raps_result_vertex_count(r); ++k) {
            if (uv[k] > high[k % 2]) high[k % 2] = uv[k];
        }
        assert_true((high[0] > 1 - 1e-9) || (high[1] > 1 - 1e-9));
        free(uv);
        assert_int_equal(raps_result_mesh_count(r), 1);
        uint64_t range[4];
        assert_int_equal(raps_result_mesh_range(r, 0, &range[0], &range[1], &range[2], &range[3]),
                         RAPS_OK);
        assert_int_equal(range[0], 0);
        assert_int_equal(range[1], raps_result_vertex_count(r));
        assert_int_equal(range[3], meshes[m].index_count);
        uint64_t triangles = 0;
        for (uint64_t c = 0; c < stats.chart_count; ++c) {
            raps_chart chart;
            chart.struct_size = sizeof(chart);
            assert_int_equal(raps_result_get_chart(r, c, &chart), RAPS_OK);
            assert_int_equal(chart.mesh, 0);
            assert_int_equal(chart.page, 0);
            assert_true(chart.x + chart.width <= stats.atlas_width);
            assert_true(chart.y + chart.height <= stats.atlas_height);
            assert_true(chart.rotation_deg >= 0 && chart.rotation_deg < 360);
            if (!(chart.stretch_l2 >= 1.0 - 1e-9 && chart.stretch_l2 < 1.1))
                fail_msg("chart %llu: L2 stretch %.17g", (unsigned long long)c, chart.stretch_l2);
            triangles += chart.triangle_count;
        }
        assert_int_equal(triangles, meshes[m].index_count / 3);
        raps_result_destroy(r);
        raps_settings_destroy(s);
        raps_mesh_destroy(mesh);
        test_mesh_free(&meshes[m]);
    }
}

/* At a density, charts that do not fit one page go on further pages, none larger than the
 * maximum; the padding holds at the final texels. */
static void a_density_fills_pages_never_larger_than_the_maximum(void** state) {
    (void)state;
    three_meshes t;
    make_three_meshes(&t);
    raps_settings* s = density_settings(0, 2, 40.0, 128, 96);
    scene_atlas a = run_scene(&t.sc, s);
    print_message("%llu charts on %llu pages of %llux%llu, utilization %.3f\n",
                  (unsigned long long)a.stats.chart_count, (unsigned long long)a.stats.page_count,
                  (unsigned long long)a.stats.atlas_width, (unsigned long long)a.stats.atlas_height,
                  a.stats.utilization);
    check_ranges(&t.sc, &a);
    check_pages(&a, 40.0, 128, 96);
    check_gaps(&a, 2, 1);
    assert_true(a.stats.page_count >= 2);
    assert_int_equal(a.stats.scaled_down_charts, 0);
    scene_atlas_free(&a);
    raps_settings_destroy(s);
    free_three_meshes(&t);
}

/* A chart larger than a page at the density is shrunk until it fits, and says so. */
static void a_chart_larger_than_a_page_is_shrunk_and_reported(void** state) {
    (void)state;
    test_mesh big = make_grid(8, 4, 8.0, 4.0), small = make_grid(2, 2, 1.0, 1.0);
    scene sc;
    sc.mesh_count = 2;
    sc.meshes[0] = &big;
    sc.meshes[1] = &small;
    set_identity(sc.transforms[0]);
    set_identity(sc.transforms[1]);
    raps_settings* s = density_settings(0, 1, 32.0, 64, 200); /* 8 units: 256 texels */
    scene_atlas a = run_scene(&sc, s);
    check_ranges(&sc, &a);
    check_pages(&a, 32.0, 64, 200);
    check_gaps(&a, 1, 1);
    assert_int_equal(a.stats.scaled_down_charts, 1);
    for (size_t c = 0; c < a.chart_count; ++c) {
        const int scaled = (a.charts[c].flags & RAPS_CHART_SCALED_DOWN) != 0;
        assert_int_equal(scaled, a.charts[c].mesh == 0);
        if (scaled) assert_true(a.charts[c].area_texels < 0.25 * 32.0 * 32.0 * a.charts[c].area_3d);
    }
    scene_atlas_free(&a);
    raps_settings_destroy(s);
    test_mesh_free(&big);
    test_mesh_free(&small);
}

static void one_meshs_charts_share_a_page_when_asked(void** state) {
    (void)state;
    three_meshes t;
    make_three_meshes(&t);
    raps_settings* s = density_settings(0, 2, 40.0, 176, 100);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_MESH_PER_PAGE, 1), RAPS_OK);
    scene_atlas a = run_scene(&t.sc, s);
    check_ranges(&t.sc, &a);
    check_pages(&a, 40.0, 176, 100);
    assert_int_equal(a.stats.scaled_down_charts, 0); /* each mesh fits a page */
    check_gaps(&a, 2, 1);
    int64_t page_of_mesh[3] = {-1, -1, -1};
    for (size_t c = 0; c < a.chart_count; ++c) {
        const uint32_t m = a.charts[c].mesh;
        if (page_of_mesh[m] < 0) page_of_mesh[m] = a.charts[c].page;
        assert_int_equal(a.charts[c].page, page_of_mesh[m]);
    }
    assert_true(a.stats.page_count >= 2); /* the three together do not fit one page */
    scene_atlas_free(&a);
    raps_settings_destroy(s);
    free_three_meshes(&t);
}

/* One mesh handle twice: the two copies' charts are the same maps, so each chart of the second
 * copy is the first's turned by a multiple of 90 degrees (its record's rotation less the
 * first's) and moved by a whole number of texels (of 4 texels with block alignment): charts
 * sit on whole texels. With RAPS_ROTATION_NONE nothing is turned, with QUARTER only by quarter
 * turns. */
static void check_whole_texel_copies(const scene_atlas* a, int step, int rotation) {
    const double w = (double)a->stats.atlas_width, h = (double)a->stats.atlas_height;
    const uint64_t* r0 = a->range[0];
    const uint64_t* r1 = a->range[1];
    assert_int_equal(r0[1], r1[1]);
    for (size_t c = 0; c < a->chart_count; ++c) {
        const double turn = a->charts[c].rotation_deg;
        if (rotation == RAPS_ROTATION_NONE) assert_true(turn == 0.0);
        if (rotation != RAPS_ROTATION_ANY) assert_true(fmod(turn, 90.0) == 0.0);
    }
    for (size_t i = 0; i < r0[3]; ++i) {
        const uint32_t v0 = (uint32_t)r0[0] + a->indices[r0[2] + i];
        const uint32_t v1 = (uint32_t)r1[0] + a->indices[r1[2] + i];
        const raps_chart* c0 = &a->charts[a->chart[(r0[2] + i) / 3]];
        const raps_chart* c1 = &a->charts[a->chart[(r1[2] + i) / 3]];
        if (c0->page != c1->page && rotation == RAPS_ROTATION_ANY) continue;
        const int quarters = (int)lround((c1->rotation_deg - c0->rotation_deg) / 90.0);
        if (rotation == RAPS_ROTATION_ANY &&
            fabs(quarters * 90.0 - (c1->rotation_deg - c0->rotation_deg)) > 1e-6)
            fail_msg("copies of a chart turned by %g and %g degrees", c0->rotation_deg,
                     c1->rotation_deg);
        /* p1 = R p0 + t: t must be whole texels (whole blocks). */
        const double x0 = a->uv[2 * v0] * w, y0 = a->uv[2 * v0 + 1] * h;
        double rx = x0, ry = y0;
        for (int k = 0; k < ((quarters % 4) + 4) % 4; ++k) {
            const double nx = -ry;
            ry = rx;
            rx = nx;
        }
        const double tx = a->uv[2 * v1] * w - rx, ty = a->uv[2 * v1 + 1] * h - ry;
        if (fabs(tx / step - round(tx / step)) > 1e-6 || fabs(ty / step - round(ty / step)) > 1e-6)
            fail_msg("corner %zu: the copy moved by (%.9f, %.9f) texels, not whole %s", i, tx, ty,
                     step == 1 ? "texels" : "blocks");
    }
}

static void charts_sit_on_whole_texels_under_each_rotation_policy(void** state) {
    (void)state;
    test_mesh cone = make_open_cone(8, 24, 1.0);
    scene sc = two_copies(&cone);
    const int policies[3] = {RAPS_ROTATION_ANY, RAPS_ROTATION_QUARTER, RAPS_ROTATION_NONE};
    for (int p = 0; p < 3; ++p) {
        /* Pages too small for both copies: charts go into holes and onto a second page. */
        raps_settings* s = density_settings(0, 2, 100.0, 256, 256);
        assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_ROTATION, policies[p]), RAPS_OK);
        scene_atlas a = run_scene(&sc, s);
        check_pages(&a, 100.0, 256, 256);
        check_gaps(&a, 2, 1);
        check_whole_texel_copies(&a, 1, policies[p]);
        scene_atlas_free(&a);
        raps_settings_destroy(s);
    }
    test_mesh_free(&cone);
}

/* Block alignment: copies moved by whole 4x4 blocks and no block holds texels of two charts;
 * the margin is kept free at every page border. */
static void blocks_and_margins(void** state) {
    (void)state;
    test_mesh cone = make_open_cone(8, 24, 1.0);
    scene sc = two_copies(&cone);
    raps_settings* s = density_settings(0, 1, 60.0, 200, 200);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_BLOCK_ALIGN, 1), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_MARGIN, 5), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_ROTATION, RAPS_ROTATION_QUARTER),
                     RAPS_OK);
    scene_atlas a = run_scene(&sc, s);
    check_pages(&a, 60.0, 200, 200);
    check_gaps(&a, 1, 1);
    check_whole_texel_copies(&a, 4, RAPS_ROTATION_QUARTER);
    assert_int_equal(a.stats.atlas_width % 4, 0);
    assert_int_equal(a.stats.atlas_height % 4, 0);
    /* Margins of 5 texels, rounded up to 8 (two blocks), on every side. */
    for (size_t c = 0; c < a.chart_count; ++c) {
        const raps_chart* chart = &a.charts[c];
        assert_true(chart->x >= 8 && chart->y >= 8);
        assert_true(chart->x + chart->width + 8 <= a.stats.atlas_width);
        assert_true(chart->y + chart->height + 8 <= a.stats.atlas_height);
    }
    /* Blocks: at least one free block (the padding of 1 texel rounded up) between any two
     * charts' blocks, so no block holds texels of two. */
    check_gaps(&a, 1, 4);
    scene_atlas_free(&a);
    raps_settings_destroy(s);
    test_mesh_free(&cone);
}

/* Whole texels at a resolution: one page, the square of the resolution, at the largest density
 * that fits, the padding exact at its texels, copies moved by whole texels. */
static void whole_texels_at_a_resolution_fill_one_page(void** state) {
    (void)state;
    three_meshes t;
    make_three_meshes(&t);
    t.sc.meshes[2] = &t.cone; /* a second cone, moved: the copies check below */
    set_scale_move(t.sc.transforms[2], 1.0, 4.0, 0.0, 0.0);
    t.sc.meshes[1] = &t.cone;
    set_identity(t.sc.transforms[1]);
    raps_settings* s = atlas_settings(0, 2);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_RESOLUTION, 256), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_WHOLE_TEXELS, 1), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_ROTATION, RAPS_ROTATION_NONE),
                     RAPS_OK);
    scene_atlas a = run_scene(&t.sc, s);
    print_message("%llu charts on %llux%llu at %.2f texels per unit, utilization %.3f\n",
                  (unsigned long long)a.stats.chart_count, (unsigned long long)a.stats.atlas_width,
                  (unsigned long long)a.stats.atlas_height, a.stats.texels_per_unit,
                  a.stats.utilization);
    assert_int_equal(a.stats.page_count, 1);
    assert_int_equal(a.stats.scaled_down_charts, 0);
    assert_int_equal(a.stats.atlas_width, 256);
    assert_int_equal(a.stats.atlas_height, 256);
    check_pages(&a, a.stats.texels_per_unit, 256, 256);
    check_gaps(&a, 2, 1);
    check_whole_texel_copies(&a, 1, RAPS_ROTATION_NONE);
    /* The largest density that fits, give or take the search's 1%: the page is mostly used. */
    assert_true(a.stats.utilization > 0.4);
    scene_atlas_free(&a);
    raps_settings_destroy(s);
    free_three_meshes(&t);
}

/* At the density whole texels find for a page of a resolution, the same page as a maximum holds
 * every chart: the density path tries one page the way the whole-texel search does before it
 * places charts first-fit, which could spill onto a second page. Over several resolutions, so
 * that some density is one only the later orders fit. */
static void a_density_one_page_holds_takes_one_page(void** state) {
    (void)state;
    three_meshes t;
    make_three_meshes(&t);
    for (int64_t resolution = 96; resolution <= 256; resolution += 16) {
        raps_settings* s = atlas_settings(0, 2);
        assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_RESOLUTION, resolution),
                         RAPS_OK);
        assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_WHOLE_TEXELS, 1), RAPS_OK);
        scene_atlas whole = run_scene(&t.sc, s);
        assert_int_equal(whole.stats.page_count, 1);
        raps_settings* d =
            density_settings(0, 2, whole.stats.texels_per_unit, resolution, resolution);
        scene_atlas a = run_scene(&t.sc, d);
        if (a.stats.page_count != 1)
            fail_msg(
                "resolution %lld: %.6g texels per unit fit one page as whole texels, but "
                "took %llu pages",
                (long long)resolution, whole.stats.texels_per_unit,
                (unsigned long long)a.stats.page_count);
        check_pages(&a, whole.stats.texels_per_unit, resolution, resolution);
        check_gaps(&a, 2, 1);
        scene_atlas_free(&a);
        scene_atlas_free(&whole);
        raps_settings_destroy(d);
        raps_settings_destroy(s);
    }
    free_three_meshes(&t);
}

/* Runs a scene of `count` handles and checks the status and that the message names `what`. */
static void expect_refused(const raps_mesh* const* meshes, size_t count,
                           const raps_settings* settings, raps_status status, const char* what) {
    raps_result* r = NULL;
    assert_int_equal(raps_result_create(&r), RAPS_OK);
    const raps_status got = raps_parameterize_scene(meshes, count, settings, r);
    if (got != status || !strstr(raps_result_last_error(r), what)) {
        fail_msg("expected status %d naming \"%s\", got %d: %s", status, what, got,
                 raps_result_last_error(r));
    }
    assert_int_equal(raps_result_vertex_count(r), 0);
    assert_int_equal(raps_result_mesh_count(r), 0);
    raps_result_destroy(r);
}

static void bad_scenes_are_refused_with_their_status(void** state) {
    (void)state;
    test_mesh grid = make_grid(2, 2, 1.0, 1.0);
    raps_mesh* good = to_raps_mesh(&grid);
    raps_mesh* empty = NULL;
    assert_int_equal(raps_mesh_create(&empty), RAPS_OK);
    raps_settings* atlas = atlas_settings(1, 1);
    raps_settings* disk = NULL;
    assert_int_equal(raps_settings_create(&disk), RAPS_OK);

    const raps_mesh* pair[2] = {good, NULL};
    expect_refused(pair, 0, atlas, RAPS_ERROR_EMPTY_MESH, "mesh_count 0");
    expect_refused(NULL, 2, atlas, RAPS_ERROR_INVALID_ARGUMENT, "meshes is NULL");
    expect_refused(pair, 2, atlas, RAPS_ERROR_INVALID_ARGUMENT, "meshes[1] is NULL");
    pair[1] = good;
    expect_refused(pair, 2, disk, RAPS_ERROR_INVALID_ARGUMENT, "RAPS_DOMAIN_ATLAS");
    expect_refused(pair, 2, NULL, RAPS_ERROR_INVALID_ARGUMENT, "settings is NULL");
    pair[1] = empty;
    expect_refused(pair, 2, atlas, RAPS_ERROR_EMPTY_MESH, "mesh 1 has no vertices");

    /* An index beyond its own mesh's vertices (which the scene's other vertices would not
     * excuse). */
    raps_mesh* beyond = to_raps_mesh(&grid);
    uint32_t indices[6] = {0, 1, 2, 2, 1, 9};
    assert_int_equal(raps_mesh_set_indices_u32(beyond, indices, 6), RAPS_OK);
    pair[1] = beyond;
    expect_refused(pair, 2, atlas, RAPS_ERROR_INDEX_OUT_OF_RANGE, "mesh 1: index 5");

    /* Transforms: non-finite and singular ones are refused by the setter (the mesh keeps its
     * transform); one that carries a vertex beyond 1e30 by the run. */
    double m[12];
    set_identity(m);
    m[7] = NAN;
    assert_int_equal(raps_mesh_set_transform(good, m), RAPS_ERROR_INVALID_TRANSFORM);
    assert_non_null(strstr(raps_mesh_last_error(good), "m[7]"));
    set_identity(m);
    m[0] = INFINITY;
    assert_int_equal(raps_mesh_set_transform(good, m), RAPS_ERROR_INVALID_TRANSFORM);
    set_identity(m);
    m[10] = 0.0; /* flattens z: singular */
    assert_int_equal(raps_mesh_set_transform(good, m), RAPS_ERROR_INVALID_TRANSFORM);
    assert_non_null(strstr(raps_mesh_last_error(good), "singular"));
    set_identity(m);
    m[4] = 1.0; /* the second row equals the first */
    m[5] = 0.0;
    assert_int_equal(raps_mesh_set_transform(good, m), RAPS_ERROR_INVALID_TRANSFORM);
    assert_int_equal(raps_mesh_set_transform(NULL, m), RAPS_ERROR_INVALID_ARGUMENT);
    set_scale_move(m, 1e31, 0, 0, 0);
    assert_int_equal(raps_mesh_set_transform(beyond, m), RAPS_OK);
    assert_int_equal(raps_mesh_set_indices_u32(beyond, grid.indices, grid.index_count), RAPS_OK);
    pair[1] = beyond;
    expect_refused(pair, 2, atlas, RAPS_ERROR_NON_FINITE_POSITION, "mesh 1: vertex");
    /* A scale of 1e120 is not singular (its determinant, 1e360, overflowed doubles and read as
     * one): the setter takes it, the run refuses the vertices it carries past 1e30. */
    set_scale_move(m, 1e120, 0, 0, 0);
    assert_int_equal(raps_mesh_set_transform(beyond, m), RAPS_OK);
    expect_refused(pair, 2, atlas, RAPS_ERROR_NON_FINITE_POSITION, "mesh 1: vertex");
    assert_int_equal(raps_mesh_set_transform(beyond, NULL), RAPS_OK); /* back to identity */

    /* Pages: a density of NaN or below 0, an unknown rotation policy, block alignment other
     * than 0 or 1 are refused by the setters; a page with no room inside its margin by the run. */
    assert_int_equal(raps_settings_set_float(atlas, RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, NAN),
                     RAPS_ERROR_INVALID_ARGUMENT);
    assert_int_equal(raps_settings_set_float(atlas, RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, -1.0),
                     RAPS_ERROR_INVALID_ARGUMENT);
    assert_int_equal(raps_settings_set_int(atlas, RAPS_PARAM_ATLAS_ROTATION, 3),
                     RAPS_ERROR_INVALID_ARGUMENT);
    assert_int_equal(raps_settings_set_int(atlas, RAPS_PARAM_ATLAS_BLOCK_ALIGN, 2),
                     RAPS_ERROR_INVALID_ARGUMENT);
    assert_int_equal(raps_settings_set_int(atlas, RAPS_PARAM_ATLAS_MAX_WIDTH, 15),
                     RAPS_ERROR_INVALID_ARGUMENT);
    raps_settings* cramped = density_settings(1, 4, 10.0, 16, 64);
    assert_int_equal(raps_settings_set_int(cramped, RAPS_PARAM_ATLAS_MARGIN, 6), RAPS_OK);
    pair[1] = good;
    expect_refused(pair, 2, cramped, RAPS_ERROR_INVALID_ARGUMENT, "inside its margin");
    raps_settings_destroy(cramped);
    cramped = atlas_settings(1, 20);
    assert_int_equal(raps_settings_set_int(cramped, RAPS_PARAM_ATLAS_RESOLUTION, 16), RAPS_OK);
    assert_int_equal(raps_settings_set_int(cramped, RAPS_PARAM_ATLAS_WHOLE_TEXELS, 1), RAPS_OK);
    expect_refused(pair, 2, cramped, RAPS_ERROR_INVALID_ARGUMENT, "inside its margin");
    raps_settings_destroy(cramped);
    /* At a resolution, a padding that leaves no texel for a chart (it overran the packer's
     * buffers): one mesh or a scene, refused by the run. 2 x 6 + 3 <= 16 still packs. */
    const int64_t paddings[] = {6, 7, 8, 64};
    for (size_t k = 0; k < sizeof(paddings) / sizeof(paddings[0]); ++k) {
        const int64_t padding = paddings[k];
        cramped = atlas_settings(1, padding);
        assert_int_equal(raps_settings_set_int(cramped, RAPS_PARAM_ATLAS_RESOLUTION, 16), RAPS_OK);
        raps_result* one = NULL;
        assert_int_equal(raps_result_create(&one), RAPS_OK);
        const raps_status status = raps_parameterize(good, cramped, one);
        if (padding == 6) {
            assert_int_equal(status, RAPS_OK);
        } else {
            assert_int_equal(status, RAPS_ERROR_INVALID_ARGUMENT);
            assert_non_null(strstr(raps_result_last_error(one), "leaves no texel for the chart"));
            expect_refused(pair, 2, cramped, RAPS_ERROR_INVALID_ARGUMENT, "leaves no texel");
        }
        raps_result_destroy(one);
        raps_settings_destroy(cramped);
    }
    /* Within that bound but too many charts for it: two meshes, each chart with 5 texels of
     * padding on every side, cannot share 16 x 16 texels at any density (the search once ended
     * at a negative density and overran the rasters). */
    cramped = atlas_settings(1, 5);
    assert_int_equal(raps_settings_set_int(cramped, RAPS_PARAM_ATLAS_RESOLUTION, 16), RAPS_OK);
    pair[1] = good;
    expect_refused(pair, 2, cramped, RAPS_ERROR_INVALID_ARGUMENT,
                   "do not fit an atlas of 16 x 16 texels at any density");
    raps_settings_destroy(cramped);
    /* A mesh far below a texel at the density asked for (a scene in the wrong units): refused
     * naming the density and the chart's size, not blamed on double precision. */
    test_mesh fine = make_grid(20, 20, 1.0, 1.0);
    raps_mesh* speck = to_raps_mesh(&fine);
    double tiny[12];
    set_scale_move(tiny, 1e-8, 0.0, 0.0, 0.0);
    assert_int_equal(raps_mesh_set_transform(speck, tiny), RAPS_OK);
    pair[1] = speck;
    raps_settings* at_density = density_settings(1, 1, 64.0, 256, 256);
    expect_refused(pair + 1, 1, at_density, RAPS_ERROR_ZERO_AREA_TRIANGLE,
                   "at 64 texels per unit the largest chart is");
    raps_settings_destroy(at_density);
    raps_mesh_destroy(speck);
    test_mesh_free(&fine);
    /* A curved mesh at 1e-83: its triangles' squared areas underflow, so every one looks
     * degenerate; refused, where it once came out as one point chart with exit status 0. */
    test_mesh ball = make_uv_sphere(8, 16);
    raps_mesh* dust = to_raps_mesh(&ball);
    set_scale_move(tiny, 1e-83, 0.0, 0.0, 0.0);
    assert_int_equal(raps_mesh_set_transform(dust, tiny), RAPS_OK);
    pair[1] = dust;
    expect_refused(pair + 1, 1, atlas, RAPS_ERROR_ZERO_AREA_TRIANGLE, "below what doubles resolve");
    raps_mesh_destroy(dust);
    test_mesh_free(&ball);
    pair[1] = good;

    /* Reading: a mesh range or chart beyond the result's, a chart of a disk map. */
    raps_result* r = NULL;
    assert_int_equal(raps_result_create(&r), RAPS_OK);
    assert_int_equal(raps_parameterize_scene(pair, 2, atlas, r), RAPS_OK);
    uint64_t first = 0;
    assert_int_equal(raps_result_mesh_range(r, 2, &first, NULL, NULL, NULL),
                     RAPS_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(raps_result_last_error(r), "mesh 2 is out of range"));
    raps_chart chart;
    chart.struct_size = sizeof(chart);
    assert_int_equal(raps_result_get_chart(r, 1000, &chart), RAPS_ERROR_INVALID_ARGUMENT);
    chart.struct_size = 4;
    assert_int_equal(raps_result_get_chart(r, 0, &chart), RAPS_ERROR_INVALID_ARGUMENT);
    assert_int_equal(raps_parameterize(good, disk, r), RAPS_OK);
    chart.struct_size = sizeof(chart);
    assert_int_equal(raps_result_get_chart(r, 0, &chart), RAPS_ERROR_INVALID_OPERATION);
    assert_int_equal(raps_result_mesh_count(r), 1);
    raps_result_destroy(r);

    raps_settings_destroy(atlas);
    raps_settings_destroy(disk);
    raps_mesh_destroy(good);
    raps_mesh_destroy(beyond);
    raps_mesh_destroy(empty);
    test_mesh_free(&grid);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(several_meshes_share_one_atlas_without_overlap),
        cmocka_unit_test(a_scaled_mesh_gets_texels_in_proportion),
        cmocka_unit_test(a_long_mesh_among_compact_ones_is_cut_across),
        cmocka_unit_test(a_chart_a_little_too_long_is_cut_where_that_packs_denser),
        cmocka_unit_test(scene_output_is_identical_for_any_thread_count),
        cmocka_unit_test(ten_shared_meshes_cover_072_of_a_2048_square),
        cmocka_unit_test(a_one_mesh_atlas_has_records_and_fits_its_resolution),
        cmocka_unit_test(bad_scenes_are_refused_with_their_status),
        cmocka_unit_test(a_density_fills_pages_never_larger_than_the_maximum),
        cmocka_unit_test(a_chart_larger_than_a_page_is_shrunk_and_reported),
        cmocka_unit_test(one_meshs_charts_share_a_page_when_asked),
        cmocka_unit_test(charts_sit_on_whole_texels_under_each_rotation_policy),
        cmocka_unit_test(blocks_and_margins),
        cmocka_unit_test(whole_texels_at_a_resolution_fill_one_page),
        cmocka_unit_test(a_density_one_page_holds_takes_one_page),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
