// Step 5 of the atlas pipeline: place the charts at one texel density in a square page of
// resolution x resolution texels, as large as it lets them be. Every chart is turned to its
// smallest bounding box (smallest_bounding_box, measured by the caller with the chart's map),
// rasterised conservatively at the texel size and padded, so that no two charts come closer than
// `padding` texels (bilinear filtering and mip levels then never mix them). Charts are placed
// largest first into a strip of fixed width, each in whichever of its four quarter turns (with
// any rotation allowed, the largest charts also turned 15 to 75 degrees further) lands lowest on
// the skyline (the top of what is already placed, per column of texels) or lower, in a hole
// under an overhang; three orders of size, several strip widths and two scoring rules are tried
// and the one held by the smallest square wins (its strip width is then refined, and up to 16
// charts its order improved by pair swaps). The texel density is then raised until the layout's
// longer side is `resolution` texels. uvs are texels over the resolution on both axes, so a
// square texture maps them at equal density in u and v. Meant for up to about 100 charts: the
// atlas pipeline packs more with the whole-texel packer (page_packing.h).
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "atlas/chart_box.h"
#include "atlas/chart_raster.h"
#include "core/progress.h"
#include "core/settings.h"
#include "core/triangle_mesh.h"
#include "parallel/thread_pool.h"

namespace raps {

struct PackInput {
    const std::vector<Eigen::Vector2d>* uv;  // chart-local uv, in 3D units (uv area = 3D area)
    const std::vector<Triangle>* triangles;
    Eigen::Vector2d rotation;  // the chart's smallest box (smallest_bounding_box)
    int32_t part = 0;          // the mesh of a scene it belongs to
};

struct PackSettings {
    int32_t resolution = 1024;  // texels per side of the square
    int32_t padding = 2;        // texels between charts
    ChartRotation rotation = ChartRotation::kAny;
};

struct PackResult {
    std::vector<std::vector<Eigen::Vector2d>> uv;  // per chart, per chart vertex, in [0,1]^2
    std::vector<int32_t> page;                     // per chart
    std::vector<double> rotation_deg;              // per chart: its map's counter-clockwise turn
    std::vector<char> scaled_down;  // per chart: below the atlas's density to fit a page
    int32_t width = 0, height = 0;  // the atlas (every page) in texels
    int32_t page_count = 1;
    double texels_per_unit = 0;  // texels per unit of the charts' uvs (3D units)
};

// Each chart's outline for rasterising (chart_raster.h), measured on `pool`; `beat` is told
// its start fraction (report(0)) every kItemsPerReport triangles.
std::vector<ChartOutline> chart_outlines(const std::vector<PackInput>& charts, ThreadPool& pool,
                                         const ProgressSpan& beat);

// Charts are rasterised, and layouts tried, on `pool`; the result does not depend on its size.
PackResult pack_charts(const std::vector<PackInput>& charts, const PackSettings& settings,
                       ThreadPool& pool, const ProgressSpan& progress = {});

}  // namespace raps
