/* The distortion statistics, each checked against an answer computed here independently (by
 * hand or by a different formula than the library's): Sander's stretch from the 3D-from-uv
 * partial derivatives, angles by the law of cosines, flips by solving a one-unknown system. */
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

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static raps_stats run(const double* xyz, size_t n, const uint32_t* tri, size_t index_count,
                      const raps_settings* settings, double* uv_out) {
    test_mesh mesh = {(double*)xyz, n, (uint32_t*)tri, index_count};
    raps_mesh* m = to_raps_mesh(&mesh);
    raps_result* r = parameterize_ok(m, settings);
    raps_stats stats = stats_of(r);
    if (uv_out) assert_status(raps_result_copy_uvs_f64(r, uv_out, n, 0), RAPS_OK);
    raps_result_destroy(r);
    raps_mesh_destroy(m);
    return stats;
}

/* Angle at the corner between sides b and c, opposite side a (law of cosines). */
static double law_of_cosines(double a, double b, double c) {
    return acos((b * b + c * c - a * a) / (2 * b * c));
}

/* Sander et al. 2001, eq. 2-3: the singular values of the 3D-from-uv Jacobian of one triangle
 * from its partial derivatives S_s, S_t. */
static void sander_stretch(const double* q1, const double* q2, const double* q3, const double* p1,
                           const double* p2, const double* p3, double* l2, double* linf) {
    const double area2 = (p2[0] - p1[0]) * (p3[1] - p1[1]) - (p3[0] - p1[0]) * (p2[1] - p1[1]);
    double ss[3], st[3];
    for (int k = 0; k < 3; ++k) {
        ss[k] =
            (q1[k] * (p2[1] - p3[1]) + q2[k] * (p3[1] - p1[1]) + q3[k] * (p1[1] - p2[1])) / area2;
        st[k] =
            (q1[k] * (p3[0] - p2[0]) + q2[k] * (p1[0] - p3[0]) + q3[k] * (p2[0] - p1[0])) / area2;
    }
    const double a = ss[0] * ss[0] + ss[1] * ss[1] + ss[2] * ss[2];
    const double b = ss[0] * st[0] + ss[1] * st[1] + ss[2] * st[2];
    const double c = st[0] * st[0] + st[1] * st[1] + st[2] * st[2];
    *l2 = sqrt((a + c) / 2);
    *linf = sqrt(((a + c) + sqrt((a - c) * (a - c) + 4 * b * b)) / 2);
}

/* One right triangle: its three vertices go onto the circle at angles proportional to the
 * chord lengths 1, sqrt 2, 1. */
static void single_triangle_on_the_circle(void** state) {
    (void)state;
    const double xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t tri[] = {0, 1, 2};
    double uv[6];
    const raps_stats s = run(xyz, 3, tri, 3, NULL, uv);
    const double total = 2 + sqrt(2.0);
    const double at[3] = {0, 2 * M_PI / total, 2 * M_PI * (1 + sqrt(2.0)) / total};
    for (int i = 0; i < 3; ++i) {
        assert_near(uv[2 * i], 0.5 + 0.5 * cos(at[i]), 1e-12);
        assert_near(uv[2 * i + 1], 0.5 + 0.5 * sin(at[i]), 1e-12);
    }
    /* uv sides opposite each corner, and the corners' angles. */
    const double a = hypot(uv[4] - uv[2], uv[5] - uv[3]);
    const double b = hypot(uv[4] - uv[0], uv[5] - uv[1]);
    const double c = hypot(uv[2] - uv[0], uv[3] - uv[1]);
    const double uv_angle[3] = {law_of_cosines(a, b, c), law_of_cosines(b, a, c),
                                law_of_cosines(c, a, b)};
    const double angle_3d[3] = {M_PI / 2, M_PI / 4, M_PI / 4};
    double sum = 0, max = 0;
    for (int i = 0; i < 3; ++i) {
        const double d = fabs(uv_angle[i] - angle_3d[i]) * 180 / M_PI;
        sum += d;
        max = fmax(max, d);
    }
    assert_near(s.angle_mean_deg, sum / 3, 1e-9);
    assert_near(s.angle_max_deg, max, 1e-9);
    /* A single triangle always has its share of area: r = 1. */
    assert_near(s.area_log_mean, 0.0, 1e-12);
    assert_near(s.area_max, 1.0, 1e-12);
    /* Stretch with the uv scaled to the 3D area (1/2). */
    const double uv_area =
        0.5 * fabs((uv[2] - uv[0]) * (uv[5] - uv[1]) - (uv[4] - uv[0]) * (uv[3] - uv[1]));
    const double k = sqrt(0.5 / uv_area);
    const double p1[2] = {k * uv[0], k * uv[1]}, p2[2] = {k * uv[2], k * uv[3]},
                 p3[2] = {k * uv[4], k * uv[5]};
    double l2, linf;
    sander_stretch(xyz, xyz + 3, xyz + 6, p1, p2, p3, &l2, &linf);
    assert_near(s.stretch_l2, l2, 1e-9);
    assert_near(s.stretch_linf, linf, 1e-9);
    assert_int_equal(s.flipped_triangles, 0);
    assert_int_equal(s.zero_area_triangles, 0);
    assert_int_equal(s.vertex_count, 3);
    assert_int_equal(s.triangle_count, 1);
}

/* A 2 x 1 rectangle onto the unit square: u = x / 2, v = y. By hand: with the uv scaled to the
 * 3D area the Jacobian's singular values are sqrt 2 and 1 / sqrt 2, so L2 = sqrt(5/4) and
 * Linf = sqrt 2; every triangle keeps its area share; the angles atan(1/2) and atan 2 become
 * 45 degrees (18.43 degrees off) and the right angles stay. */
static void rectangle_onto_the_square(void** state) {
    (void)state;
    const double xyz[] = {0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0};
    const uint32_t tri[] = {0, 1, 2, 0, 2, 3};
    raps_settings* s = make_settings(RAPS_WEIGHTS_MEAN_VALUE, RAPS_MONITOR_NONE, 1, 1);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_BOUNDARY, RAPS_BOUNDARY_SQUARE), RAPS_OK);
    double uv[8];
    const raps_stats st = run(xyz, 4, tri, 6, s, uv);
    const double corners[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    for (int i = 0; i < 8; ++i) assert_near(uv[i], corners[i], 1e-15);
    const double off = (atan(2.0) - M_PI / 4) * 180 / M_PI; /* 18.43 degrees */
    assert_near(st.stretch_l2, sqrt(1.25), 1e-12);
    assert_near(st.stretch_linf, sqrt(2.0), 1e-12);
    assert_near(st.area_log_mean, 0.0, 1e-12);
    assert_near(st.area_max, 1.0, 1e-12);
    assert_near(st.angle_max_deg, off, 1e-9);
    assert_near(st.angle_mean_deg, 4 * off / 6, 1e-9);
    raps_settings_destroy(s);
}

/* A unit square's corners are equally spaced on the circle: the map is a similarity, so every
 * figure is ideal. */
static void square_onto_the_circle_is_a_similarity(void** state) {
    (void)state;
    const double xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const uint32_t tri[] = {0, 1, 2, 0, 2, 3};
    const raps_stats s = run(xyz, 4, tri, 6, NULL, NULL);
    assert_near(s.stretch_l2, 1.0, 1e-12);
    assert_near(s.stretch_linf, 1.0, 1e-12);
    assert_near(s.area_log_mean, 0.0, 1e-12);
    assert_near(s.angle_max_deg, 0.0, 1e-9);
}

/* r_t = (uv area share) / (3D area share), recomputed here from the uv the library returns on a
 * bumpy fan, summarised as the 3D-area-weighted mean of |log r| and the max of max(r, 1/r). */
static void area_ratios_follow_their_definition(void** state) {
    (void)state;
    const double xyz[] = {0.1,  -0.05, 0.4,  1,    0,    0, 0.3, 0.9,  0.1,
                          -0.8, 0.6,   -0.2, -0.7, -0.7, 0, 0.4, -0.9, 0.3};
    const uint32_t tri[] = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 5, 0, 5, 1};
    double uv[12];
    const raps_stats s = run(xyz, 6, tri, 15, NULL, uv);
    double area3[5], area_uv[5], total3 = 0, total_uv = 0;
    for (int t = 0; t < 5; ++t) {
        const double *a = xyz + 3 * tri[3 * t], *b = xyz + 3 * tri[3 * t + 1],
                     *c = xyz + 3 * tri[3 * t + 2];
        const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2],
                     z = u[0] * v[1] - u[1] * v[0];
        area3[t] = 0.5 * sqrt(x * x + y * y + z * z);
        const double *p = uv + 2 * tri[3 * t], *q = uv + 2 * tri[3 * t + 1],
                     *w = uv + 2 * tri[3 * t + 2];
        area_uv[t] = 0.5 * ((q[0] - p[0]) * (w[1] - p[1]) - (w[0] - p[0]) * (q[1] - p[1]));
        assert_true(area_uv[t] > 0);
        total3 += area3[t];
        total_uv += area_uv[t];
    }
    double mean = 0, max = 1;
    for (int t = 0; t < 5; ++t) {
        const double r = (area_uv[t] / total_uv) / (area3[t] / total3);
        mean += area3[t] / total3 * fabs(log(r));
        max = fmax(max, fmax(r, 1 / r));
    }
    assert_near(s.area_log_mean, mean, 1e-12);
    assert_near(s.area_max, max, 1e-12);
    assert_true(s.area_log_mean > 0.01); /* the case is not trivial */
}

/* A triangle with all three vertices on one side of the square has zero uv area: counted, and
 * its area ratio is infinite. */
static void zero_area_uv_triangles_are_counted(void** state) {
    (void)state;
    /* Pentagon: v0, v1, v2 along the bottom (v1 raised in 3D, so the ear 0-1-2 has area),
     * corners of the square at v0, v2, v3, v4 (the boundary vertices nearest each quarter). */
    const double xyz[] = {0, 0, 0, 1, 0, 0.3, 2, 0, 0, 2, 3, 0, 0, 3, 0};
    const uint32_t tri[] = {0, 1, 2, 0, 2, 3, 0, 3, 4};
    raps_settings* s = make_settings(RAPS_WEIGHTS_MEAN_VALUE, RAPS_MONITOR_NONE, 1, 1);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_BOUNDARY, RAPS_BOUNDARY_SQUARE), RAPS_OK);
    double uv[10];
    const raps_stats st = run(xyz, 5, tri, 9, s, uv);
    assert_near(uv[3], 0.0, 1e-15); /* v1 lies on the bottom side */
    assert_int_equal(st.zero_area_triangles, 1);
    assert_int_equal(st.flipped_triangles, 0);
    assert_true(isinf(st.area_max));
    assert_true(isinf(st.stretch_linf));
    raps_settings_destroy(s);
}

/* Cotangent weights can be negative and then fold the map. One interior vertex (0) and three
 * boundary vertices: its position is the weighted mean sum w_j u_j / sum w_j of the fixed rim,
 * with w_j = (cot a + cot b) / 2 of the angles opposite edge (0, j). Solved here by hand, it
 * lands outside triangle (0, 2, 3)'s side: exactly one flipped triangle. */
static double cotangent(const double* apex, const double* p, const double* q) {
    const double u[3] = {p[0] - apex[0], p[1] - apex[1], p[2] - apex[2]};
    const double v[3] = {q[0] - apex[0], q[1] - apex[1], q[2] - apex[2]};
    const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2],
                 z = u[0] * v[1] - u[1] * v[0];
    return (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) / sqrt(x * x + y * y + z * z);
}

/* A fan of vertex 0 and the rim 1, 2, 3 (in loop order): uv of vertex 0 is sum w_j uv_j / sum w_j,
 * with the spoke weights w_j returned. */
static void centre_is_the_cotangent_average(const double* xyz, const double* uv, double w[3]) {
    double sum = 0, expected[2] = {0, 0};
    for (int j = 0; j < 3; ++j) {
        const double* before = xyz + 3 * (1 + (j + 2) % 3);
        const double* self = xyz + 3 * (1 + j);
        const double* after = xyz + 3 * (1 + (j + 1) % 3);
        w[j] = 0.5 * (cotangent(before, xyz, self) + cotangent(after, xyz, self));
        sum += w[j];
        expected[0] += w[j] * uv[2 * (1 + j)];
        expected[1] += w[j] * uv[2 * (1 + j) + 1];
    }
    assert_near(uv[0], expected[0] / sum, 1e-12);
    assert_near(uv[1], expected[1] / sum, 1e-12);
}

static void flipped_triangles_are_counted(void** state) {
    (void)state;
    const double xyz[] = {-0.626, -0.647, -0.84, -1.807, -0.758, 0.887,
                          -0.789, -0.819, -0.28, 1.061,  -0.124, 0.645};
    const uint32_t tri[] = {0, 1, 2, 0, 2, 3, 0, 3, 1};
    raps_settings* s = make_settings(RAPS_WEIGHTS_COTANGENT, RAPS_MONITOR_NONE, 1, 1);
    double uv[8];
    const raps_stats st = run(xyz, 4, tri, 9, s, uv);
    double w[3];
    centre_is_the_cotangent_average(xyz, uv, w);
    int flipped = 0;
    for (int t = 0; t < 3; ++t) {
        const double *p = uv + 2 * tri[3 * t], *q = uv + 2 * tri[3 * t + 1],
                     *r = uv + 2 * tri[3 * t + 2];
        flipped += (q[0] - p[0]) * (r[1] - p[1]) - (r[0] - p[0]) * (q[1] - p[1]) < 0;
    }
    assert_int_equal(flipped, 1);
    assert_int_equal(st.flipped_triangles, 1);
    /* Negative directed weights: spokes (two triangles each, computed above) and rim edges (one
     * triangle: half the cotangent of the angle at vertex 0), each counted in both directions. */
    int negative = 0;
    for (int j = 0; j < 3; ++j) {
        negative += 2 * (w[j] < 0);
        negative += 2 * (cotangent(xyz, xyz + 3 * (1 + j), xyz + 3 * (1 + (j + 1) % 3)) < 0);
    }
    assert_true(negative > 0);
    assert_int_equal(st.negative_weights, negative);
    raps_settings_destroy(s);
}

/* A fan whose cotangent solve puts the centre 0.2 outside the circle (below v = 0): the map is
 * folded, and it is scaled uniformly back into [0,1]^2 (found by fuzzing: the header promises
 * [0,1]^2). A similarity: the centre stays the cotangent average of the rim, the map's extent is
 * exactly 1 along its longer axis, and the rim's circle shrank from the unit circle's 0.5. */
static void a_map_folded_outside_is_scaled_into_the_unit_square(void** state) {
    (void)state;
    const double xyz[] = {-1.7, -1.8, -1.1, 0, 0.8, 1.7, 0.1, 1.4, 1.7, -0.7, 1.7, 0.5};
    const uint32_t tri[] = {0, 1, 2, 0, 2, 3, 0, 3, 1};
    raps_settings* s = make_settings(RAPS_WEIGHTS_COTANGENT, RAPS_MONITOR_NONE, 1, 1);
    double uv[8];
    const raps_stats st = run(xyz, 4, tri, 9, s, uv);
    double low[2] = {1, 1}, high[2] = {0, 0};
    for (int i = 0; i < 8; ++i) {
        assert_true(uv[i] >= 0.0 && uv[i] <= 1.0);
        low[i % 2] = fmin(low[i % 2], uv[i]);
        high[i % 2] = fmax(high[i % 2], uv[i]);
    }
    assert_near(fmax(high[0] - low[0], high[1] - low[1]), 1.0, 1e-12);
    /* The circle through the three rim vertices. */
    const double *a = uv + 2, *b = uv + 4, *c = uv + 6;
    const double d = 2 * (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1]));
    const double aa = a[0] * a[0] + a[1] * a[1], bb = b[0] * b[0] + b[1] * b[1],
                 cc = c[0] * c[0] + c[1] * c[1];
    const double centre[2] = {(aa * (b[1] - c[1]) + bb * (c[1] - a[1]) + cc * (a[1] - b[1])) / d,
                              (aa * (c[0] - b[0]) + bb * (a[0] - c[0]) + cc * (b[0] - a[0])) / d};
    const double radius = hypot(a[0] - centre[0], a[1] - centre[1]);
    assert_true(radius < 0.45);
    double w[3];
    centre_is_the_cotangent_average(xyz, uv, w);
    assert_true(st.flipped_triangles > 0);
    raps_settings_destroy(s);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(single_triangle_on_the_circle),
        cmocka_unit_test(rectangle_onto_the_square),
        cmocka_unit_test(square_onto_the_circle_is_a_similarity),
        cmocka_unit_test(area_ratios_follow_their_definition),
        cmocka_unit_test(zero_area_uv_triangles_are_counted),
        cmocka_unit_test(flipped_triangles_are_counted),
        cmocka_unit_test(a_map_folded_outside_is_scaled_into_the_unit_square),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
