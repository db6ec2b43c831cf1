/* raps-soak: many runs through the C ABI in one process, as a build farm makes them, and the
 * memory they leave behind. Each run creates its handles, sets the arrays, parameterizes, copies
 * the output out and destroys everything; the runs cycle through small and medium meshes of all
 * three domains, a refused mesh and a cancelled run. At checkpoints it prints the resident set
 * (/proc/self/statm) and the bytes the heap has in use (mallinfo2, or the sanitizer's count under
 * ASan, whose quarantine makes the resident set meaningless); after the warm-up (the first
 * tenth of the runs) the heap in use must not grow by more than --max-heap-growth-kb, and the
 * resident set (outside ASan) by more than --max-rss-growth-kb.
 *
 *   raps-soak [--runs N] [--max-heap-growth-kb K] [--max-rss-growth-kb K]
 *
 * Exit status 0 when memory stayed flat and every run gave its expected status and output. */
#define _GNU_SOURCE
#include <malloc.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "raps.h"
#include "support/test_meshes.h"

#if defined(__SANITIZE_ADDRESS__)
#define RAPS_SOAK_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RAPS_SOAK_ASAN 1
#endif
#endif
#ifdef RAPS_SOAK_ASAN
/* The sanitizer runtime's count of heap bytes in use (GCC ships no header declaring it). */
size_t __sanitizer_get_current_allocated_bytes(void);
#endif

/* One kind of run: a mesh, the settings it runs with, and what it must give. */
typedef struct soak_case {
    const char* name;
    test_mesh mesh;
    int32_t domain;
    int32_t sphere_uv;
    int64_t iterations;
    int cancel_at;            /* > 0: cancel at this progress call */
    raps_status expected;     /* the status every run of it must return */
    size_t output_vertices;   /* filled by the first run; later runs must agree */
    double first_uv_checksum; /* the same */
    double seconds;           /* spent in its runs */
    long runs;
} soak_case;

static size_t resident_bytes(void) {
    long pages_total = 0, pages_resident = 0;
    FILE* statm = fopen("/proc/self/statm", "r");
    if (!statm) return 0;
    if (fscanf(statm, "%ld %ld", &pages_total, &pages_resident) != 2) pages_resident = 0;
    fclose(statm);
    return (size_t)pages_resident * (size_t)sysconf(_SC_PAGESIZE);
}

/* Bytes the allocator has handed out and not had back. */
static size_t heap_in_use(void) {
#ifdef RAPS_SOAK_ASAN
    return __sanitizer_get_current_allocated_bytes();
#else
    const struct mallinfo2 info = mallinfo2();
    return info.uordblks + info.hblkhd;
#endif
}

static double seconds_since(const struct timespec* start) {
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)(now.tv_sec - start->tv_sec) + 1e-9 * (double)(now.tv_nsec - start->tv_nsec);
}

static int32_t cancel_at_call(void* user, raps_phase phase, double fraction) {
    (void)phase;
    (void)fraction;
    int* left = user;
    return --*left > 0;
}

/* One run of `c` through the whole C ABI; returns 0 when it behaved as expected. */
static int run_case(soak_case* c) {
    raps_mesh* mesh = NULL;
    raps_settings* settings = NULL;
    raps_result* result = NULL;
    int ok = raps_mesh_create(&mesh) == RAPS_OK && raps_settings_create(&settings) == RAPS_OK &&
             raps_result_create(&result) == RAPS_OK;
    ok = ok &&
         raps_mesh_set_positions_f64(mesh, c->mesh.positions, c->mesh.vertex_count, 0) == RAPS_OK &&
         raps_mesh_set_indices_u32(mesh, c->mesh.indices, c->mesh.index_count) == RAPS_OK;
    ok = ok && raps_settings_set_int(settings, RAPS_PARAM_DOMAIN, c->domain) == RAPS_OK &&
         raps_settings_set_int(settings, RAPS_PARAM_SPHERE_UV, c->sphere_uv) == RAPS_OK &&
         raps_settings_set_int(settings, RAPS_PARAM_ITERATIONS, c->iterations) == RAPS_OK &&
         raps_settings_set_int(settings, RAPS_PARAM_ATLAS_RESOLUTION, 256) == RAPS_OK;
    int calls_left = c->cancel_at;
    if (ok && c->cancel_at > 0) {
        ok = raps_settings_set_progress(settings, cancel_at_call, &calls_left) == RAPS_OK;
    }
    if (ok) {
        const raps_status status = raps_parameterize(mesh, settings, result);
        if (status != c->expected) {
            fprintf(stderr, "raps-soak: %s returned %s (%s), expected %s\n", c->name,
                    raps_status_string(status), raps_result_last_error(result),
                    raps_status_string(c->expected));
            ok = 0;
        }
    }
    if (ok && c->expected == RAPS_OK) {
        /* The output is copied out as an application would, and must be the same every run. */
        const size_t n = raps_result_vertex_count(result);
        double* uv = malloc(2 * n * sizeof(double) + 1);
        double* points = malloc(3 * n * sizeof(double) + 1);
        ok = uv && points;
        double checksum = 0;
        if (ok && raps_result_copy_uvs_f64(result, uv, n, 0) == RAPS_OK) {
            for (size_t i = 0; i < 2 * n; ++i) checksum += uv[i] * (double)(i % 7 + 1);
        } else if (ok) {
            ok = raps_result_copy_sphere_points_f64(result, points, n, 0) == RAPS_OK;
            for (size_t i = 0; ok && i < 3 * n; ++i) checksum += points[i] * (double)(i % 7 + 1);
        }
        free(uv);
        free(points);
        if (c->output_vertices == 0) {
            c->output_vertices = n;
            c->first_uv_checksum = checksum;
        } else if (n != c->output_vertices || checksum != c->first_uv_checksum) {
            fprintf(stderr, "raps-soak: %s gave a different output on a later run\n", c->name);
            ok = 0;
        }
    }
    raps_result_destroy(result);
    raps_settings_destroy(settings);
    raps_mesh_destroy(mesh);
    return ok ? 0 : -1;
}

static double ripple(double x, double y) {
    return 0.3 * sin(3 * x) * cos(2 * y) + 0.2 * x * y;
}

int main(int argc, char** argv) {
    long runs = 10000, max_heap_growth_kb = 64, max_rss_growth_kb = 4096;
    for (int a = 1; a + 1 < argc; a += 2) {
        if (strcmp(argv[a], "--runs") == 0) {
            runs = atol(argv[a + 1]);
        } else if (strcmp(argv[a], "--max-heap-growth-kb") == 0) {
            max_heap_growth_kb = atol(argv[a + 1]);
        } else if (strcmp(argv[a], "--max-rss-growth-kb") == 0) {
            max_rss_growth_kb = atol(argv[a + 1]);
        } else {
            fprintf(stderr,
                    "usage: raps-soak [--runs N] [--max-heap-growth-kb K] "
                    "[--max-rss-growth-kb K]\n");
            return 2;
        }
    }
    if (argc % 2 == 0 || runs < 10) {
        fprintf(stderr, "raps-soak: give option-value pairs, and at least 10 runs\n");
        return 2;
    }
    soak_case cases[] = {
        {"disk small (216 triangles)", make_flat_disk(6, 6, 0.2), RAPS_DOMAIN_DISK, 0, 1, 0,
         RAPS_OK, 0, 0, 0, 0},
        {"disk medium (5400 triangles, 2 iterations)", make_lifted_disk(30, 6, ripple),
         RAPS_DOMAIN_DISK, 0, 2, 0, RAPS_OK, 0, 0, 0, 0},
        {"sphere small (320 triangles, octahedral uvs)", make_icosphere(2), RAPS_DOMAIN_SPHERE,
         RAPS_SPHERE_UV_OCTAHEDRAL, 1, 0, RAPS_OK, 0, 0, 0, 0},
        {"sphere medium (5120 triangles)", make_icosphere(4), RAPS_DOMAIN_SPHERE, 0, 1, 0, RAPS_OK,
         0, 0, 0, 0},
        {"atlas small (144 triangles)", make_punctured_torus(12, 6), RAPS_DOMAIN_ATLAS, 0, 1, 0,
         RAPS_OK, 0, 0, 0, 0},
        {"atlas medium (2304 triangles)", make_closed_torus(48, 24), RAPS_DOMAIN_ATLAS, 0, 1, 0,
         RAPS_OK, 0, 0, 0, 0},
        {"refused: disk with a hole", make_annulus(6, 6), RAPS_DOMAIN_DISK, 0, 1, 0,
         RAPS_ERROR_MULTIPLE_BOUNDARIES, 0, 0, 0, 0},
        {"cancelled: atlas at its 6th progress call", make_closed_torus(48, 24), RAPS_DOMAIN_ATLAS,
         0, 1, 6, RAPS_ERROR_CANCELLED, 0, 0, 0, 0},
    };
    const size_t case_count = sizeof(cases) / sizeof(cases[0]);
    const long warm_up = runs / 10, checkpoint_every = runs / 10;
    size_t heap_after_warm_up = 0, rss_after_warm_up = 0, rss_start = resident_bytes();
    size_t heap_start = heap_in_use();
    struct timespec start;
    clock_gettime(CLOCK_MONOTONIC, &start);
    printf("raps-soak: %ld runs cycling through %zu cases\n", runs, case_count);
    printf("| runs | seconds | resident MB | heap in use KB |\n|---|---|---|---|\n");
    printf("| 0 | 0.0 | %.1f | %.1f |\n", (double)rss_start / 1048576.0, heap_start / 1024.0);
    int failures = 0;
    for (long run = 1; run <= runs; ++run) {
        soak_case* c = &cases[(size_t)(run - 1) % case_count];
        struct timespec case_start;
        clock_gettime(CLOCK_MONOTONIC, &case_start);
        if (run_case(c) != 0) ++failures;
        c->seconds += seconds_since(&case_start);
        ++c->runs;
        if (run == warm_up) {
            heap_after_warm_up = heap_in_use();
            rss_after_warm_up = resident_bytes();
        }
        if (run % checkpoint_every == 0 || run == runs) {
            printf("| %ld | %.1f | %.1f | %.1f |\n", run, seconds_since(&start),
                   (double)resident_bytes() / 1048576.0, heap_in_use() / 1024.0);
            fflush(stdout);
        }
    }
    const double heap_growth_kb = ((double)heap_in_use() - (double)heap_after_warm_up) / 1024.0;
    const double rss_growth_kb = ((double)resident_bytes() - (double)rss_after_warm_up) / 1024.0;
    printf("after the warm-up (%ld runs): heap in use %+.1f KB (at most %ld), resident %+.1f KB",
           warm_up, heap_growth_kb, max_heap_growth_kb, rss_growth_kb);
#ifdef RAPS_SOAK_ASAN
    printf(" (the %ld KB bound is not applied under ASan: its quarantine holds freed memory)\n",
           max_rss_growth_kb);
    const int rss_flat = 1;
#else
    printf(" (at most %ld)\n", max_rss_growth_kb);
    const int rss_flat = rss_growth_kb <= (double)max_rss_growth_kb;
#endif
    printf("%.1f ms per run on average; %d runs misbehaved\n",
           1000.0 * seconds_since(&start) / (double)runs, failures);
    for (size_t c = 0; c < case_count; ++c) {
        printf("  %-45s %7.2f ms per run\n", cases[c].name,
               1000.0 * cases[c].seconds / (double)(cases[c].runs ? cases[c].runs : 1));
        test_mesh_free(&cases[c].mesh);
    }
    const int flat = heap_growth_kb <= (double)max_heap_growth_kb && rss_flat;
    if (!flat) fprintf(stderr, "raps-soak: memory grew after the warm-up\n");
    return failures == 0 && flat ? 0 : 1;
}
