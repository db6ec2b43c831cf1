/* The same bits from the AVX2 and the baseline dense kernels, and for 1, 2 and 3 threads
 * (include/raps.h, docs/reproducibility.md): every shared mesh in the disk, sphere and atlas
 * domains, every output compared through a 64-bit hash of its bytes (uvs, sphere points,
 * indices, remap, chart ids, statistics but threads_used). The baseline kernels run in a child
 * process (this executable again, with RAPS_KERNELS=baseline: the library reads it once per
 * process). Thread counts are checked to have really run workers: per domain, some run used
 * 2 and some 3 threads, each compared with the 1-thread bits. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "raps.h"
#include "support/test_meshes.h"

enum { kFields = 6 };
static const char* kFieldNames[kFields] = {"uvs", "sphere points", "indices", "remap",
                                           "chart ids", "statistics"};

typedef struct test_case {
    const char* name; /* shared mesh, or "uv-sphere" (built here: large enough for 3 threads) */
    int32_t domain;
} test_case;

/* Every shared mesh in every domain it belongs to (the atlas takes them all), and a uv sphere
 * large enough for the sphere's thread pool to use 3 threads. Each domain lists its largest
 * case last. */
static const test_case kCases[] = {
    {"alligator.obj", RAPS_DOMAIN_DISK},
    {"camelhead.off", RAPS_DOMAIN_DISK},
    {"lion.off", RAPS_DOMAIN_DISK},
    {"face.obj", RAPS_DOMAIN_DISK},
    {"bunny.off", RAPS_DOMAIN_SPHERE},
    {"cheburashka.off", RAPS_DOMAIN_SPHERE},
    {"cow.off", RAPS_DOMAIN_SPHERE},
    {"decimated-knight.off", RAPS_DOMAIN_SPHERE},
    {"decimated-max.obj", RAPS_DOMAIN_SPHERE},
    {"fandisk.obj", RAPS_DOMAIN_SPHERE},
    {"horse_quad.obj", RAPS_DOMAIN_SPHERE},
    {"spot.obj", RAPS_DOMAIN_SPHERE},
    {"uv-sphere", RAPS_DOMAIN_SPHERE},
    {"3holes.off", RAPS_DOMAIN_ATLAS},
    {"alligator.obj", RAPS_DOMAIN_ATLAS},
    {"bunny.off", RAPS_DOMAIN_ATLAS},
    {"camelhead.off", RAPS_DOMAIN_ATLAS},
    {"cheburashka.off", RAPS_DOMAIN_ATLAS},
    {"cow.off", RAPS_DOMAIN_ATLAS},
    {"decimated-knight.off", RAPS_DOMAIN_ATLAS},
    {"decimated-max.obj", RAPS_DOMAIN_ATLAS},
    {"fandisk.obj", RAPS_DOMAIN_ATLAS},
    {"fertility.off", RAPS_DOMAIN_ATLAS},
    {"halftunnel.off", RAPS_DOMAIN_ATLAS},
    {"horse_quad.obj", RAPS_DOMAIN_ATLAS},
    {"lion.off", RAPS_DOMAIN_ATLAS},
    {"spot.obj", RAPS_DOMAIN_ATLAS},
    {"suzanne.obj", RAPS_DOMAIN_ATLAS},
    {"teapot.obj", RAPS_DOMAIN_ATLAS},
    {"rocker-arm.obj", RAPS_DOMAIN_ATLAS},
    {"beetle.off", RAPS_DOMAIN_ATLAS},
    {"face.obj", RAPS_DOMAIN_ATLAS},
};
enum { kCaseCount = sizeof(kCases) / sizeof(kCases[0]), kMaxThreads = 3 };

/* Under the sanitizers (RAPS_TEST_SANITIZER, tests/CMakeLists.txt) only the cases that share
 * work among threads, one or two per domain (face, the uv sphere, teapot, rocker-arm): ASan runs
 * this test about six times slower, and the shared and static builds compare every case. */
static int case_runs(int c) {
    if (getenv("RAPS_TEST_SANITIZER") == NULL) return 1;
    return (strcmp(kCases[c].name, "face.obj") == 0 && kCases[c].domain == RAPS_DOMAIN_DISK) ||
           strcmp(kCases[c].name, "uv-sphere") == 0 ||
           strcmp(kCases[c].name, "rocker-arm.obj") == 0 ||
           strcmp(kCases[c].name, "teapot.obj") == 0;
}

typedef struct digest {
    uint64_t field[kFields];
    uint64_t threads_used;
} digest;

static uint64_t fnv1a(uint64_t hash, const void* data, size_t bytes) {
    const unsigned char* p = (const unsigned char*)data;
    for (size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * 1099511628211ull;
    return hash;
}
static const uint64_t kFnvStart = 14695981039346656037ull;

static digest run_case(const test_case* c, int32_t threads) {
    test_mesh mesh = strcmp(c->name, "uv-sphere") == 0 ? make_uv_sphere(100, 128)
                                                        : load_shared_mesh(c->name);
    raps_mesh* handle = to_raps_mesh(&mesh);
    raps_settings* settings = NULL;
    assert_int_equal(raps_settings_create(&settings), RAPS_OK);
    assert_int_equal(raps_settings_set_int(settings, RAPS_PARAM_DOMAIN, c->domain), RAPS_OK);
    assert_int_equal(raps_settings_set_int(settings, RAPS_PARAM_THREADS, threads), RAPS_OK);
    if (c->domain == RAPS_DOMAIN_SPHERE) {
        /* The octahedral uvs too: they are computed from the sphere points. */
        assert_int_equal(raps_settings_set_int(settings, RAPS_PARAM_SPHERE_UV,
                                               RAPS_SPHERE_UV_OCTAHEDRAL), RAPS_OK);
    }
    raps_result* r = parameterize_ok(handle, settings);
    const size_t vertices = raps_result_vertex_count(r), indices = raps_result_index_count(r);
    digest d;
    for (int f = 0; f < kFields; ++f) d.field[f] = kFnvStart;
    double* xyz = malloc((vertices * 3 + 1) * sizeof(double));
    uint32_t* ids = malloc((indices + vertices + 1) * sizeof(uint32_t));
    assert_non_null(xyz);
    assert_non_null(ids);
    assert_int_equal(raps_result_copy_uvs_f64(r, xyz, vertices, 0), RAPS_OK);
    d.field[0] = fnv1a(d.field[0], xyz, vertices * 2 * sizeof(double));
    if (c->domain == RAPS_DOMAIN_SPHERE) {
        assert_int_equal(raps_result_copy_sphere_points_f64(r, xyz, vertices, 0), RAPS_OK);
        d.field[1] = fnv1a(d.field[1], xyz, vertices * 3 * sizeof(double));
    }
    assert_int_equal(raps_result_copy_indices_u32(r, ids, indices), RAPS_OK);
    d.field[2] = fnv1a(d.field[2], ids, indices * sizeof(uint32_t));
    assert_int_equal(raps_result_copy_vertex_remap(r, ids, vertices), RAPS_OK);
    d.field[3] = fnv1a(d.field[3], ids, vertices * sizeof(uint32_t));
    assert_int_equal(raps_result_copy_chart_ids(r, ids, indices / 3), RAPS_OK);
    d.field[4] = fnv1a(d.field[4], ids, indices / 3 * sizeof(uint32_t));
    raps_stats stats = stats_of(r);
    d.threads_used = stats.threads_used;
    stats.threads_used = 0; /* describes the run, not the map */
    d.field[5] = fnv1a(d.field[5], &stats, sizeof stats);
    free(xyz);
    free(ids);
    raps_result_destroy(r);
    raps_settings_destroy(settings);
    raps_mesh_destroy(handle);
    test_mesh_free(&mesh);
    return d;
}

/* digests[case][threads - 1], computed once, with the kernels this process chose. */
static digest g_digests[kCaseCount][kMaxThreads];
static int g_computed = 0;

static void compute_digests(void) {
    if (g_computed) return;
    for (int c = 0; c < kCaseCount; ++c)
        for (int32_t t = 1; t <= kMaxThreads && case_runs(c); ++t)
            g_digests[c][t - 1] = run_case(&kCases[c], t);
    g_computed = 1;
}

/* A worker counts in threads_used once it has computed a share, which a busy scheduler may deny
 * it when the shared part of a run is short (the disk domain shares only its statistics: a few
 * milliseconds on face.obj). So where no case of a domain showed t threads, the case that shared
 * most (or, if none shared, the domain's last) runs again at t threads until one does, each run
 * compared with the 1-thread bits too; 20 runs without a worker computing fail. */
enum { kRetries = 20 };

static void check_same_bits(int c, int32_t threads, const digest* d) {
    for (int f = 0; f < kFields; ++f) {
        if (d->field[f] != g_digests[c][0].field[f])
            fail_msg("%s (domain %d): %s differ between 1 and %d threads", kCases[c].name,
                     kCases[c].domain, kFieldNames[f], threads);
    }
}

static void thread_counts_give_the_same_bits(void** state) {
    (void)state;
    compute_digests();
    int used[3][kMaxThreads + 1] = {{0}};
    int retried[3] = {-1, -1, -1}; /* per domain: the case that shared most, else its last */
    uint64_t most[3] = {0, 0, 0};
    for (int c = 0; c < kCaseCount; ++c) {
        if (!case_runs(c)) continue;
        const int domain = kCases[c].domain;
        for (int t = 2; t <= kMaxThreads; ++t) {
            check_same_bits(c, t, &g_digests[c][t - 1]);
            const uint64_t u = g_digests[c][t - 1].threads_used;
            if (u <= kMaxThreads) used[domain][u] = 1;
            if (u > most[domain] || (most[domain] <= 1 && u <= 1)) retried[domain] = c;
            if (u > most[domain]) most[domain] = u;
        }
    }
    /* Workers really ran: otherwise the comparison above is of one thread with itself. */
    for (int domain = 0; domain < 3; ++domain) {
        for (int t = 2; t <= kMaxThreads; ++t) {
            const int c = retried[domain];
            for (int retry = 0; !used[domain][t] && c >= 0 && retry < kRetries; ++retry) {
                const digest d = run_case(&kCases[c], t);
                check_same_bits(c, t, &d);
                if (d.threads_used <= kMaxThreads) used[domain][d.threads_used] = 1;
            }
            if (!used[domain][t]) fail_msg("domain %d: no case ran on %d threads", domain, t);
        }
    }
}

static int processor_has_avx2(void) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    return __builtin_cpu_supports("avx2");
#else
    return 0;
#endif
}

/* The child: one line per case, its 1-thread digest, on stdout. */
static int print_digests(void) {
    for (int c = 0; c < kCaseCount; ++c) {
        if (!case_runs(c)) continue;
        const digest d = run_case(&kCases[c], 1);
        printf("%d", c);
        for (int f = 0; f < kFields; ++f) printf(" %016llx", (unsigned long long)d.field[f]);
        printf("\n");
    }
    return fflush(stdout) == 0 ? 0 : 1;
}

static void baseline_kernels_give_the_same_bits(void** state) {
    (void)state;
    const char* forced = getenv("RAPS_KERNELS");
    if (!processor_has_avx2() || (forced != NULL && strcmp(forced, "baseline") == 0)) {
        /* Still run: the child's 1 thread against this process's, baseline against baseline. */
        print_message("note: the baseline kernels here, not AVX2: the comparison is vacuous\n");
    }
    compute_digests();
    int pipe_fds[2];
    assert_int_equal(pipe(pipe_fds), 0);
    fflush(NULL);
    const pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        dup2(pipe_fds[1], STDOUT_FILENO);
        close(pipe_fds[0]);
        close(pipe_fds[1]);
        setenv("RAPS_KERNELS", "baseline", 1);
        setenv("RAPS_REPRODUCIBILITY_CHILD", "1", 1);
        char* const args[] = {(char*)"test_reproducibility", NULL};
        execv("/proc/self/exe", args);
        _exit(127);
    }
    close(pipe_fds[1]);
    FILE* in = fdopen(pipe_fds[0], "r");
    assert_non_null(in);
    int seen = 0;
    int index;
    while (fscanf(in, "%d", &index) == 1) {
        assert_true(index >= 0 && index < kCaseCount);
        for (int f = 0; f < kFields; ++f) {
            unsigned long long h = 0;
            assert_int_equal(fscanf(in, "%llx", &h), 1);
            if (h != g_digests[index][0].field[f])
                fail_msg("%s (domain %d): %s differ between the AVX2 and the baseline kernels",
                         kCases[index].name, kCases[index].domain, kFieldNames[f]);
        }
        ++seen;
    }
    fclose(in);
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    int expected = 0;
    for (int c = 0; c < kCaseCount; ++c) expected += case_runs(c);
    assert_int_equal(seen, expected);
}

int main(void) {
    if (getenv("RAPS_REPRODUCIBILITY_CHILD") != NULL) return print_digests();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(thread_counts_give_the_same_bits),
        cmocka_unit_test(baseline_kernels_give_the_same_bits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
