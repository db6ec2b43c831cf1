// Step 1 of the atlas pipeline: vertices that share a position (within a tolerance) become one,
// so that seams already present in the input (split normals, old uvs) do not split charts.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"

namespace raps {

// For every input vertex, the index of its representative: the smallest input index among the
// vertices within `tolerance` of it (linked transitively). tolerance 0 welds exact equals only.
std::vector<int32_t> weld_vertices(const std::vector<Eigen::Vector3d>& positions, double tolerance,
                                   const ProgressSpan& progress = {});

}  // namespace raps
