#include "sphere/sphere_problem.h"

#include "mesh/mesh_validation.h"
#include "mesh/vertex_coloring.h"

namespace raps {

SphereProblem make_sphere_problem(const TriangleMesh& mesh, Halfedges halfedges) {
    VertexAdjacency adjacency = build_vertex_adjacency(mesh, halfedges);
    VertexTriangles stars = build_vertex_triangles(mesh);
    std::vector<std::vector<int32_t>> colors = greedy_vertex_coloring(adjacency);
    std::vector<double> mass(mesh.positions.size(), 0.0), floor(mesh.triangles.size());
    double total = 0.0;
    for (int32_t t = 0; t < mesh.triangle_count(); ++t) {
        const Triangle& v = mesh.triangles[t];
        const Eigen::Vector3d& a = mesh.positions[v[0]];
        const Eigen::Vector3d& b = mesh.positions[v[1]];
        const Eigen::Vector3d& c = mesh.positions[v[2]];
        const double area = triangle_area(mesh, t);
        const double edges = (a - b).squaredNorm() + (b - c).squaredNorm() + (c - a).squaredNorm();
        floor[t] = kShapeFloor * 2.0 * area / edges;
        for (int32_t i : v) mass[i] += area / 3.0;
        total += area;
    }
    for (double& m : mass) m /= total;
    return SphereProblem{mesh,
                         std::move(halfedges),
                         std::move(adjacency),
                         std::move(stars),
                         std::move(colors),
                         std::move(mass),
                         std::move(floor)};
}

}  // namespace raps
