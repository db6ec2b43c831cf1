#include "atlas/page_packing.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <string>

#include "atlas/chart_raster.h"
#include "atlas/skyline_packing.h"
#include "core/error.h"

namespace raps {
namespace {

// Texels of a block when charts are block aligned (BC1-7 and ASTC 4x4 compress 4x4 blocks).
constexpr int32_t kBlock = 4;

// The grid charts are placed on: cells of `cell` texels. A chart's profile carries `pad_cells`
// cells of padding on each side, which may hang over the page's inner area (inside the margin):
// the strip is the inner area plus the padding on both sides.
struct PageGrid {
    int32_t cell = 1, pad_cells = 0;
    int32_t margin = 0;           // texels, a whole number of cells
    int32_t strip = 0, rows = 0;  // cells
};

PageGrid page_grid(const PageSettings& settings) {
    PageGrid grid;
    grid.cell = settings.block_align ? kBlock : 1;
    grid.pad_cells = (settings.padding + grid.cell - 1) / grid.cell;
    grid.margin = (settings.margin + grid.cell - 1) / grid.cell * grid.cell;
    grid.strip = (settings.max_width - 2 * grid.margin) / grid.cell + 2 * grid.pad_cells;
    grid.rows = (settings.max_height - 2 * grid.margin) / grid.cell + 2 * grid.pad_cells;
    return grid;
}

// A chart turned as the rotation policy allows: the rotation, its box's lower corner and size
// (in uv units) and how many quarter turns the placement may add.
struct OrientedChart {
    Eigen::Vector2d rotation = Eigen::Vector2d(1, 0), origin, extent;
    int turns = 4;
};

OrientedChart orient(const PackInput& chart, ChartRotation policy) {
    OrientedChart o;
    if (policy == ChartRotation::kAny) o.rotation = chart.rotation;
    o.turns = policy == ChartRotation::kNone ? 1 : 4;
    const TurnedBox box = turned_box(*chart.uv, o.rotation);
    o.origin = box.origin;
    o.extent = box.extent;
    return o;
}

// The chart's raster at `scale` texels per uv unit, in cells: texels up to its box's size plus
// one (a conservative raster touches one more) and the padding on both sides, rounded up to
// whole cells.
Eigen::Vector2i raster_cells(const OrientedChart& o, double scale, const PageGrid& grid) {
    const int32_t pad = grid.pad_cells * grid.cell;
    auto cells = [&](double length) {
        const double texels = std::ceil(length * scale) + 1 + 2 * pad;
        return static_cast<int32_t>(std::min(std::ceil(texels / grid.cell), 1e9));
    };
    return Eigen::Vector2i(cells(o.extent.x()), cells(o.extent.y()));
}

// How much smaller the chart must get to fit an empty page in its best allowed turn: 1 or more
// when it fits.
double fit_ratio(const OrientedChart& o, double scale, const PageGrid& grid) {
    const Eigen::Vector2i size = raster_cells(o, scale, grid);
    auto ratio = [&](int32_t w, int32_t h) {
        return std::min(static_cast<double>(grid.strip) / w, static_cast<double>(grid.rows) / h);
    };
    double best = ratio(size.x(), size.y());
    if (o.turns > 1) best = std::max(best, ratio(size.y(), size.x()));
    return best;
}

// The largest scale up to `scale` at which the chart fits an empty page.
double fitting_scale(const OrientedChart& o, double scale, const PageGrid& grid) {
    for (int attempt = 0; attempt < 200; ++attempt) {
        const double ratio = fit_ratio(o, scale, grid);
        if (ratio >= 1) return scale;
        scale *= std::min(ratio, 0.999);
    }
    throw Error(ErrorCode::kInternal, "a chart does not fit a page at any scale");
}

// A set cell for every block of `cell` x `cell` texels that holds a set texel.
BitImage to_cells(const BitImage& texels, int32_t cell) {
    BitImage cells;
    cells.resize(texels.width / cell, texels.height / cell);
    for (int32_t y = 0; y < texels.height; ++y) {
        const uint64_t* row = texels.row(y);
        for (int32_t x = 0; x < texels.width; ++x) {
            if (row[x / 64] >> (x % 64) & 1) cells.set_span(y / cell, x / cell, x / cell);
        }
    }
    return cells;
}

// The point of a chart's uv `p` in its unturned raster, in texels.
Eigen::Vector2d raster_point(const OrientedChart& o, double scale, const PageGrid& grid,
                             const Eigen::Vector2d& p) {
    const double pad = grid.pad_cells * grid.cell;
    return (turned(o.rotation, p) - o.origin) * scale + Eigen::Vector2d(pad, pad);
}

void prepare(const PackInput& input, const ChartOutline& outline, const OrientedChart& o,
             double scale, const PageGrid& grid, PreparedChart& prepared) {
    const Eigen::Vector2i size = raster_cells(o, scale, grid);
    BitImage raster;
    raster.resize(size.x() * grid.cell, size.y() * grid.cell);
    std::vector<Eigen::Vector2d> points(input.uv->size());
    for (size_t v = 0; v < points.size(); ++v)
        points[v] = raster_point(o, scale, grid, (*input.uv)[v]);
    rasterise_chart(points, *input.triangles, outline, raster);
    BitImage cells = grid.cell == 1 ? std::move(raster) : to_cells(raster, grid.cell);
    prepared.rotation = o.rotation;
    prepared.origin = o.origin;
    prepared.turns = o.turns;
    for (int q = 0; q < 4; ++q) {
        BitImage turned = q < 3 ? rotate_quarter(cells) : BitImage();
        prepared.profiles[q] = make_profile(std::move(cells), grid.pad_cells);
        cells = std::move(turned);
    }
}

// Pages still searched for room: the last few. An older page is closed (its occupancy freed),
// which bounds the search per chart and the memory (a page of 16384 x 16384 cells holds 32 MiB)
// however many pages an atlas takes.
constexpr size_t kOpenPages = 8;

// The pages (closed ones null) and where each chart went.
struct PageLayout {
    std::vector<std::unique_ptr<SkylineStrip>> pages;
    std::vector<int32_t> page;
    std::vector<Placement> place;
    bool count_waste = false;  // of the pages it opens (SkylineStrip)

    size_t first_open() const { return pages.size() > kOpenPages ? pages.size() - kOpenPages : 0; }
    void open_page(const PageGrid& grid) {
        pages.push_back(std::make_unique<SkylineStrip>(grid.strip, count_waste, true));
        if (pages.size() > kOpenPages) pages[pages.size() - kOpenPages - 1].reset();
    }
};

// Places the chart on `page` if the page has room for it below its last row.
bool place_on(SkylineStrip& page, const PreparedChart& chart, int32_t rows, Placement& place) {
    if (!page.find(chart, place)) return false;
    if (place.y + chart.profiles[place.quarter].height > rows) return false;
    page.commit(chart, place);
    return true;
}

// Each chart in `order` on the first page with room for it, or a new one.
void place_first_fit(const std::vector<PreparedChart>& prepared, const std::vector<size_t>& order,
                     const PageGrid& grid, PageLayout& layout) {
    for (size_t c : order) {
        bool placed = false;
        for (size_t p = layout.first_open(); p < layout.pages.size() && !placed; ++p) {
            placed = place_on(*layout.pages[p], prepared[c], grid.rows, layout.place[c]);
            if (placed) layout.page[c] = static_cast<int32_t>(p);
        }
        if (placed) continue;
        layout.open_page(grid);
        if (!place_on(*layout.pages.back(), prepared[c], grid.rows, layout.place[c]))
            throw Error(ErrorCode::kInternal, "a chart shrunk to fit a page does not fit one");
        layout.page[c] = static_cast<int32_t>(layout.pages.size() - 1);
    }
}

// All of `charts` on `page`, or none (the page is then unchanged).
bool place_all_on(std::unique_ptr<SkylineStrip>& page, const std::vector<PreparedChart>& prepared,
                  const std::vector<size_t>& charts, const PageGrid& grid, PageLayout& layout) {
    auto trial = std::make_unique<SkylineStrip>(*page);
    std::vector<Placement> places(charts.size());
    for (size_t k = 0; k < charts.size(); ++k) {
        if (!place_on(*trial, prepared[charts[k]], grid.rows, places[k])) return false;
    }
    page = std::move(trial);
    for (size_t k = 0; k < charts.size(); ++k) layout.place[charts[k]] = places[k];
    return true;
}

// Where no order fits a density by a few charts, the orders are repaired the way bin-packing
// heuristics promote the item that did not fit: the chart that stopped an order is moved to
// each earlier place in turn (kRepairPlaces of them, evenly spread, where it stopped later), and
// the variant that places the most charts before one does not fit is the next round's order.
// Layouts of a few large jagged charts are chaotic in their order: a chart that fits nowhere
// after the others often fits placed before some of them. Each start (rule, then order) is
// repaired for up to kRepairRounds rounds until a variant fits, while the charts placed stay
// under kRepairPlacements per chart at the density. pack_one_page repairs a density within
// kRepairWithin of one that fits (the last steps of its search, which fail by a chart or two),
// pack_pages its one-page attempt (kRepairFillAtMost). Never a lower density. Measured
// (docs/square-atlas.md, "Orders repaired"): the ten-mesh scene of issue 23 at 2048 0.716 -> 0.726
// (373 -> 505 ms); the 19 shared meshes' lightmaps, median coverage 0.653 -> 0.663, 11 of 19
// denser, pack 14 -> 26 ms; 12 of 25 held-out meshes and scenes denser, by 0.007 to 0.027, none
// less.
constexpr int kRepairRounds = 3;
constexpr double kRepairWithin = 1.01;
// pack_pages's one-page attempt at a given density is repaired only where the charts' area
// fills at most this share of the page: fuller pages are beyond what the repaired orders
// reach (the fullest whole-texel page measured, 0.834, was a scene of 400 small noisy
// charts), and their repair found nothing for 5 to 7 times the packing (the ten noisy meshes
// at 228 to 240 texels per unit on pages of 2048, 400 charts: 87-116 -> 528-755 ms).
constexpr double kRepairFillAtMost = 0.8;
constexpr int64_t kRepairPlaces = 32;
constexpr int64_t kRepairPlacements = 32;

// Charts placed or rasterised between two progress calls: a call per chart multiplied a
// packing's calls by six, and a caller's callback can cost tens of microseconds.
constexpr size_t kChartsPerReport = 16;

PageLayout empty_page_layout(size_t count) {
    PageLayout layout;
    layout.page.assign(count, 0);
    layout.place.resize(count);
    return layout;
}

// The charts of `order` from `from` on placed one after another on the layout's (one) page
// until one does not fit: the index of that one (order.size(): all fit). `beat` is told its
// start fraction every kChartsPerReport charts: an order of a thousand charts took about a
// second at 4M triangles without a progress call.
size_t place_from(const std::vector<PreparedChart>& prepared, const std::vector<size_t>& order,
                  size_t from, const PageGrid& grid, PageLayout& layout, const ProgressSpan& beat) {
    for (size_t k = from; k < order.size(); ++k) {
        if ((k - from) % kChartsPerReport == 0) beat.report(0.0);
        if (!place_on(*layout.pages[0], prepared[order[k]], grid.rows, layout.place[order[k]]))
            return k;
    }
    return order.size();
}

// The same on a fresh page from the first chart: how many were placed.
size_t place_until_full(const std::vector<PreparedChart>& prepared,
                        const std::vector<size_t>& order, const PageGrid& grid, bool count_waste,
                        PageLayout& layout, const ProgressSpan& beat) {
    layout.count_waste = count_waste;
    layout.open_page(grid);
    return place_from(prepared, order, 0, grid, layout, beat);
}

// Up to `most` places before `from`, evenly spread, ascending.
std::vector<size_t> earlier_places(size_t from, size_t most) {
    std::vector<size_t> places;
    const size_t count = std::min(from, most);
    for (size_t k = 0; k < count; ++k) places.push_back(from * k / count);
    return places;
}

// `order` with the chart at `from` moved to `to`.
std::vector<size_t> moved(const std::vector<size_t>& order, size_t from, size_t to) {
    std::vector<size_t> variant = order;
    variant.erase(variant.begin() + static_cast<std::ptrdiff_t>(from));
    variant.insert(variant.begin() + static_cast<std::ptrdiff_t>(to), order[from]);
    return variant;
}

// A variant moved to `to` places the same charts as its order before `to`: each variant starts
// from a copy of the order's layout at that point, made in one pass, where the copies together
// hold at most this much (a page of 16384 x 16384 cells holds 32 MiB).
constexpr double kRepairCopyBytes = 64.0 * 1024 * 1024;

std::vector<PageLayout> prefix_layouts(const std::vector<PreparedChart>& prepared,
                                       const std::vector<size_t>& order,
                                       const std::vector<size_t>& places, const PageGrid& grid,
                                       bool count_waste, const ProgressSpan& beat) {
    const double page_bytes = 8.0 * grid.rows * ((grid.strip + 63) / 64 + 1);
    std::vector<PageLayout> copies;
    if (page_bytes * static_cast<double>(places.size()) > kRepairCopyBytes) return copies;
    PageLayout layout = empty_page_layout(prepared.size());
    layout.count_waste = count_waste;
    layout.open_page(grid);
    size_t placed = 0;
    for (size_t to : places) {
        for (; placed < to; ++placed) {
            if (placed % kChartsPerReport == 0) beat.report(0.0);
            const size_t c = order[placed];
            if (!place_on(*layout.pages[0], prepared[c], grid.rows, layout.place[c]))
                throw Error(ErrorCode::kInternal, "a repaired order's prefix no longer fits");
        }
        PageLayout copy;
        copy.pages.push_back(std::make_unique<SkylineStrip>(*layout.pages[0]));
        copy.page = layout.page;
        copy.place = layout.place;
        copy.count_waste = count_waste;
        copies.push_back(std::move(copy));
    }
    return copies;
}

// The first repaired order that fits one page (see kRepairRounds), if any, from the orders
// and how many charts each placed (`reached`, per rule and order); the same for any number of
// threads. Each round packs about as many charts per variant as its order placed, and takes
// only as many variants as the placements left pay for.
bool repair_orders(const std::vector<PreparedChart>& prepared,
                   const std::vector<std::vector<size_t>>& orders,
                   const std::vector<size_t>& reached, const PageGrid& grid, ThreadPool& pool,
                   const ProgressSpan& progress, PageLayout& fitted) {
    const size_t count = prepared.size();
    const ProgressSpan beat = progress.part(0.5, 0.5);
    int64_t placements_left = kRepairPlacements * static_cast<int64_t>(count);
    for (size_t start = 0; start < reached.size(); ++start) {
        const bool count_waste = start >= orders.size();
        std::vector<size_t> order = orders[start % orders.size()];
        size_t placed_most = reached[start];
        for (int round = 0; round < kRepairRounds; ++round) {
            const int64_t affordable = placements_left / static_cast<int64_t>(placed_most + 1);
            if (affordable <= 0) return false;
            progress.report(0.5);
            const std::vector<size_t> places = earlier_places(
                placed_most, static_cast<size_t>(std::min<int64_t>(affordable, kRepairPlaces)));
            std::vector<PageLayout> starts =
                prefix_layouts(prepared, order, places, grid, count_waste, beat);
            // Only the counts are kept (a layout holds the page's cells): the one that fits is
            // packed again.
            std::vector<size_t> placed(places.size());
            parallel_for_each(pool, places.size(), [&](size_t k) {
                const std::vector<size_t> variant = moved(order, placed_most, places[k]);
                if (starts.empty()) {
                    PageLayout layout = empty_page_layout(count);
                    placed[k] =
                        place_until_full(prepared, variant, grid, count_waste, layout, beat);
                } else {
                    placed[k] = place_from(prepared, variant, places[k], grid, starts[k], beat);
                    starts[k] = PageLayout();  // its cells, freed as soon as they are done with
                }
            });
            size_t best = 0;
            for (size_t k = 0; k < places.size(); ++k) {
                placements_left -= static_cast<int64_t>(placed[k]) + 1;
                if (placed[k] > placed[best]) best = k;
            }
            if (places.empty() || placed[best] <= placed_most) break;
            order = moved(order, placed_most, places[best]);
            if (placed[best] == count) {
                fitted = empty_page_layout(count);
                place_until_full(prepared, order, grid, count_waste, fitted, beat);
                return true;
            }
            placed_most = placed[best];
        }
    }
    return false;
}

// Between these many charts, size_orders's three further orders are packed too where the first
// three do not fit a page: a scene of many meshes has many large jagged charts, whose layouts
// are chaotic in the order, and a layout of a few hundred charts costs little. Never a lower
// density (a density any order fits is one the search keeps). Measured (docs/square-atlas.md):
// the ten-mesh scene of issue 23 at 2048 0.696 -> 0.716; soups of 5,000 and 20,000 separate
// quads gained nothing for 60 to 70% more packing, so not above a thousand.
constexpr size_t kFurtherOrdersAbove = 100, kFurtherOrdersUpTo = 1000;

// The charts turned, at their densities (the atlas's, or less for one larger than a page),
// rasterised, and the orders they may be placed in.
struct PreparedCharts {
    const std::vector<ChartOutline>* outlines;  // per chart, measured once per packing
    std::vector<OrientedChart> oriented;
    std::vector<double> scale;
    std::vector<PreparedChart> prepared;
    // size_orders of the boxes at their densities; the first, largest first by the longer side,
    // is the order of pages.
    std::vector<std::vector<size_t>> orders;
};

PreparedCharts prepare_charts(const std::vector<PackInput>& charts,
                              const std::vector<ChartOutline>& outlines,
                              const PageSettings& settings, const PageGrid& grid, ThreadPool& pool,
                              const ProgressSpan& beat) {
    const size_t count = charts.size();
    PreparedCharts set;
    set.outlines = &outlines;
    set.oriented.resize(count);
    set.scale.resize(count);
    for (size_t c = 0; c < count; ++c) {
        set.oriented[c] = orient(charts[c], settings.rotation);
        set.scale[c] = fitting_scale(set.oriented[c], settings.texels_per_unit, grid);
    }
    set.prepared.resize(count);
    parallel_for_each(pool, count, [&](size_t c) {
        if (c % kChartsPerReport == 0) beat.report(0.0);
        prepare(charts[c], outlines[c], set.oriented[c], set.scale[c], grid, set.prepared[c]);
    });
    std::vector<Eigen::Vector2d> extents(count);
    for (size_t c = 0; c < count; ++c) extents[c] = set.oriented[c].extent * set.scale[c];
    set.orders = size_orders(extents, count > kFurtherOrdersAbove && count <= kFurtherOrdersUpTo);
    return set;
}

// One mesh's charts together: on the first page with room for all of them, or a new page;
// shrunk together while even an empty page has too little room.
void place_parts_per_page(const std::vector<PackInput>& charts, const PageGrid& grid,
                          ThreadPool& pool, PreparedCharts& set, PageLayout& layout) {
    int32_t parts = 0;
    for (const PackInput& chart : charts) parts = std::max(parts, chart.part + 1);
    for (int32_t part = 0; part < parts; ++part) {
        std::vector<size_t> members;
        for (size_t c : set.orders[0]) {
            if (charts[c].part == part) members.push_back(c);
        }
        if (members.empty()) continue;
        size_t p = layout.first_open();
        while (p < layout.pages.size() &&
               !place_all_on(layout.pages[p], set.prepared, members, grid, layout))
            ++p;
        if (p == layout.pages.size()) {
            layout.open_page(grid);
            for (int attempt = 0;
                 !place_all_on(layout.pages.back(), set.prepared, members, grid, layout);
                 ++attempt) {
                if (attempt == 100) {
                    // Each chart keeps its padding however far it shrinks: enough charts
                    // need more cells than the page has at any scale.
                    throw Error(ErrorCode::kInvalidArgument,
                                "mesh " + std::to_string(part) + "'s " +
                                    std::to_string(members.size()) +
                                    " charts fit no page of the maximum size at any scale with "
                                    "their padding and margin (one page per mesh): raise "
                                    "RAPS_PARAM_ATLAS_MAX_WIDTH and _MAX_HEIGHT or lower the "
                                    "padding or the margin");
                }
                for (size_t c : members) set.scale[c] *= 0.9;
                parallel_for_each(pool, members.size(), [&](size_t k) {
                    const size_t c = members[k];
                    prepare(charts[c], (*set.outlines)[c], set.oriented[c], set.scale[c], grid,
                            set.prepared[c]);
                });
            }
        }
        for (size_t c : members) layout.page[c] = static_cast<int32_t>(p);
    }
}

// The uvs of the laid-out charts: texel positions (the profile's place, less its padding,
// inside the margin: whole cells), every page as large as any page's charts reach with the
// margin, then normalised to it.
PackResult layout_uvs(const std::vector<PackInput>& charts, const PageSettings& settings,
                      const PageGrid& grid, const PreparedCharts& set, const PageLayout& layout) {
    const size_t count = charts.size();
    PackResult result;
    result.uv.resize(count);
    result.page.assign(count, 0);
    result.scaled_down.assign(count, 0);
    result.rotation_deg.assign(count, 0);
    result.texels_per_unit = settings.texels_per_unit;
    Eigen::Vector2d high(0, 0);
    for (size_t c = 0; c < count; ++c) {
        const Placement& place = layout.place[c];
        const Profile& unturned = set.prepared[c].profiles[0];
        result.uv[c].resize(charts[c].uv->size());
        for (size_t v = 0; v < result.uv[c].size(); ++v) {
            Eigen::Vector2d at =
                raster_point(set.oriented[c], set.scale[c], grid, (*charts[c].uv)[v]);
            int32_t height = unturned.height * grid.cell;
            for (int k = 0; k < place.quarter; ++k) {  // (x, y) -> (h - y, x), as the raster
                at = Eigen::Vector2d(height - at.y(), at.x());
                height = (k % 2 ? unturned.height : unturned.width) * grid.cell;
            }
            at += Eigen::Vector2d((place.x - grid.pad_cells) * grid.cell + grid.margin,
                                  (place.y - grid.pad_cells) * grid.cell + grid.margin);
            result.uv[c][v] = at;
            high = high.cwiseMax(at);
        }
        result.page[c] = layout.page[c];
        result.scaled_down[c] = set.scale[c] < settings.texels_per_unit;
        result.rotation_deg[c] = turn_degrees(set.oriented[c].rotation, place.quarter);
    }
    auto page_side = [&](double extent, int32_t most) {
        const int32_t side = static_cast<int32_t>(std::ceil(extent - 1e-9)) + grid.margin;
        return std::clamp((side + grid.cell - 1) / grid.cell * grid.cell, 1, most);
    };
    result.width = page_side(high.x(), settings.max_width);
    result.height = page_side(high.y(), settings.max_height);
    result.page_count = std::max<int32_t>(1, static_cast<int32_t>(layout.pages.size()));
    for (std::vector<Eigen::Vector2d>& chart_uv : result.uv) {
        for (Eigen::Vector2d& at : chart_uv) {
            at = Eigen::Vector2d(std::clamp(at.x() / result.width, 0.0, 1.0),
                                 std::clamp(at.y() / result.height, 0.0, 1.0));
        }
    }
    return result;
}

PageGrid checked_grid(const PageSettings& settings) {
    const PageGrid grid = page_grid(settings);
    if (grid.strip <= 2 * grid.pad_cells || grid.rows <= 2 * grid.pad_cells)
        throw Error(ErrorCode::kInternal, "the page has no room inside its margin");
    return grid;
}

// The layout of every chart on one page at `settings.texels_per_unit`, unshrunk, if there is
// one; with `repair`, the orders are repaired where none fits (repair_orders).
bool layout_on_one_page(const std::vector<PackInput>& charts, const PageSettings& settings,
                        const PageGrid& grid, const PreparedCharts& set, ThreadPool& pool,
                        bool repair, const ProgressSpan& progress, PackResult& result,
                        int32_t& rows_used) {
    for (double scale : set.scale) {
        if (scale < settings.texels_per_unit) return false;
    }
    // Each of size_orders on the skyline's lowest place and then, where none fits, on the place
    // that leaves the fewest cells empty under the chart: which fits varies with the density,
    // and any fits. The first that does is kept, so an order after one that fitted is not
    // packed (which ones are skipped depends on the threads, never the layout kept).
    const std::vector<std::vector<size_t>>& orders = set.orders;
    std::vector<size_t> reached;  // per rule and order: the charts placed before one did not fit
    for (bool count_waste : {false, true}) {
        std::vector<PageLayout> layouts(orders.size());
        std::vector<size_t> placed(orders.size());
        std::atomic<size_t> first_fit{orders.size()};
        parallel_for_each(pool, orders.size(), [&](size_t k) {
            if (first_fit.load() < k) return;
            layouts[k] = empty_page_layout(charts.size());
            placed[k] = place_until_full(set.prepared, orders[k], grid, count_waste, layouts[k],
                                         progress.part(0.0, 0.0));
            if (placed[k] < charts.size()) return;
            size_t now = first_fit.load();
            while (k < now && !first_fit.compare_exchange_weak(now, k)) {
            }
        });
        if (first_fit.load() < orders.size()) {
            const PageLayout& layout = layouts[first_fit.load()];
            result = layout_uvs(charts, settings, grid, set, layout);
            rows_used = layout.pages[0]->height;
            return true;
        }
        reached.insert(reached.end(), placed.begin(), placed.end());
    }
    PageLayout repaired;
    if (!repair || charts.size() > kFurtherOrdersUpTo ||
        !repair_orders(set.prepared, orders, reached, grid, pool, progress, repaired))
        return false;
    result = layout_uvs(charts, settings, grid, set, repaired);
    rows_used = repaired.pages[0]->height;
    return true;
}

// The same with the charts prepared at settings.texels_per_unit; rows_used: the rows of the
// page the layout reaches, in cells, when one fits.
bool pack_on_one_page(const std::vector<PackInput>& charts,
                      const std::vector<ChartOutline>& outlines, const PageSettings& settings,
                      const PageGrid& grid, ThreadPool& pool, bool repair,
                      const ProgressSpan& progress, PackResult& result, int32_t& rows_used) {
    return layout_on_one_page(
        charts, settings, grid,
        prepare_charts(charts, outlines, settings, grid, pool, progress.part(0.0, 0.0)), pool,
        repair, progress, result, rows_used);
}

// The charts' area in uv units (3D units), summed triangle by triangle across the charts.
double charts_uv_area(const std::vector<PackInput>& charts) {
    double area = 0;
    for (const PackInput& chart : charts) {
        for (const Triangle& t : *chart.triangles) {
            const Eigen::Vector2d a = (*chart.uv)[t[1]] - (*chart.uv)[t[0]];
            const Eigen::Vector2d b = (*chart.uv)[t[2]] - (*chart.uv)[t[0]];
            area += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
        }
    }
    return area;
}

}  // namespace

PackResult pack_pages(const std::vector<PackInput>& charts, const PageSettings& settings,
                      ThreadPool& pool, const ProgressSpan& progress) {
    const PageGrid grid = checked_grid(settings);
    const std::vector<ChartOutline> outlines =
        chart_outlines(charts, pool, progress.part(0.0, 0.0));
    PreparedCharts set =
        prepare_charts(charts, outlines, settings, grid, pool, progress.part(0.0, 0.0));
    progress.report(0.5);
    // Charts whose area one page holds are first tried on one page the way pack_one_page
    // packs them: at the density it finds, the first-fit order alone could spill onto a
    // second page. Without part_per_page the first order is tried first, so a layout it fits
    // on one page is unchanged. The orders are repaired only where the charts fill at most
    // kRepairFillAtMost of the page.
    const double fill = charts_uv_area(charts) * settings.texels_per_unit *
                        settings.texels_per_unit /
                        (static_cast<double>(settings.max_width) * settings.max_height);
    PackResult one_page;
    int32_t rows_used = 0;
    if (fill <= 1 && layout_on_one_page(charts, settings, grid, set, pool,
                                        fill <= kRepairFillAtMost, progress, one_page, rows_used))
        return one_page;
    PageLayout layout;
    layout.page.assign(charts.size(), 0);
    layout.place.resize(charts.size());
    if (settings.part_per_page) {
        place_parts_per_page(charts, grid, pool, set, layout);
    } else {
        place_first_fit(set.prepared, set.orders[0], grid, layout);
    }
    return layout_uvs(charts, settings, grid, set, layout);
}

PackResult pack_one_page(const std::vector<PackInput>& charts, PageSettings settings,
                         ThreadPool& pool, const ProgressSpan& progress) {
    const PageGrid grid = checked_grid(settings);
    const std::vector<ChartOutline> outlines =
        chart_outlines(charts, pool, progress.part(0.0, 0.0));
    // Above this density the charts' area alone overflows the page, or the longest chart its
    // longer side.
    const double area = charts_uv_area(charts);
    double longest = 0;
    for (const PackInput& chart : charts)
        longest = std::max(longest, orient(chart, settings.rotation).extent.maxCoeff());
    const double side = std::max(settings.max_width, settings.max_height);
    double high = longest > 0 ? side / longest : 1.0;
    if (area > 0) high = std::min(high, std::sqrt(settings.max_width * settings.max_height / area));
    // Down by a fifth until the charts fit, then up until the densities that fit and that do
    // not are within 1%: halfway (geometrically) between them, or, up to kFurtherOrdersAbove
    // charts, after a fit where its layout says the charts would just fill the page (a layout
    // that fits says how many of the page's rows it reaches, and they grow about as the square
    // of the density), at least 1% more so that a failure there ends the search. Measured
    // (docs/bench-packing.md): the lightmaps of the 19 shared meshes in 86 densities instead of
    // 121 and at most 1.2% fewer texels per unit; with more charts, a scene's frontier is
    // chaotic and halving the gap ended denser. A density within kRepairWithin of one that
    // fits is also tried with the orders repaired (repair_orders): its layouts are the ones that
    // fail by a chart or two.
    PackResult best;
    int32_t rows_used = 0;
    double low = high;
    for (int attempt = 0;; ++attempt) {
        low *= 0.8;
        settings.texels_per_unit = low;
        progress.report(0.0);  // each attempt packs every chart again
        if (pack_on_one_page(charts, outlines, settings, grid, pool, false, progress, best,
                             rows_used))
            break;
        high = low;
        if (attempt == 60) {
            throw Error(ErrorCode::kInvalidArgument,
                        "the " + std::to_string(charts.size()) +
                            " charts do not fit one page of the resolution at any density with "
                            "their padding: raise RAPS_PARAM_ATLAS_RESOLUTION or lower the "
                            "padding");
        }
    }
    auto after_fit = [&] {
        if (charts.size() > kFurtherOrdersAbove) return std::sqrt(low * high);
        const double filling = std::max(
            1.01 * low,
            low * std::sqrt(static_cast<double>(grid.rows) / std::max<int32_t>(rows_used, 1)));
        return filling < high ? filling : std::sqrt(low * high);
    };
    double next = after_fit();
    while (high > 1.01 * low) {
        settings.texels_per_unit = next;
        PackResult tried;
        progress.report(0.5);
        const bool repair = next <= kRepairWithin * low;
        if (pack_on_one_page(charts, outlines, settings, grid, pool, repair, progress, tried,
                             rows_used)) {
            low = settings.texels_per_unit;
            best = std::move(tried);
            next = after_fit();
        } else {
            high = settings.texels_per_unit;
            next = std::sqrt(low * high);
        }
    }
    return best;
}

}  // namespace raps
