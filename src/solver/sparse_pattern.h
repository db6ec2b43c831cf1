// A square sparsity pattern in compressed rows: the columns of row i are
// columns[row_offsets[i] .. row_offsets[i + 1]), sorted ascending, diagonal included. The
// solvers here need it structurally symmetric ((i, j) present iff (j, i) present), which the
// Laplace systems of a mesh are. Values travel separately, in the order of `columns`.
#pragma once

#include <cstdint>
#include <vector>

namespace raps {

struct SparsePattern {
    int32_t size = 0;
    std::vector<int32_t> row_offsets{0};
    std::vector<int32_t> columns;

    int64_t nonzeros() const { return static_cast<int64_t>(columns.size()); }
};

}  // namespace raps
