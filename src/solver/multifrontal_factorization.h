// Sparse factorization without pivoting of structurally symmetric matrices, by the multifrontal
// method (Duff & Reid 1983; Liu 1992) with relaxed supernodes (Ashcraft & Grimes 1989): LU for
// any such matrix, or Cholesky, with half the work and storage, for symmetric positive definite
// ones (the cotangent Laplacian of the free-boundary maps). The Laplace systems of section 3 with
// positive weights are M-matrices (row diagonally dominant, irreducible, boundary rows strictly
// dominant), for which elimination without pivoting is stable in any order, so the symbolic
// analysis - ordering, elimination tree, supernodes, front structures - is done once and reused by
// every numeric factorization (the initial map and each adaptive step). Matrices that need pivoting
// are reported by factorize() returning false.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <new>
#include <vector>

#include "core/progress.h"
#include "solver/dense_kernels.h"
#include "solver/sparse_pattern.h"

namespace raps {

enum class Factorization {
    kLU,        // any values in the pattern
    kCholesky,  // symmetric positive definite values: only the lower triangle is used
};

class MultifrontalFactorization {
  public:
    // Symbolic analysis of `pattern` eliminated in `order` (order[k] = k-th unknown eliminated):
    // elimination tree, supernodes and front structures, the same for LU and Cholesky.
    void analyze(const SparsePattern& pattern, const std::vector<int32_t>& order,
                 const ProgressSpan& progress = {});

    // Where the values of the analyzed `pattern` land in the fronts, and the factor's layout, for
    // factorizations of `kind`; nothing to do when that kind is already prepared. A chart's
    // Cholesky (free-boundary map) and LU (adaptive step) share one analysis this way.
    void prepare(const SparsePattern& pattern, Factorization kind,
                 const ProgressSpan& progress = {});

    // Numeric factorization, of the kind prepared, of the values of `pattern` (in its column
    // order). Returns false when a pivot is zero or tiny against its row's original diagonal
    // (the matrix needs pivoting), or, for Cholesky, not positive.
    // `progress` receives the fraction of the work done (by flops), about every 1%.
    bool factorize(const double* values, const ProgressSpan& progress);

    // Solves A X = B in place; b holds `rhs_count` columns of size() entries each.
    void solve(double* b, int rhs_count, const ProgressSpan& progress = {}) const;

    int32_t size() const { return size_; }

    // Frees the factors, the workspaces and the analysis, giving their memory back in runs with a
    // progress call between two (core/release_in_runs.h); analyze() must run again before use.
    void release(const ProgressSpan& progress);

  private:
    struct Supernode {
        int32_t first_column;  // in elimination order; columns first .. first + columns - 1
        int32_t columns;
        int32_t rows;           // front size: the supernode's columns plus its update rows
        int64_t row_offset;     // into row_indices_: the front's rows, its columns first
        int64_t factor_offset;  // into factors_: L panel (rows x columns), then U panel (LU)
        int32_t child_begin;    // children are child_list_[child_begin .. child_end)
        int32_t child_end;
        int64_t relative_offset;  // into relative_rows_: this front's update rows in its parent
        int64_t value_begin;      // its original entries: value_source_/value_target_ ranges
        int64_t value_end;
    };

    // The steps of analyze() after the column counts: the supernodes (fundamental ones merged
    // where merged_with_next says) with their children lists; each front's rows; where each
    // child's update rows land in its parent, and the workspaces.
    void build_supernodes(const std::vector<int32_t>& super_first,
                          const std::vector<char>& merged_with_next,
                          const std::vector<int32_t>& parent, const ProgressSpan& progress);
    void build_front_rows(const SparsePattern& pattern, const std::vector<int32_t>& position,
                          const ProgressSpan& progress);
    void build_relative_rows(const ProgressSpan& progress);

    // The triangular solves of solve(), on x (size() x rhs_count, column-major, in elimination
    // order) with a most_update x rhs_count scratch buffer; work counts what they have read.
    struct SolveWork;
    void solve_forward(double* x_data, int rhs_count, double* gathered_buffer, int32_t most_update,
                       SolveWork& work) const;
    void solve_backward(double* x_data, int rhs_count, double* gathered_buffer, int32_t most_update,
                        SolveWork& work) const;

    // Work of one front's partial factorization (progress reports, factor_flops()).
    double front_flops(const Supernode& node) const;

    int32_t size_ = 0;
    bool prepared_ = false;  // for the kind cholesky_ says
    bool cholesky_ = false;
    PartialFactorization partial_factorization_ = nullptr;
    std::vector<int32_t> order_;         // elimination position -> unknown
    std::vector<Supernode> supernodes_;  // in postorder: children before parents
    std::vector<int32_t> child_list_;
    std::vector<int32_t> row_indices_;  // elimination positions
    std::vector<int32_t> relative_rows_;
    std::vector<int64_t> value_source_;     // index into the caller's values
    std::vector<int64_t> value_target_;     // position in the front, column-major
    std::vector<int32_t> diagonal_source_;  // per elimination position: index of its diagonal
    // Uninitialized and 64-byte aligned: the vectorized kernels peel differently at different
    // alignments, which changes the order of summation, so an allocation that happened to land
    // at another address mod 32 gave results differing in the last bits from run to run.
    struct AlignedDelete {
        void operator()(double* p) const { ::operator delete[](p, std::align_val_t(64)); }
    };
    using Buffer = std::unique_ptr<double[], AlignedDelete>;
    static Buffer allocate(int64_t count) {
        const size_t bytes = static_cast<size_t>(std::max<int64_t>(count, 1)) * sizeof(double);
        return Buffer(static_cast<double*>(::operator new[](bytes, std::align_val_t(64))));
    }
    Buffer factors_;  // per supernode: L panel, then U panel (LU)
    int64_t factor_capacity_ = 0;
    Buffer front_;  // workspace: the largest front
    int64_t front_capacity_ = 0;
    Buffer stack_;  // contribution blocks waiting for their parent
    int64_t stack_peak_ = 0;
    double total_flops_ = 0;
};

}  // namespace raps
