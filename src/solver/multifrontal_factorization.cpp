#include "solver/multifrontal_factorization.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "core/fill_in_runs.h"
#include "core/release_in_runs.h"
#include "solver/dense_kernels.h"

namespace raps {
namespace {

using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic>;
using Block = Eigen::Map<Matrix, 0, Eigen::OuterStride<>>;

}  // namespace

void MultifrontalFactorization::prepare(const SparsePattern& pattern, Factorization kind,
                                        const ProgressSpan& progress) {
    if (prepared_ && cholesky_ == (kind == Factorization::kCholesky)) return;
    prepared_ = true;
    cholesky_ = kind == Factorization::kCholesky;
    partial_factorization_ = cholesky_ ? fastest_partial_cholesky() : fastest_partial_lu();
    const int32_t n = size_;
    int64_t factor_size = 0, lu_size = 0;
    total_flops_ = 0;
    for (Supernode& node : supernodes_) {
        node.factor_offset = factor_size;
        const int64_t m = node.rows, k = node.columns;
        factor_size += cholesky_ ? m * k : m * k + k * (m - k);
        lu_size += m * k + k * (m - k);
        total_flops_ += front_flops(node);
    }
    std::vector<int32_t> position(n), local(n, -1);
    for (int32_t k = 0; k < n; ++k) position[order_[k]] = k;
    // Original entries: A(i, j) goes to the front of the supernode owning column min(i, j), at
    // (local row of i, local column of j); max(i, j) is in that front because L(max, min) != 0.
    // From the rows of the supernode's columns we see the entries (j, other) with other at or
    // after its first column, and take the transposed entry (other, j) when other lies beyond.
    // transposed[p] is the index of the entry mirroring entry p; rows are sorted, so visiting
    // rows in order meets each row's entries in order. (Cholesky places no mirrors.)
    std::vector<int64_t> transposed;
    if (!cholesky_) {
        assign_in_runs(transposed, pattern.nonzeros(), int64_t(0), progress.part(0.0, 0.1));
        std::vector<int64_t> cursor(pattern.row_offsets.begin(), pattern.row_offsets.end() - 1);
        for (int32_t row = 0; row < n; ++row) {
            progress.at(row, n, 0.1, 0.3);
            for (int32_t p = pattern.row_offsets[row]; p < pattern.row_offsets[row + 1]; ++p) {
                transposed[p] = cursor[pattern.columns[p]]++;
            }
        }
    }
    // Every entry of A lands exactly once: within a supernode from its own row, across
    // supernodes from the earlier row as itself and its mirror (the later row skips both).
    // Cholesky keeps only the lower triangle: each row j gives its entries (other >= j) at
    // (other, j), and the upper ones are never placed.
    assign_in_runs(value_source_, pattern.nonzeros(), int64_t(0), progress.part(0.3, 0.4));
    assign_in_runs(value_target_, pattern.nonzeros(), int64_t(0), progress.part(0.4, 0.5));
    diagonal_source_.assign(n, -1);
    int64_t next_value = 0, next_report = kItemsPerReport;
    for (Supernode& node : supernodes_) {
        const int32_t f = node.first_column, l = f + node.columns - 1;
        if (f >= next_report) {
            next_report = f + kItemsPerReport;
            progress.report(0.5 + 0.5 * static_cast<double>(f) / n);
        }
        for (int32_t r = 0; r < node.rows; ++r) local[row_indices_[node.row_offset + r]] = r;
        node.value_begin = next_value;
        for (int32_t j = f; j <= l; ++j) {
            const int32_t row = order_[j];
            for (int32_t p = pattern.row_offsets[row]; p < pattern.row_offsets[row + 1]; ++p) {
                const int32_t other = position[pattern.columns[p]];
                if (other < f) continue;
                if (other == j) diagonal_source_[j] = p;
                if (cholesky_) {
                    if (other < j) continue;
                    value_source_[next_value] = p;
                    value_target_[next_value++] =
                        local[other] + static_cast<int64_t>(local[j]) * node.rows;
                    continue;
                }
                value_source_[next_value] = p;
                value_target_[next_value++] =
                    local[j] + static_cast<int64_t>(local[other]) * node.rows;
                if (other <= l) continue;
                value_source_[next_value] = transposed[p];
                value_target_[next_value++] =
                    local[other] + static_cast<int64_t>(local[j]) * node.rows;
            }
        }
        node.value_end = next_value;
    }
    value_source_.resize(next_value);  // Cholesky placed only about half of the entries
    value_target_.resize(next_value);

    // Left uninitialized: factorize() writes every entry before reading it, and zero-filling
    // hundreds of megabytes measured 0.19 s of a 0.5 s analysis at 413K unknowns. Kept when
    // large enough for the new kind.
    if (factor_size > factor_capacity_) {
        factors_ = allocate(lu_size);
        factor_capacity_ = lu_size;
    }
}

double MultifrontalFactorization::front_flops(const Supernode& node) const {
    // The partial LU: 2 k^2 (m - k) for the panels + 2 k (m - k)^2 for the update, about k m^2;
    // about half that for Cholesky.
    const double m = node.rows, k = node.columns;
    return k * m * m * (cholesky_ ? 0.5 : 1.0);
}

namespace {

// Progress inside one large front: the kernel's multiply-adds so far, counted toward the front's
// share of the factorization's work (its estimate, which they may exceed a little).
struct FrontProgress {
    const ProgressSpan* span;
    double before, front, total, inside;
};

void front_work_done(void* context, double multiply_adds) {
    FrontProgress& p = *static_cast<FrontProgress*>(context);
    p.inside += multiply_adds;
    p.span->report((p.before + std::min(p.inside, p.front)) / p.total);
}

// Fronts with more work than this report from inside the kernel (a few milliseconds of work).
constexpr double kFrontReportFlops = 1e7;
constexpr int32_t kFrontsPerReport = 1024;
// 2 MB of entries: the first factorization touches the workspaces' fresh pages, 512 page faults
// per report (16 MB took 44 ms of CPU between two calls at 3.3M triangles in a loaded VM).
constexpr int64_t kEntriesPerReport = int64_t(1) << 18;

}  // namespace

bool MultifrontalFactorization::factorize(const double* values, const ProgressSpan& progress) {
    // Each pivot's scale: its row's original diagonal (a pass over the unknowns, in runs).
    std::vector<double> pivot_scale;
    pivot_scale.reserve(size_);
    progress.part(0.0, 0.01).in_runs(size_, [&](int64_t begin, int64_t end) {
        for (int64_t j = begin; j < end; ++j) {
            const double scale =
                diagonal_source_[j] >= 0 ? std::abs(values[diagonal_source_[j]]) : 0.0;
            pivot_scale.push_back(scale > 0.0 ? scale : 1e-300);
        }
    });
    const ProgressSpan work = progress.part(0.01, 1.0);  // by flops
    int64_t stack_top = 0;
    std::vector<int64_t> block_starts;
    double flops_done = 0, next_report = std::min(0.01 * total_flops_, kFrontReportFlops);
    int32_t fronts_since_report = 0;
    // The largest fronts' clearing, assembly and copies move hundreds of megabytes at millions
    // of unknowns: every kEntriesPerReport entries moved, the fraction reached is reported again.
    int64_t entries_moved = 0;
    auto moved = [&](int64_t entries) {
        entries_moved += entries;
        if (entries_moved < kEntriesPerReport) return;
        entries_moved = 0;
        work.report(flops_done / total_flops_);
    };
    for (const Supernode& node : supernodes_) {
        const int32_t m = node.rows, k = node.columns;
        double* front = front_.get();
        // Cholesky reads and writes only the lower triangle: the rest is never cleared.
        for (int32_t c = 0; c < m; ++c) {
            moved(m);
            const int64_t begin = static_cast<int64_t>(c) * m;
            std::fill(front + begin + (cholesky_ ? c : 0), front + begin + m, 0.0);
        }
        for (int64_t e = node.value_begin; e < node.value_end; ++e) {
            front[value_target_[e]] += values[value_source_[e]];
        }
        // Children's contribution blocks sit on top of the stack in child order.
        const int32_t child_total = node.child_end - node.child_begin;
        for (int32_t c = 0; c < child_total; ++c) {
            const Supernode& child = supernodes_[child_list_[node.child_begin + c]];
            const int64_t start = block_starts[block_starts.size() - child_total + c];
            const int32_t update = child.rows - child.columns;
            const int32_t* relative = relative_rows_.data() + child.relative_offset;
            const double* block = stack_.get() + start;
            // Update rows are sorted, so a lower entry of the block lands in the lower triangle.
            for (int32_t jj = 0; jj < update; ++jj) {
                moved(update);
                double* target = front + static_cast<int64_t>(relative[jj]) * m;
                const double* source = block + static_cast<int64_t>(jj) * update;
                for (int32_t ii = cholesky_ ? jj : 0; ii < update; ++ii)
                    target[relative[ii]] += source[ii];
            }
        }
        if (child_total > 0) {
            stack_top = block_starts[block_starts.size() - child_total];
            block_starts.resize(block_starts.size() - child_total);
        }
        FrontProgress inside{&work, flops_done, front_flops(node), total_flops_, 0.0};
        const KernelProgress kernel_progress{front_work_done, &inside};
        const bool report_inside = work.active() && inside.front > kFrontReportFlops;
        if (!partial_factorization_(front, m, k, pivot_scale.data() + node.first_column,
                                    report_inside ? &kernel_progress : nullptr))
            return false;
        const int32_t skip_upper = cholesky_ ? 1 : 0;  // Cholesky: copy from the diagonal down
        double* lower = factors_.get() + node.factor_offset;
        for (int32_t c = 0; c < k; ++c) {
            moved(m);
            const int64_t begin = static_cast<int64_t>(c) * m + c * skip_upper;
            std::copy(front + begin, front + static_cast<int64_t>(c + 1) * m, lower + begin);
        }
        if (!cholesky_) {
            double* upper = lower + static_cast<int64_t>(m) * k;  // k x (m - k), column-major
            for (int32_t c = k; c < m; ++c) {
                moved(k);
                std::copy(front + static_cast<int64_t>(c) * m,
                          front + static_cast<int64_t>(c) * m + k,
                          upper + static_cast<int64_t>(c - k) * k);
            }
        }
        const int32_t update = m - k;
        if (update > 0) {
            block_starts.push_back(stack_top);
            double* block = stack_.get() + stack_top;
            for (int32_t c = 0; c < update; ++c) {
                moved(update);
                const int32_t from = c * skip_upper;
                const double* source = front + static_cast<int64_t>(k + c) * m + k;
                std::copy(source + from, source + update,
                          block + static_cast<int64_t>(c) * update + from);
            }
            stack_top += static_cast<int64_t>(update) * update;
        }
        flops_done += front_flops(node);
        // Every 1% of the work, or every kFrontReportFlops of it (small fronts cost more time
        // per flop), or every kFrontsPerReport fronts, whichever comes first.
        if (work.active() &&
            (flops_done >= next_report || ++fronts_since_report >= kFrontsPerReport)) {
            work.report(flops_done / total_flops_);
            next_report = flops_done + std::min(0.01 * total_flops_, kFrontReportFlops);
            fronts_since_report = 0;
        }
    }
    return true;
}

namespace {

// Progress of the triangular solves by the factor's entries read (a supernode's panel is
// rows x columns): columns alone were a poor measure, 8,192 of a separator's columns being
// tens of milliseconds of work at millions of triangles and as many leaf columns almost none.
constexpr double kEntriesPerSolveReport = 1 << 20;

}  // namespace

// Counts the panels' entries a triangular solve has read; a report every kEntriesPerSolveReport.
struct MultifrontalFactorization::SolveWork {
    const ProgressSpan& progress;
    double total, done = 0, next = kEntriesPerSolveReport;
    void add(const Supernode& node) {
        done += static_cast<double>(node.rows) * node.columns;
        if (done < next || !progress.active()) return;
        next = done + kEntriesPerSolveReport;
        progress.report(done / total);
    }
};

void MultifrontalFactorization::solve(double* b, int rhs_count,
                                      const ProgressSpan& progress) const {
    const int32_t n = size_;
    // Progress: the permutations (a pass over the right-hand sides each), then the forward and
    // the backward solve (a pass over the factor each).
    double entries = 0;
    int32_t most_update = 0;
    for (const Supernode& node : supernodes_) {
        entries += static_cast<double>(node.rows) * node.columns;
        most_update = std::max(most_update, node.rows - node.columns);
    }
    // Permute into elimination order (and back at the end), a column at a time.
    Matrix x(n, rhs_count);
    auto permute = [&](bool into, const ProgressSpan& span) {
        for (int c = 0; c < rhs_count; ++c) {
            double* xc = x.data() + static_cast<int64_t>(c) * n;
            double* bc = b + static_cast<int64_t>(c) * n;
            span.part(static_cast<double>(c) / rhs_count, static_cast<double>(c + 1) / rhs_count)
                .in_runs(n, [&](int64_t begin, int64_t end) {
                    for (int64_t k = begin; k < end; ++k) {
                        if (into) {
                            xc[k] = bc[order_[k]];
                        } else {
                            bc[order_[k]] = xc[k];
                        }
                    }
                });
        }
    };
    permute(true, progress.part(0.0, 0.05));
    // One buffer of the largest update size, used through blocks and never resized: Eigen frees
    // a matrix's storage before allocating the new one, so a resize that runs out of memory
    // leaves the matrix pointing at freed memory, freed again when it is destroyed (found by
    // failing each allocation in turn: tests/test_alloc_failures.c).
    Matrix gathered_buffer(most_update, rhs_count);
    const ProgressSpan forward_span = progress.part(0.05, 0.5);
    SolveWork forward_work{forward_span, entries};
    solve_forward(x.data(), rhs_count, gathered_buffer.data(), most_update, forward_work);
    const ProgressSpan backward_span = progress.part(0.5, 0.95);
    SolveWork backward_work{backward_span, entries};
    solve_backward(x.data(), rhs_count, gathered_buffer.data(), most_update, backward_work);
    permute(false, progress.part(0.95, 1.0));
}

// Forward: L y = b, children before parents. L is unit lower for LU; Cholesky's holds its
// diagonal. gathered_buffer: most_update x rhs columns of scratch.
void MultifrontalFactorization::solve_forward(double* x_data, int rhs_count,
                                              double* gathered_buffer, int32_t most_update,
                                              SolveWork& work) const {
    const int32_t n = size_;
    Eigen::Map<Matrix> x(x_data, n, rhs_count);
    // Supernodes this small are solved with plain loops: Eigen's triangular solves and
    // products cost more in set-up than in arithmetic at these sizes (as in partial_lu).
    constexpr int32_t kSmallFront = 64;
    for (const Supernode& node : supernodes_) {
        const int32_t m = node.rows, k = node.columns, update = m - k;
        work.add(node);
        const double* lower = factors_.get() + node.factor_offset;
        if (m <= kSmallFront) {
            const int32_t* rows = row_indices_.data() + node.row_offset + k;
            double* gathered = gathered_buffer;
            for (int c = 0; c < rhs_count; ++c) {
                double* xc = x.data() + static_cast<int64_t>(c) * n;
                double* xs = xc + node.first_column;
                std::fill(gathered, gathered + update, 0.0);
                for (int32_t j = 0; j < k; ++j) {
                    const double* column = lower + static_cast<int64_t>(j) * m;
                    if (cholesky_) xs[j] /= column[j];
                    const double v = xs[j];
                    for (int32_t i = j + 1; i < k; ++i) xs[i] -= column[i] * v;
                    for (int32_t r = 0; r < update; ++r) gathered[r] += column[k + r] * v;
                }
                for (int32_t r = 0; r < update; ++r) xc[rows[r]] -= gathered[r];
            }
            continue;
        }
        Eigen::Map<const Matrix> panel(lower, m, k);
        auto xs = x.middleRows(node.first_column, k);
        if (cholesky_) {
            panel.topRows(k).triangularView<Eigen::Lower>().solveInPlace(xs);
        } else {
            panel.topRows(k).triangularView<Eigen::UnitLower>().solveInPlace(xs);
        }
        if (update == 0) continue;
        Eigen::Map<Matrix, 0, Eigen::OuterStride<>> gathered(gathered_buffer, update, rhs_count,
                                                             Eigen::OuterStride<>(most_update));
        gathered.noalias() = panel.bottomRows(update) * xs;
        const int32_t* rows = row_indices_.data() + node.row_offset + k;
        for (int c = 0; c < rhs_count; ++c) {
            for (int32_t r = 0; r < update; ++r) x(rows[r], c) -= gathered(r, c);
        }
    }
}

// Backward: U x = y (LU) or L^T x = y (Cholesky), parents before children.
void MultifrontalFactorization::solve_backward(double* x_data, int rhs_count,
                                               double* gathered_buffer, int32_t most_update,
                                               SolveWork& work) const {
    const int32_t n = size_;
    Eigen::Map<Matrix> x(x_data, n, rhs_count);
    constexpr int32_t kSmallFront = 64;
    for (auto it = supernodes_.rbegin(); it != supernodes_.rend(); ++it) {
        const Supernode& node = *it;
        const int32_t m = node.rows, k = node.columns, update = m - k;
        work.add(node);
        const double* lower = factors_.get() + node.factor_offset;
        const int32_t* rows = row_indices_.data() + node.row_offset + k;
        if (m <= kSmallFront && cholesky_) {
            for (int c = 0; c < rhs_count; ++c) {
                double* xc = x.data() + static_cast<int64_t>(c) * n;
                double* xs = xc + node.first_column;
                for (int32_t j = k - 1; j >= 0; --j) {
                    const double* column = lower + static_cast<int64_t>(j) * m;
                    double sum = xs[j];
                    for (int32_t r = 0; r < update; ++r) sum -= column[k + r] * xc[rows[r]];
                    for (int32_t i = j + 1; i < k; ++i) sum -= column[i] * xs[i];
                    xs[j] = sum / column[j];
                }
            }
            continue;
        }
        if (m <= kSmallFront) {
            const double* upper = lower + static_cast<int64_t>(m) * k;  // k x update
            for (int c = 0; c < rhs_count; ++c) {
                double* xc = x.data() + static_cast<int64_t>(c) * n;
                double* xs = xc + node.first_column;
                for (int32_t r = 0; r < update; ++r) {
                    const double v = xc[rows[r]];
                    const double* column = upper + static_cast<int64_t>(r) * k;
                    for (int32_t i = 0; i < k; ++i) xs[i] -= column[i] * v;
                }
                for (int32_t j = k - 1; j >= 0; --j) {
                    const double* column = lower + static_cast<int64_t>(j) * m;
                    xs[j] /= column[j];
                    const double v = xs[j];
                    for (int32_t i = 0; i < j; ++i) xs[i] -= column[i] * v;
                }
            }
            continue;
        }
        Eigen::Map<const Matrix> panel(lower, m, k);
        auto xs = x.middleRows(node.first_column, k);
        if (update > 0) {
            Eigen::Map<Matrix, 0, Eigen::OuterStride<>> gathered(gathered_buffer, update, rhs_count,
                                                                 Eigen::OuterStride<>(most_update));
            for (int c = 0; c < rhs_count; ++c) {
                for (int32_t r = 0; r < update; ++r) gathered(r, c) = x(rows[r], c);
            }
            if (cholesky_) {
                xs.noalias() -= panel.bottomRows(update).transpose() * gathered;
            } else {
                Eigen::Map<const Matrix> upper(lower + static_cast<int64_t>(m) * k, k, update);
                xs.noalias() -= upper * gathered;
            }
        }
        if (cholesky_) {
            panel.topRows(k).transpose().triangularView<Eigen::Upper>().solveInPlace(xs);
        } else {
            panel.topRows(k).triangularView<Eigen::Upper>().solveInPlace(xs);
        }
    }
}

void MultifrontalFactorization::release(const ProgressSpan& progress) {
    release_pages_in_runs(factors_.get(), static_cast<size_t>(factor_capacity_) * sizeof(double),
                          progress);
    factors_.reset();
    factor_capacity_ = 0;
    release_pages_in_runs(front_.get(), static_cast<size_t>(front_capacity_) * sizeof(double),
                          progress);
    front_.reset();
    front_capacity_ = 0;
    release_pages_in_runs(stack_.get(), static_cast<size_t>(stack_peak_) * sizeof(double),
                          progress);
    stack_.reset();
    stack_peak_ = 0;
    release_in_runs(order_, progress);
    release_in_runs(supernodes_, progress);
    release_in_runs(child_list_, progress);
    release_in_runs(row_indices_, progress);
    release_in_runs(relative_rows_, progress);
    release_in_runs(value_source_, progress);
    release_in_runs(value_target_, progress);
    release_in_runs(diagonal_source_, progress);
    prepared_ = false;
    size_ = 0;
}

}  // namespace raps
