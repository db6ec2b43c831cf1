/* Resource limits: counts near SIZE_MAX and 2^31 through the mesh setters and the output copies
 * are refused before any size computation can overflow and before a byte is read or written,
 * and RAPS_PARAM_MAX_MEMORY_MB refuses runs whose estimated peak exceeds it, before any work,
 * with a message naming the estimate and the cap. (The triangle cap is in test_bad_input.c.) */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "raps.h"
#include "support/test_meshes.h"

static const float kTriangle[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
static const double kTriangle64[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};

/* Counts past what raps indexes are refused from the count alone: the 36 bytes given are never
 * read past (ASan would see it), whatever the count claims. */
static void huge_vertex_counts_are_refused_unread(void** state) {
    (void)state;
    raps_mesh* m = NULL;
    assert_status(raps_mesh_create(&m), RAPS_OK);
    const size_t counts[] = {(size_t)1 << 31,   ((size_t)1 << 31) + 1, SIZE_MAX / 24, SIZE_MAX / 12,
                             SIZE_MAX / 12 + 1, SIZE_MAX / 3,          SIZE_MAX - 1,  SIZE_MAX};
    for (size_t i = 0; i < sizeof(counts) / sizeof(counts[0]); ++i) {
        assert_status(raps_mesh_set_positions_f32(m, kTriangle, counts[i], 0),
                      RAPS_ERROR_TOO_LARGE);
        assert_non_null(strstr(raps_mesh_last_error(m), "too large"));
        assert_status(raps_mesh_set_positions_f64(m, kTriangle64, counts[i], 0),
                      RAPS_ERROR_TOO_LARGE);
    }
    assert_int_equal(raps_mesh_vertex_count(m), 0); /* nothing was replaced */
    raps_mesh_destroy(m);
}

/* A stride that would place a point past the end of the address space (count - 1 strides
 * overflow size_t) is refused before reading, whatever the count. */
static void strides_past_the_address_space_are_refused(void** state) {
    (void)state;
    raps_mesh* m = NULL;
    assert_status(raps_mesh_create(&m), RAPS_OK);
    const struct {
        size_t count, stride;
    } cases[] = {{2, SIZE_MAX},
                 {2, SIZE_MAX - 11},
                 {3, SIZE_MAX / 2 + 1},
                 {(size_t)1 << 30, (size_t)1 << 40},
                 {((size_t)1 << 31) - 1, (size_t)1 << 34}};
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); ++i) {
        assert_status(raps_mesh_set_positions_f32(m, kTriangle, cases[i].count, cases[i].stride),
                      RAPS_ERROR_INVALID_ARGUMENT);
        assert_non_null(strstr(raps_mesh_last_error(m), "address"));
        assert_status(raps_mesh_set_positions_f64(m, kTriangle64, cases[i].count, cases[i].stride),
                      RAPS_ERROR_INVALID_ARGUMENT);
    }
    /* One point at any stride reads one point: allowed. */
    assert_status(raps_mesh_set_positions_f32(m, kTriangle, 1, SIZE_MAX), RAPS_OK);
    assert_int_equal(raps_mesh_vertex_count(m), 1);
    raps_mesh_destroy(m);
}

static void huge_index_counts_are_refused_unread(void** state) {
    (void)state;
    raps_mesh* m = NULL;
    assert_status(raps_mesh_create(&m), RAPS_OK);
    const uint32_t tri[] = {0, 1, 2};
    const uint16_t tri16[] = {0, 1, 2};
    /* Multiples of 3 making more than 2^28 triangles: too large (3 half-edges per triangle
     * overflowed the library's int32 indexing from 715,827,883 triangles on). SIZE_MAX =
     * 2^64 - 1 is a multiple of 3. */
    const size_t too_large[] = {((size_t)3 << 28) + 3, (size_t)3 * 715827883, (size_t)3 << 31,
                                SIZE_MAX / 3 * 3, SIZE_MAX - 3};
    for (size_t i = 0; i < sizeof(too_large) / sizeof(too_large[0]); ++i) {
        assert_int_equal(too_large[i] % 3, 0);
        assert_status(raps_mesh_set_indices_u32(m, tri, too_large[i]), RAPS_ERROR_TOO_LARGE);
        assert_non_null(strstr(raps_mesh_last_error(m), "at most 2^28"));
        assert_status(raps_mesh_set_indices_u16(m, tri16, too_large[i]), RAPS_ERROR_TOO_LARGE);
    }
    /* Not multiples of 3: the count is wrong before it is large. */
    const size_t ragged[] = {SIZE_MAX - 1, SIZE_MAX - 2, ((size_t)3 << 31) + 1};
    for (size_t i = 0; i < sizeof(ragged) / sizeof(ragged[0]); ++i) {
        assert_status(raps_mesh_set_indices_u32(m, tri, ragged[i]), RAPS_ERROR_INDEX_COUNT);
        assert_status(raps_mesh_set_indices_u16(m, tri16, ragged[i]), RAPS_ERROR_INDEX_COUNT);
    }
    assert_int_equal(raps_mesh_triangle_count(m), 0);
    raps_mesh_destroy(m);
}

/* Output copies: a stride that spreads the output past the address space is refused before a
 * byte is written; capacities near SIZE_MAX are fine (only the output's size is written). */
static void output_copies_refuse_strides_past_the_address_space(void** state) {
    (void)state;
    test_mesh disk = make_flat_disk(2, 6, 0.0);
    raps_mesh* m = to_raps_mesh(&disk);
    raps_result* r = parameterize_ok(m, NULL);
    const size_t n = raps_result_vertex_count(r);
    double* uv = calloc(2 * n, sizeof(double));
    float* uv32 = calloc(2 * n, sizeof(float));
    assert_non_null(uv);
    assert_non_null(uv32);
    const size_t strides[] = {SIZE_MAX, SIZE_MAX / 2, SIZE_MAX / (n - 1) + 1};
    for (size_t i = 0; i < sizeof(strides) / sizeof(strides[0]); ++i) {
        assert_status(raps_result_copy_uvs_f64(r, uv, SIZE_MAX, strides[i]),
                      RAPS_ERROR_INVALID_ARGUMENT);
        assert_status(raps_result_copy_uvs_f32(r, uv32, SIZE_MAX, strides[i]),
                      RAPS_ERROR_INVALID_ARGUMENT);
    }
    for (size_t i = 0; i < 2 * n; ++i) assert_true(uv[i] == 0.0 && uv32[i] == 0.0f);
    assert_status(raps_result_copy_uvs_f64(r, uv, SIZE_MAX, 0), RAPS_OK);
    uint32_t* indices = calloc(disk.index_count, sizeof(uint32_t));
    assert_non_null(indices);
    assert_status(raps_result_copy_indices_u32(r, indices, SIZE_MAX), RAPS_OK);
    assert_memory_equal(indices, disk.indices, disk.index_count * sizeof(uint32_t));
    free(indices);
    free(uv);
    free(uv32);
    raps_result_destroy(r);
    raps_mesh_destroy(m);
    test_mesh_free(&disk);
}

static int32_t count_calls(void* user, raps_phase phase, double fraction) {
    (void)phase;
    (void)fraction;
    ++*(int*)user;
    return 1;
}

/* Cancels at the first progress call, counting it: a run the cap lets through stops there. */
static int32_t cancel_at_once(void* user, raps_phase phase, double fraction) {
    (void)phase;
    (void)fraction;
    ++*(int*)user;
    return 0;
}

/* The smallest RAPS_PARAM_MAX_MEMORY_MB a mesh passes with, by bisection: every cap below it is
 * refused (TOO_LARGE, before any progress call) and every cap from it on lets the run start
 * (which the callback then cancels). */
static int64_t smallest_passing_cap(const raps_mesh* m, raps_settings* s) {
    raps_result* r = NULL;
    assert_status(raps_result_create(&r), RAPS_OK);
    int calls = 0;
    assert_status(raps_settings_set_progress(s, cancel_at_once, &calls), RAPS_OK);
    int64_t low = 0, high = 1 << 20; /* low is refused (or 0: no cap), high passes */
    assert_status(raps_settings_set_int(s, RAPS_PARAM_MAX_MEMORY_MB, high), RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_ERROR_CANCELLED);
    while (high - low > 1) {
        const int64_t mid = (low + high) / 2;
        assert_status(raps_settings_set_int(s, RAPS_PARAM_MAX_MEMORY_MB, mid), RAPS_OK);
        calls = 0;
        const raps_status status = raps_parameterize(m, s, r);
        if (status == RAPS_ERROR_TOO_LARGE) {
            assert_int_equal(calls, 0); /* refused before any phase started */
            low = mid;
        } else {
            assert_status(status, RAPS_ERROR_CANCELLED);
            assert_int_equal(calls, 1);
            high = mid;
        }
    }
    assert_status(raps_settings_set_progress(s, NULL, NULL), RAPS_OK);
    raps_result_destroy(r);
    return high;
}

static void memory_cap_refuses_before_any_work(void** state) {
    (void)state;
    test_mesh disk = make_flat_disk(40, 6, 0.1); /* 9600 triangles */
    raps_mesh* m = to_raps_mesh(&disk);
    raps_settings* s = NULL;
    raps_result* r = NULL;
    assert_status(raps_settings_create(&s), RAPS_OK);
    assert_status(raps_result_create(&r), RAPS_OK);
    int64_t value = -1;
    assert_status(raps_settings_get_int(s, RAPS_PARAM_MAX_MEMORY_MB, &value), RAPS_OK);
    assert_int_equal(value, 0); /* no cap by default */
    assert_status(raps_settings_set_int(s, RAPS_PARAM_MAX_MEMORY_MB, -1),
                  RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_MAX_MEMORY_MB, (int64_t)1 << 31),
                  RAPS_ERROR_INVALID_ARGUMENT);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_MAX_MEMORY_MB, 1), RAPS_OK);
    int calls = 0;
    assert_status(raps_settings_set_progress(s, count_calls, &calls), RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_ERROR_TOO_LARGE);
    assert_int_equal(calls, 0);
    const char* message = raps_result_last_error(r);
    assert_non_null(strstr(message, "RAPS_PARAM_MAX_MEMORY_MB = 1"));
    assert_non_null(strstr(message, "MiB at its peak"));
    /* The handles stay usable: without the cap the same run succeeds. */
    assert_status(raps_settings_set_int(s, RAPS_PARAM_MAX_MEMORY_MB, 0), RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_OK);
    assert_true(calls > 0);
    assert_status(raps_settings_set_int(s, RAPS_PARAM_MAX_MEMORY_MB, 2147483647), RAPS_OK);
    assert_status(raps_parameterize(m, s, r), RAPS_OK);
    raps_result_destroy(r);
    raps_settings_destroy(s);
    raps_mesh_destroy(m);
    test_mesh_free(&disk);
}

/* The estimate grows with the triangle count in every domain, and with the atlas's texels:
 * four times the triangles need between 3 and 6 times the cap (linear plus the n log n fill
 * term, over a fixed part; the atlas at 256 texels, whose grids are then small), the atlas at
 * 16384 texels needs at least 2 GiB more (its packer's rasters: measured 7 to 11 bytes per
 * texel at 8192), and at a density the charts' texels count (2 bytes each measured). */
static void memory_estimate_scales_with_the_work(void** state) {
    (void)state;
    const int32_t domains[] = {RAPS_DOMAIN_DISK, RAPS_DOMAIN_SPHERE, RAPS_DOMAIN_ATLAS};
    test_mesh small_disk = make_flat_disk(40, 6, 0.1), large_disk = make_flat_disk(80, 6, 0.1);
    test_mesh small_sphere = make_uv_sphere(60, 80), large_sphere = make_uv_sphere(119, 160);
    const test_mesh* small[] = {&small_disk, &small_sphere, &small_disk};
    const test_mesh* large[] = {&large_disk, &large_sphere, &large_disk};
    for (int d = 0; d < 3; ++d) {
        raps_settings* s = NULL;
        assert_status(raps_settings_create(&s), RAPS_OK);
        assert_status(raps_settings_set_int(s, RAPS_PARAM_DOMAIN, domains[d]), RAPS_OK);
        assert_status(raps_settings_set_int(s, RAPS_PARAM_SPHERE_MAX_SWEEPS, 3), RAPS_OK);
        if (domains[d] == RAPS_DOMAIN_ATLAS)
            assert_status(raps_settings_set_int(s, RAPS_PARAM_ATLAS_RESOLUTION, 256), RAPS_OK);
        raps_mesh* m_small = to_raps_mesh(small[d]);
        raps_mesh* m_large = to_raps_mesh(large[d]);
        assert_int_equal(raps_mesh_triangle_count(m_large), 4 * raps_mesh_triangle_count(m_small));
        const int64_t cap_small = smallest_passing_cap(m_small, s);
        const int64_t cap_large = smallest_passing_cap(m_large, s);
        print_message("domain %d: %zu triangles pass from %lld MiB, %zu from %lld MiB\n",
                      domains[d], raps_mesh_triangle_count(m_small), (long long)cap_small,
                      raps_mesh_triangle_count(m_large), (long long)cap_large);
        assert_true(cap_small >= 2);
        assert_true(cap_large >= 3 * cap_small && cap_large <= 6 * cap_small);
        if (domains[d] == RAPS_DOMAIN_ATLAS) {
            assert_status(raps_settings_set_int(s, RAPS_PARAM_ATLAS_RESOLUTION, 16384), RAPS_OK);
            const int64_t cap_texels = smallest_passing_cap(m_small, s);
            print_message("  at 16384 texels: from %lld MiB\n", (long long)cap_texels);
            assert_true(cap_texels >= cap_small + 2048);
            /* About 1e8 texels of charts (the disk's area times the density squared). */
            assert_status(raps_settings_set_float(s, RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, 6000.0),
                          RAPS_OK);
            const int64_t cap_density = smallest_passing_cap(m_small, s);
            print_message("  at 6000 texels per unit: from %lld MiB\n", (long long)cap_density);
            assert_true(cap_density >= cap_small + 200);
        }
        raps_mesh_destroy(m_small);
        raps_mesh_destroy(m_large);
        raps_settings_destroy(s);
    }
    test_mesh_free(&small_disk);
    test_mesh_free(&large_disk);
    test_mesh_free(&small_sphere);
    test_mesh_free(&large_sphere);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(huge_vertex_counts_are_refused_unread),
        cmocka_unit_test(strides_past_the_address_space_are_refused),
        cmocka_unit_test(huge_index_counts_are_refused_unread),
        cmocka_unit_test(output_copies_refuse_strides_past_the_address_space),
        cmocka_unit_test(memory_cap_refuses_before_any_work),
        cmocka_unit_test(memory_estimate_scales_with_the_work),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
