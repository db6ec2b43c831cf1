// raps-bench-progress: how long a cancel can wait. Runs each domain on a large mesh it builds
// (1-to-4 midpoint subdivisions of shared meshes) with a progress callback that timestamps every
// call, and prints per phase the calls, the longest wall-clock gap before one of its calls (the
// work a cancel issued during it waits for) and whether its fractions rose monotonically to 1.
// A cancel waits at most the longest gap of the run; the header promises about 1 % of a phase.
//
//   raps-bench-progress [--data DIR] [--subdivide K] [--threads N] [--only disk|atlas|sphere]
//                       [--disk-mesh FILE] [--atlas-mesh FILE] [--sphere-mesh FILE]
//                       [--gaps-over MS]
//
// Cases: disk and atlas on face.obj subdivided K times (default 2: 827K triangles; 3: 3.3M),
// sphere on bunny.off subdivided K + 1 times (K = 2: 444K triangles); --disk-mesh another shared
// disk for the disk case (camelhead.off with K = 4: 5.8M triangles), --atlas-mesh any shared mesh
// for the atlas, --sphere-mesh a closed genus-0 one for the sphere (cow.off with K = 4: 5.9M).
// Each case runs once, in its own child process (peak MB is that process's).
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_support.h"
#include "parameter_text.h"
#include "raps.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Call {
    Clock::time_point at;
    double cpu_ms;  // the calling thread's CPU time: the gaps without the time it was not scheduled
    raps_phase phase;
    double fraction;
};

// What one run's calls say about each phase.
struct PhaseFigures {
    int calls = 0;
    double longest_gap_ms = 0;  // before one of its calls, since the previous call
    bool monotone = true;       // fractions never fell within one pass through the phase
    bool reached_one = false;
    double gap_from = 0, gap_to = 0;  // the fractions reported around the longest gap
};

struct Report {
    int ok = 0;
    uint64_t triangles = 0;
    double total_ms = 0, after_last_call_ms = 0;
    double longest_cpu_gap_ms = -1;  // between two calls, with --threads 1 only (-1: not measured)
    PhaseFigures phase[RAPS_PHASE_COUNT];
};

int32_t record_call(void* user, raps_phase phase, double fraction) {
    timespec cpu{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu);
    static_cast<std::vector<Call>*>(user)->push_back(
        {Clock::now(), cpu.tv_sec * 1e3 + cpu.tv_nsec * 1e-6, phase, fraction});
    return 1;
}

// Per phase figures from the calls of one run that began at `start`. A phase that ends (1) and
// starts again (0) begins a new pass: its fractions are compared within a pass only.
// Gaps longer than gaps_over_ms (0: none) are also listed on stderr, each with its phase and the
// fractions around it, to find the step a cancel waits for.
void summarise(const std::vector<Call>& calls, Clock::time_point start, bool one_thread,
               double gaps_over_ms, Report& report) {
    double last[RAPS_PHASE_COUNT];
    std::fill(last, last + RAPS_PHASE_COUNT, -1.0);
    Clock::time_point previous = start;
    for (const Call& c : calls) {
        PhaseFigures& p = report.phase[c.phase];
        ++p.calls;
        const double gap = std::chrono::duration<double, std::milli>(c.at - previous).count();
        const double cpu_gap =
            !one_thread || &c == &calls.front() ? 0.0 : c.cpu_ms - (&c - 1)->cpu_ms;
        if (one_thread) report.longest_cpu_gap_ms = std::max(report.longest_cpu_gap_ms, cpu_gap);
        if (gaps_over_ms > 0 && (one_thread ? cpu_gap : gap) > gaps_over_ms) {
            std::fprintf(stderr, "gap %.1f ms (CPU %.1f ms) before %s %.6f (previous call %.6f)\n",
                         gap, cpu_gap, raps_samples::phase_name(c.phase), c.fraction,
                         (&c - 1)->fraction);
        }
        if (gap > p.longest_gap_ms) {
            p.longest_gap_ms = gap;
            p.gap_from = &c == &calls.front() ? 0.0 : (&c - 1)->fraction;
            p.gap_to = c.fraction;
        }
        previous = c.at;
        const bool new_pass = last[c.phase] == 1.0 && c.fraction == 0.0;
        if (!new_pass && c.fraction < last[c.phase]) p.monotone = false;
        last[c.phase] = c.fraction;
        if (c.fraction == 1.0) p.reached_one = true;
    }
}

Report run_case(const std::vector<double>& positions, const std::vector<uint32_t>& triangles,
                int32_t domain, int threads, double gaps_over_ms) {
    Report report;
    raps_mesh* mesh = nullptr;
    raps_settings* settings = nullptr;
    raps_result* result = nullptr;
    raps_mesh_create(&mesh);
    raps_settings_create(&settings);
    raps_result_create(&result);
    raps_settings_set_int(settings, RAPS_PARAM_DOMAIN, domain);
    raps_settings_set_int(settings, RAPS_PARAM_THREADS, threads);
    // Reserved (address space only: pages are touched as calls come): a vector that grows
    // copies every call so far inside a progress call, which the gaps would count as the
    // library's work (the sphere at 5.65M triangles makes 1.26M calls; with room for 2^20 the
    // copy showed as a gap of 77 to 153 ms in its adaptive phase).
    constexpr size_t kCallRoom = size_t(1) << 24;
    std::vector<Call> calls;
    calls.reserve(kCallRoom);
    raps_settings_set_progress(settings, record_call, &calls);
    raps_mesh_set_positions_f64(mesh, positions.data(), positions.size() / 3, 0);
    raps_mesh_set_indices_u32(mesh, triangles.data(), triangles.size());
    const Clock::time_point start = Clock::now();
    const raps_status status = raps_parameterize(mesh, settings, result);
    const Clock::time_point end = Clock::now();
    if (calls.capacity() > kCallRoom) {
        std::fprintf(stderr,
                     "raps-bench-progress: more than %zu progress calls: a gap may include the "
                     "benchmark's own copy of its record\n",
                     kCallRoom);
    }
    if (status == RAPS_OK) {
        report.ok = 1;
        report.triangles = triangles.size() / 3;
        report.total_ms = std::chrono::duration<double, std::milli>(end - start).count();
        if (!calls.empty()) {
            report.after_last_call_ms =
                std::chrono::duration<double, std::milli>(end - calls.back().at).count();
        }
        // The calling thread's CPU time measures the work between two calls only when one
        // thread makes all of them (and does all the work).
        summarise(calls, start, threads == 1, gaps_over_ms, report);
    } else {
        std::fprintf(stderr, "raps-bench-progress: %s: %s\n", raps_status_string(status),
                     raps_result_last_error(result));
    }
    raps_result_destroy(result);
    raps_settings_destroy(settings);
    raps_mesh_destroy(mesh);
    return report;
}

struct Case {
    const char* name;
    int32_t domain;
    const char* file;
    int subdivisions;
};

// Runs the case in a child process; the report and the child's peak resident MB.
std::pair<Report, double> run_in_child(const std::string& data, const Case& c, int threads,
                                       double gaps_over_ms) {
    const auto child = raps_bench::run_in_child<Report>("raps-bench-progress", [&](auto emit) {
        const raps_bench::TriangleMesh mesh =
            raps_bench::load_triangles(data + "/meshes/" + c.file, c.subdivisions);
        emit(run_case(mesh.positions, mesh.triangles, c.domain, threads, gaps_over_ms));
    });
    return {child.samples.empty() ? Report{} : child.samples[0], child.peak_mb};
}

void print_case(const Case& c, const Report& r, double peak_mb) {
    if (!r.ok) {
        std::printf("| %s | %s/%d | failed |\n", c.name, c.file, 1 << (2 * c.subdivisions));
        return;
    }
    double worst = r.after_last_call_ms;
    for (const PhaseFigures& p : r.phase) worst = std::max(worst, p.longest_gap_ms);
    std::printf("| %s | %s/%d | %llu | %.0f | %.0f | **%.1f** | ", c.name, c.file,
                1 << (2 * c.subdivisions), static_cast<unsigned long long>(r.triangles), r.total_ms,
                peak_mb, worst);
    if (r.longest_cpu_gap_ms >= 0)
        std::printf("%.1f", r.longest_cpu_gap_ms);
    else
        std::printf("-");
    for (const PhaseFigures& p : r.phase) {
        if (p.calls == 0) {
            std::printf(" | -");
            continue;
        }
        std::printf(" | %d / %.1f (%.3f-%.3f)%s", p.calls, p.longest_gap_ms, p.gap_from, p.gap_to,
                    p.monotone && p.reached_one ? "" : " (not monotone to 1)");
    }
    std::printf(" | %.1f |\n", r.after_last_call_ms);
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
    std::string data = RAPS_SHARED_DATA_DIR, only, disk_mesh = "face.obj", atlas_mesh = "face.obj",
                sphere_mesh = "bunny.off";
    int subdivisions = 2, threads = 0;
    double gaps_over_ms = 0;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (i + 1 >= argc) {
            std::fprintf(stderr,
                         "usage: raps-bench-progress [--data DIR] [--subdivide K] [--threads N] "
                         "[--only disk|atlas|sphere] [--disk-mesh FILE] [--atlas-mesh FILE] "
                         "[--sphere-mesh FILE] [--gaps-over MS]\n");
            return 2;
        }
        const std::string value = argv[++i];
        if (arg == "--data")
            data = value;
        else if (arg == "--subdivide")
            subdivisions = std::max(0, std::atoi(value.c_str()));
        else if (arg == "--threads")
            threads = std::atoi(value.c_str());
        else if (arg == "--only")
            only = value;
        else if (arg == "--disk-mesh")
            disk_mesh = value;
        else if (arg == "--atlas-mesh")
            atlas_mesh = value;
        else if (arg == "--sphere-mesh")
            sphere_mesh = value;
        else if (arg == "--gaps-over")
            gaps_over_ms = std::atof(value.c_str());
        else {
            std::fprintf(stderr, "raps-bench-progress: unknown option %s\n", arg.c_str());
            return 2;
        }
    }
    const Case cases[] = {
        {"disk", RAPS_DOMAIN_DISK, disk_mesh.c_str(), subdivisions},
        {"atlas", RAPS_DOMAIN_ATLAS, atlas_mesh.c_str(), subdivisions},
        {"sphere", RAPS_DOMAIN_SPHERE, sphere_mesh.c_str(), subdivisions + 1},
    };
    std::printf("raps %s, threads %d (0 = all), one run per case\n\n", raps_version_string(),
                threads);
    std::printf(
        "Per phase: progress calls / longest gap in ms before one of them (the fractions "
        "of the calls before and after it). Worst: the "
        "longest gap of the run, the time after the last call included. CPU gap: the longest "
        "CPU time of the reporting thread between two calls (the work, without the time other "
        "processes had the core), measured with --threads 1 only, where one thread does all "
        "the work.\n\n");
    std::printf("| domain | mesh | triangles | ms | peak MB | worst gap ms | CPU gap ms");
    for (raps_phase p = 0; p < RAPS_PHASE_COUNT; ++p)
        std::printf(" | %s", raps_samples::phase_name(p));
    std::printf(" | after last call ms |\n|---|---|---:|---:|---:|---:|---:");
    for (raps_phase p = 0; p < RAPS_PHASE_COUNT; ++p) std::printf("|---:");
    std::printf("|---:|\n");
    for (const Case& c : cases) {
        if (!only.empty() && only != c.name) continue;
        const std::pair<Report, double> r = run_in_child(data, c, threads, gaps_over_ms);
        print_case(c, r.first, r.second);
    }
    return 0;
}
