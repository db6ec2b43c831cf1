#include "parameterization.h"

#include <cmath>
#include <string>

#include "atlas/atlas_pipeline.h"
#include "core/error.h"
#include "planar/disk_parameterization.h"

namespace raps {

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
    Parameterization out;
    if (settings.domain == Domain::kAtlas) {
        AtlasOutput atlas = build_atlas(mesh, settings, progress, out.phase_ms);
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
        double uv_area = 0;
        for (size_t t = 0; t < triangles.size(); ++t) {
            for (int k = 0; k < 3; ++k)
                triangles[t][k] = static_cast<int32_t>(atlas.indices[3 * t + k]);
            const Eigen::Vector2d a = atlas.uv[triangles[t][1]] - atlas.uv[triangles[t][0]];
            const Eigen::Vector2d b = atlas.uv[triangles[t][2]] - atlas.uv[triangles[t][0]];
            uv_area += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
        }
        out.distortion = measure_distortion(positions, texels, triangles);
        out.utilization = uv_area;
        out.uv = std::move(atlas.uv);
        out.indices = std::move(atlas.indices);
        out.vertex_remap = std::move(atlas.remap);
        out.chart_ids = std::move(atlas.chart_of);
        out.chart_count = atlas.chart_count;
        out.adaptive_solves = atlas.adaptive_solves;
        out.atlas_width = atlas.width;
        out.atlas_height = atlas.height;
        timer.finish();
        return out;
    }
    DiskMap map = parameterize_disk(mesh, settings, progress, out.phase_ms);
    out.uv = std::move(map.uv);
    out.negative_weights = map.negative_weights;
    out.adaptive_solves = map.adaptive_solves;
    out.indices.reserve(3 * mesh.triangles.size());
    for (const Triangle& t : mesh.triangles) {
        for (int32_t v : t) out.indices.push_back(static_cast<uint32_t>(v));
    }
    out.vertex_remap.resize(mesh.positions.size());
    for (size_t v = 0; v < out.vertex_remap.size(); ++v) {
        out.vertex_remap[v] = static_cast<uint32_t>(v);
    }
    PhaseTimer timer(Phase::kMetrics, progress, out.phase_ms);
    out.distortion = measure_distortion(mesh.positions, out.uv, mesh.triangles);
    for (const Triangle& t : mesh.triangles) {
        const Eigen::Vector2d a = out.uv[t[1]] - out.uv[t[0]], b = out.uv[t[2]] - out.uv[t[0]];
        out.utilization += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
    }
    out.chart_count = 1;
    timer.finish();
    return out;
}

}  // namespace raps
