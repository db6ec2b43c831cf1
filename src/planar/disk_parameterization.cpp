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

DiskMap parameterize_disk(const TriangleMesh& mesh, const Settings& settings,
                          const Progress& progress, PhaseTimes& times) {
    {
        PhaseTimer timer(Phase::kValidate, progress, times);
        check_indices_in_range(mesh);
        check_no_repeated_vertices(mesh);
        check_no_isolated_vertices(mesh);
        check_no_zero_area_triangles(mesh);
        timer.finish();
    }

    PhaseTimer topology_timer(Phase::kTopology, progress, times);
    const Halfedges halfedges = build_halfedges(mesh);
    const std::vector<int32_t> loop = disk_boundary_loop(mesh, halfedges);
    const VertexAdjacency adjacency = build_vertex_adjacency(mesh, halfedges);
    std::vector<char> on_boundary(mesh.positions.size(), 0);
    for (int32_t v : loop) on_boundary[v] = 1;
    LaplaceSystem system(mesh, adjacency, on_boundary);
    topology_timer.finish();

    DiskMap map;
    map.uv.assign(mesh.positions.size(), Eigen::Vector2d(0.5, 0.5));
    const std::vector<double> base_weights = laplacian_weights(mesh, adjacency, settings.weights);
    {
        PhaseTimer timer(Phase::kInitialMap, progress, times);
        const std::vector<Eigen::Vector2d> boundary =
            convex_boundary(mesh, loop, settings.boundary);
        for (size_t i = 0; i < loop.size(); ++i) map.uv[loop[i]] = boundary[i];
        for (double w : base_weights) map.negative_weights += w < 0.0;
        system.solve(base_weights, map.uv,
                     [&](double fraction) { progress.report(Phase::kInitialMap, fraction); });
        timer.finish();
    }

    PhaseTimer adapt_timer(Phase::kAdapt, progress, times);
    map.adaptive_solves =
        adapt_map(mesh, adjacency, system, base_weights, settings, map.uv,
                  [&](double fraction) { progress.report(Phase::kAdapt, fraction); });
    adapt_timer.finish();
    return map;
}

}  // namespace raps
