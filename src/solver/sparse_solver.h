// A square sparse system with a fixed, structurally symmetric pattern, solved many times with
// new values: ordering and symbolic analysis once (nested dissection + multifrontal LU, or
// Cholesky for symmetric positive definite systems, without pivoting), then for each new set of
// values a numeric factorization and solves for several right-hand sides. Values that need
// pivoting (a tiny pivot) fall back to Eigen's SparseLU.
#pragma once

#include <functional>
#include <vector>

#include <Eigen/Core>

#include "solver/multifrontal_factorization.h"
#include "solver/sparse_pattern.h"

namespace raps {

// A fill-reducing elimination order of a structurally symmetric pattern (order[k]: the unknown
// eliminated k-th); coordinates[i] is a point in space for unknown i.
std::vector<int32_t> fill_reducing_order(const SparsePattern& pattern,
                                         const std::vector<Eigen::Vector3d>& coordinates,
                                         const ProgressSpan& progress = {});

class SparseSolver {
  public:
    // coordinates[i]: a point in space for unknown i, for the fill-reducing order.
    SparseSolver(SparsePattern pattern, const std::vector<Eigen::Vector3d>& coordinates,
                 const ProgressSpan& progress = {});
    // With an elimination order the caller already has (order[k]: the unknown eliminated k-th).
    SparseSolver(SparsePattern pattern, std::vector<int32_t> order,
                 const ProgressSpan& progress = {});

    // Solves A X = B in place: `values` in the pattern's order, `rhs` holds rhs_count columns of
    // size() entries. Throws Error(kSolverFailed) for a singular system. kCholesky promises
    // values that are symmetric positive definite (a system that turns out not to be is still
    // solved, by the pivoting fallback); solves of either kind share the symbolic analysis.
    void solve(const std::vector<double>& values, double* rhs, int rhs_count,
               const ProgressSpan& progress, Factorization kind = Factorization::kLU);

    // Solves A X = B in place for more right-hand sides, with the values of the last solve()
    // (not factored again).
    void solve_more(double* rhs, int rhs_count, const ProgressSpan& progress = {}) const;

    // Frees the pattern, the order and the factorization in runs with progress calls between
    // them (core/release_in_runs.h); the solver cannot be used afterwards.
    void release(const ProgressSpan& progress);

    const SparsePattern& pattern() const { return pattern_; }
    int32_t size() const { return pattern_.size; }

  private:
    void solve_with_pivoting(const std::vector<double>& values, double* rhs, int rhs_count) const;
    void check_finite(const double* rhs, int rhs_count) const;

    SparsePattern pattern_;
    std::vector<int32_t> order_;
    MultifrontalFactorization factorization_;
    std::vector<double> pivoting_values_;  // the last values, when they needed pivoting
};

}  // namespace raps
