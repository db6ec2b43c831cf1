#include "atlas/chart_mapping.h"

#include <algorithm>

#include "atlas/polygon_units.h"

namespace raps {

namespace {

// map_chart's work; the chart's Laplace system lives only in here.
bool map_disk(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
              const std::vector<char>& seam, const Settings& settings, const ChartLimits& limits,
              AtlasChart& chart, double& unadapted_l2, const ProgressSpan& beat,
              std::pair<const ChartDisk*, const ChartDisk*> parts) {
    bool good = parts.first ? make_union_chart_disk(surface, triangles, seam, *parts.first,
                                                    *parts.second, chart.disk, beat)
                            : make_chart_disk(surface, triangles, seam, chart.disk, beat);
    if (!good && triangles.size() > 1) return false;
    beat.report(0.0);
    LaplaceSystem system = chart_laplace_system(chart.disk, beat);
    if (good) {
        chart.map = free_boundary_chart_map(chart.disk, system, limits.max_stretch_linf, beat);
        good = chart.map.injective && chart.map.stretch_linf <= limits.max_stretch_linf;
    }
    beat.report(0.0);
    // A polygon that maps badly stays whole (as a triangle does): its corners need one uv each.
    if (!good && !is_one_polygon(surface, triangles)) return false;
    if (!chart.map.injective) chart.map = circle_chart_map(chart.disk, settings, system, beat);
    unadapted_l2 = chart.map.stretch_l2;
    adapt_chart_map(chart.disk, settings, limits.max_stretch_linf, chart.map, system, beat);
    beat.report(0.0);
    chart.box =
        smallest_bounding_box(chart.map.uv, chart.disk.mesh.triangles, chart.disk.boundary_loop);
    return true;
}

}  // namespace

bool map_chart(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
               const std::vector<char>& seam, const Settings& settings, const ChartLimits& limits,
               AtlasChart& chart, double& unadapted_l2, const ProgressSpan& beat,
               std::pair<const ChartDisk*, const ChartDisk*> parts) {
    if (!map_disk(surface, triangles, seam, settings, limits, chart, unadapted_l2, beat, parts))
        return false;
    // Only the map reads the adjacency and the angle sums (about 45 bytes per triangle);
    // a mapped chart is kept through merging and packing without them, which lowers the
    // atlas's peak (reached while merging maps unions beside every kept chart).
    chart.disk.adjacency = VertexAdjacency();
    std::vector<double>().swap(chart.disk.angle_sum);
    return true;
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
