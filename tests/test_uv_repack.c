/* Repacking existing uvs through the C ABI (raps_mesh_set_corner_uvs_*, RAPS_PARAM_ATLAS_REPACK):
 * the charts are the input's uv islands, each chart's uvs come out only moved, turned (as the
 * rotation policy allows) and uniformly scaled, every chart at one texel density per 3D area,
 * flipped input charts stay flipped, islands overlapping in the input are packed apart, the
 * output does not depend on the thread count, and every bad input is refused with its own
 * status and a message. The real mesh's uvs come from a first raps atlas run, whose charts the
 * repacking must find again. */
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

#define PI 3.14159265358979323846

typedef struct atlas {
    size_t vertex_count, triangle_count, chart_count;
    double* texel; /* per output vertex: u * width, v * height */
    uint32_t* indices;
    uint32_t* chart;
    raps_chart* charts;
    raps_stats stats;
} atlas;

static void atlas_free(atlas* a) {
    free(a->texel);
    free(a->indices);
    free(a->chart);
    free(a->charts);
}

static raps_settings* repack_settings(int64_t threads, int64_t rotation) {
    raps_settings* s = NULL;
    assert_int_equal(raps_settings_create(&s), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_THREADS, threads), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_ROTATION, rotation), RAPS_OK);
    assert_int_equal(raps_settings_set_int(s, RAPS_PARAM_ATLAS_REPACK, 1), RAPS_OK);
    return s;
}

static atlas read_atlas(raps_result* r) {
    atlas a;
    memset(&a, 0, sizeof(a));
    a.vertex_count = raps_result_vertex_count(r);
    a.triangle_count = raps_result_index_count(r) / 3;
    a.stats = stats_of(r);
    a.chart_count = (size_t)a.stats.chart_count;
    a.texel = malloc(2 * a.vertex_count * sizeof(double) + 1);
    a.indices = malloc(3 * a.triangle_count * sizeof(uint32_t) + 1);
    a.chart = malloc(a.triangle_count * sizeof(uint32_t) + 1);
    a.charts = calloc(a.chart_count + 1, sizeof(raps_chart));
    assert_int_equal(raps_result_copy_uvs_f64(r, a.texel, a.vertex_count, 0), RAPS_OK);
    assert_int_equal(raps_result_copy_indices_u32(r, a.indices, 3 * a.triangle_count), RAPS_OK);
    assert_int_equal(raps_result_copy_chart_ids(r, a.chart, a.triangle_count), RAPS_OK);
    for (size_t v = 0; v < a.vertex_count; ++v) {
        a.texel[2 * v] *= (double)a.stats.atlas_width;
        a.texel[2 * v + 1] *= (double)a.stats.atlas_height;
    }
    for (size_t c = 0; c < a.chart_count; ++c) {
        a.charts[c].struct_size = sizeof(raps_chart);
        assert_int_equal(raps_result_get_chart(r, c, &a.charts[c]), RAPS_OK);
    }
    return a;
}

static atlas repack(const raps_mesh* mesh, const raps_settings* settings) {
    raps_result* r = parameterize_ok(mesh, settings);
    atlas a = read_atlas(r);
    raps_result_destroy(r);
    return a;
}

/* The similarity that takes chart c's input uvs to its output texels: out = z * in + t (complex
 * numbers: z turns and scales uniformly, and cannot mirror). Fails unless every corner of the
 * chart lies where z and t put it. Returns the turn in degrees, [0, 360), and |z|. */
static void check_similarity(const atlas* a, const double* corner_uv, uint32_t c, double* turn_deg,
                             double* scale) {
    size_t first = a->triangle_count;
    for (size_t t = 0; t < a->triangle_count && first == a->triangle_count; ++t)
        if (a->chart[t] == c) first = t;
    assert_true(first < a->triangle_count);
    /* Reference: corner 0 of the first triangle and whichever corner lies farthest from it. */
    const double* in_a = &corner_uv[6 * first];
    const double* out_a = &a->texel[2 * a->indices[3 * first]];
    double best = -1, zr = 0, zi = 0;
    for (size_t t = 0; t < a->triangle_count; ++t) {
        if (a->chart[t] != c) continue;
        for (int k = 0; k < 3; ++k) {
            const double* in_p = &corner_uv[6 * t + 2 * k];
            const double* out_p = &a->texel[2 * a->indices[3 * t + k]];
            const double dx = in_p[0] - in_a[0], dy = in_p[1] - in_a[1];
            const double d2 = dx * dx + dy * dy;
            if (d2 <= best) continue;
            best = d2;
            const double ox = out_p[0] - out_a[0], oy = out_p[1] - out_a[1];
            zr = (ox * dx + oy * dy) / d2; /* (o / d) as complex numbers */
            zi = (oy * dx - ox * dy) / d2;
        }
    }
    assert_true(best > 0);
    const double magnitude = sqrt(zr * zr + zi * zi);
    const double extent = magnitude * sqrt(best);
    for (size_t t = 0; t < a->triangle_count; ++t) {
        if (a->chart[t] != c) continue;
        for (int k = 0; k < 3; ++k) {
            const double dx = corner_uv[6 * t + 2 * k] - in_a[0];
            const double dy = corner_uv[6 * t + 2 * k + 1] - in_a[1];
            const double* out_p = &a->texel[2 * a->indices[3 * t + k]];
            assert_near(out_p[0], out_a[0] + zr * dx - zi * dy, 1e-7 * extent + 1e-9);
            assert_near(out_p[1], out_a[1] + zi * dx + zr * dy, 1e-7 * extent + 1e-9);
        }
    }
    double degrees = atan2(zi, zr) * 180.0 / PI;
    if (degrees < 0) degrees += 360.0;
    *turn_deg = degrees;
    *scale = magnitude;
}

/* The turn between two angles in degrees, folded into [0, 180]. */
static double angle_gap(double a, double b) {
    double d = fmod(fabs(a - b), 360.0);
    return d > 180.0 ? 360.0 - d : d;
}

/* The test grid's corner uvs: three islands by the triangle's centroid x (the grid is 3 x 1):
 * left as it lies, middle turned 30 degrees and halved, right mirrored (clockwise) and doubled,
 * each moved apart; islands meet in 3D but not in uv. */
static double* three_island_uvs(const test_mesh* grid) {
    const size_t triangles = grid->index_count / 3;
    double* uv = malloc(6 * triangles * sizeof(double));
    for (size_t t = 0; t < triangles; ++t) {
        double cx = 0;
        for (int k = 0; k < 3; ++k) cx += grid->positions[3 * grid->indices[3 * t + k]] / 3.0;
        const int island = cx < 1.0 ? 0 : cx < 2.0 ? 1 : 2;
        for (int k = 0; k < 3; ++k) {
            const double x = grid->positions[3 * grid->indices[3 * t + k]];
            const double y = grid->positions[3 * grid->indices[3 * t + k] + 1];
            double u = x, v = y;
            if (island == 1) {
                const double c = cos(PI / 6), s = sin(PI / 6);
                u = 0.5 * (c * x - s * y) + 4.0;
                v = 0.5 * (s * x + c * y);
            } else if (island == 2) {
                u = -2.0 * x + 20.0;
                v = 2.0 * y + 7.0;
            }
            uv[6 * t + 2 * k] = u;
            uv[6 * t + 2 * k + 1] = v;
        }
    }
    return uv;
}

static raps_mesh* mesh_with_uvs(const test_mesh* m, const double* uv) {
    raps_mesh* mesh = to_raps_mesh(m);
    assert_status(raps_mesh_set_corner_uvs_f64(mesh, uv, m->index_count, 0), RAPS_OK);
    return mesh;
}

/* Three islands of a grid come back as three charts, each only moved, turned as the policy
 * allows and scaled, at one density per 3D area; the mirrored island stays mirrored. */
static void test_islands_keep_their_shape_under_each_rotation_policy(void** state) {
    (void)state;
    test_mesh grid = make_grid(12, 4, 3.0, 1.0);
    double* uv = three_island_uvs(&grid);
    raps_mesh* mesh = mesh_with_uvs(&grid, uv);
    const int64_t policies[3] = {RAPS_ROTATION_ANY, RAPS_ROTATION_QUARTER, RAPS_ROTATION_NONE};
    for (int p = 0; p < 3; ++p) {
        raps_settings* settings = repack_settings(1, policies[p]);
        atlas a = repack(mesh, settings);
        assert_int_equal(a.chart_count, 3);
        assert_int_equal(a.stats.adaptive_solves, 0);
        /* The right island's 32 triangles are clockwise in the input and stay so. */
        assert_int_equal(a.stats.flipped_triangles, 32);
        const double density = a.charts[0].area_texels / a.charts[0].area_3d;
        for (uint32_t c = 0; c < 3; ++c) {
            double turn, scale;
            check_similarity(&a, uv, c, &turn, &scale);
            assert_near(a.charts[c].area_3d, 1.0, 1e-12);
            assert_near(a.charts[c].area_texels / a.charts[c].area_3d, density, 1e-9 * density);
            /* texels per input uv unit: the density's root over the island's own uv scale */
            const double island_scale = c == 0 ? 1.0 : c == 1 ? 0.5 : 2.0;
            assert_near(scale * island_scale, sqrt(density), 1e-9 * sqrt(density));
            assert_true(angle_gap(turn, a.charts[c].rotation_deg) < 1e-6);
            if (policies[p] == RAPS_ROTATION_NONE) assert_true(angle_gap(turn, 0.0) < 1e-6);
            if (policies[p] == RAPS_ROTATION_QUARTER)
                assert_true(angle_gap(turn, 90.0 * round(turn / 90.0)) < 1e-6);
        }
        atlas_free(&a);
        raps_settings_destroy(settings);
    }
    raps_mesh_destroy(mesh);
    free(uv);
    test_mesh_free(&grid);
}

/* Islands laid over one another in the input (each third of the grid on the same uv square)
 * are separate charts, packed apart: their texel rectangles do not meet. */
static void test_overlapping_islands_are_packed_apart(void** state) {
    (void)state;
    test_mesh grid = make_grid(12, 4, 3.0, 1.0);
    const size_t triangles = grid.index_count / 3;
    double* uv = malloc(6 * triangles * sizeof(double));
    for (size_t t = 0; t < triangles; ++t) {
        double cx = 0;
        for (int k = 0; k < 3; ++k) cx += grid.positions[3 * grid.indices[3 * t + k]] / 3.0;
        for (int k = 0; k < 3; ++k) {
            uv[6 * t + 2 * k] = grid.positions[3 * grid.indices[3 * t + k]] - floor(cx);
            uv[6 * t + 2 * k + 1] = grid.positions[3 * grid.indices[3 * t + k] + 1];
        }
    }
    raps_mesh* mesh = mesh_with_uvs(&grid, uv);
    raps_settings* settings = repack_settings(1, RAPS_ROTATION_ANY);
    atlas a = repack(mesh, settings);
    assert_int_equal(a.chart_count, 3);
    for (uint32_t c = 0; c < 3; ++c) {
        double turn, scale;
        check_similarity(&a, uv, c, &turn, &scale);
        for (uint32_t d = 0; d < c; ++d) {
            const raps_chart *p = &a.charts[c], *q = &a.charts[d];
            assert_true(p->x + p->width <= q->x || q->x + q->width <= p->x ||
                        p->y + p->height <= q->y || q->y + q->height <= p->y);
        }
    }
    atlas_free(&a);
    raps_settings_destroy(settings);
    raps_mesh_destroy(mesh);
    free(uv);
    test_mesh_free(&grid);
}

/* Triangles whose uvs touch at a corner only, or whose shared edge's uvs differ at one end, are
 * separate charts; welded positions (a vertex split for normals) still join an island. */
static void test_charts_follow_uv_edges_only(void** state) {
    (void)state;
    /* Two triangles sharing edge 1-2 in 3D; vertex 2 is split (4 is its copy). */
    const double xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 1, 0};
    const uint32_t split[] = {0, 1, 2, 1, 4, 3};
    const uint32_t shared[] = {0, 1, 2, 2, 3, 1};
    raps_mesh* mesh = NULL;
    assert_int_equal(raps_mesh_create(&mesh), RAPS_OK);
    assert_int_equal(raps_mesh_set_positions_f64(mesh, xyz, 5, 0), RAPS_OK);
    raps_settings* settings = repack_settings(1, RAPS_ROTATION_ANY);
    /* Edge 1-2 with equal uvs on both sides: one chart, also across the split vertex. */
    const double joined[] = {0, 0, 1, 0, 1, 1, 1, 0, 1, 1, 0, 1};
    for (int layout = 0; layout < 2; ++layout) {
        const uint32_t* indices = layout ? shared : split;
        assert_int_equal(raps_mesh_set_indices_u32(mesh, indices, 6), RAPS_OK);
        const double* uv = joined;
        double reordered[12];
        if (layout) { /* shared: triangle 1 is 2, 3, 1 */
            const double r[] = {0, 0, 1, 0, 1, 1, 1, 1, 0, 1, 1, 0};
            memcpy(reordered, r, sizeof(r));
            uv = reordered;
        }
        assert_status(raps_mesh_set_corner_uvs_f64(mesh, uv, 6, 0), RAPS_OK);
        atlas a = repack(mesh, settings);
        assert_int_equal(a.chart_count, 1);
        atlas_free(&a);
    }
    /* The same edge with the uv of one end moved: two charts. */
    double apart[12];
    memcpy(apart, joined, sizeof(apart));
    apart[8] = 1.5; /* triangle 1's corner at vertex 4 (3D vertex 2) */
    assert_int_equal(raps_mesh_set_indices_u32(mesh, split, 6), RAPS_OK);
    assert_status(raps_mesh_set_corner_uvs_f64(mesh, apart, 6, 0), RAPS_OK);
    atlas a = repack(mesh, settings);
    assert_int_equal(a.chart_count, 2);
    assert_int_not_equal(a.chart[0], a.chart[1]);
    atlas_free(&a);
    raps_settings_destroy(settings);
    raps_mesh_destroy(mesh);
}

/* A uv island without 3D area gets no texels but does not stop the run: its uvs are one point. */
static void test_an_island_without_surface_becomes_a_point(void** state) {
    (void)state;
    test_mesh grid = make_grid(3, 1, 3.0, 1.0);
    test_mesh_builder b;
    memset(&b, 0, sizeof(b));
    b.mesh = grid;
    b.vertex_capacity = grid.vertex_count;
    b.index_capacity = grid.index_count;
    const size_t p = test_mesh_add_vertex(&b, 5, 0, 0), q = test_mesh_add_vertex(&b, 6, 0, 0),
                 r = test_mesh_add_vertex(&b, 7, 0, 0);
    test_mesh_add_triangle(&b, p, q, r); /* collinear: no area */
    grid = b.mesh;
    const size_t triangles = grid.index_count / 3;
    double* uv = malloc(6 * triangles * sizeof(double));
    for (size_t t = 0; t < triangles; ++t) {
        for (int k = 0; k < 3; ++k) {
            uv[6 * t + 2 * k] = grid.positions[3 * grid.indices[3 * t + k]];
            uv[6 * t + 2 * k + 1] = grid.positions[3 * grid.indices[3 * t + k] + 1];
        }
    }
    uv[6 * (triangles - 1) + 3] = 1.0; /* its own uv triangle, with area */
    raps_mesh* mesh = mesh_with_uvs(&grid, uv);
    raps_settings* settings = repack_settings(1, RAPS_ROTATION_ANY);
    atlas a = repack(mesh, settings);
    const uint32_t* last = &a.indices[3 * (triangles - 1)];
    for (int k = 1; k < 3; ++k) {
        assert_near(a.texel[2 * last[k]], a.texel[2 * last[0]], 0.0);
        assert_near(a.texel[2 * last[k] + 1], a.texel[2 * last[0] + 1], 0.0);
    }
    double turn, scale;
    check_similarity(&a, uv, a.chart[0], &turn, &scale);
    atlas_free(&a);
    raps_settings_destroy(settings);
    raps_mesh_destroy(mesh);
    free(uv);
    test_mesh_free(&grid);
}

/* The number of charts of a repacked grid whose uvs are its positions (one island), and that
 * no chart holds triangles of both sides of x = 1 when `split` says the sides must part. */
static size_t repacked_grid_charts(raps_mesh* mesh, const test_mesh* grid, const double* uv,
                                   int split) {
    raps_settings* settings = repack_settings(1, RAPS_ROTATION_ANY);
    atlas a = repack(mesh, settings);
    const size_t triangles = grid->index_count / 3;
    int* side_of_chart = malloc(a.chart_count * sizeof(int));
    for (size_t c = 0; c < a.chart_count; ++c) side_of_chart[c] = -1;
    for (size_t t = 0; t < triangles; ++t) {
        double cx = 0;
        for (int k = 0; k < 3; ++k) cx += grid->positions[3 * grid->indices[3 * t + k]] / 3.0;
        const int side = cx < 1.0;
        if (side_of_chart[a.chart[t]] < 0) side_of_chart[a.chart[t]] = side;
        if (split) assert_int_equal(side_of_chart[a.chart[t]], side);
    }
    for (uint32_t c = 0; c < a.chart_count; ++c) {
        double turn, scale;
        check_similarity(&a, uv, c, &turn, &scale); /* each part keeps its shape */
    }
    const size_t charts = a.chart_count;
    free(side_of_chart);
    atlas_free(&a);
    raps_settings_destroy(settings);
    return charts;
}

/* Triangle groups and seam edges split a uv island as they split mapped charts: no chart holds
 * two groups, a seam path from boundary to boundary parts the island, a seam path that ends
 * inside it leaves it one chart (its uvs are kept as given). */
static void test_groups_and_seam_edges_split_islands(void** state) {
    (void)state;
    test_mesh grid = make_grid(12, 4, 3.0, 1.0); /* the line x = 1 is column 4 of 13 */
    const size_t triangles = grid.index_count / 3;
    double* uv = malloc(6 * triangles * sizeof(double));
    uint32_t* groups = malloc(triangles * sizeof(uint32_t));
    for (size_t t = 0; t < triangles; ++t) {
        double cx = 0;
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = grid.indices[3 * t + k];
            uv[6 * t + 2 * k] = grid.positions[3 * v];
            uv[6 * t + 2 * k + 1] = grid.positions[3 * v + 1];
            cx += grid.positions[3 * v] / 3.0;
        }
        groups[t] = cx < 1.0 ? 7u : 3u;
    }
    raps_mesh* mesh = mesh_with_uvs(&grid, uv);
    assert_int_equal(repacked_grid_charts(mesh, &grid, uv, 0), 1);

    assert_status(raps_mesh_set_triangle_groups(mesh, groups, triangles), RAPS_OK);
    assert_int_equal(repacked_grid_charts(mesh, &grid, uv, 1), 2);
    assert_status(raps_mesh_set_triangle_groups(mesh, NULL, 0), RAPS_OK);

    uint32_t seam[8];
    for (uint32_t j = 0; j < 4; ++j) {
        seam[2 * j] = j * 13 + 4;
        seam[2 * j + 1] = (j + 1) * 13 + 4;
    }
    assert_status(raps_mesh_set_seam_edges(mesh, seam, 4), RAPS_OK);
    assert_int_equal(repacked_grid_charts(mesh, &grid, uv, 1), 2);
    assert_status(raps_mesh_set_seam_edges(mesh, seam, 2), RAPS_OK); /* ends at (1, 0.5) */
    assert_int_equal(repacked_grid_charts(mesh, &grid, uv, 0), 1);

    raps_mesh_destroy(mesh);
    free(groups);
    free(uv);
    test_mesh_free(&grid);
}

/* The uvs of a first raps atlas of a shared mesh, repacked at a density with quarter turns:
 * the same charts come back (one per chart of the first run), each keeping its shape, at one
 * density, the same bits for 1 and 3 threads. */
static void test_a_raps_atlas_repacked_keeps_its_charts(void** state) {
    (void)state;
    test_mesh spot = load_shared_mesh("spot.obj");
    raps_mesh* mesh = to_raps_mesh(&spot);
    raps_settings* first = NULL;
    assert_int_equal(raps_settings_create(&first), RAPS_OK);
    assert_int_equal(raps_settings_set_int(first, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS), RAPS_OK);
    raps_result* r = parameterize_ok(mesh, first);
    atlas before = read_atlas(r);
    raps_result_destroy(r);
    const size_t triangles = spot.index_count / 3;
    assert_int_equal(before.triangle_count, triangles);
    double* uv = malloc(6 * triangles * sizeof(double));
    for (size_t i = 0; i < 3 * triangles; ++i) {
        uv[2 * i] = before.texel[2 * before.indices[i]];
        uv[2 * i + 1] = before.texel[2 * before.indices[i] + 1];
    }
    assert_status(raps_mesh_set_corner_uvs_f64(mesh, uv, 3 * triangles, 0), RAPS_OK);
    atlas runs[2];
    for (int run = 0; run < 2; ++run) {
        raps_settings* settings = repack_settings(run ? 3 : 1, RAPS_ROTATION_QUARTER);
        assert_int_equal(raps_settings_set_float(settings, RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, 300.0),
                         RAPS_OK);
        assert_int_equal(raps_settings_set_int(settings, RAPS_PARAM_ATLAS_PADDING, 2), RAPS_OK);
        runs[run] = repack(mesh, settings);
        raps_settings_destroy(settings);
    }
    const atlas* a = &runs[0];
    assert_int_equal(a->chart_count, before.chart_count);
    assert_near(a->stats.texels_per_unit, 300.0, 0.0);
    /* Triangles of one first-run chart share a repacked chart, and the other way round. */
    uint32_t* match = malloc(a->chart_count * sizeof(uint32_t));
    for (size_t c = 0; c < a->chart_count; ++c) match[c] = UINT32_MAX;
    for (size_t t = 0; t < triangles; ++t) {
        if (match[before.chart[t]] == UINT32_MAX) match[before.chart[t]] = a->chart[t];
        assert_int_equal(match[before.chart[t]], a->chart[t]);
    }
    for (uint32_t c = 0; c < a->chart_count; ++c) {
        double turn, scale;
        check_similarity(a, uv, c, &turn, &scale);
        assert_true(angle_gap(turn, 90.0 * round(turn / 90.0)) < 1e-6);
        if (a->charts[c].flags & RAPS_CHART_SCALED_DOWN) continue;
        assert_near(a->charts[c].area_texels / a->charts[c].area_3d, 300.0 * 300.0,
                    1e-6 * 300.0 * 300.0);
    }
    assert_int_equal(runs[1].vertex_count, a->vertex_count);
    assert_memory_equal(runs[1].texel, a->texel, 2 * a->vertex_count * sizeof(double));
    assert_memory_equal(runs[1].indices, a->indices, 3 * triangles * sizeof(uint32_t));
    free(match);
    atlas_free(&runs[0]);
    atlas_free(&runs[1]);
    atlas_free(&before);
    free(uv);
    raps_settings_destroy(first);
    raps_mesh_destroy(mesh);
    test_mesh_free(&spot);
}

/* Two meshes of a scene, the second drawn twice as large: one density across both, measured
 * in world units. */
static void test_a_scene_is_repacked_at_one_density(void** state) {
    (void)state;
    test_mesh grid = make_grid(12, 4, 3.0, 1.0);
    double* uv = three_island_uvs(&grid);
    raps_mesh* meshes[2] = {mesh_with_uvs(&grid, uv), mesh_with_uvs(&grid, uv)};
    const double twice[12] = {2, 0, 0, 5, 0, 2, 0, 0, 0, 0, 2, 0};
    assert_int_equal(raps_mesh_set_transform(meshes[1], twice), RAPS_OK);
    raps_settings* settings = repack_settings(1, RAPS_ROTATION_ANY);
    raps_result* r = NULL;
    assert_int_equal(raps_result_create(&r), RAPS_OK);
    assert_status(raps_parameterize_scene((const raps_mesh* const*)meshes, 2, settings, r),
                  RAPS_OK);
    atlas a = read_atlas(r);
    assert_int_equal(a.chart_count, 6);
    const double density = a.charts[0].area_texels / a.charts[0].area_3d;
    for (uint32_t c = 0; c < 6; ++c) {
        assert_int_equal(a.charts[c].mesh, c / 3);
        assert_near(a.charts[c].area_3d, c < 3 ? 1.0 : 4.0, 1e-12);
        assert_near(a.charts[c].area_texels / a.charts[c].area_3d, density, 1e-9 * density);
    }
    atlas_free(&a);
    raps_result_destroy(r);
    /* A mesh of the scene without uvs is named. */
    assert_status(raps_mesh_set_corner_uvs_f64(meshes[1], NULL, 0, 0), RAPS_OK);
    assert_int_equal(raps_result_create(&r), RAPS_OK);
    assert_status(raps_parameterize_scene((const raps_mesh* const*)meshes, 2, settings, r),
                  RAPS_ERROR_UV_COUNT);
    assert_non_null(strstr(raps_result_last_error(r), "mesh 1"));
    raps_result_destroy(r);
    raps_settings_destroy(settings);
    raps_mesh_destroy(meshes[0]);
    raps_mesh_destroy(meshes[1]);
    free(uv);
    test_mesh_free(&grid);
}

static void expect_refused(const raps_mesh* mesh, const raps_settings* settings,
                           raps_status expected, const char* word) {
    raps_result* r = NULL;
    assert_int_equal(raps_result_create(&r), RAPS_OK);
    assert_status(raps_parameterize(mesh, settings, r), expected);
    assert_int_equal(raps_result_vertex_count(r), 0);
    if (!strstr(raps_result_last_error(r), word))
        fail_msg("message \"%s\" does not name \"%s\"", raps_result_last_error(r), word);
    raps_result_destroy(r);
}

/* Wrong counts, non-finite uvs and islands without uv area: each its own status, a message,
 * and the mesh keeps what it had. */
static void test_bad_uvs_are_refused_with_their_own_status(void** state) {
    (void)state;
    test_mesh grid = make_grid(12, 4, 3.0, 1.0);
    double* uv = three_island_uvs(&grid);
    raps_mesh* mesh = to_raps_mesh(&grid);
    raps_settings* settings = repack_settings(1, RAPS_ROTATION_ANY);
    expect_refused(mesh, settings, RAPS_ERROR_UV_COUNT, "no corner uvs");
    assert_status(raps_mesh_set_corner_uvs_f64(mesh, uv, grid.index_count - 3, 0), RAPS_OK);
    expect_refused(mesh, settings, RAPS_ERROR_UV_COUNT, "corners");
    /* NaN and infinity are refused by the setter, which names the corner and keeps the uvs. */
    double bad = uv[7];
    uv[7] = NAN;
    assert_status(raps_mesh_set_corner_uvs_f64(mesh, uv, grid.index_count, 0),
                  RAPS_ERROR_NON_FINITE_UV);
    assert_non_null(strstr(raps_mesh_last_error(mesh), "corner 3"));
    uv[7] = bad;
    float uv32[6] = {0, 0, 1, 0, (float)INFINITY, 1};
    assert_status(raps_mesh_set_corner_uvs_f32(mesh, uv32, 3, 0), RAPS_ERROR_NON_FINITE_UV);
    expect_refused(mesh, settings, RAPS_ERROR_UV_COUNT, "corners"); /* still the short uvs */
    /* Arguments. */
    assert_status(raps_mesh_set_corner_uvs_f64(NULL, uv, 3, 0), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_mesh_set_corner_uvs_f64(mesh, NULL, 3, 0), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_mesh_set_corner_uvs_f64(mesh, uv, 3, 8), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_mesh_set_corner_uvs_f32(mesh, uv32, 3, 4), RAPS_ERROR_INVALID_ARGUMENT);
    /* An island squashed onto a line: no shape to keep. */
    for (size_t t = 0; t < grid.index_count / 3; ++t) {
        double cx = 0;
        for (int k = 0; k < 3; ++k) cx += grid.positions[3 * grid.indices[3 * t + k]] / 3.0;
        if (cx > 2.0) {
            for (int k = 0; k < 3; ++k) uv[6 * t + 2 * k + 1] = 7.0;
        }
    }
    assert_status(raps_mesh_set_corner_uvs_f64(mesh, uv, grid.index_count, 0), RAPS_OK);
    expect_refused(mesh, settings, RAPS_ERROR_DEGENERATE_UV_CHART, "triangle");
    /* Strided f32 uvs (a vertex of u, v and a third float) are read as packed ones are. */
    free(uv);
    uv = three_island_uvs(&grid);
    float* strided = malloc(3 * grid.index_count * sizeof(float));
    for (size_t i = 0; i < grid.index_count; ++i) {
        strided[3 * i] = (float)uv[2 * i];
        strided[3 * i + 1] = (float)uv[2 * i + 1];
        strided[3 * i + 2] = NAN; /* not read */
    }
    assert_status(raps_mesh_set_corner_uvs_f32(mesh, strided, grid.index_count, 3 * sizeof(float)),
                  RAPS_OK);
    atlas a = repack(mesh, settings);
    assert_int_equal(a.chart_count, 3);
    atlas_free(&a);
    assert_string_equal(raps_status_string(RAPS_ERROR_UV_COUNT),
                        "corner uv count differs from three per triangle");
    assert_string_not_equal(raps_status_string(RAPS_ERROR_DEGENERATE_UV_CHART), "unknown status");
    assert_string_not_equal(raps_status_string(RAPS_ERROR_NON_FINITE_UV), "unknown status");
    free(strided);
    free(uv);
    raps_settings_destroy(settings);
    raps_mesh_destroy(mesh);
    test_mesh_free(&grid);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_islands_keep_their_shape_under_each_rotation_policy),
        cmocka_unit_test(test_charts_follow_uv_edges_only),
        cmocka_unit_test(test_overlapping_islands_are_packed_apart),
        cmocka_unit_test(test_an_island_without_surface_becomes_a_point),
        cmocka_unit_test(test_groups_and_seam_edges_split_islands),
        cmocka_unit_test(test_a_raps_atlas_repacked_keeps_its_charts),
        cmocka_unit_test(test_a_scene_is_repacked_at_one_density),
        cmocka_unit_test(test_bad_uvs_are_refused_with_their_own_status),
    };
    return cmocka_run_group_tests_name("uv_repack", tests, NULL, NULL);
}
