#include "solver/sparse_solver.h"

#include <algorithm>
#include <string>

#include <Eigen/SparseLU>

#include "core/error.h"
#include "core/release_in_runs.h"
#include "solver/minimum_degree.h"
#include "solver/nested_dissection.h"

namespace raps {
namespace {

// Up to this size minimum degree alone orders faster than the dissection and the whole solve
// takes about as long; above it the dissection's factorization wins (docs/bench-ordering.md,
// CPU time: on face.obj, 25,809 unknowns, AMD 0.009 s vs 0.037 s to order; at 103K unknowns
// 0.10 vs 0.13 s to order, LU 0.42 vs 0.36 s; at 182K LU 1.16 vs 0.77 s, at 413K 3.4 vs 1.8 s:
// 9.6e9 flops against 4.3e9).
constexpr int32_t kMinimumDegreeOnly = 150000;

}  // namespace

std::vector<int32_t> fill_reducing_order(const SparsePattern& pattern,
                                         const std::vector<Eigen::Vector3d>& coordinates,
                                         const ProgressSpan& progress) {
    // Small and medium systems are ordered by minimum degree alone: there the dissection's
    // separators cost more time than the fill they save.
    if (pattern.size <= kMinimumDegreeOnly) return minimum_degree_order(pattern, progress);
    return nested_dissection_order(pattern, coordinates, progress);
}

SparseSolver::SparseSolver(SparsePattern pattern, const std::vector<Eigen::Vector3d>& coordinates,
                           const ProgressSpan& progress)
    : pattern_(std::move(pattern)) {
    order_ = fill_reducing_order(pattern_, coordinates, progress.part(0.0, 0.7));
    factorization_.analyze(pattern_, order_, progress.part(0.7, 1.0));
}

SparseSolver::SparseSolver(SparsePattern pattern, std::vector<int32_t> order,
                           const ProgressSpan& progress)
    : pattern_(std::move(pattern)), order_(std::move(order)) {
    factorization_.analyze(pattern_, order_, progress);
}

void SparseSolver::solve(const std::vector<double>& values, double* rhs, int rhs_count,
                         const ProgressSpan& progress, Factorization kind) {
    if (pattern_.size == 0) return;
    pivoting_values_.clear();
    // Progress: the values' places (a pass over the pattern), the factorization (by flops),
    // the triangular solves (a pass over the factor per right-hand side).
    factorization_.prepare(pattern_, kind, progress.part(0.0, 0.05));
    if (factorization_.factorize(values.data(), progress.part(0.05, 0.9))) {
        factorization_.solve(rhs, rhs_count, progress.part(0.9, 1.0));
    } else {
        pivoting_values_ = values;
        solve_with_pivoting(values, rhs, rhs_count);
    }
    check_finite(rhs, rhs_count);
}

void SparseSolver::solve_more(double* rhs, int rhs_count, const ProgressSpan& progress) const {
    if (pattern_.size == 0) return;
    if (pivoting_values_.empty()) {
        factorization_.solve(rhs, rhs_count, progress);
    } else {
        solve_with_pivoting(pivoting_values_, rhs, rhs_count);
    }
    check_finite(rhs, rhs_count);
}

void SparseSolver::check_finite(const double* rhs, int rhs_count) const {
    for (int64_t i = 0; i < static_cast<int64_t>(pattern_.size) * rhs_count; ++i) {
        if (!std::isfinite(rhs[i])) {
            throw Error(ErrorCode::kSolverFailed,
                        "the sparse system is numerically singular (non-finite solution)");
        }
    }
}

// Eigen's SparseLU pivots. It is given the matrix already permuted into the nested-dissection
// order with its natural ordering: its built-in AMD and METIS orderings are applied inverted
// (they return the elimination order in the Cholesky convention), which measured 3x the fill
// of COLAMD on face.obj instead of less.
void SparseSolver::solve_with_pivoting(const std::vector<double>& values, double* rhs,
                                       int rhs_count) const {
    const int32_t n = pattern_.size;
    std::vector<int32_t> position(n);
    for (int32_t k = 0; k < n; ++k) position[order_[k]] = k;
    std::vector<Eigen::Triplet<double, int>> entries;
    entries.reserve(values.size());
    for (int32_t row = 0; row < n; ++row) {
        for (int32_t p = pattern_.row_offsets[row]; p < pattern_.row_offsets[row + 1]; ++p) {
            entries.emplace_back(position[row], position[pattern_.columns[p]], values[p]);
        }
    }
    Eigen::SparseMatrix<double, Eigen::ColMajor, int> matrix(n, n);
    matrix.setFromTriplets(entries.begin(), entries.end());
    Eigen::SparseLU<Eigen::SparseMatrix<double, Eigen::ColMajor, int>, Eigen::NaturalOrdering<int>>
        lu;
    lu.compute(matrix);
    if (lu.info() != Eigen::Success) {
        throw Error(ErrorCode::kSolverFailed,
                    "the system is singular (" + lu.lastErrorMessage() +
                        "); weights that are not all positive, such as cotangent weights on "
                        "obtuse triangles, can cause this");
    }
    Eigen::MatrixXd b(n, rhs_count);
    for (int c = 0; c < rhs_count; ++c) {
        for (int32_t row = 0; row < n; ++row)
            b(position[row], c) = rhs[static_cast<int64_t>(c) * n + row];
    }
    const Eigen::MatrixXd x = lu.solve(b);
    for (int c = 0; c < rhs_count; ++c) {
        for (int32_t row = 0; row < n; ++row)
            rhs[static_cast<int64_t>(c) * n + row] = x(position[row], c);
    }
}

void SparseSolver::release(const ProgressSpan& progress) {
    factorization_.release(progress);
    release_in_runs(pattern_.columns, progress);
    release_in_runs(pattern_.row_offsets, progress);
    release_in_runs(order_, progress);
    release_in_runs(pivoting_values_, progress);
    pattern_.size = 0;
}

}  // namespace raps
