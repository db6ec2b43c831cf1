// raps-bench-memory: the peak memory one raps_parameterize call adds, per domain and mesh size,
// the measurements behind the estimate RAPS_PARAM_MAX_MEMORY_MB is checked against
// (src/core/memory_estimate.cpp).
//
//   raps-bench-memory [--data DIR] [--subdivide K] [--resolution R] [--only DOMAIN]
//
// Every case runs in its own child process: it reads the mesh (subdivided 1-to-4 up to K times,
// default 2), sets it into a raps_mesh, resets the process's peak resident set
// (/proc/self/clear_refs), runs the domain with its default settings, and reports the peak
// resident set (VmHWM) minus the resident set just before the call. Printed per case: triangles,
// that peak in MB, bytes per triangle, and the library's estimate for comparison. --resolution
// sets the atlas resolution (default 1024); --only measures one domain (disk, sphere, atlas).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bench_support.h"
#include "raps.h"

namespace {

// A "VmRSS:" or "VmHWM:" line of /proc/self/status, in bytes.
long long status_bytes(const char* field) {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.compare(0, std::strlen(field), field) == 0) {
            return std::atoll(line.c_str() + std::strlen(field)) * 1024;
        }
    }
    return -1;
}

struct Report {
    long long triangles;
    long long peak_bytes;   // peak resident set during the call, minus the set before it
    long long estimate_mb;  // the smallest RAPS_PARAM_MAX_MEMORY_MB the mesh passes
    int status;
};

// The smallest memory cap the library lets the mesh through with, found by bisection on the
// status (RAPS_ERROR_TOO_LARGE is returned before any work).
long long smallest_passing_cap(const raps_mesh* mesh, int32_t domain, int64_t resolution) {
    raps_settings* settings = nullptr;
    raps_result* result = nullptr;
    raps_settings_create(&settings);
    raps_result_create(&result);
    raps_settings_set_int(settings, RAPS_PARAM_DOMAIN, domain);
    raps_settings_set_int(settings, RAPS_PARAM_ATLAS_RESOLUTION, resolution);
    // Cancel at the first progress call: only the refusal before any work matters here.
    raps_settings_set_progress(
        settings, [](void*, raps_phase, double) -> int32_t { return 0; }, nullptr);
    long long low = 0, high = 1 << 24;  // low refused (or 0), high passes
    while (high - low > 1) {
        const long long mid = (low + high) / 2;
        raps_settings_set_int(settings, RAPS_PARAM_MAX_MEMORY_MB, mid);
        if (raps_parameterize(mesh, settings, result) == RAPS_ERROR_TOO_LARGE) {
            low = mid;
        } else {
            high = mid;
        }
    }
    raps_result_destroy(result);
    raps_settings_destroy(settings);
    return high;
}

Report measure(const std::string& file, int subdivisions, int32_t domain, int64_t resolution) {
    raps_bench::TriangleMesh input = raps_bench::load_triangles(file, subdivisions);
    std::vector<double>& positions = input.positions;
    std::vector<uint32_t>& triangles = input.triangles;
    raps_mesh* mesh = nullptr;
    raps_mesh_create(&mesh);
    raps_mesh_set_positions_f64(mesh, positions.data(), positions.size() / 3, 0);
    raps_mesh_set_indices_u32(mesh, triangles.data(), triangles.size());
    Report report{static_cast<long long>(triangles.size() / 3), 0, 0, 0};
    report.estimate_mb = smallest_passing_cap(mesh, domain, resolution);
    // The input arrays are the caller's, not the call's: give them back before measuring.
    std::vector<double>().swap(positions);
    std::vector<uint32_t>().swap(triangles);
    raps_settings* settings = nullptr;
    raps_result* result = nullptr;
    raps_settings_create(&settings);
    raps_result_create(&result);
    raps_settings_set_int(settings, RAPS_PARAM_DOMAIN, domain);
    raps_settings_set_int(settings, RAPS_PARAM_ATLAS_RESOLUTION, resolution);
    {
        std::ofstream reset("/proc/self/clear_refs");
        reset << "5";  // the peak resident set becomes the current one
    }
    const long long before = status_bytes("VmRSS:");
    report.status = raps_parameterize(mesh, settings, result);
    report.peak_bytes = status_bytes("VmHWM:") - before;
    raps_result_destroy(result);
    raps_settings_destroy(settings);
    raps_mesh_destroy(mesh);
    return report;
}

Report measure_in_child(const std::string& file, int subdivisions, int32_t domain,
                        int64_t resolution) {
    const auto child = raps_bench::run_in_child<Report>("raps-bench-memory", [&](auto emit) {
        emit(measure(file, subdivisions, domain, resolution));
    });
    if (child.samples.empty()) throw std::runtime_error("a child failed on " + file);
    return child.samples[0];
}

}  // namespace

int main(int argc, char** argv) {
    std::string data = RAPS_SHARED_DATA_DIR;
    int most_subdivisions = 2;
    int64_t resolution = 1024;
    std::string only;
    for (int a = 1; a + 1 < argc; a += 2) {
        if (std::strcmp(argv[a], "--data") == 0) {
            data = argv[a + 1];
        } else if (std::strcmp(argv[a], "--subdivide") == 0) {
            most_subdivisions = std::atoi(argv[a + 1]);
        } else if (std::strcmp(argv[a], "--resolution") == 0) {
            resolution = std::atoll(argv[a + 1]);
        } else if (std::strcmp(argv[a], "--only") == 0) {
            only = argv[a + 1];
        } else {
            std::fprintf(stderr,
                         "usage: raps-bench-memory [--data DIR] [--subdivide K] [--resolution R] "
                         "[--only DOMAIN]\n");
            return 2;
        }
    }
    struct Domain {
        const char* name;
        int32_t id;
        std::vector<std::string> meshes;
    };
    const std::vector<Domain> domains = {
        {"disk", RAPS_DOMAIN_DISK, {"alligator.obj", "camelhead.off", "face.obj"}},
        {"sphere", RAPS_DOMAIN_SPHERE, {"spot.obj", "bunny.off"}},
        {"atlas", RAPS_DOMAIN_ATLAS, {"fandisk.obj", "bunny.off"}},
    };
    std::printf(
        "raps %s: peak resident memory one raps_parameterize call adds (default settings, atlas "
        "resolution %lld)\n\n",
        raps_version_string(), static_cast<long long>(resolution));
    std::printf("| domain | mesh | triangles | peak MB | bytes per triangle | estimate MB |\n");
    std::printf("|---|---|---:|---:|---:|---:|\n");
    for (const Domain& domain : domains) {
        if (!only.empty() && only != domain.name) continue;
        for (const std::string& name : domain.meshes) {
            for (int s = 0; s <= most_subdivisions; ++s) {
                const Report r =
                    measure_in_child(data + "/meshes/" + name, s, domain.id, resolution);
                if (r.status != RAPS_OK) {
                    std::printf("| %s | %s/%d | %lld | failed: %s | | |\n", domain.name,
                                name.c_str(), 1 << (2 * s), r.triangles,
                                raps_status_string(r.status));
                    continue;
                }
                std::printf("| %s | %s/%d | %lld | %.1f | %.0f | %lld |\n", domain.name,
                            name.c_str(), 1 << (2 * s), r.triangles, r.peak_bytes / 1048576.0,
                            static_cast<double>(r.peak_bytes) / static_cast<double>(r.triangles),
                            r.estimate_mb);
                std::fflush(stdout);
            }
        }
    }
    return 0;
}
