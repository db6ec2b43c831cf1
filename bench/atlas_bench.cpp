// raps-bench-atlas: the atlas domain on every shared mesh, next to the xatlas figures the
// project measured (issue "Atlas for any mesh"): time, charts, coverage of the atlas, L2 and
// Linf stretch, area and angle distortion, flips. Each mesh runs in its own child process
// (peak memory per mesh); times are medians of several runs.
//
//   raps-bench-atlas [--data DIR] [--runs N] [--threads N] [--resolution N] [--padding N]
//                    [--mesh FILE] [--phases]
// --mesh runs only that mesh (fandisk.obj, say: for profiling); --phases adds, after the table,
// each mesh's median time per phase.
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

// Measured by the project with xatlas built natively at -O2, default options (issue text).
struct Reference {
    const char* file;
    double ms;
    int charts;
    double l2, linf, coverage;
};
const Reference kReference[] = {
    {"3holes.off", 569, 29, 1.0017, 1.17, 0.57},
    {"alligator.obj", 72, 1, 1.0000, 1.00, 0.49},
    {"beetle.off", 10231, 12, 1.0012, 1.11, 0.51},
    {"bunny.off", 516, 58, 1.0267, 8.11, 0.59},
    {"camelhead.off", 4406, 303, -1, -1, 0.57},
    {"cheburashka.off", 700, 67, 1.0037, 2.26, 0.60},
    {"decimated-max.obj", 1029, 126, 1.0042, 8.70, 0.59},
    {"face.obj", 14510, 33, 1.0042, 2.07, 0.60},
    {"fandisk.obj", 258, 15, 1.0010, 1.18, 0.64},
    {"fertility.off", 1103, 45, 1.0262, 2.52, 0.54},
    {"halftunnel.off", 76, 11, 1.0014, 1.20, 0.65},
    {"lion.off", 1474, 114, 1.0101, 7.72, 0.62},
    {"rocker-arm.obj", 6209, 43, 1.0028, 2.56, 0.58},
    {"spot.obj", 398, 39, 1.0032, 1.23, 0.66},
    {"suzanne.obj", 62, 70, 1.0173, 1.92, 0.68},
    {"teapot.obj", 150, 52, 1.0016, 1.24, 0.61},
};

struct Sample {
    double total_ms;
    double phase_ms[RAPS_PHASE_COUNT];
    raps_stats stats;
    int ok;
};

struct Options {
    int threads = 0, resolution = 1024, padding = 1;
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
                         "[--resolution N] [--padding N] [--mesh FILE] [--phases]\n");
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
        else {
            std::fprintf(stderr, "raps-bench-atlas: unknown option %s\n", arg.c_str());
            return 2;
        }
    }
    std::printf(
        "raps %s atlas, resolution %d, padding %d, threads %d (0 = all); median of %d runs\n\n",
        raps_version_string(), options.resolution, options.padding, options.threads, runs);
    std::printf(
        "| mesh | triangles | ms | xatlas ms | speed-up | charts | xatlas | coverage | xatlas | "
        "L2 | xatlas | Linf | xatlas | area mean abs log | angle mean deg | flips | peak MB |\n");
    std::printf(
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const Reference& ref : kReference) {
        if (!only.empty() && only != ref.file) continue;
        int fds[2];
        if (pipe(fds) != 0) return 1;
        const pid_t pid = fork();
        if (pid == 0) {
            close(fds[0]);
            try {
                const raps_samples::PolygonMesh mesh =
                    raps_samples::read_mesh(data + "/meshes/" + ref.file);
                const std::vector<uint32_t> triangles = mesh.triangles();
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
            std::printf("| %s | failed |\n", ref.file);
            continue;
        }
        std::vector<double> times;
        for (const Sample& x : samples) times.push_back(x.total_ms);
        std::sort(times.begin(), times.end());
        const double ms = times[times.size() / 2];
        const raps_stats& st = samples[0].stats;
        auto reference = [](double v, const char* format) {
            char buffer[32];
            if (v < 0) return std::string("inf");
            std::snprintf(buffer, sizeof(buffer), format, v);
            return std::string(buffer);
        };
        std::printf(
            "| %s | %llu | %.0f | %.0f | %.1fx | %llu | %d | %.3f | %.2f | %.4f | %s | %.2f | %s | "
            "%.3f | "
            "%.2f | %llu | %.0f |\n",
            ref.file, static_cast<unsigned long long>(st.triangle_count), ms, ref.ms, ref.ms / ms,
            static_cast<unsigned long long>(st.chart_count), ref.charts, st.utilization,
            ref.coverage, st.stretch_l2, reference(ref.l2, "%.4f").c_str(), st.stretch_linf,
            reference(ref.linf, "%.2f").c_str(), st.area_log_mean, st.angle_mean_deg,
            static_cast<unsigned long long>(st.flipped_triangles), usage.ru_maxrss / 1024.0);
        std::fflush(stdout);
        if (phases) {
            phase_lines += std::string("| ") + ref.file;
            for (raps_phase p = 0; p < RAPS_PHASE_COUNT; ++p) {
                std::vector<double> phase;
                for (const Sample& x : samples) phase.push_back(x.phase_ms[p]);
                std::sort(phase.begin(), phase.end());
                char cell[64];
                std::snprintf(cell, sizeof(cell), " | %s %.1f", raps_samples::phase_name(p),
                              phase[phase.size() / 2]);
                phase_lines += cell;
            }
            phase_lines += " |\n";
        }
    }
    if (phases) std::printf("\nmedian ms per phase\n\n%s", phase_lines.c_str());
    return 0;
}
