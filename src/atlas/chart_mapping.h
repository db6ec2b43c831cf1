// One chart's map, as the atlas makes it: the chart cut into a disk, its free-boundary map
// (chart_parameterization.h), then the adaptive step; for the first charts and for every union
// merging tries (chart_merging.h).
#pragma once

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "atlas/atlas_surface.h"
#include "atlas/chart_disk.h"
#include "atlas/chart_packing.h"
#include "atlas/chart_parameterization.h"
#include "core/progress.h"
#include "core/settings.h"
#include "parallel/thread_pool.h"

namespace raps {

struct AtlasChart {
    ChartDisk disk;
    ChartMap map;
    ChartBox box;  // of the map: merging weighs its fill, packing turns the chart by it
};

struct ChartLimits {
    double target_stretch_l2 = 1.01;  // for the whole atlas
    double max_stretch_linf = 2.5;    // for every chart
};

// The chart made of `triangles` (ascending surface triangle ids): its disk and map, or false
// when it must be split. unadapted_l2: the map's L2 stretch before its adaptive step.
bool map_chart(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
               const std::vector<char>& seam, const Settings& settings, const ChartLimits& limits,
               AtlasChart& chart, double& unadapted_l2, const ProgressSpan& beat);

// What merging would reject a union for, tested as soon as the union's map shows it, so that a
// union bound to be rejected skips the rest of its map (the adaptive step above all).
struct UnionLimits {
    double give_up_l2 = 1e300;  // for the free-boundary map's predicted L2 stretch
    double min_fill = 0;        // for the free-boundary map's bounding box fill
};

enum class UnionVerdict {
    kMapped,
    kFailed,     // not a valid chart (not a disk, overlapping, or over the Linf limit)
    kOverL2,     // predicted L2 above give_up_l2 (chart.map.predicted_l2); chart unfinished
    kUnderFill,  // box fill below min_fill; chart unfinished
};

// map_chart for the union of charts `a` and `b` (`triangles`: theirs together, ascending).
UnionVerdict map_union_chart(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
                             const std::vector<char>& seam, const Settings& settings,
                             const ChartLimits& limits, const ChartDisk& a, const ChartDisk& b,
                             const UnionLimits& union_limits, AtlasChart& chart,
                             const ProgressSpan& beat);

// The chart's 3D area.
double chart_area(const ChartDisk& disk);

// body(i) for every i on the threads, taken in order of decreasing cost (ties by index), so
// the largest charts start first and no thread is left with one big chart at the end of a
// batch. Each body writes only its own slot, so the output does not depend on the order.
void parallel_largest_first(ThreadPool& pool, const std::vector<size_t>& cost,
                            const std::function<void(size_t)>& body);

}  // namespace raps
