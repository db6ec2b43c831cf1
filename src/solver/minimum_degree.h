// Approximate minimum degree (Amestoy, Davis & Duff, "An approximate minimum degree ordering
// algorithm", SIAM J. Matrix Anal. Appl. 17(4), 1996), through Eigen's public AMDOrdering: the
// one minimum-degree ordering of src/solver. It orders whole systems up to fill_reducing_order's
// threshold (sparse_solver.cpp); the nested dissection of larger ones bisects its leaves instead
// (nested_dissection.h), which left less fill there than minimum degree.
#pragma once

#include <cstdint>
#include <vector>

#include "solver/sparse_pattern.h"

namespace raps {

// The elimination order of a structurally symmetric pattern (sorted rows; the diagonal may be
// present or not): order[k] is the unknown eliminated k-th.
std::vector<int32_t> minimum_degree_order(const SparsePattern& pattern);

}  // namespace raps
