#include "solver/minimum_degree.h"

#include <algorithm>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

namespace raps {

std::vector<int32_t> minimum_degree_order(const SparsePattern& pattern,
                                          const ProgressSpan& progress) {
    // Eigen's general overload forms A + A^T (a transpose and a sum) before its minimum degree
    // routine; the self-adjoint one expands the lower triangle given here: the same structure,
    // so the same order and bits. AMD reads only the structure, so the values are zero bytes
    // (as doubles, the copies of them took a fifth longer on a grid). At 5.8M triangles the
    // atlas's longest wait, this call at 150,000 unknowns, went from 49-51 to 41-44 ms. The
    // sorted rows of a symmetric pattern, cut at the diagonal, are its lower triangle's columns.
    const size_t n = static_cast<size_t>(pattern.size);
    Eigen::SparseMatrix<signed char, Eigen::ColMajor, int> lower(pattern.size, pattern.size);
    // (nonzeros + n) / 2 entries: exact with the diagonal present, a bound without it.
    lower.resizeNonZeros(static_cast<Eigen::Index>((pattern.columns.size() + n) / 2));
    int count = 0;
    for (size_t column = 0; column < n; ++column) {
        lower.outerIndexPtr()[column] = count;
        const auto begin = pattern.columns.begin() + pattern.row_offsets[column];
        const auto end = pattern.columns.begin() + pattern.row_offsets[column + 1];
        const auto first = std::lower_bound(begin, end, static_cast<int32_t>(column));
        count = static_cast<int>(std::copy(first, end, lower.innerIndexPtr() + count) -
                                 lower.innerIndexPtr());
    }
    lower.outerIndexPtr()[n] = count;
    lower.resizeNonZeros(count);
    std::fill(lower.valuePtr(), lower.valuePtr() + count, static_cast<signed char>(0));
    // The routine below cannot report; a call on each side keeps the copy out of its wait.
    if (progress.active()) progress.report(0.2);
    Eigen::AMDOrdering<int>::PermutationType permutation;
    Eigen::AMDOrdering<int>()(lower.selfadjointView<Eigen::Lower>(), permutation);
    if (progress.active()) progress.report(0.9);
    // AMD returns the elimination order: entry k is the unknown eliminated k-th.
    return std::vector<int32_t>(permutation.indices().data(),
                                permutation.indices().data() + pattern.size);
}

}  // namespace raps
