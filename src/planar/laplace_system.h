// The sparse linear system of paper eq. (1) with the boundary fixed:
//   sum_j W_ij (u_i - u_j) = 0  for every interior vertex i,
// one unknown per interior vertex, boundary terms moved to the right-hand side. Both uv
// coordinates are solved with one factorization. The pattern, its fill-reducing order and the
// symbolic factorization are built once by the constructor; each solve() with new weights (the
// initial map, then every adaptive step) only refactors numerically.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/triangle_mesh.h"
#include "mesh/mesh_topology.h"
#include "solver/sparse_solver.h"

namespace raps {

// A fill-reducing elimination order of the mesh's vertex graph (order[k]: the vertex eliminated
// k-th). Systems on the same mesh can share it: restricted to their unknowns it stays a good
// order (eliminating a subgraph in the induced order fills no more than the whole graph does).
std::vector<int32_t> vertex_elimination_order(const TriangleMesh& mesh,
                                              const VertexAdjacency& adjacency,
                                              const ProgressSpan& progress = {});

class LaplaceSystem {
  public:
    // vertex_order: a vertex_elimination_order() of this mesh to restrict to the interior
    // vertices, or empty to order the system here.
    LaplaceSystem(const TriangleMesh& mesh, const VertexAdjacency& adjacency,
                  const std::vector<char>& on_boundary,
                  const std::vector<int32_t>& vertex_order = {}, const ProgressSpan& progress = {});

    // Solves with `weights` (one per adjacency slot; rows of interior vertices must have a
    // nonzero sum) for the interior entries of `uv`, keeping its boundary entries.
    // Throws Error(kSolverFailed) when the system is singular.
    void solve(const std::vector<double>& weights, std::vector<Eigen::Vector2d>& uv,
               const ProgressSpan& progress = {});

    int32_t unknown_count() const { return static_cast<int32_t>(vertex_of_unknown_.size()); }

    // For other systems on the same unknowns (the free-boundary map's Cholesky): the vertex of
    // each unknown, the entry of each adjacency slot of an unknown's row (or -1) and of each
    // diagonal, and the solver, whose ordering and symbolic analysis they then share.
    const std::vector<int32_t>& vertex_of_unknown() const { return vertex_of_unknown_; }
    const std::vector<int32_t>& value_of_slot() const { return value_of_slot_; }
    const std::vector<int32_t>& diagonal_of_unknown() const { return diagonal_of_unknown_; }
    SparseSolver& solver() { return *solver_; }

    // Frees the system's memory (the factorization's first: hundreds of megabytes at millions of
    // vertices) in runs with progress calls between them (core/release_in_runs.h), where the
    // destructor would free it in one go; the system cannot be used afterwards.
    void release(const ProgressSpan& progress);

  private:
    const VertexAdjacency& adjacency_;
    std::vector<int32_t> vertex_of_unknown_;
    std::vector<int32_t> value_of_slot_;  // per slot of an interior row: its entry, or -1
    std::vector<int32_t> diagonal_of_unknown_;
    std::unique_ptr<SparseSolver> solver_;
    std::vector<double> values_, rhs_;  // solve()'s matrix and right-hand sides, kept for the next
};

}  // namespace raps
