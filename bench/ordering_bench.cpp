// The own solver's fill-reducing orders (src/solver) on the systems the library solves: for each
// system and ordering, the factor's nonzeros, the ordering's time, the symbolic analysis, the
// numeric LU of the mean value system and Cholesky of the cotangent system (the same pattern),
// and whether repeated runs give the same bits. Needs no other library, unlike
// raps-bench-solver; prints Markdown.
//
//   raps-bench-ordering [--data DIR] [--runs N] [--no-large] [--system LABEL]
//                       [--ordering library|amd|nd] [--cpu-time]
//
// --system runs one system, named by its label in the table; --ordering one ordering;
// --cpu-time times the process's CPU time instead of the wall clock.
//
// Orderings: the library's choice (fill_reducing_order), approximate minimum degree at every
// size (minimum_degree_order) and the nested dissection at every size (nested_dissection_order).
// Systems: disk meshes of the shared data with their boundary held (face.obj as it is and
// subdivided 1-to-4 once and twice, camelhead.off, lion.off, camelhead.off subdivided twice) and
// the largest atlas charts of face.obj and beetle.off (bench/laplace_systems.h).
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "laplace_systems.h"
#include "solver/minimum_degree.h"
#include "solver/multifrontal_factorization.h"
#include "solver/nested_dissection.h"
#include "solver/sparse_solver.h"

namespace {

// Wall clock, or with --cpu-time the process's CPU time (steadier where other work shares the
// machine; the solver runs on one thread).
bool cpu_time = false;

double now() {
    if (cpu_time) {
        timespec t{};
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
        return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
    }
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

std::vector<int32_t> order_of(const raps_bench::System& system, const std::string& ordering) {
    if (ordering == "amd") return raps::minimum_degree_order(system.pattern);
    if (ordering == "nd") return raps::nested_dissection_order(system.pattern, system.coordinates);
    return raps::fill_reducing_order(system.pattern, system.coordinates);
}

struct Row {
    double order = 0, analysis = 0, lu = 0, cholesky = 0, solve = 0;
    raps_bench::FactorSize factor;
    uint64_t hash = 0;
    bool runs_agree = true;
};

// Median times of `runs` runs; the analysis includes the ordering, as in SparseSolver.
Row measure(const raps_bench::System& mean_value, const raps_bench::System& cotangent,
            const std::string& ordering, int runs) {
    std::vector<double> order_s, analysis_s, lu_s, cholesky_s, solve_s;
    Row row;
    for (int r = 0; r < runs; ++r) {
        double start = now();
        const std::vector<int32_t> order = order_of(mean_value, ordering);
        order_s.push_back(now() - start);
        raps::MultifrontalFactorization lu, cholesky;
        lu.analyze(mean_value.pattern, order);
        lu.prepare(mean_value.pattern, raps::Factorization::kLU);
        analysis_s.push_back(now() - start);
        cholesky.analyze(cotangent.pattern, order);
        cholesky.prepare(cotangent.pattern, raps::Factorization::kCholesky);
        start = now();
        if (!lu.factorize(mean_value.values.data(), {}))
            throw std::runtime_error("the mean value system needs pivoting");
        lu_s.push_back(now() - start);
        start = now();
        if (!cholesky.factorize(cotangent.values.data(), {}))
            throw std::runtime_error("the cotangent system is not positive definite");
        cholesky_s.push_back(now() - start);
        std::vector<double> x = mean_value.rhs;
        start = now();
        lu.solve(x.data(), mean_value.rhs_count);
        solve_s.push_back(now() - start);
        const uint64_t hash = raps_bench::bits_hash(x);
        if (r == 0) {
            row.hash = hash;
            row.factor = raps_bench::cholesky_size(mean_value.pattern, order);
        }
        row.runs_agree = row.runs_agree && hash == row.hash;
    }
    row.order = median(order_s);
    row.analysis = median(analysis_s);
    row.lu = median(lu_s);
    row.cholesky = median(cholesky_s);
    row.solve = median(solve_s);
    return row;
}

struct Case {
    const char* name;  // for build_system
    int subdivisions;
    const char* label;
    bool large;
};

}  // namespace

int main(int argc, char** argv) {
    std::string data = RAPS_SHARED_DATA_DIR;
    int runs = 3;
    bool large = true;
    std::vector<std::string> orderings = {"", "amd", "nd"};
    std::string only;
    for (int a = 1; a < argc; ++a) {
        if (std::strcmp(argv[a], "--data") == 0 && a + 1 < argc) {
            data = argv[++a];
        } else if (std::strcmp(argv[a], "--runs") == 0 && a + 1 < argc) {
            runs = std::max(1, std::atoi(argv[++a]));
        } else if (std::strcmp(argv[a], "--no-large") == 0) {
            large = false;
        } else if (std::strcmp(argv[a], "--cpu-time") == 0) {
            cpu_time = true;
        } else if (std::strcmp(argv[a], "--system") == 0 && a + 1 < argc) {
            only = argv[++a];
        } else if (std::strcmp(argv[a], "--ordering") == 0 && a + 1 < argc) {
            const std::string name = argv[++a];
            orderings = {name == "library" ? "" : name};
        } else {
            std::fprintf(stderr,
                         "usage: raps-bench-ordering [--data DIR] [--runs N] [--no-large] "
                         "[--system LABEL] [--ordering library|amd|nd] [--cpu-time]\n");
            return 2;
        }
    }
    const Case cases[] = {
        {"chart:face.obj", 0, "largest atlas chart of face.obj", false},
        {"chart:beetle.off", 0, "largest atlas chart of beetle.off", false},
        {"disk:lion.off", 0, "lion.off", false},
        {"disk:camelhead.off", 0, "camelhead.off", false},
        {"disk:face.obj", 0, "face.obj", false},
        {"disk:face.obj", 1, "face.obj subdivided once", false},
        {"disk:camelhead.off", 2, "camelhead.off subdivided twice", true},
        {"disk:face.obj", 2, "face.obj subdivided twice", true},
    };
    std::printf(
        "Median of %d runs (%s). order: the fill-reducing order; analysis: the order and the "
        "symbolic LU analysis; LU: numeric factorization of the mean value system; "
        "Cholesky: of the cotangent system (same pattern, same order); total: analysis + "
        "LU + solve (2 right-hand sides), the disk domain's first solve. nnz(L): the "
        "Cholesky factor's nonzeros, diagonal included (the LU stores 2 nnz(L) - n); "
        "flops: the sum of its squared column counts. "
        "bits: hash of the LU solution; \"runs differ\" if a repeated run gave other "
        "bits.\n\n",
        runs, cpu_time ? "CPU time" : "wall clock");
    std::printf(
        "| system | unknowns | ordering | nnz(L) | flops | order ms | analysis ms | LU ms | "
        "Cholesky ms | total ms | bits |\n|---|---:|---|---:|---:|---:|---:|---:|---:|---:|"
        "---|\n");
    try {
        for (const Case& c : cases) {
            if ((c.large && !large) || (!only.empty() && only != c.label)) continue;
            std::fprintf(stderr, "raps-bench-ordering: %s\n", c.label);
            const raps_bench::System mean_value =
                raps_bench::build_system(data, c.name, c.subdivisions, false);
            const raps_bench::System cotangent =
                raps_bench::build_system(data, c.name, c.subdivisions, true);
            // Not timed: the first factorization of a system pays for the first touch of its
            // memory, which would count against whichever ordering came first.
            measure(mean_value, cotangent, "", 1);
            for (const std::string& ordering : orderings) {
                const Row row = measure(mean_value, cotangent, ordering, runs);
                std::printf(
                    "| %s | %d | %s | %.4g | %.3g | %.1f | %.1f | %.1f | %.1f | %.1f | %08llx%s "
                    "|\n",
                    c.label, mean_value.pattern.size,
                    ordering.empty()    ? "the library's choice"
                    : ordering == "amd" ? "minimum degree"
                                        : "nested dissection",
                    static_cast<double>(row.factor.nonzeros), row.factor.flops, 1000 * row.order,
                    1000 * row.analysis, 1000 * row.lu, 1000 * row.cholesky,
                    1000 * (row.analysis + row.lu + row.solve),
                    static_cast<unsigned long long>(row.hash >> 32),
                    row.runs_agree ? "" : " (runs differ)");
                std::fflush(stdout);
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "raps-bench-ordering: %s\n", e.what());
        return 1;
    }
    return 0;
}
