// The spherical r-adaptive parameterization of a closed genus-0 mesh (paper section 7):
// validate -> topology -> initial map (algorithm 7.1 with the base weights) -> adaptive
// relaxation (the same with W = w e^alpha) -> optionally the octahedral unfold to uvs.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/phase_timer.h"
#include "core/progress.h"
#include "core/settings.h"
#include "core/triangle_mesh.h"
#include "sphere/octahedral_unfold.h"

namespace raps {

// Sweeps per relaxation when RAPS_PARAM_SPHERE_MAX_SWEEPS is 0. Robust: measured on the shared
// meshes (README), the adapted area distortion is no better with more (bunny 0.667 at 100,
// 0.703 at 200 and 400, where all relaxations converge; spot 0.689, 0.688, 0.696), while a
// 111K-triangle mesh keeps improving (0.90 at 100, 0.76 at 200) at twice the time. Literal:
// converging took 6,000 to 22,000 sweeps on the shared meshes (the issue: 1,500 to 24,000).
constexpr int64_t kRobustMaxSweeps = 100;
constexpr int64_t kLiteralMaxSweeps = 50000;

struct SphereMap {
    std::vector<Eigen::Vector3d> points;  // one unit vector per input vertex
    int64_t negative_weights = 0;         // directed edges whose base weight is negative
    int64_t adaptive_solves = 0;          // relaxations with adaptive weights
    int64_t relaxation_sweeps = 0;        // all sweeps, initial and adaptive
    int threads_used = 1;                 // ThreadPool::threads_used of the run's pool
    // With RAPS_SPHERE_UV_OCTAHEDRAL (octahedral_unfold.h); empty otherwise.
    OctahedralUnfold unfold;
};

// Throws Error for invalid input (OPEN_MESH, NONZERO_GENUS, ... see mesh_topology.h), or a
// cancellation.
SphereMap parameterize_sphere(const TriangleMesh& mesh, const Settings& settings,
                              const Progress& progress, PhaseTimes& times);

}  // namespace raps
