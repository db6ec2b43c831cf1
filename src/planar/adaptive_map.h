// Paper section 6: the adaptive solves that follow an initial map, with its boundary held.
// Shared by the disk pipeline and the atlas's charts.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "core/settings.h"
#include "core/triangle_mesh.h"
#include "mesh/mesh_topology.h"
#include "planar/laplace_system.h"

namespace raps {

// Runs settings.iterations adaptive solves on `uv` (in place) and returns how many it did.
// Iteration (RAPS_PARAM_ITERATIONS > 1): with kAccumulate the weights of step k are those of
// step k-1 times e^alpha measured on map k-1, a fixed-point iteration of the equidistribution;
// with kReapply they are the base weights times e^alpha, so each step sees only the last map.
// Measured on the shared disk meshes (docs/bench-method.md, "Disk domain: accumulating against
// re-applying the monitor"), accumulating keeps lowering the distortion while re-applying goes
// up and down, never below its first solve's. `progress` gets the fraction done.
int64_t adapt_map(const TriangleMesh& mesh, const VertexAdjacency& adjacency, LaplaceSystem& system,
                  const std::vector<double>& base_weights, const Settings& settings,
                  std::vector<Eigen::Vector2d>& uv, const ProgressSpan& progress = {});

}  // namespace raps
