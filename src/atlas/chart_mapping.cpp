#include "atlas/chart_mapping.h"

#include <algorithm>

#include "atlas/polygon_units.h"

namespace raps {

namespace {

// map_chart's work; the chart's Laplace system lives only in here. `parts`: the two charts of a
// union, whose `union_limits` are then tested.
UnionVerdict map_disk(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
                      const std::vector<char>& seam, const Settings& settings,
                      const ChartLimits& limits, AtlasChart& chart, double& unadapted_l2,
                      const ProgressSpan& beat,
                      std::pair<const ChartDisk*, const ChartDisk*> parts,
                      const UnionLimits& union_limits) {
    bool good = parts.first ? make_union_chart_disk(surface, triangles, seam, *parts.first,
                                                    *parts.second, chart.disk, beat)
                            : make_chart_disk(surface, triangles, seam, chart.disk, beat);
    if (!good && triangles.size() > 1) return UnionVerdict::kFailed;
    beat.report(0.0);
    LaplaceSystem system = chart_laplace_system(chart.disk, beat);
    if (good) {
        chart.map = free_boundary_chart_map(chart.disk, system, limits.max_stretch_linf,
                                            union_limits.give_up_l2, beat);
        if (chart.map.over_l2) return UnionVerdict::kOverL2;
        good = chart.map.injective && chart.map.stretch_linf <= limits.max_stretch_linf;
    }
    beat.report(0.0);
    // A polygon that maps badly stays whole (as a triangle does): its corners need one uv each.
    if (!good && !is_one_polygon(surface, triangles)) return UnionVerdict::kFailed;
    if (!chart.map.injective) chart.map = circle_chart_map(chart.disk, settings, system, beat);
    unadapted_l2 = chart.map.stretch_l2;
    // The adaptive step holds the boundary, so the box it will have is known before it.
    if (union_limits.min_fill > 0 &&
        smallest_bounding_box(chart.map.uv, chart.disk.mesh.triangles, chart.disk.boundary_loop)
                .fill < union_limits.min_fill) {
        return UnionVerdict::kUnderFill;
    }
    adapt_chart_map(chart.disk, settings, limits.max_stretch_linf, chart.map, system, beat);
    beat.report(0.0);
    chart.box =
        smallest_bounding_box(chart.map.uv, chart.disk.mesh.triangles, chart.disk.boundary_loop);
    return UnionVerdict::kMapped;
}

// Only the map reads the adjacency and the angle sums (about 45 bytes per triangle); a mapped
// chart is kept through merging and packing without them, which lowers the atlas's peak
// (reached while merging maps unions beside every kept chart).
void drop_map_inputs(ChartDisk& disk) {
    disk.adjacency = VertexAdjacency();
    std::vector<double>().swap(disk.angle_sum);
}

}  // namespace

bool map_chart(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
               const std::vector<char>& seam, const Settings& settings, const ChartLimits& limits,
               AtlasChart& chart, double& unadapted_l2, const ProgressSpan& beat) {
    if (map_disk(surface, triangles, seam, settings, limits, chart, unadapted_l2, beat, {}, {}) !=
        UnionVerdict::kMapped) {
        return false;
    }
    drop_map_inputs(chart.disk);
    return true;
}

UnionVerdict map_union_chart(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
                             const std::vector<char>& seam, const Settings& settings,
                             const ChartLimits& limits, const ChartDisk& a, const ChartDisk& b,
                             const UnionLimits& union_limits, AtlasChart& chart,
                             const ProgressSpan& beat) {
    double unadapted_l2 = 0;
    const UnionVerdict verdict = map_disk(surface, triangles, seam, settings, limits, chart,
                                          unadapted_l2, beat, {&a, &b}, union_limits);
    drop_map_inputs(chart.disk);
    return verdict;
}

double chart_area(const ChartDisk& disk) {
    double area = 0;
    for (const Triangle& t : disk.mesh.triangles) {
        area += 0.5 * (disk.mesh.positions[t[1]] - disk.mesh.positions[t[0]])
                          .cross(disk.mesh.positions[t[2]] - disk.mesh.positions[t[0]])
                          .norm();
    }
    return area;
}

void parallel_largest_first(ThreadPool& pool, const std::vector<size_t>& cost,
                            const std::function<void(size_t)>& body) {
    std::vector<size_t> order(cost.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return cost[a] > cost[b]; });
    parallel_for_each(pool, order.size(), [&](size_t k) { body(order[k]); });
}

}  // namespace raps
