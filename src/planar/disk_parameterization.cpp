#include "planar/disk_parameterization.h"

#include <string>

#include "core/error.h"
#include "mesh/mesh_topology.h"
#include "mesh/mesh_validation.h"
#include "planar/adaptive_map.h"
#include "planar/convex_boundary.h"
#include "planar/laplace_system.h"
#include "weights/laplacian_weights.h"

namespace raps {
namespace {

// Negative (cotangent) weights can fold the map and carry interior vertices outside the convex
// boundary, hence outside [0,1]^2 (fuzzing found a square-boundary map reaching -1.4). The
// result promises [0,1]^2, so such a map is scaled uniformly about its bounding box back into
// the square: a similarity, which keeps the folds (counted in the statistics) and the boundary's
// shape, and leaves every map that stayed inside untouched.
void fit_into_unit_square(std::vector<Eigen::Vector2d>& uv) {
    Eigen::Vector2d low = uv.front(), high = uv.front();
    for (const Eigen::Vector2d& p : uv) {
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
    }
    if (low.minCoeff() >= 0.0 && high.maxCoeff() <= 1.0) return;
    const double scale = 1.0 / (high - low).maxCoeff();
    const Eigen::Vector2d centre = 0.5 * (low + high);
    for (Eigen::Vector2d& p : uv) {
        p = ((p - centre) * scale + Eigen::Vector2d(0.5, 0.5)).cwiseMax(0.0).cwiseMin(1.0);
    }
}

}  // namespace

DiskMap parameterize_disk(const TriangleMesh& mesh, const Settings& settings,
                          const Progress& progress, PhaseTimes& times) {
    {
        PhaseTimer timer(Phase::kValidate, progress, times);
        check_indices_in_range(mesh, timer.span(0.0, 0.2));
        check_no_repeated_vertices(mesh, timer.span(0.2, 0.4));
        check_no_isolated_vertices(mesh, timer.span(0.4, 0.6));
        check_no_zero_area_triangles(mesh, timer.span(0.6, 1.0));
        timer.finish();
    }

    PhaseTimer topology_timer(Phase::kTopology, progress, times);
    // Progress: the half-edges, the checks of a disk, the adjacency (passes over the mesh),
    // then the system's ordering and symbolic analysis (most of the phase).
    const Halfedges halfedges = build_halfedges(mesh, topology_timer.span(0.0, 0.1));
    const std::vector<int32_t> loop =
        disk_boundary_loop(mesh, halfedges, topology_timer.span(0.1, 0.15));
    DiskMap map;
    map.adjacency = std::make_unique<const VertexAdjacency>(
        build_vertex_adjacency(mesh, halfedges, topology_timer.span(0.15, 0.2)));
    const VertexAdjacency& adjacency = *map.adjacency;
    std::vector<char> on_boundary(mesh.positions.size(), 0);
    for (int32_t v : loop) on_boundary[v] = 1;
    map.system = std::make_unique<LaplaceSystem>(
        mesh, adjacency, on_boundary, std::vector<int32_t>(), topology_timer.span(0.2, 1.0));
    LaplaceSystem& system = *map.system;
    topology_timer.finish();

    map.uv.assign(mesh.positions.size(), Eigen::Vector2d(0.5, 0.5));
    std::vector<double> base_weights;
    {
        PhaseTimer timer(Phase::kInitialMap, progress, times);
        base_weights = laplacian_weights(mesh, adjacency, settings.weights, timer.span(0.0, 0.1));
        const std::vector<Eigen::Vector2d> boundary =
            convex_boundary(mesh, loop, settings.boundary);
        for (size_t i = 0; i < loop.size(); ++i) map.uv[loop[i]] = boundary[i];
        timer.span(0.1, 0.11).in_runs(static_cast<int64_t>(base_weights.size()),
                                      [&](int64_t begin, int64_t end) {
                                          for (int64_t s = begin; s < end; ++s)
                                              map.negative_weights += base_weights[s] < 0.0;
                                      });
        system.solve(base_weights, map.uv, timer.span(0.11, 1.0));
        timer.finish();
    }

    PhaseTimer adapt_timer(Phase::kAdapt, progress, times);
    map.adaptive_solves =
        adapt_map(mesh, adjacency, system, base_weights, settings, map.uv, adapt_timer.span());
    fit_into_unit_square(map.uv);
    adapt_timer.finish();
    return map;
}

}  // namespace raps
