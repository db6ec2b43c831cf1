// Steps 3-4 together: from the segmentation to one injective, low-stretch map per chart. A
// chart that cannot be made a disk, whose free-boundary map overlaps itself, or whose largest
// stretch exceeds the Linf limit, is split in two and both halves are processed again. Then,
// while the atlas's L2 stretch (the area-weighted RMS of the charts' L2) is above its target,
// the chart that contributes most to it is split: charts are only cut where it pays.
#pragma once

#include <cstdint>
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

// Charts in a deterministic order (by smallest surface triangle), whatever the pool's size.
std::vector<AtlasChart> build_charts(const AtlasSurface& surface,
                                     const std::vector<int32_t>& chart_of,
                                     const std::vector<char>& seam, const Settings& settings,
                                     const ChartLimits& limits, const Progress& progress,
                                     ThreadPool& pool);

}  // namespace raps
