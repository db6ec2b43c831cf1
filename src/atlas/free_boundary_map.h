// Step 4a: a free-boundary conformal map of a disk chart, the least squares conformal map
// (Lévy, Petitjean, Ray & Maillot 2002; in the form of Desbrun, Meyer & Alliez 2002 and Mullen
// et al. 2008): minimise the conformal energy E_D(u) - A(u), the Dirichlet energy (cotangent
// weights) minus the uv area, with two boundary vertices pinned. A developable chart comes out
// isometric, so charts keep their natural shape instead of being forced onto a circle.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/triangle_mesh.h"
#include "mesh/mesh_topology.h"

namespace raps {

// uv per vertex of the disk `mesh` (with its vertex adjacency) whose boundary is
// `boundary_loop` (mesh on its left), eliminating u and v of each vertex together in
// `vertex_order` (laplace_system.h's vertex_elimination_order). Throws Error(kSolverFailed) if
// the system is singular.
std::vector<Eigen::Vector2d> free_boundary_conformal_map(const TriangleMesh& mesh,
                                                         const VertexAdjacency& adjacency,
                                                         const std::vector<int32_t>& boundary_loop,
                                                         const std::vector<int32_t>& vertex_order);

}  // namespace raps
