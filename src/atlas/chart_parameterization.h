// Step 4: the map of one chart. A free-boundary conformal map first (free_boundary_map.h), then
// the paper's adaptive step with that boundary held; each candidate is kept only if it is
// injective, and the one with the lower L2 stretch wins. When the free boundary overlaps
// itself, the chart falls back to a convex (circle) boundary, where mean value weights
// guarantee a bijection (paper section 3), or is split by the caller.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "atlas/chart_disk.h"
#include "core/progress.h"
#include "core/settings.h"
#include "planar/laplace_system.h"

namespace raps {

enum class ChartMethod { kFreeBoundary, kFreeBoundaryAdapted, kCircle, kCircleAdapted };

struct ChartMap {
    std::vector<Eigen::Vector2d> uv;  // per chart vertex; uv area equals the 3D area
    double stretch_l2 = 1;            // Sander's L2 stretch of this chart alone
    double stretch_linf = 1;
    ChartMethod method = ChartMethod::kFreeBoundary;
    bool injective = false;
    int64_t adaptive_solves = 0;  // behind this map (0 unless the adaptive step was kept)
    // The free-boundary map's L2 stretch as its log scale factor predicted it
    // (free_boundary_map.h), and whether the map was left unfinished for that alone.
    double predicted_l2 = 0;
    bool over_l2 = false;
};

// Each function reports its progress to `progress` (the atlas gives every chart the phase's
// current fraction: a chart's work repeats it, so that a cancel is seen inside a large chart).

// The chart's Laplace system with its boundary loop held, on which every map below is solved:
// one ordering and symbolic analysis for all of a chart's solves. It refers to the disk, which
// must outlive it.
LaplaceSystem chart_laplace_system(const ChartDisk& disk, const ProgressSpan& progress = {});

// The free-boundary map, its uvs scaled to the chart's 3D area. map.injective is false when
// the free boundary overlaps itself, or when its conformal scale factors already show a Linf
// stretch well above max_linf (the map is then not finished): the caller should split the chart.
// Nor is it finished when they show an L2 stretch above give_up_l2 (map.predicted_l2 says so).
ChartMap free_boundary_chart_map(const ChartDisk& disk, LaplaceSystem& system, double max_linf,
                                 double give_up_l2 = 1e300, const ProgressSpan& progress = {});

// The paper's adaptive step on an injective map, boundary held; replaces the map when the
// result is injective with a lower L2 stretch and a Linf stretch within max_linf (or the
// map's own). A map already within 0.05% of isometric is left as it is (nothing to gain).
void adapt_chart_map(const ChartDisk& disk, const Settings& settings, double max_linf,
                     ChartMap& map, LaplaceSystem& system, const ProgressSpan& progress = {});

// The last resort for a chart that cannot be split further: the circle boundary, where mean
// value weights guarantee a bijection (paper section 3), adapted when that lowers the stretch.
ChartMap circle_chart_map(const ChartDisk& disk, const Settings& settings, LaplaceSystem& system,
                          const ProgressSpan& progress = {});

}  // namespace raps
