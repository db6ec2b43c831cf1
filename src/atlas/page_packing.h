// Step 5 at a fixed texel density (RAPS_PARAM_ATLAS_TEXELS_PER_UNIT): the charts are placed, as
// they are, at `texels_per_unit` texels per unit of their uvs (3D units: a chart's uv area is
// its 3D area), onto pages of at most max_width x max_height texels that are never exceeded. A
// chart is rasterised conservatively at its final texel size and placed on whole texels (or
// whole 4x4 blocks), so what the packer keeps apart stays apart in the texture: at least
// `padding` texels between the texels any two charts touch, at least `margin` between them and
// the page's border. Charts whose area one page holds are first tried on one page as
// pack_one_page tries them (its size orders, two scoring rules, then those orders repaired
// where none fits: page_packing.cpp's repair_orders). Otherwise charts are placed
// largest first, each on the first of the last 8 pages where the skyline search (skyline_packing.h)
// finds it room; a chart that fits none opens the next page (and closes the oldest open one).
// With part_per_page, all charts of one mesh of a scene go on one page, as a lightmap needs. A
// chart (or a mesh's charts, with part_per_page) larger than a page at that density is shrunk until
// it fits, and reported: nothing is dropped.
#pragma once

#include <cstdint>
#include <vector>

#include "atlas/chart_packing.h"
#include "core/progress.h"
#include "parallel/thread_pool.h"

namespace raps {

struct PageSettings {
    double texels_per_unit = 1;
    int32_t max_width = 4096, max_height = 4096;  // texels
    int32_t padding = 1;                          // texels between charts
    int32_t margin = 0;                           // texels between charts and the border
    bool block_align = false;  // charts on whole 4x4 blocks, no block shared by two charts
    ChartRotation rotation = ChartRotation::kAny;
    bool part_per_page = false;
};

// Every page is as large as the charts of any page reach (with the margin), uvs normalised to
// it per axis. Charts are rasterised on `pool`; the result does not depend on its size.
PackResult pack_pages(const std::vector<PackInput>& charts, const PageSettings& settings,
                      ThreadPool& pool, const ProgressSpan& progress = {});

// The same placement on one page of at most max_width x max_height at the largest density
// (within 1%, settings.texels_per_unit ignored) at which every chart fits it unshrunk: a
// search from the density at which the charts' area would fill the page, down by a fifth
// until they fit, then up by halving the gap or, up to 100 charts, to where the last fitting
// layout's rows would fill the page; a density within 1% of one that fits is also tried with
// the orders repaired. part_per_page is moot on one page. Throws
// kInvalidArgument when no density fits them (too many charts for the page with their padding).
PackResult pack_one_page(const std::vector<PackInput>& charts, PageSettings settings,
                         ThreadPool& pool, const ProgressSpan& progress = {});

}  // namespace raps
