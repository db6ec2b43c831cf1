// raps-bench-atlas: the atlas domain on every shared mesh: time, charts, coverage of the atlas,
// L2 and Linf stretch, area and angle distortion, flips. Each mesh runs in its own child process
// (peak memory per mesh); times are medians of several runs. No other tool runs here, so no
// other tool's figures are printed.
//
//   raps-bench-atlas [--data DIR] [--runs N] [--threads N] [--resolution N] [--padding N]
//                    [--mesh FILE] [--phases] [--subdivide K]
// --mesh runs only that mesh (fandisk.obj, say: for profiling); --phases adds, after the table,
// each mesh's median time per phase; --subdivide splits every triangle 1-to-4 K times first
// (the same surface with 4^K times the triangles: how the time grows with the size).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "mesh_io.h"
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

struct Sample {
    double total_ms;
    double phase_ms[RAPS_PHASE_COUNT];
    raps_stats stats;
    int ok;
};

struct Options {
    int threads = 0, resolution = 1024, padding = 1, subdivide = 0;
};

Sample run_once(const raps_samples::PolygonMesh& polygons, const std::vector<uint32_t>& triangles,
                const Options& options) {
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
    raps_mesh_set_positions_f64(mesh, polygons.positions.data(), polygons.vertex_count(), 0);
    raps_mesh_set_indices_u32(mesh, triangles.data(), triangles.size());
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
    std::string only;
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
                         "[--subdivide K]\n");
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
            only = value;
        else if (arg == "--subdivide")
            options.subdivide = std::max(0, std::atoi(value.c_str()));
        else {
            std::fprintf(stderr, "raps-bench-atlas: unknown option %s\n", arg.c_str());
            return 2;
        }
    }
    std::printf(
        "raps %s atlas, resolution %d, padding %d, threads %d (0 = all), subdivided %d times; "
        "median of %d runs\n\n",
        raps_version_string(), options.resolution, options.padding, options.threads,
        options.subdivide, runs);
    std::printf(
        "| mesh | triangles | ms | charts | coverage | L2 | Linf | area mean abs log | "
        "angle mean deg | flips | peak MB |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const char* file : kMeshes) {
        if (!only.empty() && only != file) continue;
        int fds[2];
        if (pipe(fds) != 0) return 1;
        const pid_t pid = fork();
        if (pid == 0) {
            close(fds[0]);
            try {
                raps_samples::PolygonMesh mesh = raps_samples::read_mesh(data + "/meshes/" + file);
                std::vector<uint32_t> triangles = mesh.triangles();
                for (int k = 0; k < options.subdivide; ++k)
                    raps_samples::subdivide_midpoint(mesh.positions, triangles);
                for (int r = 0; r < runs; ++r) {
                    const Sample s = run_once(mesh, triangles, options);
                    if (write(fds[1], &s, sizeof(s)) != static_cast<ssize_t>(sizeof(s))) _exit(3);
                }
            } catch (const std::exception& e) {
                std::fprintf(stderr, "raps-bench-atlas: %s\n", e.what());
                _exit(2);
            }
            _exit(0);
        }
        close(fds[1]);
        std::vector<Sample> samples;
        Sample s;
        while (read(fds[0], &s, sizeof(s)) == static_cast<ssize_t>(sizeof(s))) samples.push_back(s);
        close(fds[0]);
        int status = 0;
        struct rusage usage;
        wait4(pid, &status, 0, &usage);
        if (samples.empty() || !samples[0].ok) {
            std::printf("| %s | failed |\n", file);
            continue;
        }
        std::vector<double> times;
        for (const Sample& x : samples) times.push_back(x.total_ms);
        std::sort(times.begin(), times.end());
        const double ms = times[times.size() / 2];
        const raps_stats& st = samples[0].stats;
        std::printf(
            "| %s | %llu | %.0f | %llu | %.3f | %.4f | %.2f | %.3f | %.2f | %llu | %.0f |\n", file,
            static_cast<unsigned long long>(st.triangle_count), ms,
            static_cast<unsigned long long>(st.chart_count), st.utilization, st.stretch_l2,
            st.stretch_linf, st.area_log_mean, st.angle_mean_deg,
            static_cast<unsigned long long>(st.flipped_triangles), usage.ru_maxrss / 1024.0);
        std::fflush(stdout);
        if (phases) {
            phase_lines += std::string("| ") + file;
            for (raps_phase p = 0; p < RAPS_PHASE_COUNT; ++p) {
                std::vector<double> phase;
                for (const Sample& x : samples) phase.push_back(x.phase_ms[p]);
                std::sort(phase.begin(), phase.end());
                char cell[64];
                std::snprintf(cell, sizeof(cell), " | %.1f", phase[phase.size() / 2]);
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
