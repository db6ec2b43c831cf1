/* Fuzz target: the C ABI's mesh entry points with arbitrary counts, indices, float bit patterns,
 * all three domains and random settings (the layout: fuzz_mesh_input.h). Every call must return
 * its documented status, never crash, hang or read past what it was given, and a successful
 * run must satisfy the header's promises about its output. A broken promise aborts, which both
 * libFuzzer and the replay driver report as a failure.
 *
 * Runs are kept short: at most kMaxTriangles triangles, few iterations and sweeps, an atlas of
 * at most 256 texels (packing a 1024-texel atlas took 3 s under ASan and coverage, the same code
 * at a larger scale) and at most 4 threads, so that every input finishes in well under a
 * second. RAPS_FUZZ_VERBOSE=1 prints each input's status, message and statistics. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_mesh_input.h"
#include "raps.h"

enum { kMaxTriangles = 2000 };

#define CHECK(condition)                                                                      \
    do {                                                                                      \
        if (!(condition)) {                                                                   \
            fprintf(stderr, "fuzz_mesh_api: %s:%d: broken promise: %s\n", __FILE__, __LINE__, \
                    #condition);                                                              \
            abort();                                                                          \
        }                                                                                     \
    } while (0)

#define CHECK_STATUS(call, expected)                                                              \
    do {                                                                                          \
        const raps_status check_status_s = (call);                                                \
        if (check_status_s != (expected)) {                                                       \
            fprintf(stderr, "fuzz_mesh_api: %s:%d: %s returned %d (%s), expected %d\n", __FILE__, \
                    __LINE__, #call, (int)check_status_s, raps_status_string(check_status_s),     \
                    (int)(expected));                                                             \
            abort();                                                                              \
        }                                                                                         \
    } while (0)

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

/* The progress callback's view of a run: it cancels at call number cancel_at when asked to. */
typedef struct progress_probe {
    int cancel;
    unsigned cancel_at;
    unsigned calls;
    int cancelled;
} progress_probe;

static int32_t probe_progress(void* user, raps_phase phase, double fraction) {
    progress_probe* probe = user;
    CHECK(phase >= 0 && phase < RAPS_PHASE_COUNT);
    CHECK(fraction >= 0.0 && fraction <= 1.0);
    CHECK(!probe->cancelled); /* no call after the one that cancelled */
    if (probe->cancel && probe->calls++ == probe->cancel_at) {
        probe->cancelled = 1;
        return 0;
    }
    return 1;
}

/* The value a setting's 8 bytes stand for: as they are, or mapped into the bounds. */
static void apply_setting(raps_settings* settings, const fuzz_setting* setting) {
    const raps_param param = setting->selector & 0x3f;
    const int in_bounds = (setting->selector & FUZZ_SETTING_IN_BOUNDS) != 0;
    int32_t is_float = (setting->selector & FUZZ_SETTING_AS_FLOAT) != 0;
    double lo = 0, hi = 0;
    const int known = raps_param_info(param, NULL, &is_float, &lo, &hi, NULL) == RAPS_OK;
    raps_status status;
    int expect_ok = 0;
    if (is_float) {
        double value;
        if (in_bounds && known) {
            value = lo + (hi - lo) * ((double)(setting->raw >> 11) / 9007199254740992.0);
            if (value > hi) value = hi;
        } else {
            memcpy(&value, &setting->raw, sizeof(value));
        }
        status = raps_settings_set_float(settings, param, value);
        expect_ok = known && value >= lo && value <= hi;
    } else {
        int64_t value = (int64_t)setting->raw;
        if (in_bounds && known) {
            const uint64_t span = (uint64_t)(hi - lo) + 1;
            value = (int64_t)lo + (int64_t)(setting->raw % span);
        }
        status = raps_settings_set_int(settings, param, value);
        expect_ok = known && (double)value >= lo && (double)value <= hi;
    }
    if (expect_ok) {
        CHECK_STATUS(status, RAPS_OK);
        CHECK(raps_settings_last_error(settings)[0] == '\0');
    } else {
        CHECK_STATUS(status, RAPS_ERROR_INVALID_ARGUMENT);
        CHECK(raps_settings_last_error(settings)[0] != '\0');
    }
}

/* Lowers an int parameter to `most` (and 0, where 0 means "the default", to `most` too). */
static void cap_int(raps_settings* settings, raps_param param, int64_t most, int zero_too) {
    int64_t value = 0;
    CHECK_STATUS(raps_settings_get_int(settings, param, &value), RAPS_OK);
    if (value > most || (zero_too && value == 0)) {
        CHECK_STATUS(raps_settings_set_int(settings, param, most), RAPS_OK);
    }
}

/* Keeps every run short, whatever the settings asked for. */
static void cap_costs(raps_settings* settings) {
    cap_int(settings, RAPS_PARAM_MAX_TRIANGLES, kMaxTriangles, 0);
    cap_int(settings, RAPS_PARAM_ITERATIONS, 3, 0);
    cap_int(settings, RAPS_PARAM_SPHERE_MAX_SWEEPS, 200, 1);
    cap_int(settings, RAPS_PARAM_SPHERE_ALPHA_STEPS, 4, 0);
    cap_int(settings, RAPS_PARAM_ATLAS_RESOLUTION, 256, 0);
    cap_int(settings, RAPS_PARAM_THREADS, 4, 1);
}

/* Whether the header lets a coordinate in: finite and at most 1e30 in magnitude. */
static int acceptable(double x) {
    return fabs(x) <= 1e30;
}

/* Sets the positions and checks the status against what the input deserves. */
static void set_positions(raps_mesh* mesh, const fuzz_mesh_input* in) {
    const size_t before = raps_mesh_vertex_count(mesh);
    if (in->flags & FUZZ_FLAG_HUGE_VERTEX_COUNT) {
        /* Past what raps indexes: refused before a byte is read, the mesh unchanged. */
        const size_t huge = (in->cancel_at & 1) ? SIZE_MAX : ((size_t)1 << 31) + in->cancel_at;
        const raps_status status =
            (in->flags & FUZZ_FLAG_F64)
                ? raps_mesh_set_positions_f64(mesh, (const double*)in->points, huge,
                                              in->point_stride)
                : raps_mesh_set_positions_f32(mesh, (const float*)in->points, huge,
                                              in->point_stride);
        CHECK_STATUS(status, RAPS_ERROR_TOO_LARGE);
        CHECK(raps_mesh_vertex_count(mesh) == before);
    }
    /* The library reads unaligned points: it gets them where they lie in the input. Copies are
     * only made here to judge the coordinates. */
    int acceptable_points = 1;
    raps_status status;
    if (in->flags & FUZZ_FLAG_F64) {
        for (size_t i = 0; i < in->point_count && acceptable_points; ++i) {
            double p[3];
            memcpy(p, in->points + i * in->point_stride, sizeof(p));
            acceptable_points = acceptable(p[0]) && acceptable(p[1]) && acceptable(p[2]);
        }
        status = raps_mesh_set_positions_f64(mesh, (const double*)in->points, in->point_count,
                                             in->point_stride);
    } else {
        for (size_t i = 0; i < in->point_count && acceptable_points; ++i) {
            float p[3];
            memcpy(p, in->points + i * in->point_stride, sizeof(p));
            acceptable_points = acceptable(p[0]) && acceptable(p[1]) && acceptable(p[2]);
        }
        status = raps_mesh_set_positions_f32(mesh, (const float*)in->points, in->point_count,
                                             in->point_stride);
    }
    const raps_status expected = in->point_count == 0 ? RAPS_ERROR_EMPTY_MESH
                                 : !acceptable_points ? RAPS_ERROR_NON_FINITE_POSITION
                                                      : RAPS_OK;
    CHECK_STATUS(status, expected);
    CHECK(raps_mesh_vertex_count(mesh) == (expected == RAPS_OK ? in->point_count : before));
}

/* Sets the indices (copied to an aligned array first) and checks the status. */
static void set_indices(raps_mesh* mesh, const fuzz_mesh_input* in) {
    const size_t before = raps_mesh_triangle_count(mesh);
    const int u16 = (in->flags & FUZZ_FLAG_U16) != 0;
    const size_t bytes = u16 ? 2 : 4;
    void* indices = malloc(in->index_count * bytes + 4);
    CHECK(indices != NULL);
    memcpy(indices, in->indices, in->index_count * bytes);
    if (in->flags & FUZZ_FLAG_HUGE_INDEX_COUNT) {
        /* Multiples of 3 past 3 * 2^28 (the most triangles raps accepts), SIZE_MAX among them. */
        const size_t huge = (in->cancel_at & 2)   ? SIZE_MAX
                            : (in->cancel_at & 4) ? 3 * (((size_t)1 << 28) + 1)
                                                  : 3 * ((size_t)1 << 31);
        const raps_status status = u16 ? raps_mesh_set_indices_u16(mesh, indices, huge)
                                       : raps_mesh_set_indices_u32(mesh, indices, huge);
        CHECK_STATUS(status, RAPS_ERROR_TOO_LARGE);
        CHECK(raps_mesh_triangle_count(mesh) == before);
    }
    int in_range = 1;
    if (!u16) {
        for (size_t i = 0; i < in->index_count; ++i) {
            if (((const uint32_t*)indices)[i] > 0x7fffffffu) in_range = 0;
        }
    }
    const raps_status status = u16 ? raps_mesh_set_indices_u16(mesh, indices, in->index_count)
                                   : raps_mesh_set_indices_u32(mesh, indices, in->index_count);
    const raps_status expected = in->index_count == 0       ? RAPS_ERROR_EMPTY_MESH
                                 : in->index_count % 3 != 0 ? RAPS_ERROR_INDEX_COUNT
                                 : !in_range                ? RAPS_ERROR_INDEX_OUT_OF_RANGE
                                                            : RAPS_OK;
    CHECK_STATUS(status, expected);
    CHECK(raps_mesh_triangle_count(mesh) == (expected == RAPS_OK ? in->index_count / 3 : before));
    free(indices);
}

/* What a successful run promises about its output; fills the copies for a later comparison. */
typedef struct run_output {
    size_t vertex_count, index_count;
    double* uv;     /* NULL when the map has none */
    double* points; /* NULL unless a sphere map */
    uint32_t* indices;
    uint32_t* remap;
} run_output;

static void free_output(run_output* out) {
    free(out->uv);
    free(out->points);
    free(out->indices);
    free(out->remap);
    memset(out, 0, sizeof(*out));
}

static void check_success(const raps_mesh* mesh, const raps_result* result, int domain,
                          run_output* out) {
    const size_t n = raps_result_vertex_count(result), m = raps_result_index_count(result);
    const size_t input_vertices = raps_mesh_vertex_count(mesh);
    CHECK(n > 0 && m == 3 * raps_mesh_triangle_count(mesh));
    CHECK(raps_result_last_error(result)[0] == '\0');
    out->vertex_count = n;
    out->index_count = m;
    out->indices = malloc(m * sizeof(uint32_t));
    out->remap = malloc(n * sizeof(uint32_t));
    CHECK(out->indices && out->remap);
    CHECK_STATUS(raps_result_copy_indices_u32(result, out->indices, m), RAPS_OK);
    CHECK_STATUS(raps_result_copy_vertex_remap(result, out->remap, n), RAPS_OK);
    for (size_t i = 0; i < m; ++i) CHECK(out->indices[i] < n);
    for (size_t v = 0; v < n; ++v) CHECK(out->remap[v] < input_vertices);
    if (domain == RAPS_DOMAIN_DISK) CHECK(n == input_vertices);

    out->uv = malloc(2 * n * sizeof(double));
    CHECK(out->uv != NULL);
    const raps_status uv_status = raps_result_copy_uvs_f64(result, out->uv, n, 0);
    if (uv_status == RAPS_OK) {
        for (size_t i = 0; i < 2 * n; ++i) CHECK(out->uv[i] >= -1e-9 && out->uv[i] <= 1 + 1e-9);
    } else {
        CHECK(domain == RAPS_DOMAIN_SPHERE && uv_status == RAPS_ERROR_INVALID_OPERATION);
        free(out->uv);
        out->uv = NULL;
    }
    if (domain == RAPS_DOMAIN_SPHERE) {
        out->points = malloc(3 * n * sizeof(double));
        CHECK(out->points != NULL);
        CHECK_STATUS(raps_result_copy_sphere_points_f64(result, out->points, n, 0), RAPS_OK);
        for (size_t v = 0; v < n; ++v) {
            const double* p = out->points + 3 * v;
            CHECK(fabs(p[0] * p[0] + p[1] * p[1] + p[2] * p[2] - 1.0) < 1e-9);
        }
    }
    uint32_t* charts = malloc((m / 3 + 1) * sizeof(uint32_t));
    CHECK(charts != NULL);
    raps_stats stats;
    memset(&stats, 0, sizeof(stats));
    stats.struct_size = sizeof(stats);
    CHECK_STATUS(raps_result_get_stats(result, &stats), RAPS_OK);
    if (getenv("RAPS_FUZZ_VERBOSE")) {
        fprintf(stderr, "  %llu charts, area log mean %g, L2 %g, Linf %g, utilization %g\n",
                (unsigned long long)stats.chart_count, stats.area_log_mean, stats.stretch_l2,
                stats.stretch_linf, stats.utilization);
    }
    CHECK(stats.vertex_count == n && stats.triangle_count == m / 3 && stats.chart_count >= 1);
    CHECK(!isnan(stats.area_log_mean) && !isnan(stats.stretch_l2) && !isnan(stats.utilization));
    CHECK_STATUS(raps_result_copy_chart_ids(result, charts, m / 3), RAPS_OK);
    for (size_t t = 0; t < m / 3; ++t) CHECK(charts[t] < stats.chart_count);
    free(charts);
}

static int same_output(const run_output* a, const run_output* b) {
    if (a->vertex_count != b->vertex_count || a->index_count != b->index_count) return 0;
    if ((a->uv == NULL) != (b->uv == NULL) || (a->points == NULL) != (b->points == NULL)) return 0;
    if (a->vertex_count == 0) return 1; /* two failed runs: nothing to compare */
    const size_t n = a->vertex_count;
    return memcmp(a->indices, b->indices, a->index_count * sizeof(uint32_t)) == 0 &&
           memcmp(a->remap, b->remap, n * sizeof(uint32_t)) == 0 &&
           (!a->uv || memcmp(a->uv, b->uv, 2 * n * sizeof(double)) == 0) &&
           (!a->points || memcmp(a->points, b->points, 3 * n * sizeof(double)) == 0);
}

/* With a nonzero polygons byte: a polygon id per triangle, made from the triangles as bits 0-1
 * say, with k = bits 2-7. 0: one id too many (a count the atlas must refuse with GROUP_COUNT);
 * 1: runs of k + 2 consecutive triangles (the fans of triangulated quads and n-gons); 2: the
 * triangle's first index (fans around a corner); 3: t % (k + 1), ids scattered over the mesh
 * (k = 0: one polygon of every triangle). The setter's own refusals are checked first: NULL with
 * a count, and a count past 2^28 that must be refused before a byte is read. Returns whether
 * the count disagrees with the triangles. */
static int set_polygons(raps_mesh* mesh, const fuzz_mesh_input* in) {
    const int mode = in->polygons & 3, k = in->polygons >> 2;
    const size_t triangles = raps_mesh_triangle_count(mesh);
    const size_t count = triangles + (mode == 0);
    uint32_t* ids = malloc(count * sizeof(uint32_t) + 4);
    CHECK(ids != NULL);
    CHECK_STATUS(raps_mesh_set_triangle_polygons(NULL, ids, count), RAPS_ERROR_INVALID_ARGUMENT);
    CHECK_STATUS(raps_mesh_set_triangle_polygons(mesh, NULL, 1), RAPS_ERROR_INVALID_ARGUMENT);
    CHECK(raps_mesh_last_error(mesh)[0] != '\0');
    CHECK_STATUS(raps_mesh_set_triangle_polygons(mesh, ids, ((size_t)1 << 28) + 1 + k),
                 RAPS_ERROR_TOO_LARGE);
    const int u16 = (in->flags & FUZZ_FLAG_U16) != 0;
    for (size_t t = 0; t < count; ++t) {
        uint32_t first = 0;
        if (t < triangles) memcpy(&first, in->indices + 3 * t * (u16 ? 2 : 4), u16 ? 2 : 4);
        ids[t] = mode == 1   ? (uint32_t)(t / (size_t)(k + 2))
                 : mode == 2 ? first
                 : mode == 3 ? (uint32_t)(t % (size_t)(k + 1))
                             : (uint32_t)t;
    }
    CHECK_STATUS(raps_mesh_set_triangle_polygons(mesh, count ? ids : NULL, count), RAPS_OK);
    free(ids);
    return count != triangles;
}

/* One run; checks the status is one raps_parameterize may return and what it promises. A
 * polygon count that disagrees with the triangles (wrong_polygons) fails an atlas run. */
static raps_status run_once(const raps_mesh* mesh, raps_settings* settings, int domain,
                            const fuzz_mesh_input* in, int wrong_polygons, run_output* out) {
    progress_probe probe = {(in->flags & FUZZ_FLAG_CANCEL) != 0, in->cancel_at, 0, 0};
    CHECK_STATUS(raps_settings_set_progress(settings, probe_progress, &probe), RAPS_OK);
    raps_result* result = NULL;
    CHECK_STATUS(raps_result_create(&result), RAPS_OK);
    const raps_status status = raps_parameterize(mesh, settings, result);
    if (getenv("RAPS_FUZZ_VERBOSE")) { /* what each input reached, when looking at a corpus */
        fprintf(stderr, "domain %d, %zu vertices, %zu triangles: %s %s\n", domain,
                raps_mesh_vertex_count(mesh), raps_mesh_triangle_count(mesh),
                raps_status_string(status), raps_result_last_error(result));
    }
    /* Repacking corner uvs (FUZZ_FLAG_CORNER_UVS, or the repack parameter set from the bytes)
     * adds its own refusals: no uvs for the triangles, an island without uv area. */
    CHECK((status >= RAPS_OK && status <= RAPS_ERROR_OPEN_MESH) || status == RAPS_ERROR_UV_COUNT ||
          status == RAPS_ERROR_DEGENERATE_UV_CHART ||
          (status == RAPS_ERROR_GROUP_COUNT && wrong_polygons && domain == RAPS_DOMAIN_ATLAS));
    CHECK(!(status == RAPS_OK && wrong_polygons && domain == RAPS_DOMAIN_ATLAS));
    /* Neither a bug report nor an argument error: the handles given are all valid. */
    CHECK(status != RAPS_ERROR_INTERNAL && status != RAPS_ERROR_INVALID_ARGUMENT &&
          status != RAPS_ERROR_INVALID_OPERATION);
    CHECK((status == RAPS_ERROR_CANCELLED) == (probe.cancelled != 0));
    memset(out, 0, sizeof(*out));
    if (status == RAPS_OK) {
        check_success(mesh, result, domain, out);
    } else {
        CHECK(raps_result_vertex_count(result) == 0 && raps_result_index_count(result) == 0);
        CHECK(raps_result_last_error(result)[0] != '\0');
    }
    raps_result_destroy(result);
    return status;
}

/* With FUZZ_FLAG_CORNER_UVS: each triangle corner's uv is the (x, y) of the point its index
 * names (modulo the points; (0, 0) without points), whatever those bytes hold, and the run
 * repacks them. The setter refuses a uv that is not finite, leaving the mesh without uvs; the
 * run must then refuse with UV_COUNT, which run_once accepts like any input's status. */
static void set_corner_uvs(raps_mesh* mesh, raps_settings* settings, const fuzz_mesh_input* in) {
    const int u16 = (in->flags & FUZZ_FLAG_U16) != 0;
    double* uv = malloc(2 * in->index_count * sizeof(double) + 16);
    CHECK(uv != NULL);
    int acceptable_uvs = 1;
    for (size_t i = 0; i < in->index_count; ++i) {
        uint32_t index = 0;
        memcpy(&index, in->indices + i * (u16 ? 2 : 4), u16 ? 2 : 4);
        double p[2] = {0, 0};
        if (in->point_count > 0) {
            const uint8_t* point = in->points + (index % in->point_count) * in->point_stride;
            if (in->flags & FUZZ_FLAG_F64) {
                memcpy(p, point, sizeof(p));
            } else {
                float f[2];
                memcpy(f, point, sizeof(f));
                p[0] = f[0];
                p[1] = f[1];
            }
        }
        acceptable_uvs = acceptable_uvs && acceptable(p[0]) && acceptable(p[1]);
        uv[2 * i] = p[0];
        uv[2 * i + 1] = p[1];
    }
    CHECK_STATUS(
        raps_mesh_set_corner_uvs_f64(mesh, in->index_count ? uv : NULL, in->index_count, 0),
        acceptable_uvs ? RAPS_OK : RAPS_ERROR_NON_FINITE_UV);
    free(uv);
    CHECK_STATUS(raps_settings_set_int(settings, RAPS_PARAM_ATLAS_REPACK, 1), RAPS_OK);
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    fuzz_mesh_input in;
    fuzz_mesh_input_decode(data, size, &in);
    raps_mesh* mesh = NULL;
    raps_settings* settings = NULL;
    CHECK_STATUS(raps_mesh_create(&mesh), RAPS_OK);
    CHECK_STATUS(raps_settings_create(&settings), RAPS_OK);
    for (size_t s = 0; s < in.setting_count; ++s) apply_setting(settings, &in.settings[s]);
    CHECK_STATUS(raps_settings_set_int(settings, RAPS_PARAM_DOMAIN, in.domain), RAPS_OK);
    cap_costs(settings);
    if (in.flags & FUZZ_FLAG_INDICES_FIRST) {
        set_indices(mesh, &in);
        set_positions(mesh, &in);
    } else {
        set_positions(mesh, &in);
        set_indices(mesh, &in);
    }
    if (in.flags & FUZZ_FLAG_CORNER_UVS) set_corner_uvs(mesh, settings, &in);
    const int wrong_polygons = in.polygons ? set_polygons(mesh, &in) : 0;
    run_output first, second;
    const raps_status status = run_once(mesh, settings, in.domain, &in, wrong_polygons, &first);
    if (in.flags & FUZZ_FLAG_RUN_TWICE) {
        /* Same handles, same input: the same status and the same bits. */
        CHECK_STATUS(run_once(mesh, settings, in.domain, &in, wrong_polygons, &second), status);
        CHECK(same_output(&first, &second));
        free_output(&second);
    }
    free_output(&first);
    raps_settings_destroy(settings);
    raps_mesh_destroy(mesh);
    return 0;
}
