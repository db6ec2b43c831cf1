#include "test_meshes.h"

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

size_t test_mesh_add_vertex(test_mesh_builder* b, double x, double y, double z) {
    if (b->mesh.vertex_count == b->vertex_capacity) {
        b->vertex_capacity = b->vertex_capacity ? 2 * b->vertex_capacity : 64;
        b->mesh.positions = realloc(b->mesh.positions, 3 * b->vertex_capacity * sizeof(double));
        assert_non_null(b->mesh.positions);
    }
    double* p = b->mesh.positions + 3 * b->mesh.vertex_count;
    p[0] = x;
    p[1] = y;
    p[2] = z;
    return b->mesh.vertex_count++;
}

void test_mesh_add_triangle(test_mesh_builder* b, size_t i, size_t j, size_t k) {
    if (b->mesh.index_count + 3 > b->index_capacity) {
        b->index_capacity = b->index_capacity ? 2 * b->index_capacity : 192;
        b->mesh.indices = realloc(b->mesh.indices, b->index_capacity * sizeof(uint32_t));
        assert_non_null(b->mesh.indices);
    }
    uint32_t* t = b->mesh.indices + b->mesh.index_count;
    t[0] = (uint32_t)i;
    t[1] = (uint32_t)j;
    t[2] = (uint32_t)k;
    b->mesh.index_count += 3;
}

void test_mesh_free(test_mesh* mesh) {
    free(mesh->positions);
    free(mesh->indices);
    memset(mesh, 0, sizeof(*mesh));
}

/* A fixed pseudo-random sequence in [-1, 1] (no global state: the caller keeps the seed). */
static double jitter_value(uint32_t* state) {
    *state = *state * 1664525u + 1013904223u;
    return ((double)(*state >> 8) / (double)(1u << 24)) * 2.0 - 1.0;
}

/* Polar disk: ring k (k = 1..rings) has sectors * k vertices at radius k / rings. Consecutive
 * rings are stitched by walking both in angle order. first_ring = 0 adds the centre vertex. */
static test_mesh polar_disk(int rings, int sectors, double jitter, int first_ring,
                            double (*height)(double, double), double cone_height) {
    test_mesh_builder b;
    memset(&b, 0, sizeof(b));
    size_t* ring_start = calloc((size_t)rings + 2, sizeof(size_t));
    int* ring_size = calloc((size_t)rings + 2, sizeof(int));
    assert_non_null(ring_start);
    assert_non_null(ring_size);
    uint32_t seed = 12345u;
    for (int k = first_ring; k <= rings; ++k) {
        ring_start[k] = b.mesh.vertex_count;
        ring_size[k] = k == 0 ? 1 : sectors * k;
        for (int s = 0; s < ring_size[k]; ++s) {
            const double r = (double)k / rings;
            const double a = 2.0 * M_PI * s / ring_size[k];
            double x = r * cos(a), y = r * sin(a);
            if (jitter > 0 && k > 0 && k < rings) {
                x += jitter_value(&seed) * jitter / rings;
                y += jitter_value(&seed) * jitter / rings;
            }
            double z = height ? height(x, y) : 0.0;
            if (cone_height > 0) z = cone_height * (1.0 - r);
            test_mesh_add_vertex(&b, x, y, z);
        }
    }
    for (int k = first_ring; k < rings; ++k) {
        /* Stitch ring k (inner) and ring k + 1 (outer) by merging their angle sequences. */
        const int n_in = ring_size[k], n_out = ring_size[k + 1];
        if (k == 0) { /* the centre's fan */
            for (int o = 0; o < n_out; ++o) {
                test_mesh_add_triangle(&b, 0, ring_start[1] + (size_t)o,
                                       ring_start[1] + (size_t)((o + 1) % n_out));
            }
            continue;
        }
        int i = 0, o = 0;
        while (i < n_in || o < n_out) {
            const double next_in = (double)(i + 1) / n_in, next_out = (double)(o + 1) / n_out;
            const size_t in0 = ring_start[k] + (size_t)(i % n_in);
            const size_t out0 = ring_start[k + 1] + (size_t)(o % n_out);
            if (o < n_out && (i >= n_in || next_out <= next_in)) {
                test_mesh_add_triangle(&b, in0, out0,
                                       ring_start[k + 1] + (size_t)((o + 1) % n_out));
                ++o;
            } else {
                test_mesh_add_triangle(&b, in0, out0, ring_start[k] + (size_t)((i + 1) % n_in));
                ++i;
            }
        }
    }
    free(ring_start);
    free(ring_size);
    return b.mesh;
}

test_mesh make_flat_disk(int rings, int sectors, double jitter) {
    return polar_disk(rings, sectors, jitter, 0, NULL, 0.0);
}

test_mesh make_lifted_disk(int rings, int sectors, double (*height)(double x, double y)) {
    return polar_disk(rings, sectors, 0.0, 0, height, 0.0);
}

test_mesh make_fan_disk(int rim) {
    return polar_disk(1, rim, 0.0, 0, NULL, 0.0);
}

test_mesh make_open_cone(int rings, int sectors, double height) {
    return polar_disk(rings, sectors, 0.0, 0, NULL, height);
}

test_mesh make_annulus(int rings, int sectors) {
    return polar_disk(rings, sectors, 0.0, 1, NULL, 0.0);
}

test_mesh make_grid(int nx, int ny, double width, double height) {
    test_mesh_builder b;
    memset(&b, 0, sizeof(b));
    for (int j = 0; j <= ny; ++j) {
        for (int i = 0; i <= nx; ++i)
            test_mesh_add_vertex(&b, width * i / nx, height * j / ny, 0.0);
    }
    for (int j = 0; j < ny; ++j) {
        for (int i = 0; i < nx; ++i) {
            const size_t a = (size_t)j * (nx + 1) + i, c = a + (size_t)nx + 1;
            test_mesh_add_triangle(&b, a, a + 1, c + 1);
            test_mesh_add_triangle(&b, a, c + 1, c);
        }
    }
    return b.mesh;
}

test_mesh make_icosphere(int subdivisions) {
    test_mesh_builder b;
    memset(&b, 0, sizeof(b));
    const double t = (1.0 + sqrt(5.0)) / 2.0;
    const double v[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                             {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                             {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    const int f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                          {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                          {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                          {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int i = 0; i < 12; ++i) {
        const double n = sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
        test_mesh_add_vertex(&b, v[i][0] / n, v[i][1] / n, v[i][2] / n);
    }
    for (int i = 0; i < 20; ++i) test_mesh_add_triangle(&b, f[i][0], f[i][1], f[i][2]);
    for (int s = 0; s < subdivisions; ++s) {
        /* 1-to-4 split with midpoints projected to the sphere; midpoints found by a linear
         * scan of the new vertices (tiny meshes only). */
        test_mesh old = b.mesh;
        test_mesh_builder next;
        memset(&next, 0, sizeof(next));
        for (size_t i = 0; i < old.vertex_count; ++i) {
            test_mesh_add_vertex(&next, old.positions[3 * i], old.positions[3 * i + 1],
                                 old.positions[3 * i + 2]);
        }
        for (size_t t3 = 0; t3 < old.index_count; t3 += 3) {
            size_t mid[3];
            for (int e = 0; e < 3; ++e) {
                const uint32_t a = old.indices[t3 + e], c = old.indices[t3 + (e + 1) % 3];
                double p[3];
                for (int k = 0; k < 3; ++k)
                    p[k] = old.positions[3 * a + k] + old.positions[3 * c + k];
                const double n = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
                size_t found = (size_t)-1;
                for (size_t q = old.vertex_count; q < next.mesh.vertex_count; ++q) {
                    const double* x = next.mesh.positions + 3 * q;
                    if (fabs(x[0] - p[0] / n) + fabs(x[1] - p[1] / n) + fabs(x[2] - p[2] / n) <
                        1e-12) {
                        found = q;
                    }
                }
                mid[e] = found != (size_t)-1
                             ? found
                             : test_mesh_add_vertex(&next, p[0] / n, p[1] / n, p[2] / n);
            }
            const uint32_t* c = old.indices + t3;
            test_mesh_add_triangle(&next, c[0], mid[0], mid[2]);
            test_mesh_add_triangle(&next, mid[0], c[1], mid[1]);
            test_mesh_add_triangle(&next, mid[2], mid[1], c[2]);
            test_mesh_add_triangle(&next, mid[0], mid[1], mid[2]);
        }
        test_mesh_free(&old);
        b = next;
    }
    return b.mesh;
}

test_mesh make_uv_sphere(int rings, int sectors) {
    test_mesh_builder b;
    memset(&b, 0, sizeof(b));
    test_mesh_add_vertex(&b, 0, 0, 1); /* north pole: vertex 0 */
    for (int i = 1; i < rings; ++i) {
        const double polar = M_PI * i / rings;
        for (int j = 0; j < sectors; ++j) {
            const double azimuth = 2.0 * M_PI * j / sectors;
            test_mesh_add_vertex(&b, sin(polar) * cos(azimuth), sin(polar) * sin(azimuth),
                                 cos(polar));
        }
    }
    const size_t south = test_mesh_add_vertex(&b, 0, 0, -1);
    for (int j = 0; j < sectors; ++j) { /* counter-clockwise seen from outside */
        const size_t next = (size_t)(j + 1) % (size_t)sectors;
        test_mesh_add_triangle(&b, 0, 1 + (size_t)j, 1 + next);
        const size_t last = 1 + (size_t)(rings - 2) * (size_t)sectors;
        test_mesh_add_triangle(&b, south, last + next, last + (size_t)j);
    }
    for (int i = 1; i + 1 < rings; ++i) {
        const size_t row = 1 + (size_t)(i - 1) * (size_t)sectors, below = row + (size_t)sectors;
        for (int j = 0; j < sectors; ++j) {
            const size_t next = (size_t)(j + 1) % (size_t)sectors;
            test_mesh_add_triangle(&b, row + (size_t)j, below + (size_t)j, below + next);
            test_mesh_add_triangle(&b, row + (size_t)j, below + next, row + next);
        }
    }
    return b.mesh;
}

static test_mesh make_torus(int nu, int nv, int punctured) {
    test_mesh_builder b;
    memset(&b, 0, sizeof(b));
    for (int i = 0; i < nu; ++i) {
        for (int j = 0; j < nv; ++j) {
            const double u = 2.0 * M_PI * i / nu, w = 2.0 * M_PI * j / nv;
            test_mesh_add_vertex(&b, (2.0 + cos(w)) * cos(u), (2.0 + cos(w)) * sin(u), sin(w));
        }
    }
    for (int i = 0; i < nu; ++i) {
        for (int j = 0; j < nv; ++j) {
            if (punctured && i == 0 && j == 0) continue; /* the puncture: one quad left out */
            const size_t a = (size_t)i * nv + j, c = (size_t)((i + 1) % nu) * nv + j;
            const size_t a1 = (size_t)i * nv + (j + 1) % nv,
                         c1 = (size_t)((i + 1) % nu) * nv + (j + 1) % nv;
            test_mesh_add_triangle(&b, a, c, c1);
            test_mesh_add_triangle(&b, a, c1, a1);
        }
    }
    return b.mesh;
}

test_mesh make_punctured_torus(int nu, int nv) {
    return make_torus(nu, nv, 1);
}

test_mesh make_closed_torus(int nu, int nv) {
    return make_torus(nu, nv, 0);
}

/* Midpoint subdivision, 1 -> 4 triangles, with an edge table; `onto_sphere` projects the new
 * vertices onto the unit sphere. */
static uint64_t edge_key(uint32_t a, uint32_t b) {
    return a < b ? ((uint64_t)a << 32) | b : ((uint64_t)b << 32) | a;
}

static test_mesh subdivide(const test_mesh* m, int onto_sphere) {
    const size_t slots = 4 * m->index_count + 1;
    uint64_t* keys = malloc(slots * sizeof(uint64_t));
    uint32_t* values = malloc(slots * sizeof(uint32_t));
    assert_non_null(keys);
    assert_non_null(values);
    for (size_t s = 0; s < slots; ++s) keys[s] = UINT64_MAX;
    test_mesh_builder g;
    memset(&g, 0, sizeof(g));
    for (size_t i = 0; i < m->vertex_count; ++i) {
        test_mesh_add_vertex(&g, m->positions[3 * i], m->positions[3 * i + 1],
                             m->positions[3 * i + 2]);
    }
    for (size_t t = 0; t < m->index_count; t += 3) {
        uint32_t mid[3];
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = m->indices[t + e], b = m->indices[t + (e + 1) % 3];
            const uint64_t key = edge_key(a, b);
            size_t s = (size_t)((key * 0x9E3779B97F4A7C15ull) >> 20) % slots;
            while (keys[s] != UINT64_MAX && keys[s] != key) s = (s + 1) % slots;
            if (keys[s] == UINT64_MAX) {
                double p[3];
                for (int q = 0; q < 3; ++q) {
                    p[q] = 0.5 * (m->positions[3 * a + q] + m->positions[3 * b + q]);
                }
                if (onto_sphere) {
                    const double n = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
                    for (int q = 0; q < 3; ++q) p[q] /= n;
                }
                keys[s] = key;
                values[s] = (uint32_t)test_mesh_add_vertex(&g, p[0], p[1], p[2]);
            }
            mid[e] = values[s];
        }
        const uint32_t* c = m->indices + t;
        test_mesh_add_triangle(&g, c[0], mid[0], mid[2]);
        test_mesh_add_triangle(&g, mid[0], c[1], mid[1]);
        test_mesh_add_triangle(&g, mid[2], mid[1], c[2]);
        test_mesh_add_triangle(&g, mid[0], mid[1], mid[2]);
    }
    free(keys);
    free(values);
    return g.mesh;
}

test_mesh subdivided_mesh(test_mesh mesh, int levels, int onto_sphere) {
    for (int k = 0; k < levels; ++k) {
        test_mesh next = subdivide(&mesh, onto_sphere);
        test_mesh_free(&mesh);
        mesh = next;
    }
    return mesh;
}

test_mesh join_meshes(const test_mesh* a, const test_mesh* b, double dx, double dy, double dz) {
    test_mesh_builder out;
    memset(&out, 0, sizeof(out));
    for (size_t i = 0; i < a->vertex_count; ++i) {
        test_mesh_add_vertex(&out, a->positions[3 * i], a->positions[3 * i + 1],
                             a->positions[3 * i + 2]);
    }
    for (size_t i = 0; i < b->vertex_count; ++i) {
        test_mesh_add_vertex(&out, b->positions[3 * i] + dx, b->positions[3 * i + 1] + dy,
                             b->positions[3 * i + 2] + dz);
    }
    for (size_t t = 0; t < a->index_count; t += 3) {
        test_mesh_add_triangle(&out, a->indices[t], a->indices[t + 1], a->indices[t + 2]);
    }
    const size_t offset = a->vertex_count;
    for (size_t t = 0; t < b->index_count; t += 3) {
        test_mesh_add_triangle(&out, offset + b->indices[t], offset + b->indices[t + 1],
                               offset + b->indices[t + 2]);
    }
    return out.mesh;
}

raps_mesh* to_raps_mesh(const test_mesh* mesh) {
    raps_mesh* m = NULL;
    assert_status(raps_mesh_create(&m), RAPS_OK);
    assert_status(raps_mesh_set_positions_f64(m, mesh->positions, mesh->vertex_count, 0), RAPS_OK);
    assert_status(raps_mesh_set_indices_u32(m, mesh->indices, mesh->index_count), RAPS_OK);
    return m;
}

raps_result* parameterize_ok(const raps_mesh* mesh, const raps_settings* settings) {
    raps_result* result = NULL;
    assert_status(raps_result_create(&result), RAPS_OK);
    const raps_status status = raps_parameterize(mesh, settings, result);
    if (status != RAPS_OK) {
        fail_msg("raps_parameterize: %s: %s", raps_status_string(status),
                 raps_result_last_error(result));
    }
    return result;
}

raps_settings* make_settings(int32_t weights, int32_t monitor, double alpha, int64_t iterations) {
    raps_settings* s = NULL;
    assert_status(raps_settings_create(&s), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_WEIGHTS, weights), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_MONITOR, monitor), RAPS_OK);
    assert_status(raps_settings_set_float(s, RAPS_PARAM_ALPHA, alpha), RAPS_OK);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_ITERATIONS, iterations), RAPS_OK);
    return s;
}

raps_stats stats_of(const raps_result* result) {
    raps_stats stats;
    memset(&stats, 0, sizeof(stats));
    stats.struct_size = sizeof(stats);
    assert_status(raps_result_get_stats(result, &stats), RAPS_OK);
    return stats;
}

double* uvs_of(const raps_result* result) {
    const size_t n = raps_result_vertex_count(result);
    double* uv = malloc(2 * n * sizeof(double) + 1);
    assert_non_null(uv);
    assert_status(raps_result_copy_uvs_f64(result, uv, n, 0), RAPS_OK);
    return uv;
}

int read_shared_mesh(const char* name, test_mesh* out, char* error, size_t error_size);

test_mesh load_shared_mesh(const char* name) {
    test_mesh mesh;
    char error[512];
    memset(&mesh, 0, sizeof(mesh));
    if (read_shared_mesh(name, &mesh, error, sizeof(error)) != 0) {
        fail_msg("cannot read shared mesh %s: %s (RAPS_SHARED_DATA_DIR=%s)", name, error,
                 shared_data_dir());
    }
    return mesh;
}
