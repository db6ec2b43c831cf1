/* The sphere domain (paper section 7) on hard closed genus-0 inputs, built here: capsules of
 * aspect ratio 10 to 50, a dumbbell with a thin neck, a starfish with five long arms, a noisy
 * scan-like sphere, and shared meshes with long limbs (cow, horse_quad, decimated-knight)
 * subdivided to 64K-90K triangles. What is pinned down, through the C ABI:
 *  - never a folded map with RAPS_OK: a result that comes back is a bijection of the unit sphere
 *    (every triangle counter-clockwise by the exact sign of det[a, b, c], |r - 1| < 1e-12,
 *    spherical areas adding up to 4 pi), and a refusal is RAPS_ERROR_SOLVER_FAILED with a
 *    message that names the folded triangles;
 *  - every map that comes back is centred: the 3D-area-weighted centre of mass of its points
 *    within 0.05 of the origin;
 *  - the area monitor lowers the area distortion (raps_stats.area_log_mean) by at least 40 %
 *    against the initial map (RAPS_MONITOR_NONE), and never leaves it worse, where stated;
 *  - which of these inputs are mapped (docs/sphere-status.md has the figures measured on each). */
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
#include "support/exact_orientation.h"
#include "support/test_meshes.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- building meshes ----------------------------------------------------------------------- */

/* Reverses every triangle if the signed volume is negative, so that triangles run
 * counter-clockwise seen from outside. */
static void orient_outwards(test_mesh* m) {
    double volume = 0.0;
    for (size_t t = 0; t < m->index_count; t += 3) {
        const double* a = m->positions + 3 * m->indices[t];
        const double* b = m->positions + 3 * m->indices[t + 1];
        const double* c = m->positions + 3 * m->indices[t + 2];
        volume += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                  a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    if (volume >= 0.0) return;
    for (size_t t = 0; t < m->index_count; t += 3) {
        const uint32_t s = m->indices[t + 1];
        m->indices[t + 1] = m->indices[t + 2];
        m->indices[t + 2] = s;
    }
}

/* A surface of revolution about the z axis: profile(s) = (rho, z) for the arclength-like
 * parameter s in [0, 1], rho = 0 at both ends. Rings are spaced along the profile by the
 * circumferential edge length there (at least that of radius `min_rho`), so the quads are about
 * square. */
typedef void (*profile_fn)(double s, const void* shape, double* rho, double* z);

static test_mesh make_revolution(profile_fn profile, const void* shape, int sectors,
                                 double min_rho) {
    enum { kSamples = 20000 };
    double* arc = malloc((kSamples + 1) * sizeof(double));
    assert_non_null(arc);
    double prev_rho, prev_z;
    profile(0.0, shape, &prev_rho, &prev_z);
    arc[0] = 0.0;
    for (int k = 1; k <= kSamples; ++k) {
        double rho, z;
        profile((double)k / kSamples, shape, &rho, &z);
        arc[k] = arc[k - 1] + hypot(rho - prev_rho, z - prev_z);
        prev_rho = rho;
        prev_z = z;
    }
    test_mesh_builder g;
    memset(&g, 0, sizeof(g));
    double rho, z;
    profile(0.0, shape, &rho, &z);
    const uint32_t north = (uint32_t)test_mesh_add_vertex(&g, 0.0, 0.0, z);
    int rings = 0;
    double at = 0.0;
    int k = 0;
    for (;;) {
        profile((double)k / kSamples, shape, &rho, &z);
        at += 2.0 * M_PI * fmax(rho, min_rho) / sectors;
        while (k < kSamples && arc[k] < at) ++k;
        if (k >= kSamples || arc[kSamples] - at < 0.5 * 2.0 * M_PI * min_rho / sectors) break;
        profile((double)k / kSamples, shape, &rho, &z);
        const double twist = (rings % 2) * M_PI / sectors;
        for (int j = 0; j < sectors; ++j) {
            const double phi = 2.0 * M_PI * j / sectors + twist;
            test_mesh_add_vertex(&g, rho * cos(phi), rho * sin(phi), z);
        }
        ++rings;
    }
    profile(1.0, shape, &rho, &z);
    const uint32_t south = (uint32_t)test_mesh_add_vertex(&g, 0.0, 0.0, z);
    const uint32_t n = (uint32_t)sectors;
    for (uint32_t j = 0; j < n; ++j) test_mesh_add_triangle(&g, north, 1 + j, 1 + (j + 1) % n);
    for (int r = 0; r + 1 < rings; ++r) {
        const uint32_t a = 1 + (uint32_t)r * n, b = a + n;
        for (uint32_t j = 0; j < n; ++j) {
            const uint32_t j1 = (j + 1) % n;
            if (r % 2 == 0) { /* ring r+1 is turned by half a sector */
                test_mesh_add_triangle(&g, a + j, b + j, a + j1);
                test_mesh_add_triangle(&g, a + j1, b + j, b + j1);
            } else {
                test_mesh_add_triangle(&g, a + j, b + j, b + j1);
                test_mesh_add_triangle(&g, a + j, b + j1, a + j1);
            }
        }
    }
    const uint32_t last = 1 + (uint32_t)(rings - 1) * n;
    for (uint32_t j = 0; j < n; ++j)
        test_mesh_add_triangle(&g, last + (j + 1) % n, last + j, south);
    free(arc);
    orient_outwards(&g.mesh);
    return g.mesh;
}

/* Capsule of radius 1 and total length 2 * aspect (aspect = length / diameter). */
static void capsule_profile(double s, const void* shape, double* rho, double* z) {
    const double h = *(const double*)shape - 1.0; /* half-length of the cylinder */
    const double total = M_PI + 2.0 * h, at = s * total;
    if (at < 0.5 * M_PI) {
        *rho = sin(at);
        *z = h + cos(at);
    } else if (at < 0.5 * M_PI + 2.0 * h) {
        *rho = 1.0;
        *z = h - (at - 0.5 * M_PI);
    } else {
        const double a = at - 0.5 * M_PI - 2.0 * h;
        *rho = cos(a);
        *z = -h - sin(a);
    }
}

static test_mesh make_capsule(double aspect, int sectors) {
    return make_revolution(capsule_profile, &aspect, sectors, 1.0);
}

/* Two unit spheres whose centres are 3 apart, joined by a neck of the given radius. The
 * profile is parameterised by z; the arclength spacing of make_revolution evens it out. */
static void dumbbell_profile(double s, const void* shape, double* rho, double* z) {
    const double neck = *(const double*)shape, c = 1.5;
    *z = (c + 1.0) * cos(M_PI * s); /* denser near the poles */
    const double a = 1.0 - (*z - c) * (*z - c), b = 1.0 - (*z + c) * (*z + c);
    double r = neck;
    if (a > 0.0) r = fmax(r, sqrt(a));
    if (b > 0.0) r = fmax(r, sqrt(b));
    if (s == 0.0 || s == 1.0) r = 0.0;
    *rho = r;
}

static test_mesh make_dumbbell(double neck, int sectors) {
    return make_revolution(dumbbell_profile, &neck, sectors, neck);
}

/* A fixed pseudo-random value in [0, 1) per integer. */
static double hash01(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return (double)x / 4294967296.0;
}

/* A starfish: the unit sphere flattened to a third in z, with five arms in the xy plane that
 * reach out to `reach` (radial displacement of a subdivided icosahedron). */
static test_mesh make_starfish(double reach, int levels) {
    test_mesh m = subdivided_mesh(make_icosphere(0), levels, 1);
    for (size_t i = 0; i < m.vertex_count; ++i) {
        double* p = m.positions + 3 * i;
        double arm = 0.0;
        for (int k = 0; k < 5; ++k) {
            const double c = p[0] * cos(2.0 * M_PI * k / 5) + p[1] * sin(2.0 * M_PI * k / 5);
            if (c > 0.0) arm = fmax(arm, pow(c, 24.0));
        }
        const double r = 1.0 + (reach - 1.0) * arm;
        p[0] *= r;
        p[1] *= r;
        p[2] *= 0.35 * (1.0 - 0.7 * arm);
    }
    return m;
}

/* A scan-like sphere: a subdivided icosahedron, each vertex moved radially by up to +-3% and
 * along the surface by up to a quarter of an edge, plus a few bumps. */
static test_mesh make_noisy_sphere(int levels) {
    test_mesh m = subdivided_mesh(make_icosphere(0), levels, 1);
    const double edge = 1.1 / pow(2.0, levels);
    for (size_t i = 0; i < m.vertex_count; ++i) {
        double* p = m.positions + 3 * i;
        const uint32_t id = (uint32_t)i * 3u;
        for (int q = 0; q < 3; ++q) p[q] += 0.25 * edge * (2.0 * hash01(id + (uint32_t)q) - 1.0);
        const double n = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        const double bump = 0.15 * exp(-20.0 * ((p[0] / n - 0.6) * (p[0] / n - 0.6) +
                                                (p[1] / n - 0.8) * (p[1] / n - 0.8)));
        const double r = (1.0 + 0.03 * (2.0 * hash01(0x51ed270bu ^ (uint32_t)i) - 1.0) + bump) / n;
        for (int q = 0; q < 3; ++q) p[q] *= r;
    }
    return m;
}

/* ---- checking maps ------------------------------------------------------------------------- */

typedef struct sphere_check {
    size_t folded;
    double area_sum; /* signed spherical areas */
    double centre;   /* 3D-area-weighted centre of mass, distance from the origin */
    double worst_norm;
} sphere_check;

static double dot3(const double* a, const double* b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static sphere_check check_sphere_map(const test_mesh* mesh, const double* u) {
    sphere_check c = {0, 0.0, 0.0, 0.0};
    double centre[3] = {0, 0, 0}, total = 0;
    for (size_t i = 0; i < mesh->vertex_count; ++i) {
        c.worst_norm = fmax(c.worst_norm, fabs(sqrt(dot3(u + 3 * i, u + 3 * i)) - 1.0));
    }
    for (size_t t = 0; t < mesh->index_count; t += 3) {
        const uint32_t* v = mesh->indices + t;
        const double *a = u + 3 * v[0], *b = u + 3 * v[1], *d = u + 3 * v[2];
        /* det[a, b, d] as a . ((b - a) x (d - a)), rounded relative to the triangle's size, for
         * the area; the fold test is the exact sign. */
        const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        const double ad[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        const double n_abd[3] = {ab[1] * ad[2] - ab[2] * ad[1], ab[2] * ad[0] - ab[0] * ad[2],
                                 ab[0] * ad[1] - ab[1] * ad[0]};
        const double det = dot3(a, n_abd);
        c.folded += exact_orientation_sign(a, b, d) <= 0;
        c.area_sum += 2.0 * atan2(det, 1.0 + dot3(a, b) + dot3(b, d) + dot3(d, a));
        const double *x = mesh->positions + 3 * v[0], *y = mesh->positions + 3 * v[1],
                     *z = mesh->positions + 3 * v[2];
        const double e1[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
        const double e2[3] = {z[0] - x[0], z[1] - x[1], z[2] - x[2]};
        const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                             e1[0] * e2[1] - e1[1] * e2[0]};
        const double area = 0.5 * sqrt(dot3(n, n));
        for (int k = 0; k < 3; ++k) {
            for (int q = 0; q < 3; ++q) centre[q] += area / 3.0 * u[3 * v[k] + q];
        }
        total += area;
    }
    c.centre = sqrt(dot3(centre, centre)) / total;
    return c;
}

/* max_sweeps: RAPS_PARAM_SPHERE_MAX_SWEEPS (0: the method's own). */
static raps_settings* sphere_settings(int32_t monitor, int64_t max_sweeps) {
    raps_settings* s = NULL;
    assert_status(raps_settings_create(&s), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_SPHERE), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_MONITOR, monitor), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_SPHERE_MAX_SWEEPS, max_sweeps), RAPS_OK);
    return s;
}

typedef struct outcome {
    raps_status status;
    sphere_check check;
    double area_log_mean;
} outcome;

/* Runs the robust method with `monitor`; on RAPS_OK the map must be a bijection of the unit
 * sphere and centred (the 3D-area-weighted centre of mass within 0.05 of the origin), otherwise the
 * refusal must be SOLVER_FAILED with a message about folds. Prints the figures either way. */
static outcome map_or_refuse_with(const char* name, const test_mesh* mesh, int32_t monitor,
                                  int64_t max_sweeps) {
    raps_mesh* handle = to_raps_mesh(mesh);
    raps_settings* settings = sphere_settings(monitor, max_sweeps);
    raps_result* result = NULL;
    assert_status(raps_result_create(&result), RAPS_OK);
    outcome o;
    memset(&o, 0, sizeof(o));
    o.status = raps_parameterize(handle, settings, result);
    const char* label = monitor == RAPS_MONITOR_NONE ? "initial" : "adapted";
    if (o.status == RAPS_OK) {
        const size_t n = raps_result_vertex_count(result);
        assert_int_equal(n, mesh->vertex_count);
        double* u = malloc(3 * n * sizeof(double));
        assert_non_null(u);
        assert_status(raps_result_copy_sphere_points_f64(result, u, n, 0), RAPS_OK);
        o.check = check_sphere_map(mesh, u);
        o.area_log_mean = stats_of(result).area_log_mean;
        free(u);
        print_message(
            "%-26s %s: %zu triangles, OK, area |log r| %.3f, centre %.3f, "
            "|r-1| %.1e, area sum - 4pi %.1e, %llu sweeps\n",
            name, label, mesh->index_count / 3, o.area_log_mean, o.check.centre, o.check.worst_norm,
            o.check.area_sum - 4.0 * M_PI, (unsigned long long)stats_of(result).relaxation_sweeps);
        if (o.check.folded != 0 || o.check.worst_norm > 1e-12 ||
            fabs(o.check.area_sum - 4.0 * M_PI) > 1e-6) {
            fail_msg(
                "%s: RAPS_OK with %zu folded triangles, |r - 1| up to %.2g, spherical "
                "areas summing to %.9f",
                name, o.check.folded, o.check.worst_norm, o.check.area_sum);
        }
        assert_int_equal(stats_of(result).flipped_triangles, 0);
        assert_below(o.check.centre, 0.05);
    } else {
        const char* message = raps_result_last_error(result);
        print_message("%-26s %s: %zu triangles, refused: %s\n", name, label, mesh->index_count / 3,
                      message);
        assert_status(o.status, RAPS_ERROR_SOLVER_FAILED);
        assert_non_null(strstr(message, "fold"));
        assert_int_equal(raps_result_vertex_count(result), 0);
    }
    raps_result_destroy(result);
    raps_settings_destroy(settings);
    raps_mesh_destroy(handle);
    return o;
}

static outcome map_or_refuse(const char* name, const test_mesh* mesh, int32_t monitor) {
    return map_or_refuse_with(name, mesh, monitor, 0);
}

/* Maps `mesh` twice, initial and area-adapted, with at most `max_sweeps` per relaxation (0: the
 * method's own): both must come back, and the area monitor must lower the area distortion to at
 * most `fraction` of the initial map's (0.6: issue 18's 40 %). */
static void assert_area_lowered_with(const char* name, const test_mesh* mesh, double fraction,
                                     int64_t max_sweeps) {
    const outcome initial = map_or_refuse_with(name, mesh, RAPS_MONITOR_NONE, max_sweeps);
    const outcome adapted = map_or_refuse_with(name, mesh, RAPS_MONITOR_AREA, max_sweeps);
    assert_status(initial.status, RAPS_OK);
    assert_status(adapted.status, RAPS_OK);
    if (!(adapted.area_log_mean <= fraction * initial.area_log_mean)) {
        fail_msg("%s: area distortion %.3f -> %.3f, above %.2f of the initial map's", name,
                 initial.area_log_mean, adapted.area_log_mean, fraction);
    }
}

static void assert_area_lowered(const char* name, const test_mesh* mesh, double fraction) {
    assert_area_lowered_with(name, mesh, fraction, 0);
}

/* ---- the cases ----------------------------------------------------------------------------- */

/* Capsules: the conformal initial map squeezes each end by about e^-aspect. Up to aspect 30 the
 * one-puncture map resolves that; from aspect 40 its plane loses the far end in rounding, and the
 * two-puncture cylinder map (src/sphere/cylinder_initial_map.h) puts both ends at the poles,
 * where it is resolved (before: aspect 40 and 50 refused). The area monitor starts from the
 * equal-area cylinder map and lowers the area distortion by at least 40 % (measured 99 % at
 * every aspect: 6.31 -> 0.070 at 10, 41.8 -> 0.452 at 50; before, 70 % at 10 to 56 % at 30).
 * Under the sanitizers (RAPS_TEST_SANITIZER) aspect 50 is left out (the same paths as 40). */
static void capsules_map_bijectively_to_aspect_50(void** state) {
    (void)state;
    const double aspects[] = {10, 20, 30, 40, 50};
    const int count = getenv("RAPS_TEST_SANITIZER") != NULL ? 4 : 5;
    for (int k = 0; k < count; ++k) {
        test_mesh m = make_capsule(aspects[k], 24);
        char name[64];
        snprintf(name, sizeof(name), "capsule aspect %.0f", aspects[k]);
        assert_area_lowered(name, &m, 0.6);
        test_mesh_free(&m);
    }
}

/* Necks of 0.2 and 0.05 (48 sectors) and 0.02 (24 sectors; refused before the cylinder map):
 * the area monitor lowers the area distortion by at least 40 % (measured 6.21 -> 0.017, 22.4 ->
 * 0.069 and 53.1 -> 0.088 from the equal-area start; 0.02 reached 15 % before its floor on sliver
 * areas, src/sphere/cylinder_initial_map.cpp). A neck of 0.01 squeezes each ball by about e^-100
 * against the other: it maps or is refused with its status, never folded with RAPS_OK
 * (measured: the initial map refused, 16 folds; the adapted one maps). Under the sanitizers only
 * the first two. */
static void dumbbell_with_a_thin_neck_maps_bijectively_and_area_adapted(void** state) {
    (void)state;
    const double necks[] = {0.2, 0.05, 0.02, 0.01};
    const int sectors[] = {48, 48, 24, 24};
    const int count = getenv("RAPS_TEST_SANITIZER") != NULL ? 2 : 4;
    for (int k = 0; k < count; ++k) {
        test_mesh m = make_dumbbell(necks[k], sectors[k]);
        char name[64];
        snprintf(name, sizeof(name), "dumbbell neck %.2f", necks[k]);
        if (k < 3) assert_area_lowered(name, &m, 0.6);
        if (k == 3) {
            map_or_refuse(name, &m, RAPS_MONITOR_NONE);
            map_or_refuse(name, &m, RAPS_MONITOR_AREA);
        }
        test_mesh_free(&m);
    }
}

static void starfish_with_five_long_arms_maps_bijectively_and_area_adapted(void** state) {
    (void)state;
    test_mesh m = make_starfish(5.0, 5);
    assert_area_lowered("starfish reach 5", &m, 0.6);
    test_mesh_free(&m);
}

static void noisy_scan_like_sphere_maps_bijectively_and_area_adapted(void** state) {
    (void)state;
    test_mesh m = make_noisy_sphere(4);
    assert_area_lowered("noisy sphere", &m, 0.6);
    test_mesh_free(&m);
}

/* A sphere squashed to 2 % of its diameter: two nearly coincident sheets joined by a rim of
 * needles (ratio about 50). Measured: 0.477 -> 0.047 (5,120 triangles; 20,480: 0.722 -> 0.061). */
static void pancake_maps_bijectively_and_area_adapted(void** state) {
    (void)state;
    test_mesh m = subdivided_mesh(make_icosphere(0), 4, 1);
    for (size_t i = 0; i < m.vertex_count; ++i) m.positions[3 * i + 2] *= 0.02;
    assert_area_lowered("pancake 1:1:0.02", &m, 0.6);
    test_mesh_free(&m);
}

/* Hostile triangulations of a round sphere: latitude-longitude spheres of 200 sectors, whose
 * poles have degree 200; with 60 rings the polar triangles are needles (edge ratio about 30),
 * with 8 rings every triangle is (about 12 at the equator, 32 at the poles). The 8-ring sphere's
 * initial map is already equiareal (0.001), so there the area monitor only must not make it
 * worse. */
static void high_degree_vertices_and_needles_map_bijectively_and_centred(void** state) {
    (void)state;
    const int rings[] = {60, 8};
    const double fraction[] = {0.6, 1.0};
    for (int k = 0; k < 2; ++k) {
        test_mesh m = make_uv_sphere(rings[k], 200);
        char name[64];
        snprintf(name, sizeof(name), "uv sphere %d x 200", rings[k]);
        assert_area_lowered(name, &m, fraction[k]);
        test_mesh_free(&m);
    }
}

/* cow, horse_quad and decimated-knight subdivided to 88K, 77K and 64K triangles (midpoint
 * subdivision: the same shapes, many more triangles on the limbs). Initial and area-adapted:
 * both bijective by the exact sign of det and centred, and the area distortion lowered by at
 * least 40 %. Main before issue 18's third session returned the initial maps of cow x16 and
 * horse_quad x16 with RAPS_OK and 8 and 3 triangles folded by the exact determinant (its fold
 * tests read a rounded one; docs/sphere-status.md). */
/* Under the sanitizers (RAPS_TEST_SANITIZER, set by tests/CMakeLists.txt) only cow, not
 * subdivided (5.8K triangles): the same code paths, where ASan + UBSan run this test about twenty
 * times slower (78 s of ./quickstart test with cow x4); the shared build runs all three. */
static void subdivided_shared_meshes_with_long_limbs_map_bijectively_and_centred(void** state) {
    (void)state;
    const char* names[] = {"cow.off", "horse_quad.obj", "decimated-knight.off"};
    const int levels[] = {2, 2, 3};
    const int smaller = getenv("RAPS_TEST_SANITIZER") != NULL;
    for (int k = 0; k < (smaller ? 1 : 3); ++k) {
        const int level = smaller ? 0 : levels[k];
        test_mesh m = subdivided_mesh(load_shared_mesh(names[k]), level, 0);
        char name[64];
        snprintf(name, sizeof(name), "%s x%d", names[k], 1 << (2 * level));
        assert_area_lowered(name, &m, 0.6);
        test_mesh_free(&m);
    }
}

/* A relaxation cut short: 4 sweeps per relaxation on spot (5.8K triangles), the way every
 * relaxation of a mesh of several 100K triangles stops far from its fixed point at the default
 * sweeps (bunny subdivided to 446K: 27 % lower before). Where the continuation ends less than 40 %
 * below the initial map, the equal-area cylinder map competes as the result (measured: spot
 * 1.735 -> 0.615 with 4 sweeps; bunny x64 1.645 -> 0.505 at the defaults). */
static void sweep_limited_relaxation_still_lowers_the_area_by_40_percent(void** state) {
    (void)state;
    test_mesh m = load_shared_mesh("spot.obj");
    assert_area_lowered_with("spot.obj, 4 sweeps", &m, 0.6, 4);
    test_mesh_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(capsules_map_bijectively_to_aspect_50),
        cmocka_unit_test(dumbbell_with_a_thin_neck_maps_bijectively_and_area_adapted),
        cmocka_unit_test(starfish_with_five_long_arms_maps_bijectively_and_area_adapted),
        cmocka_unit_test(noisy_scan_like_sphere_maps_bijectively_and_area_adapted),
        cmocka_unit_test(pancake_maps_bijectively_and_area_adapted),
        cmocka_unit_test(high_degree_vertices_and_needles_map_bijectively_and_centred),
        cmocka_unit_test(subdivided_shared_meshes_with_long_limbs_map_bijectively_and_centred),
        cmocka_unit_test(sweep_limited_relaxation_still_lowers_the_area_by_40_percent),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
