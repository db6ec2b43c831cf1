// Step 3 of the atlas pipeline: grow charts over the surface. Charts grow from seeds in order of
// geodesic distance (so they come out compact, a geodesic Voronoi diagram of the seeds) and
// stop at what would make them hard to flatten: a triangle whose normal deviates too far from
// the chart's mean normal, a hard edge, a cut. Triangles no chart can take become new seeds.
// Charts that still map badly are split later, by their measured stretch (atlas_charts.h). Lloyd
// iterations then move every seed to its chart's centre and regrow, which evens the charts out
// (the Lloyd relaxation of Cohen-Steiner et al. 2004's variational shape approximation).
#pragma once

#include <cstdint>
#include <vector>

#include "atlas/atlas_surface.h"
#include "core/progress.h"
#include "parallel/thread_pool.h"

namespace raps {

struct SegmentationSettings {
    double max_normal_deviation_deg = 75.0;  // triangle normal vs the chart's mean normal
    double hard_edge_angle_deg = 180.0;      // dihedral angle above which an edge is a seam
    int lloyd_iterations = 3;
};

// Moves triangles whose two uncut neighbours belong to another chart into that chart, which
// removes saw-tooth boundaries. barrier[h] marks half-edges that separate charts regardless;
// only `triangles` (ascending) are visited and may move.
void smooth_chart_boundaries(const AtlasSurface& surface, const std::vector<char>& barrier,
                             const std::vector<int32_t>& triangles, std::vector<int32_t>& chart,
                             const ProgressSpan& progress = {});

// The same on a chart of its own: chart[i] per chart triangle i, neighbour[3i+k] the chart
// triangle across its side k, or -1 where a barrier is; pinned[i] (empty: none) keeps triangle
// i where it is (a part of a polygon, polygon_units.h).
void smooth_chart_boundaries(const std::vector<int32_t>& neighbour, std::vector<int32_t>& chart,
                             const ProgressSpan& progress = {},
                             const std::vector<char>& pinned = {});

// Chart id per surface triangle, ids 0 .. chart count - 1, numbered by their first triangle.
// The triangles' geometry is measured on `pool` (the same charts for any thread count).
std::vector<int32_t> segment_charts(const AtlasSurface& surface,
                                    const SegmentationSettings& settings, ThreadPool& pool,
                                    const ProgressSpan& progress = {});

}  // namespace raps
