// Is a chart's map injective? For a disk whose triangles all keep their orientation (no flip),
// the map is injective exactly when its boundary polygon does not cross itself, so two tests
// suffice: triangle orientations, and boundary segments against each other (on a grid of cells,
// so that only nearby segments are compared).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "core/triangle_mesh.h"

namespace raps {

// Triangles whose uv area is not positive (below 1e-14 of the mean uv area).
int64_t count_flipped_or_degenerate(const TriangleMesh& mesh,
                                    const std::vector<Eigen::Vector2d>& uv,
                                    const ProgressSpan& progress = {});

// Whether the closed polygon uv[loop[0]], uv[loop[1]], ... crosses or touches itself.
bool boundary_self_intersects(const std::vector<Eigen::Vector2d>& uv,
                              const std::vector<int32_t>& loop);

}  // namespace raps
