// The planar r-adaptive parameterization of a topological disk (paper sections 3-6):
// validate -> topology -> initial map (convex boundary, base weights, one solve) -> adaptive
// solves (monitor, W = w e^alpha, one solve each).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/phase_timer.h"
#include "core/progress.h"
#include "core/settings.h"
#include "core/triangle_mesh.h"
#include "mesh/mesh_topology.h"
#include "planar/laplace_system.h"

namespace raps {

struct DiskMap {
    std::vector<Eigen::Vector2d> uv;  // one per input vertex, in [0,1]^2
    int64_t negative_weights = 0;     // directed edges whose base weight is negative
    int64_t adaptive_solves = 0;
    // The Laplace system and the adjacency it refers to, handed over so that the caller
    // releases their memory after the run's last progress call: the factors take a gigabyte at
    // 3M triangles, and giving it back measured a third of a second between two phases.
    std::unique_ptr<const VertexAdjacency> adjacency;
    std::unique_ptr<LaplaceSystem> system;
};

// Throws Error for invalid input (see the checks in mesh_validation.h and mesh_topology.h),
// a cancellation, or a singular system.
DiskMap parameterize_disk(const TriangleMesh& mesh, const Settings& settings,
                          const Progress& progress, PhaseTimes& times);

}  // namespace raps
