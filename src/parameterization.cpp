#include "parameterization.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "atlas/atlas_pipeline.h"
#include "core/error.h"
#include "core/memory_estimate.h"
#include "parallel/thread_pool.h"
#include "planar/disk_parameterization.h"
#include "sphere/sphere_parameterization.h"
#include "sphere/spherical_geometry.h"

namespace raps {
namespace {

// One output vertex per input vertex, the input triangles.
void identity_output(const TriangleMesh& mesh, Parameterization& out) {
    out.indices.reserve(3 * mesh.triangles.size());
    for (const Triangle& t : mesh.triangles) {
        for (int32_t v : t) out.indices.push_back(static_cast<uint32_t>(v));
    }
    out.vertex_remap.resize(mesh.positions.size());
    for (size_t v = 0; v < out.vertex_remap.size(); ++v) {
        out.vertex_remap[v] = static_cast<uint32_t>(v);
    }
}

// Total uv area of `triangles`: the fraction of [0,1]^2 the map covers. A map that tiles the
// whole square (the octahedral unfold) sums to 1 give or take rounding; the fraction covered
// cannot exceed 1, so neither does the figure.
double uv_area(const std::vector<Eigen::Vector2d>& uv, const std::vector<Triangle>& triangles) {
    double area = 0;
    for (const Triangle& t : triangles) {
        const Eigen::Vector2d a = uv[t[1]] - uv[t[0]], b = uv[t[2]] - uv[t[0]];
        area += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
    }
    return std::min(area, 1.0);
}

// The statistics of a map measured alone (the disk and sphere domains, which keep no pool):
// one thread per 16K triangles, about 2 ms of work each, so that small meshes start none.
// Raises *threads_used to the threads the measuring ran on.
DistortionStats measure_alone(const Settings& settings,
                              const std::vector<Eigen::Vector3d>& positions, const MapGeometry& map,
                              const std::vector<Triangle>& triangles, int* threads_used) {
    ThreadPool pool(
        choose_thread_count(settings.threads, static_cast<int64_t>(triangles.size()), 16384));
    DistortionStats stats = measure_distortion(positions, map, triangles, pool);
    *threads_used = std::max(*threads_used, pool.threads_used());
    return stats;
}

}  // namespace

Parameterization parameterize(const TriangleMesh& mesh, const Settings& settings,
                              const Progress& progress) {
    if (mesh.positions.empty() || mesh.triangles.empty()) {
        throw Error(ErrorCode::kEmptyMesh, mesh.positions.empty()
                                               ? "the mesh has no vertices (set its positions)"
                                               : "the mesh has no triangles (set its indices)");
    }
    if (mesh.triangle_count() > settings.max_triangles) {
        throw Error(ErrorCode::kTooLarge, "the mesh has " + std::to_string(mesh.triangle_count()) +
                                              " triangles, more than RAPS_PARAM_MAX_TRIANGLES = " +
                                              std::to_string(settings.max_triangles));
    }
    if (settings.max_memory_mb > 0) {
        const double estimate = estimated_peak_bytes(mesh, settings);
        if (estimate > static_cast<double>(settings.max_memory_mb) * 1048576.0) {
            throw Error(ErrorCode::kTooLarge,
                        "the run is estimated to need " +
                            std::to_string(static_cast<int64_t>(estimate / 1048576.0) + 1) +
                            " MiB at its peak, more than RAPS_PARAM_MAX_MEMORY_MB = " +
                            std::to_string(settings.max_memory_mb));
        }
    }
    Parameterization out;
    if (settings.domain == Domain::kSphere) {
        SphereMap map = parameterize_sphere(mesh, settings, progress, out.phase_ms);
        out.negative_weights = map.negative_weights;
        out.adaptive_solves = map.adaptive_solves;
        out.relaxation_sweeps = map.relaxation_sweeps;
        out.threads_used = map.threads_used;
        if (map.unfold.uv.empty()) {
            identity_output(mesh, out);
            out.sphere_points = std::move(map.points);
            PhaseTimer timer(Phase::kMetrics, progress, out.phase_ms);
            out.distortion =
                measure_alone(settings, mesh.positions, SphericalMapGeometry(out.sphere_points),
                              mesh.triangles, &out.threads_used);
            timer.finish();
            return out;
        }
        // The octahedral unfold: more output vertices than input (the cut's), statistics of
        // the uvs over the output triangles.
        out.uv = std::move(map.unfold.uv);
        out.vertex_remap = std::move(map.unfold.vertex_remap);
        out.indices = std::move(map.unfold.indices);
        out.sphere_points.resize(out.vertex_remap.size());
        std::vector<Eigen::Vector3d> positions(out.vertex_remap.size());
        for (size_t o = 0; o < out.vertex_remap.size(); ++o) {
            out.sphere_points[o] = map.points[out.vertex_remap[o]];
            positions[o] = mesh.positions[out.vertex_remap[o]];
        }
        std::vector<Triangle> triangles(mesh.triangles.size());
        for (size_t t = 0; t < triangles.size(); ++t) {
            for (int k = 0; k < 3; ++k)
                triangles[t][k] = static_cast<int32_t>(out.indices[3 * t + k]);
        }
        PhaseTimer timer(Phase::kMetrics, progress, out.phase_ms);
        out.distortion = measure_alone(settings, positions, PlanarMapGeometry(out.uv), triangles,
                                       &out.threads_used);
        out.utilization = uv_area(out.uv, triangles);
        timer.finish();
        return out;
    }
    if (settings.domain == Domain::kAtlas) {
        // One pool of threads for the whole atlas and its statistics: starting threads for
        // each parallel loop (17 of them on cheburashka) cost about 2% of the atlas.
        ThreadPool pool(settings.threads);
        AtlasOutput atlas = build_atlas(mesh, settings, progress, out.phase_ms, pool);
        PhaseTimer timer(Phase::kMetrics, progress, out.phase_ms);
        // Statistics in texel space, where the map is isotropic: uv scaled back per axis.
        std::vector<Eigen::Vector3d> positions(atlas.remap.size());
        std::vector<Eigen::Vector2d> texels(atlas.uv.size());
        for (size_t v = 0; v < atlas.remap.size(); ++v) {
            positions[v] = mesh.positions[atlas.remap[v]];
            texels[v] =
                Eigen::Vector2d(atlas.uv[v].x() * atlas.width, atlas.uv[v].y() * atlas.height);
        }
        std::vector<Triangle> triangles(mesh.triangles.size());
        for (size_t t = 0; t < triangles.size(); ++t) {
            for (int k = 0; k < 3; ++k)
                triangles[t][k] = static_cast<int32_t>(atlas.indices[3 * t + k]);
        }
        out.distortion = measure_distortion(positions, PlanarMapGeometry(texels), triangles, pool);
        out.utilization = uv_area(atlas.uv, triangles);
        out.uv = std::move(atlas.uv);
        out.indices = std::move(atlas.indices);
        out.vertex_remap = std::move(atlas.remap);
        out.chart_ids = std::move(atlas.chart_of);
        out.chart_count = atlas.chart_count;
        out.adaptive_solves = atlas.adaptive_solves;
        out.atlas_width = atlas.width;
        out.atlas_height = atlas.height;
        out.threads_used = pool.threads_used();
        timer.finish();
        return out;
    }
    DiskMap map = parameterize_disk(mesh, settings, progress, out.phase_ms);
    out.uv = std::move(map.uv);
    out.negative_weights = map.negative_weights;
    out.adaptive_solves = map.adaptive_solves;
    identity_output(mesh, out);
    PhaseTimer timer(Phase::kMetrics, progress, out.phase_ms);
    out.distortion = measure_alone(settings, mesh.positions, PlanarMapGeometry(out.uv),
                                   mesh.triangles, &out.threads_used);
    out.utilization = uv_area(out.uv, mesh.triangles);
    timer.finish();
    return out;
}

}  // namespace raps
