// The promise the robust sphere method keeps (issue 18): a map that comes back with RAPS_OK is
// a bijection of the unit sphere. The maps are bijective in exact arithmetic (a Tutte embedding
// lifted by a conformal bijection, then moves and Moebius steps that refuse to turn a triangle
// over), but not in floating point: a conformal map squeezes a long limb by about
// e^-(length / radius), and a capsule of aspect 50 has triangles of 1e-22 of the sphere, far
// below the 1e-16 that doubles resolve on it. Measured on such inputs (docs/sphere-status.md):
// up to thousands of triangles with det[a, b, c] <= 0, which the old pipeline returned as a
// success. The check is the exact orientation test of the statistics and of uvmetrics.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "core/triangle_mesh.h"

namespace raps {

struct FoldCount {
    int64_t folded = 0;      // triangles with det[a, b, c] <= 0 (or not finite)
    int64_t first = -1;      // the lowest such triangle index, -1 if none
    int64_t off_sphere = 0;  // points with | |u| - 1 | > kUnitTolerance (or not finite)
};

constexpr double kUnitTolerance = 1e-12;

FoldCount count_folds(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& points,
                      const ProgressSpan& progress = {});

// Throws Error(kSolverFailed) naming the folded triangles of `mesh` (the input mesh, `points` in
// its vertex order) unless the map is fold-free and on the unit sphere.
void require_bijective_sphere_map(const TriangleMesh& mesh,
                                  const std::vector<Eigen::Vector3d>& points,
                                  const ProgressSpan& progress = {});

}  // namespace raps
