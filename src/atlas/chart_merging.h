// The last step of making charts: splits and the segmentation's limits leave more charts than
// needed. Adjacent charts whose union is a valid chart are merged while the atlas's L2 stretch
// stays within its target, smallest charts first (they cost the most in packing and seams).
#pragma once

#include <vector>

#include "atlas/atlas_surface.h"
#include "atlas/chart_mapping.h"
#include "core/progress.h"
#include "core/settings.h"
#include "parallel/thread_pool.h"

namespace raps {

// `charts` (adapted maps) with their 3D `area`s are merged in place. `target`: the budget of
// the sum over charts of area times L2 squared. Progress goes to Phase::kInitialMap from
// `start` towards 1, `beat` inside each chart.
void merge_charts(const AtlasSurface& surface, const std::vector<char>& seam,
                  const Settings& settings, const ChartLimits& limits, double target,
                  std::vector<AtlasChart>& charts, const std::vector<double>& area,
                  const Progress& progress, double start, const ProgressSpan& beat,
                  ThreadPool& pool);

}  // namespace raps
