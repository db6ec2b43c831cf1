#include "atlas/corner_sources.h"

#include <algorithm>
#include <map>
#include <utility>

#include "atlas/polygon_units.h"
#include "core/fill_in_runs.h"

namespace raps {

CornerSources corner_sources(const TriangleMesh& mesh, const AtlasParts& parts,
                             const std::vector<int32_t>& welded, const AtlasSurface& surface,
                             const std::vector<AtlasChart>& charts, const ProgressSpan& progress) {
    const int32_t triangle_count = mesh.triangle_count();
    CornerSources sources;
    // Filled in runs (fill_in_runs.h): 39 ms without a progress call at 5.8M triangles.
    const ProgressSpan start = progress.part(0.0, 0.0);
    assign_in_runs(sources.chart, static_cast<size_t>(triangle_count), -1, start);
    assign_in_runs(sources.vertex, static_cast<size_t>(triangle_count), {0, 0, 0}, start);
    // (welded vertex, chart) -> chart vertex, for triangles placed beside a chart; only built
    // when there are such triangles (most meshes have none, and it was most of this step).
    std::map<std::pair<int32_t, int32_t>, int32_t> chart_vertex_of;
    const bool any_aside = !surface.aside_triangles.empty();
    std::vector<int32_t> first_chart_of_welded = filled_in_runs(mesh.positions.size(), -1, start);
    for (size_t c = 0; c < charts.size(); ++c) {
        const ChartDisk& disk = charts[c].disk;
        progress.report(0.8 * static_cast<double>(c) / static_cast<double>(charts.size()));
        for (size_t t = 0; t < disk.surface_triangle.size(); ++t) {
            const int32_t input = surface.input_triangle[disk.surface_triangle[t]];
            sources.chart[input] = static_cast<int32_t>(c);
            sources.vertex[input] = disk.mesh.triangles[t];
        }
        for (size_t v = 0; v < disk.surface_vertex.size(); ++v) {
            const int32_t w = surface.welded_vertex[disk.surface_vertex[v]];
            if (any_aside) {
                chart_vertex_of.emplace(std::make_pair(w, static_cast<int32_t>(c)),
                                        static_cast<int32_t>(v));
            }
            if (first_chart_of_welded[w] < 0) first_chart_of_welded[w] = static_cast<int32_t>(c);
        }
    }
    // Triangles set aside: duplicates copy their primary; degenerate ones go on the chart of
    // their polygon or else of one of their vertices (their uv triangle is then as degenerate
    // as their 3D one).
    const std::vector<int32_t> polygon_chart =
        aside_polygon_charts(mesh, welded, surface, sources.chart);
    std::vector<int32_t> point_chart_of_part(parts.count(), -1);
    const int64_t aside_count = static_cast<int64_t>(surface.aside_triangles.size());
    if (aside_count > 0) sources.copy.assign(triangle_count, 0);
    progress.part(0.8, 1.0).in_runs(aside_count, [&](int64_t run_begin, int64_t run_end) {
        for (int64_t i = static_cast<int64_t>(run_begin); i < run_end; ++i) {
            const int32_t t = surface.aside_triangles[i];
            const Triangle& v = mesh.triangles[t];
            int32_t chart = -1;
            if (surface.aside_primary[i] >= 0) {
                // A copy takes its primary's corners, corner for corner: a welded vertex can lie
                // on one chart more than once (where the chart's boundary passes it twice), and
                // the first of them need not be the primary's (a mesh given twice in one place
                // came out with flipped copies).
                const int32_t primary = surface.input_triangle[surface.aside_primary[i]];
                const Triangle& p = mesh.triangles[primary];
                sources.chart[t] = sources.chart[primary];
                sources.copy[t] = 1;
                for (int k = 0; k < 3; ++k) {
                    for (int j = 0; j < 3; ++j) {
                        if (welded[p[j]] == welded[v[k]])
                            sources.vertex[t][k] = sources.vertex[primary][j];
                    }
                }
                continue;
            }
            if (polygon_chart[i] >= 0) {
                chart = polygon_chart[i];
            } else {
                for (int k = 0; k < 3 && chart < 0; ++k)
                    chart = first_chart_of_welded[welded[v[k]]];
            }
            if (chart < 0) {
                int32_t& point = point_chart_of_part[parts.part_of_triangle(t)];
                if (point < 0) {
                    point = static_cast<int32_t>(charts.size() + sources.point_chart_part.size());
                    sources.point_chart_part.push_back(parts.part_of_triangle(t));
                }
                sources.chart[t] = point;
                continue;
            }
            sources.chart[t] = chart;
            std::array<int32_t, 3>& corner = sources.vertex[t];
            for (int k = 0; k < 3; ++k) {
                const auto it = chart_vertex_of.find({welded[v[k]], chart});
                corner[k] = it != chart_vertex_of.end() ? it->second : -1;
            }
            for (int k = 0; k < 3; ++k) {  // a vertex the chart lacks sits on one it has
                if (corner[k] < 0) corner[k] = std::max({corner[0], corner[1], corner[2], 0});
            }
        }
    });
    return sources;
}

}  // namespace raps
