#include "parameterization.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "atlas/atlas_pipeline.h"
#include "atlas/scene_mesh.h"
#include "core/error.h"
#include "core/memory_estimate.h"
#include "parallel/thread_pool.h"
#include "planar/disk_parameterization.h"
#include "sphere/sphere_parameterization.h"
#include "sphere/spherical_geometry.h"

namespace raps {
namespace {

// One output vertex per input vertex, the input triangles.
void identity_output(const TriangleMesh& mesh, Parameterization& out,
                     const ProgressSpan& progress) {
    out.indices.reserve(3 * mesh.triangles.size());
    progress.in_runs(mesh.triangle_count(), [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            for (int32_t v : mesh.triangles[t]) out.indices.push_back(static_cast<uint32_t>(v));
        }
    });
    out.vertex_remap.resize(mesh.positions.size());
    for (size_t v = 0; v < out.vertex_remap.size(); ++v) {
        out.vertex_remap[v] = static_cast<uint32_t>(v);
    }
}

// The output triangles, from their indices.
std::vector<Triangle> output_triangles(const std::vector<uint32_t>& indices,
                                       const ProgressSpan& progress) {
    std::vector<Triangle> triangles(indices.size() / 3);
    const int64_t count = static_cast<int64_t>(triangles.size());
    progress.in_runs(count, [&](int64_t run_begin, int64_t run_end) {
        for (int64_t t = static_cast<int64_t>(run_begin); t < run_end; ++t) {
            for (int k = 0; k < 3; ++k) triangles[t][k] = static_cast<int32_t>(indices[3 * t + k]);
        }
    });
    return triangles;
}

// The fraction of [0,1]^2 the map covers. A map that tiles the whole square (the octahedral
// unfold) sums to 1 give or take rounding; the fraction covered cannot exceed 1, so neither does
// the figure.
double uv_area(const std::vector<Eigen::Vector2d>& uv, const std::vector<Triangle>& triangles,
               const ProgressSpan& progress) {
    double area = 0;
    const int64_t count = static_cast<int64_t>(triangles.size());
    progress.in_runs(count, [&](int64_t run_begin, int64_t run_end) {
        for (int64_t i = static_cast<int64_t>(run_begin); i < run_end; ++i) {
            const Triangle& t = triangles[i];
            const Eigen::Vector2d a = uv[t[1]] - uv[t[0]], b = uv[t[2]] - uv[t[0]];
            area += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
        }
    });
    return std::min(area, 1.0);
}

// The statistics of a map measured alone (the disk and sphere domains, which keep no pool):
// one thread per 16K triangles, about 2 ms of work each, so that small meshes start none.
// Raises *threads_used to the threads the measuring ran on.
DistortionStats measure_alone(const Settings& settings,
                              const std::vector<Eigen::Vector3d>& positions, const MapGeometry& map,
                              const std::vector<Triangle>& triangles, int* threads_used,
                              const ProgressSpan& progress) {
    ThreadPool pool(
        choose_thread_count(settings.threads, static_cast<int64_t>(triangles.size()), 16384));
    DistortionStats stats = measure_distortion(positions, map, triangles, pool, progress);
    *threads_used = std::max(*threads_used, pool.threads_used());
    return stats;
}

// Refuses a run past the caller's limits before any work is done.
void check_limits(const TriangleMesh& mesh, const Settings& settings) {
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
}

// The fraction of the pages the charts cover: each place counted once (a stacked chart's
// texels are its place's, an exact copy's its original's: chart records count those once).
double atlas_utilization(const AtlasOutput& atlas) {
    double texels = 0;
    for (size_t c = 0; c < atlas.charts.size(); ++c) {
        if (atlas.charts[c].stacked_on == static_cast<int64_t>(c))
            texels += atlas.charts[c].area_texels;
    }
    const double page_texels = static_cast<double>(atlas.width) * atlas.height;
    return page_texels > 0 ? texels / (page_texels * atlas.page_count) : 0.0;
}

// The atlas of `mesh` made of `parts`; indices and remap global (into the whole mesh).
Parameterization atlas_map(const TriangleMesh& mesh, const AtlasParts& parts,
                           const Settings& settings, const Progress& progress) {
    Parameterization out;
    // One pool of threads for the whole atlas and its statistics: starting threads for
    // each parallel loop (17 of them on cheburashka) cost about 2% of the atlas.
    ThreadPool pool(settings.threads);
    AtlasOutput atlas = build_atlas(mesh, parts, settings, progress, out.phase_ms, pool);
    PhaseTimer timer(Phase::kMetrics, progress, out.phase_ms);
    // Statistics in texel space, where the map is isotropic: uv scaled back per axis.
    std::vector<Eigen::Vector3d> positions(atlas.remap.size());
    std::vector<Eigen::Vector2d> texels(atlas.uv.size());
    const int64_t vertex_count = static_cast<int64_t>(atlas.remap.size());
    const ProgressSpan copying = timer.span(0.0, 0.1);
    copying.in_runs(vertex_count, [&](int64_t run_begin, int64_t run_end) {
        for (int64_t v = static_cast<int64_t>(run_begin); v < run_end; ++v) {
            positions[v] = mesh.positions[atlas.remap[v]];
            texels[v] =
                Eigen::Vector2d(atlas.uv[v].x() * atlas.width, atlas.uv[v].y() * atlas.height);
        }
    });
    const std::vector<Triangle> triangles = output_triangles(atlas.indices, timer.span(0.1, 0.2));
    out.distortion = measure_distortion(positions, PlanarMapGeometry(texels), triangles, pool,
                                        timer.span(0.2, 0.95));
    out.utilization = atlas_utilization(atlas);
    out.uv = std::move(atlas.uv);
    out.indices = std::move(atlas.indices);
    out.vertex_remap = std::move(atlas.remap);
    out.chart_ids = std::move(atlas.chart_of);
    out.chart_count = atlas.chart_count();
    out.charts = std::move(atlas.charts);
    out.adaptive_solves = atlas.adaptive_solves;
    out.atlas_width = atlas.width;
    out.atlas_height = atlas.height;
    out.page_count = atlas.page_count;
    out.texels_per_unit = atlas.texels_per_unit;
    out.threads_used = pool.threads_used();
    for (int32_t p = 0; p < parts.count(); ++p) {
        OutputRange range;
        range.first_vertex = atlas.first_output_vertex[p];
        range.vertex_count = atlas.first_output_vertex[p + 1] - range.first_vertex;
        range.first_index = 3 * static_cast<int64_t>(parts.first_triangle[p]);
        range.index_count =
            3 * static_cast<int64_t>(parts.first_triangle[p + 1]) - range.first_index;
        out.ranges.push_back(range);
    }
    timer.finish();
    return out;
}

// The disk or sphere map of `mesh` (checked against the limits).
Parameterization disk_or_sphere_map(const TriangleMesh& mesh, const Settings& settings,
                                    const Progress& progress) {
    Parameterization out;
    if (settings.domain == Domain::kSphere) {
        SphereMap map = parameterize_sphere(mesh, settings, progress, out.phase_ms);
        out.negative_weights = map.negative_weights;
        out.adaptive_solves = map.adaptive_solves;
        out.relaxation_sweeps = map.relaxation_sweeps;
        out.threads_used = map.threads_used;
        if (map.unfold.uv.empty()) {
            PhaseTimer timer(Phase::kMetrics, progress, out.phase_ms);
            identity_output(mesh, out, timer.span(0.0, 0.1));
            out.sphere_points = std::move(map.points);
            out.distortion =
                measure_alone(settings, mesh.positions, SphericalMapGeometry(out.sphere_points),
                              mesh.triangles, &out.threads_used, timer.span());
            timer.finish();
            return out;
        }
        // The octahedral unfold: more output vertices than input (the cut's), statistics of
        // the uvs over the output triangles.
        PhaseTimer timer(Phase::kMetrics, progress, out.phase_ms);
        out.uv = std::move(map.unfold.uv);
        out.vertex_remap = std::move(map.unfold.vertex_remap);
        out.indices = std::move(map.unfold.indices);
        out.sphere_points.resize(out.vertex_remap.size());
        std::vector<Eigen::Vector3d> positions(out.vertex_remap.size());
        const int64_t vertex_count = static_cast<int64_t>(out.vertex_remap.size());
        const ProgressSpan copying = timer.span(0.0, 0.1);
        copying.in_runs(vertex_count, [&](int64_t run_begin, int64_t run_end) {
            for (int64_t o = static_cast<int64_t>(run_begin); o < run_end; ++o) {
                out.sphere_points[o] = map.points[out.vertex_remap[o]];
                positions[o] = mesh.positions[out.vertex_remap[o]];
            }
        });
        const std::vector<Triangle> triangles = output_triangles(out.indices, timer.span(0.1, 0.2));
        out.distortion = measure_alone(settings, positions, PlanarMapGeometry(out.uv), triangles,
                                       &out.threads_used, timer.span(0.2, 0.95));
        out.utilization = uv_area(out.uv, triangles, timer.span(0.95, 1.0));
        timer.finish();
        return out;
    }
    DiskMap map = parameterize_disk(mesh, settings, progress, out.phase_ms);
    out.uv = std::move(map.uv);
    out.negative_weights = map.negative_weights;
    out.adaptive_solves = map.adaptive_solves;
    PhaseTimer timer(Phase::kMetrics, progress, out.phase_ms);
    identity_output(mesh, out, timer.span(0.0, 0.1));
    out.distortion = measure_alone(settings, mesh.positions, PlanarMapGeometry(out.uv),
                                   mesh.triangles, &out.threads_used, timer.span(0.1, 0.95));
    out.utilization = uv_area(out.uv, mesh.triangles, timer.span(0.95, 1.0));
    timer.finish();
    return out;
}

}  // namespace

Parameterization parameterize(const TriangleMesh& mesh, const Settings& settings,
                              const Progress& progress) {
    if (mesh.positions.empty() || mesh.triangles.empty()) {
        throw Error(ErrorCode::kEmptyMesh, mesh.positions.empty()
                                               ? "the mesh has no vertices (set its positions)"
                                               : "the mesh has no triangles (set its indices)");
    }
    check_limits(mesh, settings);
    if (settings.domain == Domain::kAtlas)
        return atlas_map(mesh, single_part(mesh), settings, progress);
    Parameterization out = disk_or_sphere_map(mesh, settings, progress);
    out.ranges.push_back({0, static_cast<int64_t>(out.vertex_remap.size()), 0,
                          static_cast<int64_t>(out.indices.size())});
    return out;
}

Parameterization parameterize_scene(const std::vector<ScenePart>& parts, const Settings& settings,
                                    const Progress& progress) {
    if (settings.domain != Domain::kAtlas) {
        throw Error(ErrorCode::kInvalidArgument,
                    "a scene is parameterized into one atlas only: set RAPS_PARAM_DOMAIN to "
                    "RAPS_DOMAIN_ATLAS");
    }
    if (parts.empty()) throw Error(ErrorCode::kEmptyMesh, "the scene has no meshes (mesh_count 0)");
    std::vector<const TriangleMesh*> meshes;
    std::vector<Eigen::Matrix<double, 3, 4>> transforms;
    for (const ScenePart& part : parts) {
        meshes.push_back(part.mesh);
        transforms.push_back(part.transform);
    }
    const SceneMesh scene = combine_scene(meshes, transforms, settings.atlas_repack);
    check_limits(scene.mesh, settings);
    Parameterization out = atlas_map(scene.mesh, scene.parts, settings, progress);
    // Each mesh's share reads as its own: remap to its own input vertices, indices to its own
    // output vertices.
    for (int32_t p = 0; p < scene.parts.count(); ++p) {
        const OutputRange& range = out.ranges[p];
        for (int64_t v = range.first_vertex; v < range.first_vertex + range.vertex_count; ++v)
            out.vertex_remap[v] -= static_cast<uint32_t>(scene.parts.first_vertex[p]);
        for (int64_t i = range.first_index; i < range.first_index + range.index_count; ++i)
            out.indices[i] -= static_cast<uint32_t>(range.first_vertex);
    }
    return out;
}

}  // namespace raps
