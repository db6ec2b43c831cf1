#include "solver/minimum_degree.h"

#include <algorithm>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>

namespace raps {

std::vector<int32_t> minimum_degree_order(const SparsePattern& pattern) {
    // The pattern is structurally symmetric with sorted rows, so its rows already are the
    // columns of A + A^T: copied as they are, where a triplet assembly took as long as the
    // ordering itself. AMDOrdering forms A + A^T once more (a transpose and a sum of the same
    // sorted structure) before its minimum degree routine; AMD reads only the structure, so the
    // values are zeros.
    Eigen::SparseMatrix<double, Eigen::ColMajor, int> matrix(pattern.size, pattern.size);
    matrix.resizeNonZeros(static_cast<Eigen::Index>(pattern.columns.size()));
    std::copy(pattern.row_offsets.begin(), pattern.row_offsets.end(), matrix.outerIndexPtr());
    std::copy(pattern.columns.begin(), pattern.columns.end(), matrix.innerIndexPtr());
    std::fill(matrix.valuePtr(), matrix.valuePtr() + pattern.columns.size(), 0.0);
    Eigen::AMDOrdering<int>::PermutationType permutation;
    Eigen::AMDOrdering<int>()(matrix, permutation);
    // AMD returns the elimination order: entry k is the unknown eliminated k-th.
    return std::vector<int32_t>(permutation.indices().data(),
                                permutation.indices().data() + pattern.size);
}

}  // namespace raps
