// raps-bench-atlas: the atlas domain on every shared mesh: time, charts, coverage of the atlas,
// L2 and Linf stretch, area and angle distortion, flips. Each mesh runs in its own child process
// (peak memory per mesh); times are medians of several runs. No other tool runs here, so no
// other tool's figures are printed.
//
//   raps-bench-atlas [--data DIR] [--runs N] [--threads N] [--resolution N] [--padding N]
//                    [--mesh FILE] [--phases] [--subdivide K] [--scan TRIANGLES] [--noise F]
// --mesh runs only that mesh (fandisk.obj, say: for profiling; repeated, those meshes); --phases
// adds, after the table, each mesh's median time per phase; --subdivide splits every shared
// mesh's triangles 1-to-4 K times first (the same surface with 4^K times the triangles: how the
// time grows with the size); --scan adds
// a generated scan-like mesh of about that many triangles (its row is "scan", --mesh scan runs it
// alone): a height field of random bumps over the unit square with noise on every vertex, random
// diagonals and three holes, the way photogrammetry and range scans come out (seed 20, fixed).
// --noise moves every vertex of the shared meshes, after subdividing, by up to F times their
// mean edge length along each axis (seed 20): noise at the scale of the triangles, as in a raw
// scan, where the scan above is smooth at that scale. Such meshes make thousands of charts:
// the L2 target holds only for small patches of a rough surface.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "bench_support.h"
#include "parameter_text.h"
#include "raps.h"

namespace {

// The shared meshes the atlas is measured on, every one in data/meshes.
const char* const kMeshes[] = {
    "3holes.off",     "alligator.obj",   "beetle.off",        "bunny.off",
    "camelhead.off",  "cheburashka.off", "decimated-max.obj", "face.obj",
    "fandisk.obj",    "fertility.off",   "halftunnel.off",    "lion.off",
    "rocker-arm.obj", "spot.obj",        "suzanne.obj",       "teapot.obj",
};

// Uniform in [0, 1) from the generator's raw bits (std::uniform_real_distribution differs
// between standard libraries; this does not).
double uniform(std::mt19937_64& random) { return static_cast<double>(random() >> 11) * 0x1p-53; }

// The scan-like mesh described above, about `count` triangles.
raps_bench::TriangleMesh scan_like_mesh(int64_t count) {
    std::mt19937_64 random(20);
    const int n = std::max(4, static_cast<int>(std::sqrt(static_cast<double>(count) / 2.0)));
    const double h = 1.0 / n;
    struct Bump {
        double x, y, height, width;
    };
    std::vector<Bump> bumps(12);
    for (Bump& b : bumps) {
        b = {uniform(random), uniform(random), 0.4 * (uniform(random) - 0.3),
             0.05 + 0.2 * uniform(random)};
    }
    raps_bench::TriangleMesh mesh;
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            const double x = (i + 0.3 * (uniform(random) - 0.5)) * h;
            const double y = (j + 0.3 * (uniform(random) - 0.5)) * h;
            double z = 0.15 * h * (uniform(random) - 0.5);
            for (const Bump& b : bumps) {
                const double d2 = (x - b.x) * (x - b.x) + (y - b.y) * (y - b.y);
                z += b.height * std::exp(-d2 / (b.width * b.width));
            }
            mesh.positions.insert(mesh.positions.end(), {x, y, z});
        }
    }
    double holes[3][3];  // centre x, y and radius
    for (auto& hole : holes) {
        hole[0] = uniform(random);
        hole[1] = uniform(random);
        hole[2] = 0.02 + 0.03 * uniform(random);
    }
    auto in_hole = [&](int i, int j) {
        for (const auto& hole : holes) {
            const double dx = (i + 0.5) * h - hole[0], dy = (j + 0.5) * h - hole[1];
            if (dx * dx + dy * dy < hole[2] * hole[2]) return true;
        }
        return false;
    };
    std::vector<uint32_t>& triangles = mesh.triangles;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const bool flip = uniform(random) < 0.5;
            if (in_hole(i, j)) continue;
            const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + (n + 1), d = c + 1;
            if (flip)
                triangles.insert(triangles.end(), {a, b, d, a, d, c});
            else
                triangles.insert(triangles.end(), {a, b, c, b, d, c});
        }
    }
    return mesh;
}

// `mesh` with every vertex moved by up to `noise` times the mean edge length along each axis.
void add_noise(raps_bench::TriangleMesh& mesh, double noise) {
    const std::vector<double>& p = mesh.positions;
    double length = 0;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const size_t a = mesh.triangles[t], b = mesh.triangles[t % 3 == 2 ? t - 2 : t + 1];
        length += std::sqrt((p[3 * a] - p[3 * b]) * (p[3 * a] - p[3 * b]) +
                            (p[3 * a + 1] - p[3 * b + 1]) * (p[3 * a + 1] - p[3 * b + 1]) +
                            (p[3 * a + 2] - p[3 * b + 2]) * (p[3 * a + 2] - p[3 * b + 2]));
    }
    length /= std::max<size_t>(mesh.triangles.size(), 1);
    std::mt19937_64 random(20);
    for (double& x : mesh.positions) x += noise * length * (2 * uniform(random) - 1);
}

struct Sample {
    double total_ms;
    double phase_ms[RAPS_PHASE_COUNT];
    raps_stats stats;
    int ok;
};

struct Options {
    int threads = 0, resolution = 1024, padding = 1, subdivide = 0;
    int64_t scan = 0;  // triangles of the scan-like mesh, 0: none
    double noise = 0;  // --noise, in mean edge lengths
};

Sample run_once(const raps_bench::TriangleMesh& input, const Options& options) {
    Sample sample{};
    raps_mesh* mesh = nullptr;
    raps_settings* settings = nullptr;
    raps_result* result = nullptr;
    raps_mesh_create(&mesh);
    raps_settings_create(&settings);
    raps_result_create(&result);
    raps_settings_set_int(settings, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS);
    raps_settings_set_int(settings, RAPS_PARAM_THREADS, options.threads);
    raps_settings_set_int(settings, RAPS_PARAM_ATLAS_RESOLUTION, options.resolution);
    raps_settings_set_int(settings, RAPS_PARAM_ATLAS_PADDING, options.padding);
    const auto start = std::chrono::steady_clock::now();
    raps_mesh_set_positions_f64(mesh, input.positions.data(), input.positions.size() / 3, 0);
    raps_mesh_set_indices_u32(mesh, input.triangles.data(), input.triangles.size());
    if (raps_parameterize(mesh, settings, result) == RAPS_OK) {
        sample.total_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        sample.stats.struct_size = sizeof(sample.stats);
        raps_result_get_stats(result, &sample.stats);
        for (raps_phase p = 0; p < RAPS_PHASE_COUNT; ++p)
            sample.phase_ms[p] = raps_result_phase_ms(result, p);
        sample.ok = 1;
    } else {
        std::fprintf(stderr, "raps-bench-atlas: %s\n", raps_result_last_error(result));
    }
    raps_result_destroy(result);
    raps_settings_destroy(settings);
    raps_mesh_destroy(mesh);
    return sample;
}

}  // namespace

int main(int argc, char** argv) {
    std::string data = RAPS_SHARED_DATA_DIR;
    std::vector<std::string> only;
    bool phases = false;
    std::string phase_lines;
    int runs = 3;
    Options options;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--phases") {
            phases = true;
            continue;
        }
        if (i + 1 >= argc) {
            std::fprintf(stderr,
                         "usage: raps-bench-atlas [--data DIR] [--runs N] [--threads N] "
                         "[--resolution N] [--padding N] [--mesh FILE] [--phases] "
                         "[--subdivide K] [--scan TRIANGLES] [--noise F]\n");
            return 2;
        }
        const std::string value = argv[++i];
        if (arg == "--data")
            data = value;
        else if (arg == "--runs")
            runs = std::max(1, std::atoi(value.c_str()));
        else if (arg == "--threads")
            options.threads = std::atoi(value.c_str());
        else if (arg == "--resolution")
            options.resolution = std::atoi(value.c_str());
        else if (arg == "--padding")
            options.padding = std::atoi(value.c_str());
        else if (arg == "--mesh")
            only.push_back(value);
        else if (arg == "--scan")
            options.scan = std::max(0LL, std::atoll(value.c_str()));
        else if (arg == "--subdivide")
            options.subdivide = std::max(0, std::atoi(value.c_str()));
        else if (arg == "--noise")
            options.noise = std::max(0.0, std::atof(value.c_str()));
        else {
            std::fprintf(stderr, "raps-bench-atlas: unknown option %s\n", arg.c_str());
            return 2;
        }
    }
    std::printf(
        "raps %s atlas, resolution %d, padding %d, threads %d (0 = all), subdivided %d times, "
        "noise %g; median of %d runs\n\n",
        raps_version_string(), options.resolution, options.padding, options.threads,
        options.subdivide, options.noise, runs);
    std::printf(
        "| mesh | triangles | ms | charts | coverage | L2 | Linf | area mean abs log | "
        "angle mean deg | flips | peak MB |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    std::vector<std::string> names(std::begin(kMeshes), std::end(kMeshes));
    if (options.scan > 0) names.push_back("scan");
    for (const std::string& name : names) {
        const char* file = name.c_str();
        if (!only.empty() && std::find(only.begin(), only.end(), name) == only.end()) continue;
        const auto child = raps_bench::run_in_child<Sample>("raps-bench-atlas", [&](auto emit) {
            // --subdivide leaves the generated scan alone (--scan sets its size).
            raps_bench::TriangleMesh mesh =
                name == "scan"
                    ? scan_like_mesh(options.scan)
                    : raps_bench::load_triangles(data + "/meshes/" + file, options.subdivide);
            if (name != "scan" && options.noise > 0) add_noise(mesh, options.noise);
            for (int r = 0; r < runs; ++r) emit(run_once(mesh, options));
        });
        const std::vector<Sample>& samples = child.samples;
        if (samples.empty() || !samples[0].ok) {
            std::printf("| %s | failed |\n", file);
            continue;
        }
        std::vector<double> times;
        for (const Sample& x : samples) times.push_back(x.total_ms);
        const double ms = raps_bench::median(times);
        const raps_stats& st = samples[0].stats;
        std::printf(
            "| %s | %llu | %.0f | %llu | %.3f | %.4f | %.2f | %.3f | %.2f | %llu | %.0f |\n", file,
            static_cast<unsigned long long>(st.triangle_count), ms,
            static_cast<unsigned long long>(st.chart_count), st.utilization, st.stretch_l2,
            st.stretch_linf, st.area_log_mean, st.angle_mean_deg,
            static_cast<unsigned long long>(st.flipped_triangles), child.peak_mb);
        std::fflush(stdout);
        if (phases) {
            phase_lines += std::string("| ") + file;
            for (raps_phase p = 0; p < RAPS_PHASE_COUNT; ++p) {
                std::vector<double> phase;
                for (const Sample& x : samples) phase.push_back(x.phase_ms[p]);
                char cell[64];
                std::snprintf(cell, sizeof(cell), " | %.1f", raps_bench::median(phase));
                phase_lines += cell;
            }
            phase_lines += " |\n";
        }
    }
    if (phases) {
        std::printf("\nmedian ms per phase\n\n| mesh");
        for (raps_phase p = 0; p < RAPS_PHASE_COUNT; ++p)
            std::printf(" | %s", raps_samples::phase_name(p));
        std::printf(" |\n|---");
        for (raps_phase p = 0; p < RAPS_PHASE_COUNT; ++p) std::printf("|---:");
        std::printf("|\n%s", phase_lines.c_str());
    }
    return 0;
}
