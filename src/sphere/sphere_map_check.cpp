#include "sphere/sphere_map_check.h"

#include <cmath>
#include <string>

#include "core/error.h"
#include "sphere/spherical_geometry.h"

namespace raps {

FoldCount count_folds(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& points,
                      const ProgressSpan& progress) {
    FoldCount count;
    progress.in_runs(mesh.triangle_count(), [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            const Triangle& v = mesh.triangles[t];
            if (orientation(points[v[0]], points[v[1]], points[v[2]]) > 0.0) continue;
            if (count.first < 0) count.first = static_cast<int64_t>(t);
            ++count.folded;
        }
    });
    for (const Eigen::Vector3d& u : points) {
        count.off_sphere += !(std::abs(u.norm() - 1.0) <= kUnitTolerance);
    }
    return count;
}

void require_bijective_sphere_map(const TriangleMesh& mesh,
                                  const std::vector<Eigen::Vector3d>& points,
                                  const ProgressSpan& progress) {
    const FoldCount count = count_folds(mesh, points, progress);
    if (count.folded == 0 && count.off_sphere == 0) return;
    std::string message = "sphere domain: no fold-free map found: ";
    if (count.folded > 0) {
        const Triangle& v = mesh.triangles[count.first];
        message += std::to_string(count.folded) + " of " + std::to_string(mesh.triangles.size()) +
                   " spherical triangles fold (det <= 0 in double precision), the first " +
                   std::to_string(count.first) + " (vertices " + std::to_string(v[0]) + ", " +
                   std::to_string(v[1]) + ", " + std::to_string(v[2]) + ")";
    }
    if (count.off_sphere > 0) {
        message += std::string(count.folded > 0 ? "; " : "") + std::to_string(count.off_sphere) +
                   " points off the unit sphere";
    }
    message +=
        "; long or thin parts of the mesh are squeezed below what doubles resolve on the sphere";
    throw Error(ErrorCode::kSolverFailed, message);
}

}  // namespace raps
