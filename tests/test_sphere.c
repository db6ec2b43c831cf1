/* The sphere domain (paper section 7) through the C ABI: bijective, centred maps of every shared
 * closed genus-0 mesh; the area monitor lowering spherical area distortion; a subdivided
 * icosahedron mapped onto itself; the same bits for any thread count; open, non-manifold and
 * genus > 0 meshes refused with their own status; the octahedral unfold; the literal method;
 * cancellation inside the sphere phases. Thresholds are values measured on this implementation
 * with a small margin (the current figures per mesh: docs/bench-method.md, "Sphere domain,
 * robust method"). */
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

static raps_settings* sphere_settings(int32_t method, int32_t monitor, int32_t uv) {
    raps_settings* s = NULL;
    assert_status(raps_settings_create(&s), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_SPHERE), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_SPHERE_METHOD, method), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_MONITOR, monitor), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_SPHERE_UV, uv), RAPS_OK);
    return s;
}

/* Per output vertex its point on the sphere, malloc'ed. */
static double* sphere_points_of(const raps_result* r) {
    const size_t n = raps_result_vertex_count(r);
    double* p = malloc(3 * n * sizeof(double) + 1);
    assert_non_null(p);
    assert_status(raps_result_copy_sphere_points_f64(r, p, n, 0), RAPS_OK);
    return p;
}

static void sub3(const double* a, const double* b, double* out) {
    for (int c = 0; c < 3; ++c) out[c] = a[c] - b[c];
}
static double dot3(const double* a, const double* b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static void cross3(const double* a, const double* b, double* out) {
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* What makes a spherical map a bijection that has not collapsed: unit points, every triangle
 * counter-clockwise seen from outside (det > 0), signed spherical areas (Van Oosterom and
 * Strackee) adding up to 4 pi, and the 3D-area-weighted centre of mass near the origin. */
typedef struct sphere_check {
    size_t folded;
    double area_sum;
    double centre;
    double worst_norm;
} sphere_check;

static sphere_check check_sphere_map(const test_mesh* mesh, const double* u) {
    sphere_check c = {0, 0.0, 0.0, 0.0};
    double centre[3] = {0, 0, 0}, total = 0;
    for (size_t i = 0; i < mesh->vertex_count; ++i) {
        c.worst_norm = fmax(c.worst_norm, fabs(sqrt(dot3(u + 3 * i, u + 3 * i)) - 1.0));
    }
    for (size_t t = 0; t < mesh->index_count; t += 3) {
        const uint32_t* v = mesh->indices + t;
        const double *a = u + 3 * v[0], *b = u + 3 * v[1], *d = u + 3 * v[2];
        double bc[3];
        cross3(b, d, bc);
        const double det = dot3(a, bc);
        c.folded += !(det > 0);
        c.area_sum += 2.0 * atan2(det, 1.0 + dot3(a, b) + dot3(b, d) + dot3(d, a));
        double e1[3], e2[3], n[3];
        sub3(mesh->positions + 3 * v[1], mesh->positions + 3 * v[0], e1);
        sub3(mesh->positions + 3 * v[2], mesh->positions + 3 * v[0], e2);
        cross3(e1, e2, n);
        const double area = 0.5 * sqrt(dot3(n, n));
        for (int k = 0; k < 3; ++k) {
            for (int q = 0; q < 3; ++q) centre[q] += area / 3.0 * u[3 * v[k] + q];
        }
        total += area;
    }
    c.centre = sqrt(dot3(centre, centre)) / total;
    return c;
}

static sphere_check assert_bijective(const char* name, const test_mesh* mesh, const double* u) {
    const sphere_check c = check_sphere_map(mesh, u);
    if (c.folded != 0 || fabs(c.area_sum - 4.0 * M_PI) > 1e-6 || c.centre > 0.01 ||
        c.worst_norm > 1e-12) {
        fail_msg(
            "%s: %zu folded, spherical areas sum to %.9f (4 pi = %.9f), centre %.3g, "
            "|norm - 1| up to %.2g",
            name, c.folded, c.area_sum, 4.0 * M_PI, c.centre, c.worst_norm);
    }
    return c;
}

static const char* kSpheres[] = {
    "bunny.off",         "cheburashka.off", "cow.off",        "decimated-knight.off",
    "decimated-max.obj", "fandisk.obj",     "horse_quad.obj", "spot.obj"};

/* Every shared genus-0 mesh: the initial map (monitor none) and the area-adapted one are
 * bijective and centred, and the area monitor lowers the spherical area distortion by at least
 * 40 % (issue 18's promise). Measured (mean |log r| with exact spherical areas, initial -> area
 * alpha 1; docs/sphere-status.md): bunny 1.641 -> 0.651, cheburashka 2.455 -> 0.907, cow 2.839
 * -> 1.631, decimated-knight 4.550 -> 2.121, decimated-max 0.605 -> 0.211, fandisk 0.729 ->
 * 0.181, horse_quad 3.772 -> 1.650, spot 2.061 -> 0.650; centre of mass at most 1.5e-3 from
 * the origin. The bounds below are those figures plus 8 % (cow: the 40 %), since last-bit
 * changes move the continuation's path: the own elementary functions (issue 19) took cow from
 * 1.468 to 1.631. */
static void shared_meshes_map_bijectively_and_the_area_monitor_equidistributes(void** state) {
    (void)state;
    const double initial_at_least[] = {1.58, 2.40, 2.80, 4.50, 0.57, 0.70, 3.70, 2.00};
    const double adapted_at_most[] = {0.70, 0.98, 1.70, 2.29, 0.23, 0.20, 1.78, 0.70};
    raps_settings* initial = sphere_settings(RAPS_SPHERE_ROBUST, RAPS_MONITOR_NONE, 0);
    raps_settings* adapted = sphere_settings(RAPS_SPHERE_ROBUST, RAPS_MONITOR_AREA, 0);
    /* Under the sanitizers (RAPS_TEST_SANITIZER, tests/CMakeLists.txt) every other mesh: the
     * same code paths, since ASan runs this test about five times slower; the shared and static
     * builds run all eight. */
    const size_t step = getenv("RAPS_TEST_SANITIZER") != NULL ? 2 : 1;
    for (size_t m = 0; m < sizeof(kSpheres) / sizeof(kSpheres[0]); m += step) {
        test_mesh mesh = load_shared_mesh(kSpheres[m]);
        raps_mesh* handle = to_raps_mesh(&mesh);
        raps_result* r0 = parameterize_ok(handle, initial);
        raps_result* r1 = parameterize_ok(handle, adapted);
        const raps_stats s0 = stats_of(r0), s1 = stats_of(r1);
        double* u0 = sphere_points_of(r0);
        double* u1 = sphere_points_of(r1);
        const sphere_check c0 = assert_bijective(kSpheres[m], &mesh, u0);
        const sphere_check c1 = assert_bijective(kSpheres[m], &mesh, u1);
        print_message(
            "%-18s spherical area |log r| %.3f -> %.3f, flipped %llu, %llu sweeps, "
            "centre %.1e, %.1e\n",
            kSpheres[m], s0.area_log_mean, s1.area_log_mean,
            (unsigned long long)s1.flipped_triangles, (unsigned long long)s1.relaxation_sweeps,
            c0.centre, c1.centre);
        assert_int_equal(s0.flipped_triangles, 0);
        assert_int_equal(s1.flipped_triangles, 0);
        assert_int_equal(s1.vertex_count, mesh.vertex_count);
        assert_true(s1.relaxation_sweeps > s0.relaxation_sweeps);
        assert_true(s0.area_log_mean >= initial_at_least[m]);
        assert_below(s1.area_log_mean, adapted_at_most[m]);
        assert_below(s1.area_log_mean, 0.6 * s0.area_log_mean);
        free(u0);
        free(u1);
        raps_result_destroy(r0);
        raps_result_destroy(r1);
        raps_mesh_destroy(handle);
        test_mesh_free(&mesh);
    }
    raps_settings_destroy(initial);
    raps_settings_destroy(adapted);
}

/* The rotation R minimising sum |u_i - R x_i|^2 among linear maps, R = (sum u x^T)(sum x x^T)^-1,
 * must come out orthogonal and fit every point: then u is x turned. */
static void assert_rotation_of(const test_mesh* mesh, const double* u, double tolerance) {
    double ux[3][3] = {{0}}, xx[3][3] = {{0}};
    for (size_t i = 0; i < mesh->vertex_count; ++i) {
        const double* x = mesh->positions + 3 * i;
        for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < 3; ++b) {
                ux[a][b] += u[3 * i + a] * x[b];
                xx[a][b] += x[a] * x[b];
            }
        }
    }
    double inv[3][3];
    const double det = xx[0][0] * (xx[1][1] * xx[2][2] - xx[1][2] * xx[2][1]) -
                       xx[0][1] * (xx[1][0] * xx[2][2] - xx[1][2] * xx[2][0]) +
                       xx[0][2] * (xx[1][0] * xx[2][1] - xx[1][1] * xx[2][0]);
    for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
            const int a1 = (b + 1) % 3, a2 = (b + 2) % 3, b1 = (a + 1) % 3, b2 = (a + 2) % 3;
            inv[a][b] = (xx[a1][b1] * xx[a2][b2] - xx[a1][b2] * xx[a2][b1]) / det;
        }
    }
    double r[3][3] = {{0}};
    for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
            for (int k = 0; k < 3; ++k) r[a][b] += ux[a][k] * inv[k][b];
        }
    }
    double orthogonality = 0, worst = 0;
    for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
            double rtr = 0;
            for (int k = 0; k < 3; ++k) rtr += r[k][a] * r[k][b];
            orthogonality = fmax(orthogonality, fabs(rtr - (a == b)));
        }
    }
    for (size_t i = 0; i < mesh->vertex_count; ++i) {
        double d2 = 0;
        for (int a = 0; a < 3; ++a) {
            double rx = 0;
            for (int k = 0; k < 3; ++k) rx += r[a][k] * mesh->positions[3 * i + k];
            d2 += (u[3 * i + a] - rx) * (u[3 * i + a] - rx);
        }
        worst = fmax(worst, sqrt(d2));
    }
    print_message("best linear fit: |R^T R - I| %.2e, largest distance %.2e\n", orthogonality,
                  worst);
    assert_below(orthogonality, tolerance);
    assert_below(worst, tolerance);
}

/* A subdivided icosahedron whose vertices lie on the unit sphere is its own spherical map: both
 * methods, with and without the area monitor, return it turned. Measured largest distance to
 * the best rotation: robust 3.3e-4 (no monitor), 7.5e-5 (area); literal 1.2e-4, 6.0e-5. */
static void a_subdivided_icosahedron_maps_to_itself_up_to_rotation(void** state) {
    (void)state;
    test_mesh ico = make_icosphere(3);
    raps_mesh* handle = to_raps_mesh(&ico);
    const int32_t methods[] = {RAPS_SPHERE_ROBUST, RAPS_SPHERE_LITERAL};
    const int32_t monitors[] = {RAPS_MONITOR_NONE, RAPS_MONITOR_AREA};
    for (int m = 0; m < 2; ++m) {
        for (int k = 0; k < 2; ++k) {
            raps_settings* s = sphere_settings(methods[m], monitors[k], 0);
            raps_result* r = parameterize_ok(handle, s);
            double* u = sphere_points_of(r);
            assert_bijective("icosphere", &ico, u);
            assert_rotation_of(&ico, u, 1e-3);
            assert_below(stats_of(r).area_log_mean, 2e-3);
            free(u);
            raps_result_destroy(r);
            raps_settings_destroy(s);
        }
    }
    raps_mesh_destroy(handle);
    test_mesh_free(&ico);
}

/* A closed genus-0 mesh of any size: a latitude-longitude sphere with its radius rippled, so
 * that the map has work to do. */
static test_mesh make_bumpy_sphere(int rings, int sectors) {
    test_mesh m = make_uv_sphere(rings, sectors);
    for (size_t i = 0; i < m.vertex_count; ++i) {
        double* p = m.positions + 3 * i;
        const double r = 1.0 + 0.2 * sin(3.0 * p[0]) * cos(2.0 * p[1]) + 0.15 * p[2] * p[2];
        for (int c = 0; c < 3; ++c) p[c] *= r;
    }
    return m;
}

/* The relaxation runs on RAPS_PARAM_THREADS threads with a fixed split of the work: 2, 3 and 4
 * threads give the bits of 1 thread, for the sphere points and for the octahedral uvs. The mesh
 * is large enough that the sphere domain shares the relaxation out (one thread per 4,096
 * vertices: 3 here) and small enough that the statistics do not (below 32,768 triangles), so
 * the threads the statistics report computed are the relaxation's (measured: 1, 2, 3 and 3, on
 * 2 cores at a load average of 4 to 5). A worker counts once it has computed a share, which a
 * busy scheduler may deny it: each run with threads must have had at least one worker compute,
 * and none more than the mesh allows. */
static void output_is_bit_identical_for_any_thread_count(void** state) {
    (void)state;
    test_mesh mesh = make_bumpy_sphere(96, 170); /* 16,152 vertices, 32,300 triangles */
    raps_mesh* handle = to_raps_mesh(&mesh);
    double *first_points = NULL, *first_uvs = NULL;
    size_t count = 0;
    for (int threads = 1; threads <= 4; ++threads) {
        raps_settings* s =
            sphere_settings(RAPS_SPHERE_ROBUST, RAPS_MONITOR_AREA, RAPS_SPHERE_UV_OCTAHEDRAL);
        assert_status(raps_settings_set_int(s, RAPS_PARAM_THREADS, threads), RAPS_OK);
        assert_status(raps_settings_set_int(s, RAPS_PARAM_SPHERE_MAX_SWEEPS, 30), RAPS_OK);
        raps_result* r = parameterize_ok(handle, s);
        const raps_stats stats = stats_of(r);
        print_message("%d threads asked: %llu computed, %llu sweeps\n", threads,
                      (unsigned long long)stats.threads_used,
                      (unsigned long long)stats.relaxation_sweeps);
        if (threads == 1) {
            assert_int_equal(stats.threads_used, 1);
        } else {
            assert_true(stats.threads_used >= 2);
            assert_true(stats.threads_used <= (uint64_t)(threads < 3 ? threads : 3));
        }
        double* points = sphere_points_of(r);
        double* uvs = uvs_of(r);
        if (threads == 1) {
            first_points = points;
            first_uvs = uvs;
            count = raps_result_vertex_count(r);
        } else {
            assert_int_equal(raps_result_vertex_count(r), count);
            assert_memory_equal(points, first_points, 3 * count * sizeof(double));
            assert_memory_equal(uvs, first_uvs, 2 * count * sizeof(double));
            free(points);
            free(uvs);
        }
        raps_result_destroy(r);
        raps_settings_destroy(s);
    }
    free(first_points);
    free(first_uvs);
    raps_mesh_destroy(handle);
    test_mesh_free(&mesh);
}

static void expect_sphere_refusal(const test_mesh* mesh, raps_status expected,
                                  const char* fragment) {
    raps_mesh* m = to_raps_mesh(mesh);
    raps_settings* s = sphere_settings(RAPS_SPHERE_ROBUST, RAPS_MONITOR_AREA, 0);
    raps_result* r = NULL;
    assert_status(raps_result_create(&r), RAPS_OK);
    const raps_status status = raps_parameterize(m, s, r);
    if (status != expected) {
        fail_msg("got %s (%s), expected %s", raps_status_string(status), raps_result_last_error(r),
                 raps_status_string(expected));
    }
    const char* message = raps_result_last_error(r);
    if (!strstr(message, fragment)) fail_msg("message '%s' lacks '%s'", message, fragment);
    assert_int_equal(raps_result_vertex_count(r), 0);
    double point[3];
    assert_status(raps_result_copy_sphere_points_f64(r, point, 1, 0), RAPS_ERROR_INVALID_OPERATION);
    raps_result_destroy(r);
    raps_settings_destroy(s);
    raps_mesh_destroy(m);
}

/* Each kind of mesh the sphere cannot take gets its own status and a message. */
static void open_non_manifold_and_genus_meshes_are_refused(void** state) {
    (void)state;
    test_mesh disk = make_flat_disk(3, 6, 0.0);
    expect_sphere_refusal(&disk, RAPS_ERROR_OPEN_MESH,
                          "needs a closed mesh: it has 1 boundary loop");
    test_mesh annulus = make_annulus(3, 6);
    expect_sphere_refusal(&annulus, RAPS_ERROR_OPEN_MESH, "2 boundary loops");
    test_mesh torus = make_closed_torus(8, 6);
    expect_sphere_refusal(&torus, RAPS_ERROR_NONZERO_GENUS, "genus 1");
    test_mesh sphere = make_icosphere(1);
    test_mesh two = join_meshes(&sphere, &sphere, 3.0, 0.0, 0.0);
    expect_sphere_refusal(&two, RAPS_ERROR_MULTIPLE_COMPONENTS, "2 separate pieces");
    /* Two spheres touching at one point: the second, moved by twice the first's vertex 0, has
     * its vertex antipodal to 0 there; that vertex becomes vertex 0 itself. */
    size_t antipode = 0;
    for (size_t i = 1; i < sphere.vertex_count; ++i) {
        if (dot3(sphere.positions + 3 * i, sphere.positions) <
            dot3(sphere.positions + 3 * antipode, sphere.positions)) {
            antipode = i;
        }
    }
    test_mesh pinched = join_meshes(&sphere, &sphere, 2.0 * sphere.positions[0],
                                    2.0 * sphere.positions[1], 2.0 * sphere.positions[2]);
    const uint32_t merged = (uint32_t)(sphere.vertex_count + antipode);
    const uint32_t last = (uint32_t)pinched.vertex_count - 1;
    for (size_t i = 0; i < pinched.index_count; ++i) {
        if (pinched.indices[i] == merged) pinched.indices[i] = 0;
    }
    /* The merged vertex's slot is now unused: the last vertex moves into it. */
    memcpy(pinched.positions + 3 * merged, pinched.positions + 3 * last, 3 * sizeof(double));
    for (size_t i = 0; i < pinched.index_count; ++i) {
        if (pinched.indices[i] == last) pinched.indices[i] = merged;
    }
    pinched.vertex_count--;
    expect_sphere_refusal(&pinched, RAPS_ERROR_NON_MANIFOLD_VERTEX, "vertex 0");
    /* A fin: a third triangle on an edge of a closed sphere. */
    test_mesh fin = join_meshes(&sphere, &sphere, 0, 0, 0);
    fin.vertex_count = sphere.vertex_count + 1;
    fin.index_count = sphere.index_count + 3;
    fin.positions[3 * sphere.vertex_count] = 2.0;
    fin.indices[sphere.index_count] = sphere.indices[0];
    fin.indices[sphere.index_count + 1] = sphere.indices[1];
    fin.indices[sphere.index_count + 2] = (uint32_t)sphere.vertex_count;
    expect_sphere_refusal(&fin, RAPS_ERROR_NON_MANIFOLD_EDGE, "more than two triangles");
    test_mesh genus3 = load_shared_mesh("3holes.off");
    expect_sphere_refusal(&genus3, RAPS_ERROR_NONZERO_GENUS, "genus 3");
    test_mesh_free(&genus3);
    test_mesh_free(&fin);
    test_mesh_free(&pinched);
    test_mesh_free(&two);
    test_mesh_free(&sphere);
    test_mesh_free(&torus);
    test_mesh_free(&annulus);
    test_mesh_free(&disk);
}

/* The octahedral unfold: one chart in [0, 1]^2, no flipped uv triangle, every input triangle
 * present through the remap, the cut's vertices duplicated, the sphere points those of the map
 * without uvs. */
static void octahedral_unfold_gives_one_flip_free_chart(void** state) {
    (void)state;
    const char* names[] = {"spot.obj", "fandisk.obj"};
    for (int m = 0; m < 2; ++m) {
        test_mesh mesh = load_shared_mesh(names[m]);
        raps_mesh* handle = to_raps_mesh(&mesh);
        raps_settings* plain = sphere_settings(RAPS_SPHERE_ROBUST, RAPS_MONITOR_AREA, 0);
        raps_settings* unfolded =
            sphere_settings(RAPS_SPHERE_ROBUST, RAPS_MONITOR_AREA, RAPS_SPHERE_UV_OCTAHEDRAL);
        raps_result* r0 = parameterize_ok(handle, plain);
        raps_result* r = parameterize_ok(handle, unfolded);
        const size_t n = raps_result_vertex_count(r);
        assert_true(n > mesh.vertex_count);
        assert_int_equal(raps_result_index_count(r), mesh.index_count);
        uint32_t* remap = malloc(n * sizeof(uint32_t));
        uint32_t* indices = malloc(mesh.index_count * sizeof(uint32_t));
        assert_status(raps_result_copy_vertex_remap(r, remap, n), RAPS_OK);
        assert_status(raps_result_copy_indices_u32(r, indices, mesh.index_count), RAPS_OK);
        double* uv = uvs_of(r);
        double* u = sphere_points_of(r);
        double* u0 = sphere_points_of(r0);
        for (size_t o = 0; o < n; ++o) {
            assert_true(remap[o] < mesh.vertex_count);
            if (o < mesh.vertex_count) assert_int_equal(remap[o], o);
            assert_true(uv[2 * o] >= 0.0 && uv[2 * o] <= 1.0);
            assert_true(uv[2 * o + 1] >= 0.0 && uv[2 * o + 1] <= 1.0);
            assert_memory_equal(u + 3 * o, u0 + 3 * remap[o], 3 * sizeof(double));
        }
        size_t flipped = 0;
        double uv_area = 0;
        for (size_t t = 0; t < mesh.index_count; t += 3) {
            for (int k = 0; k < 3; ++k)
                assert_int_equal(remap[indices[t + k]], mesh.indices[t + k]);
            const double* a = uv + 2 * indices[t];
            const double* b = uv + 2 * indices[t + 1];
            const double* c = uv + 2 * indices[t + 2];
            const double area =
                0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
            flipped += !(area > 0);
            uv_area += area;
        }
        const raps_stats s = stats_of(r);
        print_message("%s: %zu output vertices for %zu, uv area %.9f, stretch L2 %.2f\n", names[m],
                      n, mesh.vertex_count, uv_area, s.stretch_l2);
        assert_int_equal(flipped, 0);
        assert_int_equal(s.flipped_triangles, 0);
        assert_int_equal(s.vertex_count, n);
        assert_near(uv_area, 1.0, 1e-9); /* one chart covering the square */
        /* The fraction of the square covered, never above it (the C# tests saw bunny sum to just
         * above 1). */
        assert_true(s.utilization > 1.0 - 1e-9 && s.utilization <= 1.0);
        free(uv);
        free(u);
        free(u0);
        free(remap);
        free(indices);
        raps_result_destroy(r);
        raps_result_destroy(r0);
        raps_settings_destroy(unfolded);
        raps_settings_destroy(plain);
        raps_mesh_destroy(handle);
        test_mesh_free(&mesh);
    }
}

/* RAPS_SPHERE_LITERAL is algorithm 7.1 as written. Measured on spot, damping 0.5, 1,500 sweeps:
 * 413 folded triangles (1,968 with damping 1 after 3,000), where the robust method folds none. */
static void the_literal_algorithm_is_available_and_folds(void** state) {
    (void)state;
    test_mesh mesh = load_shared_mesh("spot.obj");
    raps_mesh* handle = to_raps_mesh(&mesh);
    raps_settings* s = sphere_settings(RAPS_SPHERE_LITERAL, RAPS_MONITOR_NONE, 0);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_SPHERE_MAX_SWEEPS, 1500), RAPS_OK);
    assert_status(raps_settings_set_float(s, RAPS_PARAM_SPHERE_DAMPING, 0.5), RAPS_OK);
    raps_result* r = parameterize_ok(handle, s);
    const raps_stats stats = stats_of(r);
    print_message("literal on spot: %llu folded after %llu sweeps\n",
                  (unsigned long long)stats.flipped_triangles,
                  (unsigned long long)stats.relaxation_sweeps);
    assert_true(stats.flipped_triangles > 0);
    assert_int_equal(stats.relaxation_sweeps, 1500);
    raps_result_destroy(r);
    raps_settings_destroy(s);
    raps_mesh_destroy(handle);
    test_mesh_free(&mesh);
}

/* Cancels at the first call (after `skip`) in the target phase and fraction window. */
typedef struct cancel_state {
    raps_phase phase;
    double from, to;
    int skip; /* matching calls to let pass first */
    int cancelled;
} cancel_state;

static int32_t cancel_inside(void* user, raps_phase phase, double fraction) {
    cancel_state* c = user;
    assert_true(phase >= 0 && phase < RAPS_PHASE_COUNT);
    assert_true(fraction >= 0.0 && fraction <= 1.0);
    if (phase == c->phase && fraction > c->from && fraction < c->to && c->skip-- == 0) {
        c->cancelled = 1;
        return 0;
    }
    return 1;
}

/* Cancellation reaches into the relaxation loops: in the initial map's relaxation, in the middle
 * of the adaptive relaxations, and in the octahedral unfold. The handles stay usable. */
static void cancellation_works_inside_the_sphere_phases(void** state) {
    (void)state;
    test_mesh mesh = load_shared_mesh("spot.obj");
    raps_mesh* handle = to_raps_mesh(&mesh);
    raps_settings* s =
        sphere_settings(RAPS_SPHERE_ROBUST, RAPS_MONITOR_AREA, RAPS_SPHERE_UV_OCTAHEDRAL);
    raps_result* r = NULL;
    assert_status(raps_result_create(&r), RAPS_OK);
    /* The initial map's relaxation (the second half of its phase), an adaptive relaxation (the
     * first four fifths of ADAPT), and the unfold's solve (inside the last fifth). */
    const cancel_state points[] = {{RAPS_PHASE_INITIAL_MAP, 0.6, 0.9, 0, 0},
                                   {RAPS_PHASE_ADAPT, 0.3, 0.7, 0, 0},
                                   {RAPS_PHASE_ADAPT, 0.9, 0.999, 1, 0}};
    for (size_t p = 0; p < sizeof(points) / sizeof(points[0]); ++p) {
        cancel_state c = points[p];
        assert_status(raps_settings_set_progress(s, cancel_inside, &c), RAPS_OK);
        assert_status(raps_parameterize(handle, s, r), RAPS_ERROR_CANCELLED);
        assert_true(c.cancelled);
        assert_non_null(strstr(raps_result_last_error(r), "cancelled"));
        assert_int_equal(raps_result_vertex_count(r), 0);
    }
    assert_status(raps_settings_set_progress(s, NULL, NULL), RAPS_OK);
    assert_status(raps_parameterize(handle, s, r), RAPS_OK);
    assert_true(raps_result_vertex_count(r) > mesh.vertex_count);
    raps_result_destroy(r);
    raps_settings_destroy(s);
    raps_mesh_destroy(handle);
    test_mesh_free(&mesh);
}

/* The result accessors of the sphere domain: points as f32 and f64 through a stride, the input
 * vertices and triangles, no uvs without the unfold; a disk result has no sphere points. */
static void sphere_results_answer_their_accessors(void** state) {
    (void)state;
    test_mesh ico = make_icosphere(2);
    raps_mesh* handle = to_raps_mesh(&ico);
    raps_settings* s = sphere_settings(RAPS_SPHERE_ROBUST, RAPS_MONITOR_AREA, 0);
    raps_result* r = parameterize_ok(handle, s);
    const size_t n = raps_result_vertex_count(r);
    assert_int_equal(n, ico.vertex_count);
    assert_int_equal(raps_result_index_count(r), ico.index_count);
    double* packed = sphere_points_of(r);
    float* strided = malloc(n * 4 * sizeof(float));
    assert_status(raps_result_copy_sphere_points_f32(r, strided, n - 1, 0),
                  RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_result_copy_sphere_points_f32(r, strided, n, 8),
                  RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_result_copy_sphere_points_f32(r, NULL, n, 0), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_result_copy_sphere_points_f32(r, strided, n, 4 * sizeof(float)), RAPS_OK);
    for (size_t i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) assert_near(strided[4 * i + c], packed[3 * i + c], 1e-6);
    }
    uint32_t* indices = malloc(ico.index_count * sizeof(uint32_t));
    uint32_t* remap = malloc(n * sizeof(uint32_t));
    assert_status(raps_result_copy_indices_u32(r, indices, ico.index_count), RAPS_OK);
    assert_memory_equal(indices, ico.indices, ico.index_count * sizeof(uint32_t));
    assert_status(raps_result_copy_vertex_remap(r, remap, n), RAPS_OK);
    for (size_t i = 0; i < n; ++i) assert_int_equal(remap[i], i);
    double uv[2];
    assert_status(raps_result_copy_uvs_f64(r, uv, n, 0), RAPS_ERROR_INVALID_OPERATION);
    const raps_stats stats = stats_of(r);
    assert_true(stats.relaxation_sweeps > 0);
    assert_int_equal(stats.adaptive_solves, 2); /* one iteration in 2 continuation steps */
    assert_true(raps_result_phase_ms(r, RAPS_PHASE_INITIAL_MAP) > 0.0);
    assert_true(raps_result_phase_ms(r, RAPS_PHASE_ADAPT) > 0.0);

    test_mesh disk = make_flat_disk(3, 6, 0.0);
    raps_mesh* disk_handle = to_raps_mesh(&disk);
    raps_result* d = parameterize_ok(disk_handle, NULL);
    assert_status(raps_result_copy_sphere_points_f64(d, packed, n, 0),
                  RAPS_ERROR_INVALID_OPERATION);
    assert_int_equal(stats_of(d).relaxation_sweeps, 0);

    free(packed);
    free(strided);
    free(indices);
    free(remap);
    raps_result_destroy(d);
    raps_mesh_destroy(disk_handle);
    test_mesh_free(&disk);
    raps_result_destroy(r);
    raps_settings_destroy(s);
    raps_mesh_destroy(handle);
    test_mesh_free(&ico);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(shared_meshes_map_bijectively_and_the_area_monitor_equidistributes),
        cmocka_unit_test(a_subdivided_icosahedron_maps_to_itself_up_to_rotation),
        cmocka_unit_test(output_is_bit_identical_for_any_thread_count),
        cmocka_unit_test(open_non_manifold_and_genus_meshes_are_refused),
        cmocka_unit_test(octahedral_unfold_gives_one_flip_free_chart),
        cmocka_unit_test(the_literal_algorithm_is_available_and_folds),
        cmocka_unit_test(cancellation_works_inside_the_sphere_phases),
        cmocka_unit_test(sphere_results_answer_their_accessors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
