// Steps 3-4 together: from the segmentation to one injective, low-stretch map per chart. A
// chart that cannot be made a disk, whose free-boundary map overlaps itself, or whose largest
// stretch exceeds the Linf limit, is split in two and both halves are processed again. Then,
// while the atlas's L2 stretch (the area-weighted RMS of the charts' L2) is above its target,
// the chart that contributes most to it is split: charts are only cut where it pays.
#pragma once

#include <cstdint>
#include <vector>

#include "atlas/atlas_surface.h"
#include "atlas/chart_mapping.h"
#include "core/progress.h"
#include "core/settings.h"
#include "parallel/thread_pool.h"

namespace raps {

// Charts in a deterministic order (by smallest surface triangle), whatever the pool's size.
std::vector<AtlasChart> build_charts(const AtlasSurface& surface, std::vector<int32_t> chart_of,
                                     const std::vector<char>& seam, const Settings& settings,
                                     const ChartLimits& limits, const Progress& progress,
                                     ThreadPool& pool);

}  // namespace raps
