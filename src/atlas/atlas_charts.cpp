#include "atlas/atlas_charts.h"

#include <algorithm>
#include <cmath>

#include "atlas/chart_merging.h"
#include "atlas/chart_segmentation.h"
#include "atlas/local_index.h"
#include "atlas/polygon_units.h"

namespace raps {
namespace {

// Per chart triangle i, the chart triangle across its side k (3i+k), or -1: outside the chart
// or across a seam.
std::vector<int32_t> chart_neighbours(const AtlasSurface& surface,
                                      const std::vector<int32_t>& triangles,
                                      const std::vector<char>& seam) {
    const LocalIndex local(triangles, surface.mesh.triangles.size());
    std::vector<int32_t> neighbour(3 * triangles.size(), -1);
    for (size_t i = 0; i < triangles.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            const int32_t h = 3 * triangles[i] + k, o = surface.twin[h];
            if (o >= 0 && !seam[h]) neighbour[3 * i + k] = local(o / 3);
        }
    }
    return neighbour;
}

// Hops from chart triangle `from` to every chart triangle (-1: not reached).
std::vector<int32_t> hops(const std::vector<int32_t>& neighbour, int32_t from) {
    std::vector<int32_t> distance(neighbour.size() / 3, -1), frontier = {from};
    distance[from] = 0;
    for (size_t i = 0; i < frontier.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            const int32_t o = neighbour[3 * frontier[i] + k];
            if (o < 0 || distance[o] >= 0) continue;
            distance[o] = distance[frontier[i]] + 1;
            frontier.push_back(o);
        }
    }
    return distance;
}

// Splits `triangles` in two: breadth-first from one end of the chart to find its farthest
// triangle a, from a to find b, then every triangle goes to the nearer of a and b (ties to a).
std::pair<std::vector<int32_t>, std::vector<int32_t>> split_chart(
    const AtlasSurface& surface, const std::vector<int32_t>& triangles,
    const std::vector<char>& seam, const ProgressSpan& beat) {
    const std::vector<int32_t> neighbour = chart_neighbours(surface, triangles, seam);
    auto farthest = [](const std::vector<int32_t>& distance) {
        return static_cast<int32_t>(std::max_element(distance.begin(), distance.end()) -
                                    distance.begin());
    };
    const int32_t a = farthest(hops(neighbour, 0));
    beat.report(0.0);
    const std::vector<int32_t> from_a = hops(neighbour, a);
    beat.report(0.0);
    const int32_t b = farthest(from_a);
    const std::vector<int32_t> from_b = hops(neighbour, b);
    beat.report(0.0);
    // Side per chart triangle, smoothed like the segmentation's boundaries so the split does
    // not leave a saw-tooth seam.
    std::vector<int32_t> side(triangles.size());
    for (size_t i = 0; i < triangles.size(); ++i) {
        // Unreached triangles (a chart in several pieces) follow a's side if not reached by b.
        const bool to_b = from_b[i] >= 0 && (from_a[i] < 0 || from_b[i] < from_a[i]);
        side[i] = to_b ? 1 : 0;
    }
    keep_polygons_together(surface, triangles, neighbour, side);
    smooth_chart_boundaries(neighbour, side, beat, polygon_triangles(surface, triangles));
    auto halve = [&] {
        std::pair<std::vector<int32_t>, std::vector<int32_t>> halves;
        for (size_t i = 0; i < triangles.size(); ++i)
            (side[i] == 1 ? halves.second : halves.first).push_back(triangles[i]);
        return halves;
    };
    auto halves = halve();
    if (halves.first.empty() || halves.second.empty()) {
        // One triangle or polygon, or nothing reachable: halve by polygons in their order.
        halve_by_polygons(surface, triangles, neighbour, side);
        halves = halve();
    }
    return halves;
}

// The charts made so far, with what the L2 budget weighs them by.
struct MappedCharts {
    std::vector<AtlasChart> charts;
    // Per chart, its L2 stretch before the adaptive step: the budget splits charts by it, while
    // merging judges by the adapted maps.
    std::vector<double> unadapted_l2;
};

// What every step of building the charts works with.
struct ChartWork {
    const AtlasSurface& surface;
    const std::vector<char>& seam;
    const Settings& settings;
    const ChartLimits& limits;
    const Progress& progress;
    ThreadPool& pool;
    // Inside a chart the work repeats the fraction reached (a span at 0, which the phase's
    // progress never lets fall), so that a cancel is seen inside the largest charts too.
    ProgressSpan beat;
    double done_triangles = 0;
};

// Progress: the first maps by their share of the triangles to kMapped, then each merge pass
// half of what is left, by its share of candidates.
constexpr double kMapped = 0.4;

// Rounds: every pending chart in parallel; the ones that fail are split into the next round.
// Each chart's result lands in its own slot, so the outcome is the same for any thread count.
void map_in_rounds(ChartWork& work, std::vector<std::vector<int32_t>> round, MappedCharts& out) {
    const double total_triangles = static_cast<double>(work.surface.mesh.triangles.size());
    while (!round.empty()) {
        std::vector<AtlasChart> built(round.size());
        std::vector<char> good(round.size(), 0);
        std::vector<double> built_l2(round.size(), 0.0);
        std::vector<size_t> cost(round.size());
        for (size_t i = 0; i < round.size(); ++i) cost[i] = round[i].size();
        parallel_largest_first(work.pool, cost, [&](size_t i) {
            good[i] = map_chart(work.surface, round[i], work.seam, work.settings, work.limits,
                                built[i], built_l2[i], work.beat);
            // The chart keeps its own copy of its triangles: the list goes while the other
            // charts of the round are still being mapped (the first round holds them all).
            if (good[i]) std::vector<int32_t>().swap(round[i]);
            work.progress.report(Phase::kInitialMap,
                                 kMapped * std::min(1.0, work.done_triangles / total_triangles));
        });
        std::vector<std::vector<int32_t>> next;
        for (size_t i = 0; i < round.size(); ++i) {
            if (good[i]) {
                work.done_triangles += static_cast<double>(built[i].disk.surface_triangle.size());
                out.charts.push_back(std::move(built[i]));
                out.unadapted_l2.push_back(built_l2[i]);
            } else {
                auto halves = split_chart(work.surface, round[i], work.seam, work.beat);
                next.push_back(std::move(halves.first));
                next.push_back(std::move(halves.second));
            }
        }
        round = std::move(next);
    }
}

// The L2 budget: splits the largest contributor to the atlas's stretch until it meets the
// target (or nothing splittable is left). Returns each chart's area and sets the target: the
// budget of the sum over charts of area times L2 squared.
std::vector<double> split_for_budget(ChartWork& work, MappedCharts& mapped, double& target) {
    std::vector<AtlasChart>& charts = mapped.charts;
    std::vector<double>& l2 = mapped.unadapted_l2;
    std::vector<double> area(charts.size());
    double total_area = 0, weighted = 0;
    for (size_t c = 0; c < charts.size(); ++c) {
        area[c] = chart_area(charts[c].disk);
        total_area += area[c];
        weighted += area[c] * l2[c] * l2[c];
    }
    target = work.limits.target_stretch_l2 * work.limits.target_stretch_l2 * total_area;
    while (weighted > target) {
        size_t worst = charts.size();
        double worst_excess = 0;
        for (size_t c = 0; c < charts.size(); ++c) {
            const double excess = area[c] * (l2[c] * l2[c] - 1.0);
            if (excess > worst_excess &&
                !is_one_polygon(work.surface, charts[c].disk.surface_triangle)) {
                worst = c;
                worst_excess = excess;
            }
        }
        if (worst == charts.size()) break;
        const std::vector<int32_t> triangles = charts[worst].disk.surface_triangle;
        weighted -= area[worst] * l2[worst] * l2[worst];
        charts.erase(charts.begin() + static_cast<std::ptrdiff_t>(worst));
        area.erase(area.begin() + static_cast<std::ptrdiff_t>(worst));
        l2.erase(l2.begin() + static_cast<std::ptrdiff_t>(worst));
        const size_t before = charts.size();
        auto halves = split_chart(work.surface, triangles, work.seam, work.beat);
        map_in_rounds(work, {std::move(halves.first), std::move(halves.second)}, mapped);
        for (size_t c = before; c < charts.size(); ++c) {
            area.push_back(chart_area(charts[c].disk));
            weighted += area.back() * l2[c] * l2[c];
        }
    }
    return area;
}

}  // namespace

std::vector<AtlasChart> build_charts(const AtlasSurface& surface, std::vector<int32_t> chart_of,
                                     const std::vector<char>& seam, const Settings& settings,
                                     const ChartLimits& limits, const Progress& progress,
                                     ThreadPool& pool) {
    ChartWork work{surface, seam, settings, limits, progress, pool,
                   ProgressSpan(progress, Phase::kInitialMap, 0.0, 0.0)};
    const int64_t triangle_count = static_cast<int64_t>(chart_of.size());
    int32_t count = 0;
    for (int32_t c : chart_of) count = std::max(count, c + 1);
    // Each chart's triangles, reserved to their count (no doubling's slack); chart_of goes as
    // soon as they are listed, before the first maps (where large meshes peak).
    std::vector<size_t> size(count, 0);
    work.beat.in_runs(triangle_count, [&](int64_t begin, int64_t end) {
        for (int64_t t = begin; t < end; ++t) ++size[chart_of[t]];
    });
    std::vector<std::vector<int32_t>> pending(count);
    for (int32_t c = 0; c < count; ++c) pending[c].reserve(size[c]);
    work.beat.in_runs(triangle_count, [&](int64_t begin, int64_t end) {
        for (int64_t t = begin; t < end; ++t)
            pending[chart_of[t]].push_back(static_cast<int32_t>(t));
    });
    std::vector<int32_t>().swap(chart_of);
    MappedCharts mapped;
    map_in_rounds(work, std::move(pending), mapped);
    double target = 0;
    const std::vector<double> area = split_for_budget(work, mapped, target);
    // Merging judges the charts by their adapted maps: the budget counts what they will really
    // stretch (the free-boundary figures above overstate it).
    std::vector<AtlasChart> charts = std::move(mapped.charts);
    merge_charts(surface, seam, settings, limits, target, charts, area, progress, kMapped,
                 work.beat, pool);
    // In order of their first triangles, each chart's first in its list (ascending: see
    // chart_merging.cpp; a search of every list in every comparison was 40 ms without a
    // progress call at 3.3M triangles).
    std::sort(charts.begin(), charts.end(), [](const AtlasChart& x, const AtlasChart& y) {
        return x.disk.surface_triangle.front() < y.disk.surface_triangle.front();
    });
    return charts;
}

}  // namespace raps
