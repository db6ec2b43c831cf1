#include "parameterization.h"

#include <string>

#include "core/error.h"
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
    Parameterization out;
    if (settings.domain == Domain::kSphere) {
        SphereMap map = parameterize_sphere(mesh, settings, progress, out.phase_ms);
        out.negative_weights = map.negative_weights;
        out.adaptive_solves = map.adaptive_solves;
        out.relaxation_sweeps = map.relaxation_sweeps;
        identity_output(mesh, out);
        out.sphere_points = std::move(map.points);
        PhaseTimer timer(Phase::kMetrics, progress, out.phase_ms);
        out.distortion = measure_distortion(mesh.positions, SphericalMapGeometry(out.sphere_points),
                                            mesh.triangles);
        timer.finish();
        return out;
    }
    DiskMap map = parameterize_disk(mesh, settings, progress, out.phase_ms);
    out.uv = std::move(map.uv);
    out.negative_weights = map.negative_weights;
    out.adaptive_solves = map.adaptive_solves;
    identity_output(mesh, out);
    PhaseTimer timer(Phase::kMetrics, progress, out.phase_ms);
    out.distortion = measure_distortion(mesh.positions, PlanarMapGeometry(out.uv), mesh.triangles);
    timer.finish();
    return out;
}

}  // namespace raps
