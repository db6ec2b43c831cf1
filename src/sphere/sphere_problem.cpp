#include "sphere/sphere_problem.h"

#include "mesh/mesh_validation.h"
#include "mesh/vertex_coloring.h"

namespace raps {

SphereProblem make_sphere_problem(const TriangleMesh& mesh, Halfedges halfedges,
                                  const ProgressSpan& progress) {
    VertexAdjacency adjacency = build_vertex_adjacency(mesh, halfedges, progress.part(0.0, 0.4));
    VertexTriangles stars = build_vertex_triangles(mesh, progress.part(0.4, 0.6));
    std::vector<std::vector<int32_t>> colors =
        greedy_vertex_coloring(adjacency, progress.part(0.6, 0.8));
    std::vector<double> mass(mesh.positions.size(), 0.0);
    double total = 0.0;
    progress.part(0.8, 1.0).in_runs(mesh.triangle_count(), [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            const Triangle& v = mesh.triangles[t];
            const double area = triangle_area(mesh, t);
            for (int32_t i : v) mass[i] += area / 3.0;
            total += area;
        }
    });
    for (double& m : mass) m /= total;
    return SphereProblem{mesh,
                         std::move(halfedges),
                         std::move(adjacency),
                         std::move(stars),
                         std::move(colors),
                         std::move(mass)};
}

}  // namespace raps
