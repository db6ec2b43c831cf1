// The distortion statistics every result carries. The definitions follow the project's reference
// measurement (shared/tools/uvmetrics.py), so the two can be cross-checked figure by figure:
// triangles whose 3D area is below 1e-12 of the mean are left out; r_t is the triangle's share
// of the uv area over its share of the 3D area; stretch is Sander et al. 2001 with the uv scaled
// so that its area equals the 3D area (an isometry gives 1). The map is seen through MapGeometry:
// for the sphere domain "uv area" reads spherical triangle area (exact), "uv angle" the angle
// between great-circle arcs, "flipped" a negative det[a, b, c], and stretch is that of each
// triangle's flat image scaled to its spherical area.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "core/triangle_mesh.h"
#include "metrics/map_geometry.h"
#include "parallel/thread_pool.h"

namespace raps {

struct DistortionStats {
    int64_t flipped_triangles = 0;    // clockwise in uv (the maps here are counter-clockwise)
    int64_t zero_area_triangles = 0;  // |uv area| <= 1e-14 * mean |uv area|
    double area_log_mean = 0;         // sum over t of (3D area share) * |log r_t|
    double area_max = 1;              // max of max(r_t, 1 / r_t); infinite for a zero uv area
    double angle_mean_deg = 0;        // mean over corners of |uv angle - 3D angle|
    double angle_max_deg = 0;
    double stretch_l2 = 1;    // sqrt(sum (3D area share) * (G^2 + g^2) / 2)
    double stretch_linf = 1;  // max G; G >= g singular values of the 3D-from-uv Jacobian
};

// Sander's L2 and Linf stretch alone (as in DistortionStats), without the angle and area
// figures: what the atlas needs to judge a chart, many times per run.
struct Stretch {
    double l2 = 1, linf = 1;
};
Stretch measure_stretch(const std::vector<Eigen::Vector3d>& positions,
                        const std::vector<Eigen::Vector2d>& uv,
                        const std::vector<Triangle>& triangles, const ProgressSpan& progress = {});

// Statistics of the map of `triangles` (indices into positions and the map alike), on the pool's
// threads: the same bits for any thread count.
DistortionStats measure_distortion(const std::vector<Eigen::Vector3d>& positions,
                                   const MapGeometry& map, const std::vector<Triangle>& triangles,
                                   ThreadPool& pool, const ProgressSpan& progress = {});

}  // namespace raps
