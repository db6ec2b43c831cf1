/* Meshes for the tests: small analytic ones built here, and the shared real ones read from
 * disk. Tests drive the library through the C ABI only, exactly as an FFI user does. */
#ifndef RAPS_TEST_MESHES_H
#define RAPS_TEST_MESHES_H

#include <stddef.h>
#include <stdint.h>

#include "raps.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct test_mesh {
    double* positions; /* x, y, z per vertex */
    size_t vertex_count;
    uint32_t* indices; /* 3 per triangle, counter-clockwise */
    size_t index_count;
} test_mesh;

void test_mesh_free(test_mesh* mesh);

/* A mesh built vertex by vertex: start from {0}, add, then take .mesh (test_mesh_free frees it).
 * The add functions return the new vertex's index and fail the test when memory runs out. */
typedef struct test_mesh_builder {
    test_mesh mesh;
    size_t vertex_capacity, index_capacity;
} test_mesh_builder;
size_t test_mesh_add_vertex(test_mesh_builder* b, double x, double y, double z);
void test_mesh_add_triangle(test_mesh_builder* b, size_t i, size_t j, size_t k);

/* A flat disk in the z = 0 plane: a centre vertex, `rings` rings of `sectors * k` vertices at
 * radius k / rings (ring k, k = 1..rings), the outer ring equally spaced on the unit circle.
 * With jitter > 0 the interior vertices are moved by up to jitter * ring spacing (a fixed
 * pseudo-random pattern), so the triangulation is irregular. */
test_mesh make_flat_disk(int rings, int sectors, double jitter);

/* The same disk with each vertex lifted to z = height(x, y). */
test_mesh make_lifted_disk(int rings, int sectors, double (*height)(double x, double y));

/* A fan: one centre vertex and `rim` vertices on the unit circle at z = 0. */
test_mesh make_fan_disk(int rim);

/* An open cone of the given height over the unit disk: apex at (0, 0, height), the rim (its
 * one boundary loop) on the unit circle at z = 0. */
test_mesh make_open_cone(int rings, int sectors, double height);

/* A regular grid of (nx + 1) x (ny + 1) vertices on [0, width] x [0, height], z = 0. */
test_mesh make_grid(int nx, int ny, double width, double height);

/* Closed meshes and other topologies the disk domain refuses. */
test_mesh make_icosphere(int subdivisions);
/* A latitude-longitude sphere: the poles and rings - 1 rings of `sectors` vertices (closed,
 * genus 0; quick to build at any size, unlike the icosphere). */
test_mesh make_uv_sphere(int rings, int sectors);
test_mesh make_annulus(int rings, int sectors); /* two boundary loops */
test_mesh make_punctured_torus(int nu, int nv); /* one boundary loop, genus 1 */
test_mesh make_closed_torus(int nu, int nv);    /* no boundary, genus 1 */
/* `mesh` after `levels` midpoint subdivisions (1 -> 4 triangles each; the new vertices first
 * projected onto the unit sphere with onto_sphere). Takes `mesh` (frees it). */
test_mesh subdivided_mesh(test_mesh mesh, int levels, int onto_sphere);
/* `a` and `b` in one mesh (b's vertices after a's), b moved by (dx, dy, dz). */
test_mesh join_meshes(const test_mesh* a, const test_mesh* b, double dx, double dy, double dz);

/* Reads a mesh of the shared data set (.obj or .off; polygons fanned into triangles).
 * name is relative to the shared data's meshes/ folder. Fails the test if it cannot. */
test_mesh load_shared_mesh(const char* name);
/* The shared data folder (RAPS_SHARED_DATA_DIR at build time). */
const char* shared_data_dir(void);

/* A raps_mesh holding `mesh`; fails the test if the library refuses it. */
raps_mesh* to_raps_mesh(const test_mesh* mesh);

/* Runs raps_parameterize; fails the test (with the library's message) unless it returns OK. */
raps_result* parameterize_ok(const raps_mesh* mesh, const raps_settings* settings);

/* Convenience: settings with weights / monitor / alpha / iterations set. */
raps_settings* make_settings(int32_t weights, int32_t monitor, double alpha, int64_t iterations);

raps_stats stats_of(const raps_result* result);
/* uv pairs of a result, malloc'ed (free()). */
double* uvs_of(const raps_result* result);

#ifdef __cplusplus
}
#endif

/* assert |a - b| <= tol for doubles (cmocka's assert_float_equal compares floats). */
#define assert_near(a, b, tol)                                                             \
    do {                                                                                   \
        const double assert_near_a = (a), assert_near_b = (b), assert_near_t = (tol);      \
        if (!(assert_near_a - assert_near_b <= assert_near_t &&                            \
              assert_near_b - assert_near_a <= assert_near_t)) {                           \
            fail_msg("%s = %.12g, expected %s = %.12g within %.3g", #a, assert_near_a, #b, \
                     assert_near_b, assert_near_t);                                        \
        }                                                                                  \
    } while (0)

#define assert_below(a, b)                                                         \
    do {                                                                           \
        const double assert_below_a = (a), assert_below_b = (b);                   \
        if (!(assert_below_a < assert_below_b)) {                                  \
            fail_msg("%s = %.12g is not below %s = %.12g", #a, assert_below_a, #b, \
                     assert_below_b);                                              \
        }                                                                          \
    } while (0)

#define assert_status(call, expected)                                                 \
    do {                                                                              \
        const raps_status assert_status_s = (call);                                   \
        if (assert_status_s != (expected)) {                                          \
            fail_msg("%s returned %d (%s), expected %s", #call, (int)assert_status_s, \
                     raps_status_string(assert_status_s), #expected);                 \
        }                                                                             \
    } while (0)

#endif
