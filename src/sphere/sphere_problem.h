// What the sphere domain's algorithms share about one mesh, built once per run by the pipeline
// (sphere_parameterization.cpp): the vertex adjacency the weights live on, the triangles around
// each vertex (for the fold checks), a vertex colouring (for parallel Gauss-Seidel), the
// vertices' shares of the 3D area (the mass that the Moebius centring balances).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/progress.h"
#include "core/triangle_mesh.h"
#include "mesh/mesh_topology.h"

namespace raps {

struct SphereProblem {
    const TriangleMesh& mesh;
    Halfedges halfedges;
    VertexAdjacency adjacency;
    VertexTriangles stars;
    std::vector<std::vector<int32_t>> colors;
    std::vector<double> mass;  // a third of the 3D area of each incident triangle; sums to 1
};

// Builds everything above; the mesh must have passed check_closed_genus_zero.
SphereProblem make_sphere_problem(const TriangleMesh& mesh, Halfedges halfedges,
                                  const ProgressSpan& progress = {});

// The plane floor. The robust relaxation never leaves a triangle whose plane (through its three
// points) passes closer than kPlaneFloor to the centre of the sphere (it may leave one that
// already does, but not bring it closer). That distance, det[a, b, c] / |(b - a) x (c - a)|, is
// the cosine of the angular radius of the triangle's circumcircle: near 1 for a small triangle
// of any shape, 0 when the circumcircle is a great circle, negative when turned over. It is what
// the Moebius centring needs: a boost turns a triangle over exactly when it blows its
// circumcircle past a great circle (mobius_centring.h), and a small boost cannot do that to a
// circle of angular radius 72.5 degrees (0.3), however flat the triangle is.
// Why not a floor on the triangle's shape (kShapeFloor = 0.05 times its 3D shape, before issue
// 18): it held flat triangles of long limbs where they were, measured as the adaptive
// relaxation refusing a fifth of cow.off's moves in every sweep, so that the area monitor
// lowered the area distortion by 30 % (horse_quad 25 %); with this floor by 45 % and 55 %
// (docs/sphere-status.md). Without any floor (det > 0 only) the centring stalled on triangles
// parked at det = 0 (cow: the centre of mass drifted to 0.24).
constexpr double kPlaneFloor = 0.3;

// Whether triangle abc keeps the plane floor, decided without a division or a root.
inline bool above_plane_floor(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c) {
    const double det = a.dot(b.cross(c));
    return det > 0.0 && det * det >= kPlaneFloor * kPlaneFloor * (b - a).cross(c - a).squaredNorm();
}

// Whether moving one corner of a triangle from `before` to `after` (b and c staying) makes it
// no worse: neither its det nor its plane's distance from the centre decreases (compared without
// a division).
inline bool no_worse(const Eigen::Vector3d& before, const Eigen::Vector3d& after,
                     const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const double det_before = before.dot(b.cross(c)), det_after = after.dot(b.cross(c));
    const double n_before = (b - before).cross(c - before).norm();
    const double n_after = (b - after).cross(c - after).norm();
    return det_after >= det_before && det_after * n_before >= det_before * n_after;
}

}  // namespace raps
