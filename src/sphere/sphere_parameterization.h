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

// Sweeps per relaxation when RAPS_PARAM_SPHERE_MAX_SWEEPS is 0. Robust: 100 for the initial
// relaxation and 200 for each adaptive one, with 2 continuation steps
// (RAPS_PARAM_SPHERE_ALPHA_STEPS): the same 500 sweeps as 4 steps of 100, but each step nearer
// its fixed point, which lowered the adapted area distortion on 8 of 9 meshes measured (cow
// 1.553 -> 1.468, spot subdivided to 94K triangles 1.059 -> 0.975, cheburashka 0.892 -> 0.907
// the exception; docs/sphere-status.md). Before issue 18, with 4 steps of 100, more sweeps were
// not uniformly better: docs/bench-method.md ("Sphere domain: most sweeps per relaxation") has the adapted area distortion at 100, 200 and 400 on the shared meshes: lower
// with more on some (cheburashka 0.895, 0.899, 0.847; fandisk 0.223, 0.221, 0.221), higher on
// others (bunny 0.667, 0.703, 0.703; decimated-max 0.217, 0.226, 0.222). Literal: all
// relaxations of one run together took 6,372 to 22,392 sweeps on the shared meshes, each
// relaxation converging well before 50,000 (docs/bench-method.md, "algorithm 7.1 as written").
constexpr int64_t kRobustMaxSweeps = 100;
constexpr int64_t kRobustAdaptiveMaxSweeps = 200;
constexpr int64_t kLiteralMaxSweeps = 50000;

// Robust: how many times per adaptive iteration a continuation step may be taken back and
// halved (sphere_parameterization.cpp).
constexpr int kStepRetries = 3;

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
