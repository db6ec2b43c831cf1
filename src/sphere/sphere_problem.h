// What the sphere domain's algorithms share about one mesh, built once per run by the pipeline
// (sphere_parameterization.cpp): the vertex adjacency the weights live on, the triangles around
// each vertex (for the fold checks), a vertex colouring (for parallel Gauss-Seidel), the
// vertices' shares of the 3D area (the mass that the Moebius centring balances) and the shape
// of each 3D triangle (for the shape floor below).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/triangle_mesh.h"
#include "mesh/mesh_topology.h"

namespace raps {

struct SphereProblem {
    const TriangleMesh& mesh;
    Halfedges halfedges;
    VertexAdjacency adjacency;
    VertexTriangles stars;
    std::vector<std::vector<int32_t>> colors;
    std::vector<double> mass;   // a third of the 3D area of each incident triangle; sums to 1
    std::vector<double> floor;  // per triangle: the least shape() a move may leave it with
};

// Builds everything above; the mesh must have passed check_closed_genus_zero.
SphereProblem make_sphere_problem(const TriangleMesh& mesh, Halfedges halfedges);

// Shape of a triangle: det[a, b, c] / (|a - b|^2 + |b - c|^2 + |c - a|^2), for points on the
// sphere, or 2 area / (sum of squared edges) in 3D: scale-free, sqrt(3) / 6 for an equilateral
// triangle, 0 for a flat one, negative for one turned over on the sphere.
inline double shape(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const double edges = (a - b).squaredNorm() + (b - c).squaredNorm() + (c - a).squaredNorm();
    return edges > 0.0 ? a.dot(b.cross(c)) / edges : 0.0;
}

// The shape floor. The robust relaxation never makes a triangle flatter than kShapeFloor times
// its 3D shape (it may leave one that already is, but not make it worse). Without it, vertices
// that the relaxation keeps pushing towards a fold are stopped only at det = 0: measured on
// spot.obj, 35 vertices sat on triangles with det ~ 1e-8 (area ratio 1 / 37000), whose
// circumcircles are nearly great circles, so that even a small centring step turned them over
// and centring stalled. 0.05 still allows an equilateral triangle to open to 174 degrees.
constexpr double kShapeFloor = 0.05;

// Whether moving triangle `t` from shape `before` to shape `after` is allowed: it keeps its
// floor, or it gets no worse.
inline bool shape_allowed(const SphereProblem& problem, int32_t t, double before, double after) {
    return after >= problem.floor[t] || after >= before;
}

}  // namespace raps
