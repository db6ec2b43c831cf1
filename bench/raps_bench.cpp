// raps-bench: times the whole planar pipeline through the C API on the shared disk meshes and on
// a large mesh it builds itself (face.obj subdivided 1-to-4 twice: 827K triangles), and prints
// per phase the median of several runs, triangles per second and peak memory.
//
//   raps-bench [--data DIR] [--runs N] [--large-runs N] [--subdivide K] [--monitor area|none]
//   raps-bench --sphere [--data DIR] [--runs N] [--large-runs N] [--subdivide K] [--threads N]
//
// --sphere times the sphere domain instead (robust method, area monitor, alpha 1) on the shared
// closed genus-0 meshes, on a capsule of aspect 50 and a dumbbell with a neck of 0.05 built here
// (built_shapes.h), and on bunny.off and cow.off subdivided K times (default 2: 111K and 88K
// triangles): sweeps, time per phase, spherical area and angle distortion of the initial map (a
// run with no monitor) and of the adapted one, the adapted map's centre of mass, folded
// triangles, peak memory, and the speed-up from 1 thread to N (default: all cores).
//
// Every case runs in its own child process (fork), so the peak resident memory reported is that
// case's alone. Numbers are printed, never judged: speed targets live here, not in tests.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "bench_support.h"
#include "built_shapes.h"
#include "mesh_io.h"
#include "raps.h"

namespace {

using raps_bench::median;

struct Case {
    std::string name;
    std::string file;
    int subdivisions;
    // A mesh built here instead of a file (built_shapes.h), or none.
    std::function<void(std::vector<double>&, std::vector<uint32_t>&)> build = nullptr;
};

// What one child process reports back through its pipe.
struct Sample {
    double phase_ms[RAPS_PHASE_COUNT];
    double total_ms;
    double area_log_mean;
    double angle_mean_deg;
    double centre;  // sphere: the 3D-area-weighted centre of mass of the points, from the origin
    uint64_t flipped;
    uint64_t triangles;
    uint64_t sweeps;
    uint64_t threads_used;
    int ok;
};

// What one run asks of the library.
struct Config {
    int32_t domain = RAPS_DOMAIN_DISK;
    int32_t monitor = RAPS_MONITOR_AREA;
    int32_t threads = 0;
};

// Distance from the origin of the 3D-area-weighted centre of mass of a sphere result's points.
double sphere_centre(const std::vector<double>& p, const std::vector<uint32_t>& triangles,
                     const raps_result* result) {
    const size_t n = p.size() / 3;
    std::vector<double> u(3 * n);
    if (raps_result_copy_sphere_points_f64(result, u.data(), n, 0) != RAPS_OK) return -1.0;
    double c[3] = {0, 0, 0}, total = 0;
    for (size_t t = 0; t < triangles.size(); t += 3) {
        const double* a = &p[3 * triangles[t]];
        const double* b = &p[3 * triangles[t + 1]];
        const double* d = &p[3 * triangles[t + 2]];
        const double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        const double f[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        const double area = 0.5 * std::sqrt(std::pow(e[1] * f[2] - e[2] * f[1], 2) +
                                            std::pow(e[2] * f[0] - e[0] * f[2], 2) +
                                            std::pow(e[0] * f[1] - e[1] * f[0], 2));
        total += area;
        for (int k = 0; k < 3; ++k) {
            for (int q = 0; q < 3; ++q) c[q] += area / 3.0 * u[3 * triangles[t + k] + q];
        }
    }
    return std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / total;
}

Sample run_once(const std::vector<double>& positions, const std::vector<uint32_t>& triangles,
                const Config& config) {
    Sample sample{};
    raps_mesh* mesh = nullptr;
    raps_settings* settings = nullptr;
    raps_result* result = nullptr;
    raps_mesh_create(&mesh);
    raps_settings_create(&settings);
    raps_result_create(&result);
    raps_settings_set_int(settings, RAPS_PARAM_MONITOR, config.monitor);
    raps_settings_set_int(settings, RAPS_PARAM_DOMAIN, config.domain);
    raps_settings_set_int(settings, RAPS_PARAM_THREADS, config.threads);
    const auto start = std::chrono::steady_clock::now();
    raps_mesh_set_positions_f64(mesh, positions.data(), positions.size() / 3, 0);
    raps_mesh_set_indices_u32(mesh, triangles.data(), triangles.size());
    const raps_status status = raps_parameterize(mesh, settings, result);
    sample.total_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (status == RAPS_OK) {
        raps_stats stats;
        stats.struct_size = sizeof(stats);
        raps_result_get_stats(result, &stats);
        for (int p = 0; p < RAPS_PHASE_COUNT; ++p)
            sample.phase_ms[p] = raps_result_phase_ms(result, p);
        sample.area_log_mean = stats.area_log_mean;
        sample.angle_mean_deg = stats.angle_mean_deg;
        if (config.domain == RAPS_DOMAIN_SPHERE)
            sample.centre = sphere_centre(positions, triangles, result);
        sample.flipped = stats.flipped_triangles;
        sample.triangles = stats.triangle_count;
        sample.sweeps = stats.relaxation_sweeps;
        sample.threads_used = stats.threads_used;
        sample.ok = 1;
    } else {
        std::fprintf(stderr, "raps-bench: %s\n", raps_result_last_error(result));
    }
    raps_result_destroy(result);
    raps_settings_destroy(settings);
    raps_mesh_destroy(mesh);
    return sample;
}

// Runs `runs` samples in one child process (after loading the mesh there, so the parent stays
// small), returning them and the child's peak resident set in MB.
std::pair<std::vector<Sample>, double> run_case(const Case& c, int runs, const Config& config) {
    auto child = raps_bench::run_in_child<Sample>("raps-bench", [&](auto emit) {
        raps_bench::TriangleMesh mesh;
        if (c.build) {
            c.build(mesh.positions, mesh.triangles);
            for (int s = 0; s < c.subdivisions; ++s)
                raps_samples::subdivide_midpoint(mesh.positions, mesh.triangles);
        } else {
            mesh = raps_bench::load_triangles(c.file, c.subdivisions);
        }
        for (int r = 0; r < runs; ++r) emit(run_once(mesh.positions, mesh.triangles, config));
    });
    return {std::move(child.samples), child.peak_mb};
}

// The sphere section: per closed genus-0 mesh, the initial map's distortion (one run with no
// monitor), then `runs` adapted runs on all threads and `runs` on one.
int run_sphere(const std::string& data, int runs, int large_runs, int subdivisions, int threads) {
    std::vector<Case> cases = {{"bunny", data + "/meshes/bunny.off", 0},
                               {"cheburashka", data + "/meshes/cheburashka.off", 0},
                               {"cow", data + "/meshes/cow.off", 0},
                               {"decimated-knight", data + "/meshes/decimated-knight.off", 0},
                               {"decimated-max", data + "/meshes/decimated-max.obj", 0},
                               {"fandisk", data + "/meshes/fandisk.obj", 0},
                               {"horse_quad", data + "/meshes/horse_quad.obj", 0},
                               {"spot", data + "/meshes/spot.obj", 0}};
    // Issue 18's built shapes: a capsule whose ends a conformal map squeezes by e^-50, and a
    // dumbbell with a thin neck.
    cases.push_back(
        {"capsule, aspect 50", "", 0, [](std::vector<double>& p, std::vector<uint32_t>& t) {
             raps_bench::build_capsule(50.0, 24, p, t);
         }});
    cases.push_back(
        {"dumbbell, neck 0.05", "", 0, [](std::vector<double>& p, std::vector<uint32_t>& t) {
             raps_bench::build_dumbbell(0.05, 48, p, t);
         }});
    if (subdivisions > 0) {
        // bunny, and cow with its long legs, each 1-to-4 subdivided `subdivisions` times.
        for (const char* name : {"bunny.off", "cow.off"}) {
            const std::string stem(name, std::strchr(name, '.'));
            cases.push_back({stem + "/" + std::to_string(1 << (2 * subdivisions)),
                             data + "/meshes/" + name, subdivisions});
        }
    }
    const int all = threads > 0 ? threads : static_cast<int>(sysconf(_SC_NPROCESSORS_ONLN));
    std::printf(
        "raps %s, sphere domain: robust method, mean value weights, area monitor alpha 1 in 2 "
        "continuation steps; median of runs per case; %d threads against 1\n\n",
        raps_version_string(), all);
    std::printf(
        "| mesh | triangles | runs | sweeps | topology ms | initial map ms | adapt ms | "
        "total ms | total ms, 1 thread | speed-up | threads used | peak MB | area initial -> "
        "adapted | angle deg initial -> adapted | centre | flips |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---:|---:|\n");
    for (const Case& c : cases) {
        const int n = c.subdivisions > 0 ? large_runs : runs;
        Config initial;
        initial.domain = RAPS_DOMAIN_SPHERE;
        initial.monitor = RAPS_MONITOR_NONE;
        initial.threads = all;
        Config adapted = initial;
        adapted.monitor = RAPS_MONITOR_AREA;
        Config single = adapted;
        single.threads = 1;
        const auto first = run_case(c, 1, initial);
        const auto [samples, peak_mb] = run_case(c, n, adapted);
        const auto serial = run_case(c, n, single);
        if (first.first.empty() || samples.empty() || serial.first.empty() || !samples[0].ok) {
            std::printf("| %s | failed |\n", c.name.c_str());
            continue;
        }
        std::vector<double> phase[RAPS_PHASE_COUNT], total, total_serial;
        for (const Sample& s : samples) {
            for (int p = 0; p < RAPS_PHASE_COUNT; ++p) phase[p].push_back(s.phase_ms[p]);
            total.push_back(s.total_ms);
        }
        for (const Sample& s : serial.first) total_serial.push_back(s.total_ms);
        const double t = median(total), t1 = median(total_serial);
        std::printf(
            "| %s | %llu | %zu | %llu | %.1f | %.1f | %.1f | %.1f | %.1f | %.2f | %llu | %.0f | "
            "%.3f -> %.3f | %.2f -> %.2f | %.4f | %llu |\n",
            c.name.c_str(), static_cast<unsigned long long>(samples[0].triangles), samples.size(),
            static_cast<unsigned long long>(samples[0].sweeps), median(phase[RAPS_PHASE_TOPOLOGY]),
            median(phase[RAPS_PHASE_INITIAL_MAP]), median(phase[RAPS_PHASE_ADAPT]), t, t1, t1 / t,
            static_cast<unsigned long long>(samples[0].threads_used), peak_mb,
            first.first[0].area_log_mean, samples[0].area_log_mean, first.first[0].angle_mean_deg,
            samples[0].angle_mean_deg, samples[0].centre,
            static_cast<unsigned long long>(samples[0].flipped));
        std::fflush(stdout);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    std::string data = RAPS_SHARED_DATA_DIR;
    int runs = 7, large_runs = 3, subdivisions = 2, threads = 0;
    int32_t monitor = RAPS_MONITOR_AREA;
    bool sphere = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "%s needs a value\n", arg.c_str());
                std::exit(2);
            }
            return argv[++i];
        };
        if (arg == "--data")
            data = value();
        else if (arg == "--runs")
            runs = std::max(1, std::atoi(value().c_str()));
        else if (arg == "--large-runs")
            large_runs = std::max(1, std::atoi(value().c_str()));
        else if (arg == "--subdivide")
            subdivisions = std::max(0, std::atoi(value().c_str()));
        else if (arg == "--monitor")
            monitor = value() == "none" ? RAPS_MONITOR_NONE : RAPS_MONITOR_AREA;
        else if (arg == "--sphere")
            sphere = true;
        else if (arg == "--threads")
            threads = std::max(0, std::atoi(value().c_str()));
        else {
            std::fprintf(stderr,
                         "usage: raps-bench [--data DIR] [--runs N] [--large-runs N] "
                         "[--subdivide K] [--monitor area|none]\n"
                         "       raps-bench --sphere [--data DIR] [--runs N] [--large-runs N] "
                         "[--subdivide K] [--threads N]\n");
            return 2;
        }
    }
    if (sphere) return run_sphere(data, runs, large_runs, subdivisions, threads);
    std::vector<Case> cases = {{"alligator", data + "/meshes/alligator.obj", 0},
                               {"camelhead", data + "/meshes/camelhead.off", 0},
                               {"lion", data + "/meshes/lion.off", 0},
                               {"face", data + "/meshes/face.obj", 0}};
    if (subdivisions > 0) {
        cases.push_back({"face/" + std::to_string(1 << (2 * subdivisions)),
                         data + "/meshes/face.obj", subdivisions});
    }
    std::printf(
        "raps %s, mean value weights + %s, RAPS_PARAM_THREADS %d (0 = all cores; the disk "
        "domain uses more than one only for the statistics of 32,768 triangles or more); median "
        "of runs per case\n\n",
        raps_version_string(),
        monitor == RAPS_MONITOR_AREA ? "1 area-adaptive solve (alpha 1)" : "no adaptive step",
        threads);
    std::printf(
        "| mesh | triangles | runs | validate ms | topology ms | initial map ms | adapt ms | "
        "metrics ms | total ms | Mtri/s | peak MB | area mean abs log | flips |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const Case& c : cases) {
        const int n = c.subdivisions > 0 ? large_runs : runs;
        Config config;
        config.monitor = monitor;
        config.threads = threads;
        const auto [samples, peak_mb] = run_case(c, n, config);
        if (samples.empty() || !samples[0].ok) {
            std::printf("| %s | failed |\n", c.name.c_str());
            continue;
        }
        std::vector<double> phase[RAPS_PHASE_COUNT], total;
        for (const Sample& s : samples) {
            for (int p = 0; p < RAPS_PHASE_COUNT; ++p) phase[p].push_back(s.phase_ms[p]);
            total.push_back(s.total_ms);
        }
        const double total_ms = median(total);
        std::printf(
            "| %s | %llu | %zu | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.2f | %.0f | %.3f | "
            "%llu |\n",
            c.name.c_str(), static_cast<unsigned long long>(samples[0].triangles), samples.size(),
            median(phase[0]), median(phase[1]), median(phase[2]), median(phase[3]),
            median(phase[4]), total_ms, samples[0].triangles / total_ms / 1000.0, peak_mb,
            samples[0].area_log_mean, static_cast<unsigned long long>(samples[0].flipped));
        std::fflush(stdout);
    }
    return 0;
}
