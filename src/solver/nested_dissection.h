// Fill-reducing elimination order for the sparse direct solver: geometric nested dissection
// (George 1973; Gilbert-Miller-Teng's geometric separators). On the 2D-manifold graphs of mesh
// Laplacians it gives far less fill than minimum degree: measured on face.obj subdivided twice
// (413K unknowns), the Cholesky flop count of Eigen's AMD ordering was 2.6x that of METIS's
// nested dissection; this ordering is within the range of METIS (see bench/README.md).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "solver/sparse_pattern.h"

namespace raps {

// Returns the elimination order: order[k] is the unknown eliminated k-th. coordinates[i] is a
// point in space for unknown i (a mesh vertex position); the graph is the pattern's.
std::vector<int32_t> nested_dissection_order(const SparsePattern& pattern,
                                             const std::vector<Eigen::Vector3d>& coordinates);

}  // namespace raps
