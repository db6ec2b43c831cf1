// A vertex order for memory locality: vertices sorted along a Morton (Z-order) curve through
// their 3D positions, so that vertices near each other on the surface sit near each other in
// memory. Relaxation sweeps read each vertex's ring, wherever it is stored; in input order a
// subdivided mesh keeps a triangle's new midpoints far from its corners. Measured: 500 sweeps on
// bunny.off subdivided twice (111,456 triangles) took 4.0 s in input order and 2.7 s in this
// order, on one thread.
#pragma once

#include <cstdint>
#include <vector>

#include "core/progress.h"
#include "core/triangle_mesh.h"

namespace raps {

// order[k] = the input vertex placed at position k. Deterministic (ties keep input order).
std::vector<int32_t> morton_vertex_order(const std::vector<Eigen::Vector3d>& positions,
                                         const ProgressSpan& progress = {});

// The same mesh with its vertices renumbered: vertex k of the result is vertex order[k] of
// `mesh`; triangles keep their order and orientation.
TriangleMesh reorder_vertices(const TriangleMesh& mesh, const std::vector<int32_t>& order,
                              const ProgressSpan& progress = {});

}  // namespace raps
