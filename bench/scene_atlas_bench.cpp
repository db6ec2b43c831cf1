// raps-bench-scene: the ten shared meshes of issue 23 as one scene (raps_parameterize_scene):
// time, charts, atlas size, pages, utilization and how uniform the texel density is across the
// charts. Three rows: resolution-driven (the atlas fills --resolution, as xatlas is asked to in
// the issue), whole texels on one page of --resolution (RAPS_PARAM_ATLAS_WHOLE_TEXELS), and at a
// density (--texels-per-unit, by default the density the first row found, on pages of at most
// --max-size). Times are medians of --runs runs. No other tool runs here.
//
//   raps-bench-scene [--data DIR] [--runs N] [--threads N] [--resolution N] [--padding N]
//                    [--texels-per-unit T] [--max-size N]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_support.h"
#include "mesh_io.h"
#include "raps.h"

namespace {

// The scene of issue 23 (74,698 triangles together).
const char* const kMeshes[] = {
    "bunny.off",       "spot.obj",          "suzanne.obj",    "teapot.obj", "fandisk.obj",
    "cheburashka.off", "decimated-max.obj", "halftunnel.off", "3holes.off", "fertility.off"};

struct Options {
    std::string data = RAPS_SHARED_DATA_DIR;
    int runs = 3, threads = 0, resolution = 2048, padding = 2, max_size = 2048;
    double texels_per_unit = 0;  // 0: the first row's density
};

struct Row {
    double median_ms = 0;
    raps_stats stats{};
    double density_spread = 0;  // (max - min) / min of texels per unit area, charts not shrunk
};

void require(raps_status status, const char* what) {
    if (status != RAPS_OK) throw std::runtime_error(std::string(what) + " failed");
}

// Runs the scene `runs` times with `settings`; the statistics of the last run.
Row measure(const std::vector<raps_mesh*>& meshes, raps_settings* settings, int runs) {
    Row row;
    std::vector<double> ms;
    raps_result* result = nullptr;
    require(raps_result_create(&result), "raps_result_create");
    for (int run = 0; run < runs; ++run) {
        const auto start = std::chrono::steady_clock::now();
        const raps_status status = raps_parameterize_scene(
            const_cast<const raps_mesh* const*>(meshes.data()), meshes.size(), settings, result);
        ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count());
        if (status != RAPS_OK) {
            const std::string message = raps_result_last_error(result);
            raps_result_destroy(result);
            throw std::runtime_error("raps_parameterize_scene: " + message);
        }
    }
    row.median_ms = raps_bench::median(ms);
    row.stats.struct_size = sizeof(row.stats);
    require(raps_result_get_stats(result, &row.stats), "raps_result_get_stats");
    double lo = 1e300, hi = 0;
    for (uint64_t c = 0; c < row.stats.chart_count; ++c) {
        raps_chart chart;
        chart.struct_size = sizeof(chart);
        require(raps_result_get_chart(result, c, &chart), "raps_result_get_chart");
        if (chart.area_3d <= 0 || (chart.flags & RAPS_CHART_SCALED_DOWN)) continue;
        const double density = chart.area_texels / chart.area_3d;
        lo = std::min(lo, density);
        hi = std::max(hi, density);
    }
    row.density_spread = hi > 0 ? (hi - lo) / lo : 0;
    raps_result_destroy(result);
    return row;
}

void print_row(const char* mode, const Row& row) {
    std::printf("%-34s %9.0f %7llu %5llu x %-5llu %5llu %11.3f %9.2f %10.4f%% %7llu\n", mode,
                row.median_ms, static_cast<unsigned long long>(row.stats.chart_count),
                static_cast<unsigned long long>(row.stats.atlas_width),
                static_cast<unsigned long long>(row.stats.atlas_height),
                static_cast<unsigned long long>(row.stats.page_count), row.stats.utilization,
                row.stats.texels_per_unit, 100.0 * row.density_spread,
                static_cast<unsigned long long>(row.stats.scaled_down_charts));
}

int run(const Options& options) {
    std::vector<raps_mesh*> meshes;
    uint64_t triangles = 0;
    for (const char* name : kMeshes) {
        const raps_samples::PolygonMesh polygons =
            raps_samples::read_mesh(options.data + "/meshes/" + name);
        const std::vector<uint32_t> indices = polygons.triangles();
        raps_mesh* mesh = nullptr;
        require(raps_mesh_create(&mesh), "raps_mesh_create");
        meshes.push_back(mesh);
        require(raps_mesh_set_positions_f64(mesh, polygons.positions.data(),
                                            polygons.vertex_count(), 0),
                name);
        require(raps_mesh_set_indices_u32(mesh, indices.data(), indices.size()), name);
        triangles += indices.size() / 3;
    }
    raps_settings* settings = nullptr;
    require(raps_settings_create(&settings), "raps_settings_create");
    require(raps_settings_set_int(settings, RAPS_PARAM_DOMAIN, RAPS_DOMAIN_ATLAS), "domain");
    require(raps_settings_set_int(settings, RAPS_PARAM_THREADS, options.threads), "--threads");
    require(raps_settings_set_int(settings, RAPS_PARAM_ATLAS_PADDING, options.padding),
            "--padding");
    require(raps_settings_set_int(settings, RAPS_PARAM_ATLAS_RESOLUTION, options.resolution),
            "--resolution");
    std::printf("scene: %zu meshes, %llu triangles; padding %d, threads %d, median of %d runs\n",
                meshes.size(), static_cast<unsigned long long>(triangles), options.padding,
                options.threads, options.runs);
    std::printf("%-34s %9s %7s %13s %5s %11s %9s %11s %7s\n", "mode", "ms", "charts", "atlas",
                "pages", "utilization", "texels/u", "density", "shrunk");
    const Row by_resolution = measure(meshes, settings, options.runs);
    const std::string resolution_mode = "resolution " + std::to_string(options.resolution);
    print_row(resolution_mode.c_str(), by_resolution);

    require(raps_settings_set_int(settings, RAPS_PARAM_ATLAS_WHOLE_TEXELS, 1), "whole texels");
    const Row whole_texels = measure(meshes, settings, options.runs);
    const std::string whole_mode = "whole texels, " + std::to_string(options.resolution);
    print_row(whole_mode.c_str(), whole_texels);
    require(raps_settings_set_int(settings, RAPS_PARAM_ATLAS_WHOLE_TEXELS, 0), "whole texels");

    const double density =
        options.texels_per_unit > 0 ? options.texels_per_unit : by_resolution.stats.texels_per_unit;
    require(raps_settings_set_float(settings, RAPS_PARAM_ATLAS_TEXELS_PER_UNIT, density),
            "--texels-per-unit");
    require(raps_settings_set_int(settings, RAPS_PARAM_ATLAS_MAX_WIDTH, options.max_size),
            "--max-size");
    require(raps_settings_set_int(settings, RAPS_PARAM_ATLAS_MAX_HEIGHT, options.max_size),
            "--max-size");
    const Row by_density = measure(meshes, settings, options.runs);
    char mode[64];
    std::snprintf(mode, sizeof(mode), "density %.2f, pages <= %d", density, options.max_size);
    print_row(mode, by_density);
    raps_settings_destroy(settings);
    for (raps_mesh* mesh : meshes) raps_mesh_destroy(mesh);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options options;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (i + 1 >= argc) {
            std::fprintf(stderr, "raps-bench-scene: %s needs a value\n", arg.c_str());
            return 2;
        }
        const char* value = argv[++i];
        if (arg == "--data") {
            options.data = value;
        } else if (arg == "--runs") {
            options.runs = std::max(1, std::atoi(value));
        } else if (arg == "--threads") {
            options.threads = std::atoi(value);
        } else if (arg == "--resolution") {
            options.resolution = std::atoi(value);
        } else if (arg == "--padding") {
            options.padding = std::atoi(value);
        } else if (arg == "--texels-per-unit") {
            options.texels_per_unit = std::atof(value);
        } else if (arg == "--max-size") {
            options.max_size = std::atoi(value);
        } else {
            std::fprintf(stderr, "raps-bench-scene: unknown option %s\n", arg.c_str());
            return 2;
        }
    }
    try {
        return run(options);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "raps-bench-scene: %s\n", e.what());
        return 1;
    }
}
