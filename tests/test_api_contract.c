/* The C ABI's contract, independent of any algorithm: versions, statuses, handle life cycles,
 * settings as key/value pairs with bounds, result accessors and the stats struct's size rule. */
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

static void version_query_matches_header(void** state) {
    (void)state;
    assert_int_equal(raps_version(), RAPS_VERSION);
    char expected[32];
    snprintf(expected, sizeof(expected), "%d.%d.%d", RAPS_VERSION_MAJOR, RAPS_VERSION_MINOR,
             RAPS_VERSION_PATCH);
    assert_string_equal(raps_version_string(), expected);
}

static void status_values_are_pinned(void** state) {
    (void)state;
    /* These numbers are ABI: bindings and stored logs rely on them. */
    assert_int_equal(RAPS_OK, 0);
    assert_int_equal(RAPS_ERROR_INVALID_ARGUMENT, 1);
    assert_int_equal(RAPS_ERROR_OUT_OF_MEMORY, 2);
    assert_int_equal(RAPS_ERROR_EMPTY_MESH, 3);
    assert_int_equal(RAPS_ERROR_INDEX_COUNT, 4);
    assert_int_equal(RAPS_ERROR_INDEX_OUT_OF_RANGE, 5);
    assert_int_equal(RAPS_ERROR_NON_FINITE_POSITION, 6);
    assert_int_equal(RAPS_ERROR_REPEATED_VERTEX, 7);
    assert_int_equal(RAPS_ERROR_ZERO_AREA_TRIANGLE, 8);
    assert_int_equal(RAPS_ERROR_NON_MANIFOLD_EDGE, 9);
    assert_int_equal(RAPS_ERROR_NON_MANIFOLD_VERTEX, 10);
    assert_int_equal(RAPS_ERROR_INCONSISTENT_ORIENTATION, 11);
    assert_int_equal(RAPS_ERROR_ISOLATED_VERTEX, 12);
    assert_int_equal(RAPS_ERROR_MULTIPLE_COMPONENTS, 13);
    assert_int_equal(RAPS_ERROR_NO_BOUNDARY, 14);
    assert_int_equal(RAPS_ERROR_MULTIPLE_BOUNDARIES, 15);
    assert_int_equal(RAPS_ERROR_NONZERO_GENUS, 16);
    assert_int_equal(RAPS_ERROR_TOO_LARGE, 17);
    assert_int_equal(RAPS_ERROR_CANCELLED, 18);
    assert_int_equal(RAPS_ERROR_SOLVER_FAILED, 19);
    assert_int_equal(RAPS_ERROR_INVALID_OPERATION, 20);
    assert_int_equal(RAPS_ERROR_INTERNAL, 21);
    assert_int_equal(RAPS_ERROR_OPEN_MESH, 22);
    assert_int_equal(RAPS_ERROR_INVALID_TRANSFORM, 23);
    assert_int_equal(RAPS_ERROR_GROUP_COUNT, 24);
    assert_int_equal(RAPS_ERROR_SEAM_NOT_AN_EDGE, 25);
    assert_int_equal(RAPS_ERROR_UV_COUNT, 26);
    assert_int_equal(RAPS_ERROR_NON_FINITE_UV, 27);
    assert_int_equal(RAPS_ERROR_DEGENERATE_UV_CHART, 28);
    assert_int_equal(RAPS_PARAM_ATLAS_REPACK, 47);
    assert_int_equal(RAPS_PARAM_ATLAS_STACK, 48);
    assert_int_equal(RAPS_PARAM_ATLAS_STACK_TOLERANCE, 49);
    assert_int_equal(RAPS_STACK_MIRRORED, 2);
    assert_int_equal(RAPS_CHART_STACKED, 2);
    assert_int_equal(offsetof(raps_chart, stacked_on), 72);
    assert_int_equal(sizeof(raps_chart), 80);
    assert_int_equal(RAPS_PARAM_DOMAIN, 1);
    assert_int_equal(RAPS_PARAM_MAX_TRIANGLES, 8);
    assert_int_equal(RAPS_PARAM_THREADS, 9);
    assert_int_equal(RAPS_PARAM_SPHERE_METHOD, 10);
    assert_int_equal(RAPS_PARAM_SPHERE_UV, 11);
    assert_int_equal(RAPS_PARAM_SPHERE_DAMPING, 12);
    assert_int_equal(RAPS_PARAM_SPHERE_TOLERANCE, 13);
    assert_int_equal(RAPS_PARAM_SPHERE_MAX_SWEEPS, 14);
    assert_int_equal(RAPS_PARAM_SPHERE_ALPHA_STEPS, 15);
    assert_int_equal(RAPS_PARAM_MAX_MEMORY_MB, 16);
    assert_int_equal(RAPS_DOMAIN_DISK, 0);
    assert_int_equal(RAPS_DOMAIN_SPHERE, 1);
    assert_int_equal(RAPS_SPHERE_LITERAL, 0);
    assert_int_equal(RAPS_SPHERE_ROBUST, 1);
    assert_int_equal(RAPS_SPHERE_UV_NONE, 0);
    assert_int_equal(RAPS_SPHERE_UV_OCTAHEDRAL, 1);
    assert_int_equal(RAPS_PHASE_METRICS, 4);
    assert_int_equal(RAPS_PARAM_ATLAS_RESOLUTION, 32);
    assert_int_equal(RAPS_PARAM_ATLAS_MAX_LINF_STRETCH, 37);
    assert_int_equal(RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, 38);
    assert_int_equal(RAPS_PARAM_ATLAS_MAX_WIDTH, 39);
    assert_int_equal(RAPS_PARAM_ATLAS_MAX_HEIGHT, 40);
    assert_int_equal(RAPS_PARAM_ATLAS_ROTATION, 41);
    assert_int_equal(RAPS_PARAM_ATLAS_MARGIN, 42);
    assert_int_equal(RAPS_PARAM_ATLAS_BLOCK_ALIGN, 43);
    assert_int_equal(RAPS_PARAM_ATLAS_MESH_PER_PAGE, 44);
    assert_int_equal(RAPS_PARAM_ATLAS_WHOLE_TEXELS, 45);
    assert_int_equal(RAPS_PARAM_ATLAS_KEEP_INPUT_SEAMS, 46);
    assert_int_equal(RAPS_ROTATION_ANY, 0);
    assert_int_equal(RAPS_ROTATION_QUARTER, 1);
    assert_int_equal(RAPS_ROTATION_NONE, 2);
    assert_int_equal(RAPS_CHART_SCALED_DOWN, 1);
    assert_int_equal(RAPS_DOMAIN_ATLAS, 2);
    assert_int_equal(RAPS_PHASE_PACK, 6);
    assert_int_equal(sizeof(raps_stats), 176);
    assert_int_equal(offsetof(raps_stats, area_log_mean), 56);
    assert_int_equal(offsetof(raps_stats, stretch_linf), 96);
    assert_int_equal(offsetof(raps_stats, relaxation_sweeps), 104);
    assert_int_equal(offsetof(raps_stats, utilization), 136);
    assert_int_equal(offsetof(raps_stats, threads_used), 144);
    assert_int_equal(offsetof(raps_stats, page_count), 152);
    assert_int_equal(offsetof(raps_stats, texels_per_unit), 168);
    assert_int_equal(offsetof(raps_chart, x), 16);
    assert_int_equal(offsetof(raps_chart, rotation_deg), 32);
    assert_int_equal(offsetof(raps_chart, stretch_l2), 64);
}

static void every_status_has_a_description(void** state) {
    (void)state;
    for (int s = RAPS_OK; s <= RAPS_ERROR_DEGENERATE_UV_CHART; ++s) {
        const char* text = raps_status_string(s);
        assert_non_null(text);
        assert_string_not_equal(text, "unknown status");
    }
    assert_string_equal(raps_status_string(-1), "unknown status");
    assert_string_equal(raps_status_string(1000), "unknown status");
}

static void destroy_null_is_a_noop_and_create_rejects_null(void** state) {
    (void)state;
    raps_mesh_destroy(NULL);
    raps_settings_destroy(NULL);
    raps_result_destroy(NULL);
    assert_status(raps_mesh_create(NULL), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_settings_create(NULL), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_result_create(NULL), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_settings_clone(NULL, NULL), RAPS_ERROR_INVALID_ARGUMENT);
    assert_non_null(raps_mesh_last_error(NULL));
    assert_non_null(raps_settings_last_error(NULL));
    assert_non_null(raps_result_last_error(NULL));
    assert_int_equal(raps_mesh_vertex_count(NULL), 0);
    assert_int_equal(raps_result_vertex_count(NULL), 0);
}

static void settings_hold_the_documented_defaults(void** state) {
    (void)state;
    raps_settings* s = NULL;
    assert_status(raps_settings_create(&s), RAPS_OK);
    const struct {
        raps_param param;
        int64_t value;
    } expected[] = {{RAPS_PARAM_DOMAIN, RAPS_DOMAIN_DISK},
                    {RAPS_PARAM_WEIGHTS, RAPS_WEIGHTS_MEAN_VALUE},
                    {RAPS_PARAM_MONITOR, RAPS_MONITOR_AREA},
                    {RAPS_PARAM_ITERATIONS, 1},
                    {RAPS_PARAM_ITERATION_MODE, RAPS_ITERATION_ACCUMULATE},
                    {RAPS_PARAM_BOUNDARY, RAPS_BOUNDARY_CIRCLE},
                    {RAPS_PARAM_MAX_TRIANGLES, 2147483647},
                    {RAPS_PARAM_THREADS, 0},
                    {RAPS_PARAM_SPHERE_METHOD, RAPS_SPHERE_ROBUST},
                    {RAPS_PARAM_SPHERE_UV, RAPS_SPHERE_UV_NONE},
                    {RAPS_PARAM_SPHERE_MAX_SWEEPS, 0},
                    {RAPS_PARAM_SPHERE_ALPHA_STEPS, 2},
                    {RAPS_PARAM_MAX_MEMORY_MB, 0},
                    {RAPS_PARAM_ATLAS_KEEP_INPUT_SEAMS, 0},
                    {RAPS_PARAM_ATLAS_REPACK, 0},
                    {RAPS_PARAM_ATLAS_STACK, RAPS_STACK_NONE}};
    for (size_t i = 0; i < sizeof(expected) / sizeof(expected[0]); ++i) {
        int64_t value = -1;
        assert_status(raps_settings_get_int(s, expected[i].param, &value), RAPS_OK);
        assert_int_equal(value, expected[i].value);
        double lo, hi, fallback;
        int32_t is_float = -1;
        const char* name = NULL;
        assert_status(raps_param_info(expected[i].param, &name, &is_float, &lo, &hi, &fallback),
                      RAPS_OK);
        assert_non_null(name);
        assert_int_equal(is_float, 0);
        assert_near(fallback, (double)expected[i].value, 0);
    }
    const struct {
        raps_param param;
        double value;
    } expected_float[] = {{RAPS_PARAM_ALPHA, 1.0},
                          {RAPS_PARAM_SPHERE_DAMPING, 1.0},
                          {RAPS_PARAM_SPHERE_TOLERANCE, 1e-4},
                          {RAPS_PARAM_ATLAS_STACK_TOLERANCE, 1e-4}};
    for (size_t i = 0; i < sizeof(expected_float) / sizeof(expected_float[0]); ++i) {
        double value = 0, fallback = -1;
        int32_t is_float = -1;
        assert_status(raps_settings_get_float(s, expected_float[i].param, &value), RAPS_OK);
        assert_near(value, expected_float[i].value, 0);
        assert_status(
            raps_param_info(expected_float[i].param, NULL, &is_float, NULL, NULL, &fallback),
            RAPS_OK);
        assert_int_equal(is_float, 1);
        assert_near(fallback, expected_float[i].value, 0);
    }
    raps_settings_destroy(s);
}

/* Every parameter the library knows (ids 1..63 probed through raps_param_info) round-trips
 * through its setter and getter at its bounds and starts at its documented default. */
static void every_parameter_round_trips(void** state) {
    (void)state;
    raps_settings* s = NULL;
    assert_status(raps_settings_create(&s), RAPS_OK);
    int known = 0;
    for (raps_param p = 1; p < 64; ++p) {
        const char* name = NULL;
        int32_t is_float = 0;
        double lo = 0, hi = 0, fallback = 0;
        if (raps_param_info(p, &name, &is_float, &lo, &hi, &fallback) != RAPS_OK) continue;
        ++known;
        if (is_float) {
            double v = -1;
            assert_status(raps_settings_get_float(s, p, &v), RAPS_OK);
            assert_near(v, fallback, 0);
            const double hi_value = hi > 1e300 ? 1e6 : hi;
            assert_status(raps_settings_set_float(s, p, hi_value), RAPS_OK);
            assert_status(raps_settings_get_float(s, p, &v), RAPS_OK);
            assert_near(v, hi_value, 0);
        } else {
            int64_t v = -1;
            assert_status(raps_settings_get_int(s, p, &v), RAPS_OK);
            assert_int_equal(v, (int64_t)fallback);
            for (int64_t value = (int64_t)lo; value <= (int64_t)hi && value <= (int64_t)lo + 2;
                 ++value) {
                assert_status(raps_settings_set_int(s, p, value), RAPS_OK);
                assert_status(raps_settings_get_int(s, p, &v), RAPS_OK);
                assert_int_equal(v, value);
            }
            assert_status(raps_settings_set_int(s, p, (int64_t)hi), RAPS_OK);
            assert_status(raps_settings_get_int(s, p, &v), RAPS_OK);
            assert_int_equal(v, (int64_t)hi);
            assert_status(raps_settings_set_int(s, p, (int64_t)hi + 1),
                          RAPS_ERROR_INVALID_ARGUMENT);
        }
    }
    assert_int_equal(known, 34);
    raps_settings_destroy(s);
}

static void settings_refuse_bad_keys_types_and_values(void** state) {
    (void)state;
    raps_settings* s = NULL;
    assert_status(raps_settings_create(&s), RAPS_OK);
    assert_status(raps_settings_set_int(s, 9999, 1), RAPS_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(raps_settings_last_error(s), "unknown parameter"));
    assert_status(raps_settings_set_int(s, RAPS_PARAM_ALPHA, 2), RAPS_ERROR_INVALID_ARGUMENT);
    assert_non_null(strstr(raps_settings_last_error(s), "float"));
    assert_status(raps_settings_set_float(s, RAPS_PARAM_MONITOR, 1.0), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_MONITOR, 4), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_MONITOR, -1), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_ITERATIONS, 0), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_ITERATIONS, 101),
                  RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_settings_set_float(s, RAPS_PARAM_ALPHA, 0.0), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_settings_set_float(s, RAPS_PARAM_ALPHA, -1.0), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_settings_set_float(s, RAPS_PARAM_ALPHA, NAN), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_settings_set_float(s, RAPS_PARAM_ALPHA, INFINITY),
                  RAPS_ERROR_INVALID_ARGUMENT);
    /* The message gives the value as it was given and the bounds as they are: closed where the
     * bound is accepted (a density of 0 means "fill the resolution"). */
    assert_status(raps_settings_set_float(s, RAPS_PARAM_ALPHA, -1e-9), RAPS_ERROR_INVALID_ARGUMENT);
    assert_string_equal(raps_settings_last_error(s),
                        "value -1e-09 of parameter alpha is outside (0, 100]");
    assert_status(raps_settings_set_float(s, RAPS_PARAM_ATLAS_MAX_L2_STRETCH, 0.9999999),
                  RAPS_ERROR_INVALID_ARGUMENT);
    assert_string_equal(raps_settings_last_error(s),
                        "value 0.9999999 of parameter atlas_max_l2_stretch is outside [1, 10]");
    assert_status(raps_settings_set_float(s, RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, -0.5),
                  RAPS_ERROR_INVALID_ARGUMENT);
    assert_string_equal(raps_settings_last_error(s),
                        "value -0.5 of parameter atlas_texels_per_unit is outside [0, 1e+15]");
    assert_status(raps_settings_set_float(s, RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, 0.0), RAPS_OK);
    assert_status(raps_settings_set_int(NULL, RAPS_PARAM_MONITOR, 1), RAPS_ERROR_INVALID_ARGUMENT);
    /* A refused value leaves the settings unchanged. */
    int64_t monitor = -1;
    double alpha = 0;
    assert_status(raps_settings_get_int(s, RAPS_PARAM_MONITOR, &monitor), RAPS_OK);
    assert_int_equal(monitor, RAPS_MONITOR_AREA);
    assert_status(raps_settings_get_float(s, RAPS_PARAM_ALPHA, &alpha), RAPS_OK);
    assert_near(alpha, 1.0, 0);
    /* A success clears the message. */
    assert_status(raps_settings_set_float(s, RAPS_PARAM_ALPHA, 2.5), RAPS_OK);
    assert_string_equal(raps_settings_last_error(s), "");
    assert_status(raps_settings_get_int(s, RAPS_PARAM_ALPHA, &monitor),
                  RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_settings_get_int(s, RAPS_PARAM_MONITOR, NULL), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_param_info(0, NULL, NULL, NULL, NULL, NULL), RAPS_ERROR_INVALID_ARGUMENT);
    raps_settings_destroy(s);
}

static void settings_clone_is_independent(void** state) {
    (void)state;
    raps_settings* a = make_settings(RAPS_WEIGHTS_UNIFORM, RAPS_MONITOR_ANGLE, 3.0, 4);
    raps_settings* b = NULL;
    assert_status(raps_settings_clone(a, &b), RAPS_OK);
    assert_status(raps_settings_set_int(a, RAPS_PARAM_ITERATIONS, 1), RAPS_OK);
    int64_t iterations = 0, monitor = 0;
    double alpha = 0;
    assert_status(raps_settings_get_int(b, RAPS_PARAM_ITERATIONS, &iterations), RAPS_OK);
    assert_status(raps_settings_get_int(b, RAPS_PARAM_MONITOR, &monitor), RAPS_OK);
    assert_status(raps_settings_get_float(b, RAPS_PARAM_ALPHA, &alpha), RAPS_OK);
    assert_int_equal(iterations, 4);
    assert_int_equal(monitor, RAPS_MONITOR_ANGLE);
    assert_near(alpha, 3.0, 0);
    raps_settings_destroy(a);
    raps_settings_destroy(b);
}

static void empty_result_refuses_reads(void** state) {
    (void)state;
    raps_result* r = NULL;
    assert_status(raps_result_create(&r), RAPS_OK);
    assert_int_equal(raps_result_vertex_count(r), 0);
    assert_int_equal(raps_result_index_count(r), 0);
    float uv[2];
    uint32_t idx[3];
    raps_stats stats;
    stats.struct_size = sizeof(stats);
    assert_status(raps_result_copy_uvs_f32(r, uv, 1, 0), RAPS_ERROR_INVALID_OPERATION);
    assert_status(raps_result_copy_indices_u32(r, idx, 3), RAPS_ERROR_INVALID_OPERATION);
    assert_status(raps_result_copy_vertex_remap(r, idx, 3), RAPS_ERROR_INVALID_OPERATION);
    assert_status(raps_result_get_stats(r, &stats), RAPS_ERROR_INVALID_OPERATION);
    assert_near(raps_result_phase_ms(r, RAPS_PHASE_ADAPT), 0.0, 0);
    raps_result_destroy(r);
}

static void result_copies_check_capacity_and_stride(void** state) {
    (void)state;
    test_mesh disk = make_flat_disk(3, 6, 0.0);
    raps_mesh* mesh = to_raps_mesh(&disk);
    raps_result* r = parameterize_ok(mesh, NULL);
    const size_t n = raps_result_vertex_count(r);
    assert_int_equal(n, disk.vertex_count);
    assert_int_equal(raps_result_index_count(r), disk.index_count);

    float* packed = malloc(2 * n * sizeof(float));
    float* strided = malloc(4 * n * sizeof(float));
    assert_status(raps_result_copy_uvs_f32(r, packed, n - 1, 0), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_result_copy_uvs_f32(r, packed, n, 4), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_result_copy_uvs_f32(r, NULL, n, 0), RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_result_copy_uvs_f32(r, packed, n, 0), RAPS_OK);
    assert_status(raps_result_copy_uvs_f32(r, strided, n, 4 * sizeof(float)), RAPS_OK);
    double* exact = uvs_of(r);
    for (size_t i = 0; i < n; ++i) {
        assert_near(packed[2 * i], strided[4 * i], 0);
        assert_near(packed[2 * i + 1], strided[4 * i + 1], 0);
        assert_near(packed[2 * i], exact[2 * i], 1e-6);
    }
    uint32_t* indices = malloc(disk.index_count * sizeof(uint32_t));
    uint32_t* remap = malloc(n * sizeof(uint32_t));
    assert_status(raps_result_copy_indices_u32(r, indices, disk.index_count - 1),
                  RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_result_copy_indices_u32(r, indices, disk.index_count), RAPS_OK);
    assert_memory_equal(indices, disk.indices, disk.index_count * sizeof(uint32_t));
    assert_status(raps_result_copy_vertex_remap(r, remap, n), RAPS_OK);
    for (size_t i = 0; i < n; ++i) assert_int_equal(remap[i], i);

    free(packed);
    free(strided);
    free(exact);
    free(indices);
    free(remap);
    raps_result_destroy(r);
    raps_mesh_destroy(mesh);
    test_mesh_free(&disk);
}

/* Fails unless the handle's message contains `fragment`. */
#define assert_message(message, fragment)                                                   \
    do {                                                                                    \
        const char* assert_message_m = (message);                                           \
        if (!strstr(assert_message_m, (fragment))) {                                        \
            fail_msg("%s is '%s', which lacks '%s'", #message, assert_message_m, fragment); \
        }                                                                                   \
    } while (0)

/* Every failing call stores a message naming its problem in the handle it was given, const
 * handles included: the getters in the settings, the copies and the statistics in the result.
 * A successful call on a const handle leaves the message as it was (it only reads); one that
 * changes the handle clears it. */
static void failing_reads_store_their_message_in_the_handle(void** state) {
    (void)state;
    raps_settings* s = NULL;
    assert_status(raps_settings_create(&s), RAPS_OK);
    int64_t i = 0;
    double f = 0;
    assert_status(raps_settings_get_int(s, 9999, &i), RAPS_ERROR_INVALID_ARGUMENT);
    assert_message(raps_settings_last_error(s), "unknown parameter 9999");
    assert_status(raps_settings_get_float(s, RAPS_PARAM_MONITOR, &f), RAPS_ERROR_INVALID_ARGUMENT);
    assert_message(raps_settings_last_error(s), "an int: use raps_settings_set_int/get_int");
    assert_status(raps_settings_get_int(s, RAPS_PARAM_ALPHA, &i), RAPS_ERROR_INVALID_ARGUMENT);
    assert_message(raps_settings_last_error(s), "a float");
    assert_status(raps_settings_get_int(s, RAPS_PARAM_MONITOR, NULL), RAPS_ERROR_INVALID_ARGUMENT);
    assert_message(raps_settings_last_error(s), "NULL pointer");
    assert_status(raps_settings_get_int(s, RAPS_PARAM_MONITOR, &i), RAPS_OK);
    assert_message(raps_settings_last_error(s), "NULL pointer");
    assert_status(raps_settings_set_int(s, RAPS_PARAM_MONITOR, RAPS_MONITOR_AREA), RAPS_OK);
    assert_string_equal(raps_settings_last_error(s), "");
    raps_settings_destroy(s);

    raps_result* r = NULL;
    assert_status(raps_result_create(&r), RAPS_OK);
    float uv[2];
    uint32_t u32[3];
    raps_stats stats;
    stats.struct_size = sizeof(stats);
    assert_status(raps_result_copy_uvs_f32(r, uv, 1, 0), RAPS_ERROR_INVALID_OPERATION);
    assert_message(raps_result_last_error(r), "holds no map");
    assert_status(raps_result_copy_vertex_remap(r, NULL, 3), RAPS_ERROR_INVALID_ARGUMENT);
    assert_message(raps_result_last_error(r), "dst is NULL");
    assert_status(raps_result_get_stats(r, &stats), RAPS_ERROR_INVALID_OPERATION);
    assert_message(raps_result_last_error(r), "holds no map");

    test_mesh disk = make_flat_disk(3, 6, 0.0);
    raps_mesh* mesh = to_raps_mesh(&disk);
    assert_status(raps_parameterize(mesh, NULL, r), RAPS_OK);
    assert_string_equal(raps_result_last_error(r), "");
    const size_t n = raps_result_vertex_count(r);
    float* packed = malloc(2 * n * sizeof(float));
    uint32_t* indices = malloc(disk.index_count * sizeof(uint32_t));
    assert_status(raps_result_copy_uvs_f32(r, packed, n - 1, 0), RAPS_ERROR_INVALID_ARGUMENT);
    assert_message(raps_result_last_error(r), "is smaller than the");
    assert_status(raps_result_copy_uvs_f32(r, packed, n, 4), RAPS_ERROR_INVALID_ARGUMENT);
    assert_message(raps_result_last_error(r), "stride_bytes is smaller");
    assert_status(raps_result_copy_indices_u32(r, indices, 2), RAPS_ERROR_INVALID_ARGUMENT);
    assert_message(raps_result_last_error(r), "capacity 2 is smaller");
    assert_status(raps_result_copy_vertex_remap(r, u32, 1), RAPS_ERROR_INVALID_ARGUMENT);
    assert_message(raps_result_last_error(r), "capacity 1 is smaller");
    assert_status(raps_result_copy_chart_ids(r, u32, 1), RAPS_ERROR_INVALID_ARGUMENT);
    assert_message(raps_result_last_error(r), "capacity is smaller than the output triangles");
    assert_status(raps_result_copy_sphere_points_f32(r, packed, n, 0),
                  RAPS_ERROR_INVALID_OPERATION);
    assert_message(raps_result_last_error(r), "no sphere points");
    stats.struct_size = 4;
    assert_status(raps_result_get_stats(r, &stats), RAPS_ERROR_INVALID_ARGUMENT);
    assert_message(raps_result_last_error(r), "struct_size 4");
    /* Successful reads keep the last failure's message; the next run clears it. */
    assert_status(raps_result_copy_uvs_f32(r, packed, n, 0), RAPS_OK);
    stats.struct_size = sizeof(stats);
    assert_status(raps_result_get_stats(r, &stats), RAPS_OK);
    assert_message(raps_result_last_error(r), "struct_size 4");
    assert_status(raps_parameterize(mesh, NULL, r), RAPS_OK);
    assert_string_equal(raps_result_last_error(r), "");
    free(packed);
    free(indices);
    raps_result_destroy(r);
    raps_mesh_destroy(mesh);
    test_mesh_free(&disk);
}

/* A caller compiled against an older, shorter raps_stats sets a smaller struct_size: the
 * library must write nothing beyond it. */
static void stats_respect_the_callers_struct_size(void** state) {
    (void)state;
    test_mesh disk = make_flat_disk(3, 6, 0.0);
    raps_mesh* mesh = to_raps_mesh(&disk);
    raps_result* r = parameterize_ok(mesh, NULL);
    unsigned char buffer[sizeof(raps_stats) + 16];
    memset(buffer, 0xAB, sizeof(buffer));
    raps_stats* partial = (raps_stats*)buffer;
    partial->struct_size = offsetof(raps_stats, area_log_mean);
    assert_status(raps_result_get_stats(r, partial), RAPS_OK);
    assert_int_equal(partial->struct_size, offsetof(raps_stats, area_log_mean));
    assert_int_equal(partial->triangle_count, disk.index_count / 3);
    for (size_t i = offsetof(raps_stats, area_log_mean); i < sizeof(buffer); ++i) {
        assert_int_equal(buffer[i], 0xAB);
    }
    raps_stats tiny;
    tiny.struct_size = 4;
    assert_status(raps_result_get_stats(r, &tiny), RAPS_ERROR_INVALID_ARGUMENT);
    raps_result_destroy(r);
    raps_mesh_destroy(mesh);
    test_mesh_free(&disk);
}

static void phase_times_are_recorded(void** state) {
    (void)state;
    test_mesh disk = make_flat_disk(8, 6, 0.2);
    raps_mesh* mesh = to_raps_mesh(&disk);
    raps_result* r = parameterize_ok(mesh, NULL);
    for (int p = 0; p < RAPS_PHASE_COUNT; ++p) assert_true(raps_result_phase_ms(r, p) >= 0.0);
    assert_true(raps_result_phase_ms(r, RAPS_PHASE_INITIAL_MAP) > 0.0);
    assert_near(raps_result_phase_ms(r, -1), 0.0, 0);
    assert_near(raps_result_phase_ms(r, RAPS_PHASE_COUNT), 0.0, 0);
    raps_result_destroy(r);
    raps_mesh_destroy(mesh);
    test_mesh_free(&disk);
}

static void mesh_setters_replace_and_count(void** state) {
    (void)state;
    raps_mesh* m = NULL;
    assert_status(raps_mesh_create(&m), RAPS_OK);
    const float xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    const uint16_t tri[] = {0, 1, 2, 1, 3, 2};
    assert_status(raps_mesh_set_positions_f32(m, xyz, 4, 0), RAPS_OK);
    assert_status(raps_mesh_set_indices_u16(m, tri, 6), RAPS_OK);
    assert_int_equal(raps_mesh_vertex_count(m), 4);
    assert_int_equal(raps_mesh_triangle_count(m), 2);
    assert_status(raps_mesh_set_indices_u16(m, tri, 3), RAPS_OK);
    assert_int_equal(raps_mesh_triangle_count(m), 1);
    assert_string_equal(raps_mesh_last_error(m), "");
    raps_mesh_destroy(m);
}

/* Interleaved vertex data (position + normal + uv, 32 bytes) is read through the stride: the
 * map equals the one from tightly packed positions, and the bytes between are never read. */
static void positions_are_read_through_a_stride(void** state) {
    (void)state;
    test_mesh disk = make_flat_disk(4, 6, 0.2);
    const size_t n = disk.vertex_count;
    float* interleaved = calloc(n, 32);
    float* packed = calloc(n, 12);
    for (size_t i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) {
            interleaved[8 * i + c] = (float)disk.positions[3 * i + c];
            packed[3 * i + c] = (float)disk.positions[3 * i + c];
        }
        interleaved[8 * i + 3] = NAN; /* not a position: must never be read as one */
    }
    raps_mesh *a = NULL, *b = NULL;
    assert_status(raps_mesh_create(&a), RAPS_OK);
    assert_status(raps_mesh_create(&b), RAPS_OK);
    assert_status(raps_mesh_set_positions_f32(a, interleaved, n, 32), RAPS_OK);
    assert_status(raps_mesh_set_positions_f32(b, packed, n, 0), RAPS_OK);
    assert_status(raps_mesh_set_indices_u32(a, disk.indices, disk.index_count), RAPS_OK);
    assert_status(raps_mesh_set_indices_u32(b, disk.indices, disk.index_count), RAPS_OK);
    raps_result* ra = parameterize_ok(a, NULL);
    raps_result* rb = parameterize_ok(b, NULL);
    double* ua = uvs_of(ra);
    double* ub = uvs_of(rb);
    assert_memory_equal(ua, ub, 2 * n * sizeof(double));
    free(ua);
    free(ub);
    free(interleaved);
    free(packed);
    raps_result_destroy(ra);
    raps_result_destroy(rb);
    raps_mesh_destroy(a);
    raps_mesh_destroy(b);
    test_mesh_free(&disk);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(version_query_matches_header),
        cmocka_unit_test(status_values_are_pinned),
        cmocka_unit_test(every_status_has_a_description),
        cmocka_unit_test(destroy_null_is_a_noop_and_create_rejects_null),
        cmocka_unit_test(settings_hold_the_documented_defaults),
        cmocka_unit_test(every_parameter_round_trips),
        cmocka_unit_test(settings_refuse_bad_keys_types_and_values),
        cmocka_unit_test(settings_clone_is_independent),
        cmocka_unit_test(empty_result_refuses_reads),
        cmocka_unit_test(result_copies_check_capacity_and_stride),
        cmocka_unit_test(failing_reads_store_their_message_in_the_handle),
        cmocka_unit_test(stats_respect_the_callers_struct_size),
        cmocka_unit_test(phase_times_are_recorded),
        cmocka_unit_test(mesh_setters_replace_and_count),
        cmocka_unit_test(positions_are_read_through_a_stride),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
