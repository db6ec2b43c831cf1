#include "atlas_checks.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>

#include <cmocka.h>

atlas atlas_of(const raps_result* r) {
    atlas a;
    a.vertex_count = raps_result_vertex_count(r);
    a.index_count = raps_result_index_count(r);
    a.uv = malloc(2 * a.vertex_count * sizeof(float) + 1);
    a.indices = malloc(a.index_count * sizeof(uint32_t) + 1);
    a.remap = malloc(a.vertex_count * sizeof(uint32_t) + 1);
    a.chart = malloc(a.index_count / 3 * sizeof(uint32_t) + 1);
    assert_non_null(a.uv);
    assert_non_null(a.indices);
    assert_non_null(a.remap);
    assert_non_null(a.chart);
    assert_status(raps_result_copy_uvs_f32(r, a.uv, a.vertex_count, 0), RAPS_OK);
    assert_status(raps_result_copy_indices_u32(r, a.indices, a.index_count), RAPS_OK);
    assert_status(raps_result_copy_vertex_remap(r, a.remap, a.vertex_count), RAPS_OK);
    assert_status(raps_result_copy_chart_ids(r, a.chart, a.index_count / 3), RAPS_OK);
    a.stats = stats_of(r);
    return a;
}

void atlas_free(atlas* a) {
    free(a->uv);
    free(a->indices);
    free(a->remap);
    free(a->chart);
}

static double cross2(double ax, double ay, double bx, double by) {
    return ax * by - ay * bx;
}

/* Structural checks: triangles in input order over the right input vertices, remap and chart
 * ids in range, uvs in the unit square. */
void check_atlas_structure(const test_mesh* mesh, const atlas* a) {
    assert_int_equal(a->index_count, mesh->index_count);
    assert_true(a->stats.chart_count >= 1);
    for (size_t i = 0; i < a->index_count; ++i) {
        assert_true(a->indices[i] < a->vertex_count);
        if (a->remap[a->indices[i]] != mesh->indices[i]) {
            fail_msg("corner %zu: output vertex %u comes from input vertex %u, expected %u", i,
                     a->indices[i], a->remap[a->indices[i]], mesh->indices[i]);
        }
    }
    for (size_t t = 0; t < a->index_count / 3; ++t) assert_true(a->chart[t] < a->stats.chart_count);
    /* At a resolution (here the default, 1024) the atlas is its square, whichever packer. */
    assert_int_equal(a->stats.atlas_width, 1024);
    assert_int_equal(a->stats.atlas_height, 1024);
    for (size_t v = 0; v < a->vertex_count; ++v) {
        assert_true(a->remap[v] < mesh->vertex_count);
        assert_true(a->uv[2 * v] >= 0.0f && a->uv[2 * v] <= 1.0f);
        assert_true(a->uv[2 * v + 1] >= 0.0f && a->uv[2 * v + 1] <= 1.0f);
    }
}

/* Whether triangle t repeats an earlier triangle's vertices in the same rotation: such a
 * duplicate shares its original's uvs by design. */
static int is_duplicate(const test_mesh* mesh, size_t t) {
    const uint32_t* a = mesh->indices + 3 * t;
    for (size_t u = 0; u < t; ++u) {
        const uint32_t* b = mesh->indices + 3 * u;
        for (int r = 0; r < 3; ++r) {
            if (a[0] == b[r] && a[1] == b[(r + 1) % 3] && a[2] == b[(r + 2) % 3]) return 1;
        }
    }
    return 0;
}

/* Rasterises the atlas at its own texel size: conservative footprints per chart must keep
 * `padding - 1` free texels between different charts (the packer promises `padding` in
 * continuous texel units), and within a chart no texel centre may be covered twice (top-left
 * rule, so shared edges count once). Triangles with zero 3D area, and exact duplicates, are
 * skipped. */
void check_atlas_overlap(const test_mesh* mesh, const atlas* a, int padding) {
    const int w = (int)a->stats.atlas_width, h = (int)a->stats.atlas_height;
    assert_true(w >= 1 && h >= 1);
    int32_t* owner = malloc((size_t)w * h * sizeof(int32_t));
    uint8_t* centre = calloc((size_t)w * h, 1);
    for (size_t i = 0; i < (size_t)w * h; ++i) owner[i] = -1;
    const size_t triangles = a->index_count / 3;
    for (size_t t = 0; t < triangles; ++t) {
        const double* p0 = mesh->positions + 3 * mesh->indices[3 * t];
        const double* p1 = mesh->positions + 3 * mesh->indices[3 * t + 1];
        const double* p2 = mesh->positions + 3 * mesh->indices[3 * t + 2];
        const double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        const double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        const double nx = e1[1] * e2[2] - e1[2] * e2[1], ny = e1[2] * e2[0] - e1[0] * e2[2];
        const double nz = e1[0] * e2[1] - e1[1] * e2[0];
        if (nx * nx + ny * ny + nz * nz == 0.0) continue;
        if (triangles < 5000 && is_duplicate(mesh, t)) continue;
        double x[3], y[3];
        for (int k = 0; k < 3; ++k) {
            x[k] = a->uv[2 * a->indices[3 * t + k]] * (double)w;
            y[k] = a->uv[2 * a->indices[3 * t + k] + 1] * (double)h;
        }
        const double area = cross2(x[1] - x[0], y[1] - y[0], x[2] - x[0], y[2] - y[0]);
        if (area <= 0) fail_msg("triangle %zu is flipped or flat in uv (area %g)", t, area);
        const int x0 = (int)floor(fmin(x[0], fmin(x[1], x[2]))),
                  x1 = (int)floor(fmax(x[0], fmax(x[1], x[2])));
        const int y0 = (int)floor(fmin(y[0], fmin(y[1], y[2]))),
                  y1 = (int)floor(fmax(y[0], fmax(y[1], y[2])));
        for (int ty = y0; ty <= y1; ++ty) {
            for (int tx = x0; tx <= x1; ++tx) {
                if (tx < 0 || ty < 0 || tx >= w || ty >= h) continue;
                /* Does the triangle touch texel [tx, tx+1] x [ty, ty+1]? Separating axes: the
                 * three edges (the box axes are covered by the bounding box loop). */
                int separated = 0;
                for (int e = 0; e < 3 && !separated; ++e) {
                    const double ax = x[e], ay = y[e], bx = x[(e + 1) % 3], by = y[(e + 1) % 3];
                    int inside = 0;
                    for (int c = 0; c < 4; ++c) {
                        const double cx = tx + (c & 1), cy = ty + (c >> 1);
                        if (cross2(bx - ax, by - ay, cx - ax, cy - ay) >= 0) inside = 1;
                    }
                    separated = !inside;
                }
                if (separated) continue;
                const size_t cell = (size_t)ty * w + tx;
                if (owner[cell] >= 0 && owner[cell] != (int32_t)a->chart[t]) {
                    fail_msg("charts %d and %u share texel (%d, %d)", owner[cell], a->chart[t], tx,
                             ty);
                }
                owner[cell] = (int32_t)a->chart[t];
                /* Texel centre coverage with the top-left rule. */
                const double cx = tx + 0.5, cy = ty + 0.5;
                int covered = 1;
                for (int e = 0; e < 3 && covered; ++e) {
                    const double ax = x[e], ay = y[e], bx = x[(e + 1) % 3], by = y[(e + 1) % 3];
                    const double f = cross2(bx - ax, by - ay, cx - ax, cy - ay);
                    const int top_left = (by == ay && bx < ax) || by < ay;
                    covered = f > 0 || (f == 0 && top_left);
                }
                if (covered) {
                    if (centre[cell])
                        fail_msg("texel (%d, %d) covered twice in chart %u", tx, ty, a->chart[t]);
                    centre[cell] = 1;
                }
            }
        }
    }
    /* Padding: different charts' footprints at least padding - 1 texels apart. */
    const int gap = padding - 1;
    for (int ty = 0; ty < h && gap > 0; ++ty) {
        for (int tx = 0; tx < w; ++tx) {
            const int32_t c = owner[(size_t)ty * w + tx];
            if (c < 0) continue;
            for (int dy = -gap; dy <= gap; ++dy) {
                for (int dx = -gap; dx <= gap; ++dx) {
                    const int sx = tx + dx, sy = ty + dy;
                    if (sx < 0 || sy < 0 || sx >= w || sy >= h) continue;
                    const int32_t o = owner[(size_t)sy * w + sx];
                    if (o >= 0 && o != c)
                        fail_msg("charts %d and %d closer than the padding at (%d, %d)", c, o, tx,
                                 ty);
                }
            }
        }
    }
    free(owner);
    free(centre);
}
