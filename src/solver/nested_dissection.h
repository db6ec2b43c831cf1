// Fill-reducing elimination order for the sparse direct solver: multilevel nested dissection
// (George 1973) with flow-based separators. A hierarchy of coarser graphs is built by heavy-edge
// matching (Karypis & Kumar 1998). The graph is bisected recursively on a coarse level (1/8 of
// the vertices); each cut is inertial flow (Schild & Sommer 2015) - the minimum vertex cut
// between the first and last 30% of the part along four directions - on a still coarser level,
// moved to the minimum vertex cut of a band around it on every level back down. The tree is then
// projected to the finer levels, every separator refined the same way on every second level, and
// the leaves (n/200 vertices, 256 to 2048) are ordered by recursive coordinate bisection down
// to pieces of eight vertices (no minimum degree: the one minimum-degree ordering of src/solver,
// minimum_degree.h, orders whole systems; on leaf pieces it left more fill than bisection, see
// docs/bench-solver.md). Unlike straight geometric cuts, flow cuts curve around the dense regions
// of a mesh with varying resolution. Measured (Cholesky flops = sum of squared column counts of
// L; ordering time of one call on one core): face.obj subdivided twice (413K unknowns) 4.3e9 in
// 0.38 s, against 7.6e9 in 0.59 s for the geometric bisection this replaced, 9.6e9 for AMD and
// 3.6e9 for METIS's nested dissection; face.obj 5.7e7 (was 9.8e7; AMD 7.7e7, METIS 4.7e7); a
// 400x400 grid 1.22e9 (was 1.43e9; METIS 1.19e9). raps-bench-ordering prints the fill, flops and
// times of this order and of AMD on the benchmark systems (docs/bench-ordering.md).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "solver/sparse_pattern.h"

namespace raps {

// Returns the elimination order: order[k] is the unknown eliminated k-th. coordinates[i] is a
// point in space for unknown i (a mesh vertex position); the graph is the pattern's.
std::vector<int32_t> nested_dissection_order(const SparsePattern& pattern,
                                             const std::vector<Eigen::Vector3d>& coordinates,
                                             const ProgressSpan& progress = {});

}  // namespace raps
