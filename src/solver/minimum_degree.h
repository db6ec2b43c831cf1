// Approximate minimum degree (Amestoy, Davis & Duff, "An approximate minimum degree ordering
// algorithm", SIAM J. Matrix Anal. Appl. 17(4), 1996), through Eigen's public AMDOrdering: the
// one minimum-degree ordering of src/solver. It orders whole systems up to fill_reducing_order's
// threshold (sparse_solver.cpp); the nested dissection of larger ones bisects its leaves instead
// (nested_dissection.h), which left less fill there than minimum degree.
#pragma once

#include <cstdint>
#include <vector>

#include "core/progress.h"
#include "solver/sparse_pattern.h"

namespace raps {

// The elimination order of a structurally symmetric pattern (sorted rows; the diagonal may be
// present or not): order[k] is the unknown eliminated k-th. `progress` hears on both sides of
// Eigen's routine, which cannot report: at 150,000 unknowns (the largest it orders) it waited
// 41 to 44 ms, the longest wait of an atlas at 5.8M triangles (docs/cancel-latency.md).
std::vector<int32_t> minimum_degree_order(const SparsePattern& pattern,
                                          const ProgressSpan& progress = {});

}  // namespace raps
