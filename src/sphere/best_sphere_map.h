// Which of the maps that the robust adaptive continuation passes through is returned (issue 18).
// Each continuation step starts from the map the previous one left, and a step can be worse than
// the one before: on horse_quad.obj with three iterations the area distortion rose from 2.76 to
// 3.09 over three steps, and on a capsule of aspect 30 the centre of mass drifted 0.5 from the
// origin in the last step (docs/sphere-status.md). So the pipeline scores the initial map and
// every step's map and returns the best: fewer folded triangles first, then centred (the
// 3D-area-weighted centre of mass within kCentredEnough of the origin), then, for the area
// monitor, the lower area distortion; for the other monitors the later map. The initial map
// competes too, so the area-adapted result is never worse than it in area distortion.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "parallel/thread_pool.h"
#include "sphere/sphere_problem.h"

namespace raps {

// A centre of mass this close to the origin counts as centred: the issue promises 0.05, and
// the centring reaches 0.01 or better wherever it is not stalled (docs/sphere-status.md).
constexpr double kCentredEnough = 0.02;

struct SphereMapScore {
    int64_t folded = 0;   // triangles with det[a, b, c] <= 0 in their stored vertex order
    double centre = 0;    // distance of the 3D-area-weighted centre of mass from the origin
    double area_log = 0;  // 3D-area-weighted mean |log r|, as raps_stats.area_log_mean
};

// `beat` is told its start fraction as the triangles are measured.
SphereMapScore score_sphere_map(const SphereProblem& problem, const std::vector<Eigen::Vector3d>& u,
                                ThreadPool& pool, const ProgressSpan& beat = {});

// Whether `candidate`, a later map than `best`, is to be returned instead of it (the order
// above); `by_area` for the area monitor.
bool better_sphere_map(const SphereMapScore& candidate, const SphereMapScore& best, bool by_area);

}  // namespace raps
