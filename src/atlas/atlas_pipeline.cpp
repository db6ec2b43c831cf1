#include "atlas/atlas_pipeline.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "atlas/atlas_charts.h"
#include "atlas/atlas_surface.h"
#include "atlas/chart_packing.h"
#include "atlas/chart_segmentation.h"
#include "atlas/vertex_welding.h"
#include "core/portable_math.h"
#include "mesh/mesh_validation.h"

namespace raps {
namespace {

// Charts are scaled to one texel density, so a mesh whose extent dwarfs its triangles (fuzzing
// found a vertex at 1e29 beside a unit-sized patch) leaves every chart thinner than double
// precision resolves next to its place in the atlas: all uv triangles come out with zero area.
// That is no map; say so instead of returning it.
// The weld tolerance can do the same on purpose: merge vertices until no triangle keeps an
// area, leaving no chart, while the input's triangles had area.
void refuse_collapsed_atlas(const TriangleMesh& mesh, double weld_tolerance,
                            const std::vector<AtlasChart>& charts, const PackResult& packed) {
    if (charts.empty()) {
        for (const Triangle& t : mesh.triangles) {
            const Eigen::Vector3d& a = mesh.positions[t[0]];
            if ((mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a).squaredNorm() > 0) {
                char tolerance[32];
                std::snprintf(tolerance, sizeof(tolerance), "%g", weld_tolerance);
                throw Error(
                    ErrorCode::kZeroAreaTriangle,
                    std::string("welding vertices closer than RAPS_PARAM_WELD_TOLERANCE = ") +
                        tolerance + " leaves every triangle with zero area: no chart to map");
            }
        }
        return;  // the input has no area either: every triangle maps to one point
    }
    // Rounding uvs in [0, 1] to doubles leaves collapsed triangles with areas up to about
    // 1e-16 (an ulp times an edge); any real triangle of an atlas is many orders larger.
    for (size_t c = 0; c < charts.size(); ++c) {
        const std::vector<Eigen::Vector2d>& uv = packed.uv[c];
        for (const Triangle& t : charts[c].disk.mesh.triangles) {
            const Eigen::Vector2d a = uv[t[1]] - uv[t[0]], b = uv[t[2]] - uv[t[0]];
            if (std::abs(a.x() * b.y() - a.y() * b.x()) > 2e-14) return;
        }
    }
    throw Error(ErrorCode::kZeroAreaTriangle,
                "every triangle of the atlas has zero uv area: the mesh's extent is too large "
                "next to its triangles for double precision at one texel density");
}

}  // namespace

AtlasOutput build_atlas(const TriangleMesh& mesh, const Settings& settings,
                        const Progress& progress, PhaseTimes& times, ThreadPool& pool) {
    {
        PhaseTimer timer(Phase::kValidate, progress, times);
        check_indices_in_range(mesh);  // everything else an atlas takes as it comes
        timer.finish();
    }
    PhaseTimer topology_timer(Phase::kTopology, progress, times);
    const std::vector<int32_t> welded = weld_vertices(mesh.positions, settings.weld_tolerance);
    const AtlasSurface surface = build_atlas_surface(mesh, welded, pool);
    topology_timer.finish();

    PhaseTimer segment_timer(Phase::kSegment, progress, times);
    SegmentationSettings segmentation;
    // Charts do not grow across creases sharper than 60 degrees (CAD edges): growing across
    // them leaves charts that wrap around corners and must be split again; merging may still
    // join the pieces later where the union maps well (fandisk: 24 -> 6 charts). Creases are
    // forced seams only when the caller's hard-edge angle says so.
    segmentation.hard_edge_angle_deg = std::min(settings.hard_edge_angle_deg, 60.0);
    segmentation.max_normal_deviation_deg = 90.0;
    const std::vector<int32_t> chart_of_surface = segment_charts(surface, segmentation);
    // Hard edges are seams inside charts as well.
    std::vector<char> seam(surface.twin.size(), 0);
    if (settings.hard_edge_angle_deg < 180.0) {
        const double limit = portable::cos(settings.hard_edge_angle_deg * M_PI / 180.0);
        auto normal = [&](int32_t t) {
            const Triangle& v = surface.mesh.triangles[t];
            return (surface.mesh.positions[v[1]] - surface.mesh.positions[v[0]])
                .cross(surface.mesh.positions[v[2]] - surface.mesh.positions[v[0]])
                .normalized();
        };
        for (size_t h = 0; h < seam.size(); ++h) {
            const int32_t o = surface.twin[h];
            seam[h] = o >= 0 && normal(static_cast<int32_t>(h / 3)).dot(normal(o / 3)) < limit;
        }
    }
    segment_timer.finish();

    PhaseTimer chart_timer(Phase::kInitialMap, progress, times);
    ChartLimits limits;
    limits.target_stretch_l2 = settings.atlas_target_l2;
    limits.max_stretch_linf = settings.atlas_max_linf;
    const std::vector<AtlasChart> charts =
        build_charts(surface, chart_of_surface, seam, settings, limits, progress, pool);
    chart_timer.finish();

    PhaseTimer pack_timer(Phase::kPack, progress, times);
    std::vector<PackInput> inputs;
    inputs.reserve(charts.size());
    for (const AtlasChart& chart : charts)
        inputs.push_back({&chart.map.uv, &chart.disk.mesh.triangles, chart.box.rotation});
    PackSettings pack_settings;
    pack_settings.resolution = settings.atlas_resolution;
    pack_settings.padding = settings.atlas_padding;
    const PackResult packed = pack_charts(inputs, pack_settings, pool);
    refuse_collapsed_atlas(mesh, settings.weld_tolerance, charts, packed);
    pack_timer.finish();

    // Output: walk the input triangles in order; each corner becomes the output vertex of its
    // (input vertex, chart, chart vertex), created on first sight.
    AtlasOutput out;
    out.width = packed.width;
    out.height = packed.height;
    out.chart_count = static_cast<int64_t>(charts.size());
    for (const AtlasChart& chart : charts) out.adaptive_solves += chart.map.adaptive_solves;
    const int32_t triangle_count = mesh.triangle_count();
    std::vector<int32_t> chart_of_input(triangle_count, -1), local_of_input(triangle_count, -1);
    // (welded vertex, chart) -> chart vertex, for triangles placed beside a chart; only built
    // when there are such triangles (most meshes have none, and it was most of this step).
    std::map<std::pair<int32_t, int32_t>, int32_t> chart_vertex_of;
    const bool any_aside = !surface.aside_triangles.empty();
    std::vector<int32_t> first_chart_of_welded(mesh.positions.size(), -1);
    for (size_t c = 0; c < charts.size(); ++c) {
        const ChartDisk& disk = charts[c].disk;
        for (size_t t = 0; t < disk.surface_triangle.size(); ++t) {
            const int32_t input = surface.input_triangle[disk.surface_triangle[t]];
            chart_of_input[input] = static_cast<int32_t>(c);
            local_of_input[input] = static_cast<int32_t>(t);
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
    // Triangles set aside: duplicates copy their primary; degenerate ones go on the chart of one
    // of their vertices (their uv triangle is then as degenerate as their 3D one).
    const int32_t point_chart = static_cast<int32_t>(charts.size());
    bool point_chart_used = false;
    std::vector<std::array<int32_t, 3>> aside_corner(triangle_count, {-1, -1, -1});
    for (size_t i = 0; i < surface.aside_triangles.size(); ++i) {
        const int32_t t = surface.aside_triangles[i];
        const Triangle& v = mesh.triangles[t];
        int32_t chart = -1;
        if (surface.aside_primary[i] >= 0) {
            chart = chart_of_input[surface.input_triangle[surface.aside_primary[i]]];
        } else {
            for (int k = 0; k < 3 && chart < 0; ++k) chart = first_chart_of_welded[welded[v[k]]];
        }
        if (chart < 0) {
            chart = point_chart;
            point_chart_used = true;
        }
        chart_of_input[t] = chart;
        for (int k = 0; k < 3; ++k) {
            const auto it = chart_vertex_of.find({welded[v[k]], chart});
            aside_corner[t][k] = it != chart_vertex_of.end() ? it->second : -1;
        }
        for (int k = 0; k < 3; ++k) {  // a vertex the chart lacks sits on one it has
            if (aside_corner[t][k] < 0) {
                aside_corner[t][k] =
                    std::max({aside_corner[t][0], aside_corner[t][1], aside_corner[t][2]});
            }
        }
    }
    if (point_chart_used) ++out.chart_count;

    // Chart vertices numbered globally (chart offsets, the point chart last); each keeps the
    // short list of (input vertex, output vertex) pairs seen at it, usually one.
    std::vector<int64_t> chart_offset(charts.size() + 2, 0);
    for (size_t c = 0; c < charts.size(); ++c) {
        chart_offset[c + 1] =
            chart_offset[c] + static_cast<int64_t>(charts[c].disk.mesh.positions.size());
    }
    chart_offset[charts.size() + 1] = chart_offset[charts.size()] + 1;
    struct Seen {
        int32_t input_vertex;
        uint32_t output_vertex;
        int32_t next;
    };
    std::vector<int32_t> head(static_cast<size_t>(chart_offset.back()), -1);
    std::vector<Seen> seen;
    out.indices.resize(3 * static_cast<size_t>(triangle_count));
    out.chart_of.resize(triangle_count);
    for (int32_t t = 0; t < triangle_count; ++t) {
        const int32_t c = chart_of_input[t];
        out.chart_of[t] = static_cast<uint32_t>(c);
        for (int k = 0; k < 3; ++k) {
            const int32_t input_vertex = mesh.triangles[t][k];
            int32_t chart_vertex = 0;
            if (c != point_chart) {
                chart_vertex = local_of_input[t] >= 0
                                   ? charts[c].disk.mesh.triangles[local_of_input[t]][k]
                                   : std::max(0, aside_corner[t][k]);
            }
            const int64_t global = chart_offset[c] + chart_vertex;
            int32_t found = head[global];
            while (found >= 0 && seen[found].input_vertex != input_vertex) found = seen[found].next;
            if (found < 0) {
                seen.push_back({input_vertex, static_cast<uint32_t>(out.uv.size()), head[global]});
                found = head[global] = static_cast<int32_t>(seen.size() - 1);
                out.remap.push_back(static_cast<uint32_t>(input_vertex));
                out.uv.push_back(c == point_chart ? Eigen::Vector2d::Zero()
                                                  : packed.uv[c][chart_vertex]);
            }
            out.indices[3 * static_cast<size_t>(t) + k] = seen[found].output_vertex;
        }
    }
    return out;
}

}  // namespace raps
