#include "atlas/atlas_pipeline.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "atlas/atlas_charts.h"
#include "atlas/atlas_surface.h"
#include "atlas/chart_box.h"
#include "atlas/chart_packing.h"
#include "atlas/chart_segmentation.h"
#include "atlas/chart_stacking.h"
#include "atlas/corner_sources.h"
#include "atlas/instanced_parts.h"
#include "atlas/long_chart_split.h"
#include "atlas/page_packing.h"
#include "atlas/polygon_units.h"
#include "atlas/user_seams.h"
#include "atlas/uv_repack.h"
#include "atlas/vertex_welding.h"
#include "core/fill_in_runs.h"
#include "core/hash_mix.h"
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
        bool underflows = false;  // areas whose squares doubles cannot hold (a mesh at 1e-80)
        for (const Triangle& t : mesh.triangles) {
            const Eigen::Vector3d& a = mesh.positions[t[0]];
            const Eigen::Vector3d normal =
                (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a);
            underflows = underflows || normal.cwiseAbs().maxCoeff() > 0;
            if (normal.squaredNorm() > 0) {
                char tolerance[32];
                std::snprintf(tolerance, sizeof(tolerance), "%g", weld_tolerance);
                throw Error(
                    ErrorCode::kZeroAreaTriangle,
                    std::string("welding vertices closer than RAPS_PARAM_WELD_TOLERANCE = ") +
                        tolerance + " leaves every triangle with zero area: no chart to map");
            }
        }
        if (underflows) {
            throw Error(ErrorCode::kZeroAreaTriangle,
                        "every triangle's area is below what doubles resolve: the mesh is too "
                        "small (its triangles' squared areas underflow); scale it up");
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
    // Either the charts are far below a texel at the density asked for (a mesh in the wrong
    // units), or one texel density cannot hold the mesh's extent and its triangles at once.
    double longest = 0;  // texels
    for (const AtlasChart& chart : charts) {
        longest = std::max(longest, turned_box(chart.map.uv, chart.box.rotation).extent.maxCoeff() *
                                        packed.texels_per_unit);
    }
    if (longest < 1) {
        char figures[96];
        std::snprintf(figures, sizeof(figures), "at %g texels per unit the largest chart is %.3g",
                      packed.texels_per_unit, longest);
        throw Error(ErrorCode::kZeroAreaTriangle,
                    std::string("every triangle of the atlas has zero uv area: ") + figures +
                        " texels across, far below the texel the charts are placed on (raise "
                        "RAPS_PARAM_ATLAS_TEXELS_PER_UNIT or scale the mesh up)");
    }
    throw Error(ErrorCode::kZeroAreaTriangle,
                "every triangle of the atlas has zero uv area: the mesh's extent is too large "
                "next to its triangles for double precision at one texel density");
}

// Welds within each part only: parts that touch (or overlap) in space stay apart, so no chart
// crosses from one mesh of a scene to another.
std::vector<int32_t> weld_parts(const TriangleMesh& mesh, const AtlasParts& parts, double tolerance,
                                const ProgressSpan& progress) {
    if (parts.count() == 1) return weld_vertices(mesh.positions, tolerance, progress);
    std::vector<int32_t> welded(mesh.positions.size());
    for (int32_t p = 0; p < parts.count(); ++p) {
        const auto begin = mesh.positions.begin() + parts.first_vertex[p];
        const auto end = mesh.positions.begin() + parts.first_vertex[p + 1];
        const std::vector<int32_t> local =
            weld_vertices(std::vector<Eigen::Vector3d>(begin, end), tolerance,
                          progress.part(static_cast<double>(p) / parts.count(),
                                        static_cast<double>(p + 1) / parts.count()));
        for (size_t v = 0; v < local.size(); ++v)
            welded[parts.first_vertex[p] + v] = parts.first_vertex[p] + local[v];
    }
    return welded;
}

// Seams inside charts: hard edges (none at the default angle of 180 degrees).
std::vector<char> hard_edge_seams(const AtlasSurface& surface, double hard_edge_angle_deg,
                                  const ProgressSpan& progress) {
    std::vector<char> seam(surface.twin.size(), 0);
    if (hard_edge_angle_deg >= 180.0) return seam;
    const double limit = portable::cos(hard_edge_angle_deg * M_PI / 180.0);
    auto normal = [&](int32_t t) {
        const Triangle& v = surface.mesh.triangles[t];
        return (surface.mesh.positions[v[1]] - surface.mesh.positions[v[0]])
            .cross(surface.mesh.positions[v[2]] - surface.mesh.positions[v[0]])
            .normalized();
    };
    for (size_t h = 0; h < seam.size(); ++h) {
        progress.at(static_cast<int64_t>(h), static_cast<int64_t>(seam.size()));
        const int32_t o = surface.twin[h];
        // A polygon's own edges stay inside it, bent or not (its corners get one uv each).
        seam[h] = o >= 0 && !joins_polygon(surface, static_cast<int32_t>(h)) &&
                  normal(static_cast<int32_t>(h / 3)).dot(normal(o / 3)) < limit;
    }
    return seam;
}

// Output vertex numbers by key (chart vertex << 32 | input vertex): open addressing with
// linear probing, doubled at half load, so it stays about as large as the output.
class OutputVertexTable {
  public:
    // Filled in runs (fill_in_runs.h): at 5.8M triangles the table and the output's index
    // arrays, filled in one go, were 110 ms without a progress call.
    OutputVertexTable(size_t expected, const ProgressSpan& progress) {
        assign_in_runs(keys_, hash_table_size(expected), kEmpty, progress.part(0.0, 0.5));
        assign_in_runs(values_, keys_.size(), uint32_t{0}, progress.part(0.5, 1.0));
    }

    // The number stored under `key`, or `candidate` stored there now (second: true).
    std::pair<uint32_t, bool> find_or_add(uint64_t key, uint32_t candidate) {
        size_t i = slot_of(key);
        if (keys_[i] == key) return {values_[i], false};
        keys_[i] = key;
        values_[i] = candidate;
        if (++used_ > keys_.size() / 2) grow();
        return {candidate, true};
    }

  private:
    static constexpr uint64_t kEmpty = ~uint64_t{0};  // chart vertices stay below 2^31

    size_t slot_of(uint64_t key) const {
        const size_t mask = keys_.size() - 1;
        size_t i = mix_bits(key) & mask;
        while (keys_[i] != kEmpty && keys_[i] != key) i = (i + 1) & mask;
        return i;
    }

    void grow() {
        std::vector<uint64_t> keys(2 * keys_.size(), kEmpty);
        std::vector<uint32_t> values(keys.size());
        keys.swap(keys_);
        values.swap(values_);
        for (size_t i = 0; i < keys.size(); ++i) {
            if (keys[i] == kEmpty) continue;
            const size_t j = slot_of(keys[i]);
            keys_[j] = keys[i];
            values_[j] = values[i];
        }
    }

    std::vector<uint64_t> keys_;
    std::vector<uint32_t> values_;
    size_t used_ = 0;
};

// Output: walk the input triangles in order; each corner becomes the output vertex of its
// (input vertex, chart, chart vertex), created on first sight. Parts never share a chart, so
// each part's output vertices come out contiguous.
void emit_output(const TriangleMesh& mesh, const AtlasParts& parts,
                 const std::vector<AtlasChart>& charts, const CornerSources& sources,
                 const PackResult& packed, AtlasOutput& out, const ProgressSpan& progress) {
    // Chart vertices numbered globally (chart offsets, the point charts last, one vertex
    // each). An output vertex is a (chart vertex, input vertex) pair, numbered in the order the
    // corners first name it, found in a hash table of the pairs: a list per chart vertex was
    // quadratic where many input vertices weld to one point (30,000 collapsed triangles: 27 s),
    // and a list per input vertex would be where one vertex lies in many charts.
    const size_t all_charts = charts.size() + sources.point_chart_part.size();
    std::vector<int64_t> chart_offset(all_charts + 1, 0);
    for (size_t c = 0; c < all_charts; ++c) {
        chart_offset[c + 1] =
            chart_offset[c] +
            (c < charts.size() ? static_cast<int64_t>(charts[c].disk.mesh.positions.size()) : 1);
    }
    const ProgressSpan start = progress.part(0.0, 0.0);
    OutputVertexTable table(mesh.positions.size(), start);
    const int32_t triangle_count = mesh.triangle_count();
    assign_in_runs(out.indices, 3 * static_cast<size_t>(triangle_count), uint32_t{0}, start);
    assign_in_runs(out.chart_of, static_cast<size_t>(triangle_count), uint32_t{0}, start);
    out.first_output_vertex.assign(1, 0);
    progress.in_runs(triangle_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            while (t == parts.first_triangle[out.first_output_vertex.size()])
                out.first_output_vertex.push_back(static_cast<int64_t>(out.uv.size()));
            const int32_t c = sources.chart[t];
            const bool point = c >= static_cast<int32_t>(charts.size());
            out.chart_of[t] = static_cast<uint32_t>(c);
            for (int k = 0; k < 3; ++k) {
                const int32_t input_vertex = mesh.triangles[t][k];
                const int32_t chart_vertex = point ? 0 : sources.vertex[t][k];
                const uint64_t global = static_cast<uint64_t>(chart_offset[c] + chart_vertex);
                const auto [output_vertex, added] =
                    table.find_or_add(global << 32 | static_cast<uint32_t>(input_vertex),
                                      static_cast<uint32_t>(out.uv.size()));
                if (added) {
                    out.remap.push_back(static_cast<uint32_t>(input_vertex));
                    out.uv.push_back(point ? Eigen::Vector2d::Zero() : packed.uv[c][chart_vertex]);
                }
                out.indices[3 * static_cast<size_t>(t) + k] = output_vertex;
            }
        }
    });
    while (out.first_output_vertex.size() <= static_cast<size_t>(parts.count()))
        out.first_output_vertex.push_back(static_cast<int64_t>(out.uv.size()));
}

// The chart records: what the packer did with each chart, and its areas, measured on the
// output (texel rectangles from the uvs as a texture of the page's size maps them).
void record_charts(const TriangleMesh& mesh, const AtlasParts& parts,
                   const std::vector<AtlasChart>& charts, const CornerSources& sources,
                   const PackResult& packed, const std::vector<int32_t>& place, AtlasOutput& out,
                   const ProgressSpan& progress) {
    const size_t all_charts = charts.size() + sources.point_chart_part.size();
    out.charts.assign(all_charts, AtlasChartRecord());
    std::vector<Eigen::Vector2d> low(all_charts, Eigen::Vector2d::Constant(1e300));
    std::vector<Eigen::Vector2d> high(all_charts, Eigen::Vector2d::Constant(-1e300));
    const Eigen::Vector2d size(out.width, out.height);
    progress.in_runs(mesh.triangle_count(), [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            AtlasChartRecord& record = out.charts[out.chart_of[t]];
            record.part = parts.part_of_triangle(t);
            ++record.triangle_count;
            if (!sources.copy.empty() && sources.copy[t]) continue;  // its original's area
            const Triangle& v = mesh.triangles[t];
            record.area_3d += 0.5 * (mesh.positions[v[1]] - mesh.positions[v[0]])
                                        .cross(mesh.positions[v[2]] - mesh.positions[v[0]])
                                        .norm();
            Eigen::Vector2d p[3];
            for (int k = 0; k < 3; ++k) {
                p[k] = out.uv[out.indices[3 * static_cast<size_t>(t) + k]].cwiseProduct(size);
                low[out.chart_of[t]] = low[out.chart_of[t]].cwiseMin(p[k]);
                high[out.chart_of[t]] = high[out.chart_of[t]].cwiseMax(p[k]);
            }
            const Eigen::Vector2d a = p[1] - p[0], b = p[2] - p[0];
            record.area_texels += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
        }
    });
    for (size_t c = 0; c < all_charts; ++c) {
        AtlasChartRecord& record = out.charts[c];
        // Texels touched: a chart placed on whole texels starts exactly on a texel's edge,
        // which rounding to the page's size may leave a hair below.
        const Eigen::Vector2i lo((low[c].array() + 1e-9).floor().cast<int>());
        const Eigen::Vector2i hi((high[c].array() - 1e-9).ceil().cast<int>());
        record.x = lo.x();
        record.y = lo.y();
        record.width = std::max(1, hi.x() - lo.x());
        record.height = std::max(1, hi.y() - lo.y());
        record.stacked_on = c < charts.size() ? place[c] : static_cast<int64_t>(c);
        if (c < charts.size()) {
            record.page = packed.page[c];
            record.rotation_deg = packed.rotation_deg[c];
            record.scaled_down = packed.scaled_down[c] != 0;
            record.stretch_l2 = charts[c].map.stretch_l2;
        }
    }
}

// The page settings at a density, or, for whole texels at a resolution, of the one page.
PageSettings page_settings(const Settings& settings) {
    PageSettings pages;
    pages.texels_per_unit = settings.atlas_texels_per_unit;
    const bool at_density = settings.atlas_texels_per_unit > 0;
    pages.max_width = at_density ? settings.atlas_max_width : settings.atlas_resolution;
    pages.max_height = at_density ? settings.atlas_max_height : settings.atlas_resolution;
    pages.padding = settings.atlas_padding;
    pages.margin = settings.atlas_margin;
    pages.block_align = settings.atlas_block_align;
    pages.rotation = settings.atlas_rotation;
    pages.part_per_page = settings.atlas_mesh_per_page;
    return pages;
}

// Above this many charts, the square of the resolution is filled by the whole-texel packer,
// which searches the density at the charts' final texels; pack_charts's search (every trial
// with holes filled, pair swaps) is for fewer, and ranked layouts on the skyline alone to bound
// its time beyond 100. Measured (docs/square-atlas.md): the ten-mesh scene (157 charts) 3.30 ->
// 3.39 texels per unit; noisy scans of 110 to 139 charts +0.05 to +0.08 of the square. Up to
// 100 charts pack_charts is denser on most shared meshes (up to 0.1 of the square).
constexpr size_t kSquareOnWholeTexelsAbove = 100;

// The whole-texel page at a resolution as the square atlas of the resolution (the lightmap of a
// fixed size it is for): its uvs, normalised per axis to the page's cropped width x height,
// become texels over the resolution on both axes, and the page's texels stay whole.
PackResult as_square(PackResult page, int32_t resolution) {
    const double to_u = static_cast<double>(page.width) / resolution;
    const double to_v = static_cast<double>(page.height) / resolution;
    for (std::vector<Eigen::Vector2d>& chart_uv : page.uv) {
        for (Eigen::Vector2d& at : chart_uv) at = Eigen::Vector2d(at.x() * to_u, at.y() * to_v);
    }
    page.width = page.height = resolution;
    return page;
}

// At a density, onto pages; at a resolution, into its square: on whole texels at the largest
// density that fits, or with pack_charts's search.
PackResult pack(const std::vector<PackInput>& inputs, const Settings& settings, ThreadPool& pool,
                const ProgressSpan& progress) {
    if (settings.atlas_texels_per_unit > 0)
        return pack_pages(inputs, page_settings(settings), pool, progress);
    if (settings.atlas_whole_texels) {
        return as_square(pack_one_page(inputs, page_settings(settings), pool, progress),
                         settings.atlas_resolution);
    }
    if (inputs.size() > kSquareOnWholeTexelsAbove) {
        PageSettings square = page_settings(settings);
        square.margin = 0;  // the lightmap settings are the whole-texel atlas's, not this one's
        square.block_align = false;
        return as_square(pack_one_page(inputs, square, pool, progress), settings.atlas_resolution);
    }
    PackSettings pack_settings;
    pack_settings.resolution = settings.atlas_resolution;
    pack_settings.padding = settings.atlas_padding;
    pack_settings.rotation = settings.atlas_rotation;
    return pack_charts(inputs, pack_settings, pool, progress);
}

// Per chart, the chart whose place it takes (RAPS_PARAM_ATLAS_STACK), itself when none.
std::vector<int32_t> chart_places(const std::vector<AtlasChart>& charts,
                                  const std::vector<int32_t>& part, const Settings& settings) {
    if (settings.atlas_stack == ChartStacking::kNone) {
        std::vector<int32_t> place(charts.size());
        for (size_t c = 0; c < place.size(); ++c) place[c] = static_cast<int32_t>(c);
        return place;
    }
    StackSettings stacking;
    stacking.allow_mirror = settings.atlas_stack == ChartStacking::kMirrored;
    stacking.tolerance = settings.atlas_stack_tolerance;
    stacking.within_part = settings.atlas_mesh_per_page;
    stacking.compare_uvs = settings.atlas_repack;
    return stack_charts(charts, part, stacking);
}

// Packs the charts that hold a place; the stacked ones take their place's uvs, page and turn.
PackResult pack_places(const std::vector<AtlasChart>& charts, const std::vector<int32_t>& part,
                       const std::vector<int32_t>& place, const Settings& settings,
                       ThreadPool& pool, const ProgressSpan& progress) {
    std::vector<PackInput> inputs;
    std::vector<int32_t> slot(charts.size(), -1);
    for (size_t c = 0; c < charts.size(); ++c) {
        if (place[c] != static_cast<int32_t>(c)) continue;
        slot[c] = static_cast<int32_t>(inputs.size());
        const AtlasChart& chart = charts[c];
        inputs.push_back({&chart.map.uv, &chart.disk.mesh.triangles, chart.box.rotation, part[c]});
    }
    PackResult packed = pack(inputs, settings, pool, progress);
    if (inputs.size() == charts.size()) return packed;
    PackResult all = packed;
    all.uv.resize(charts.size());
    all.page.resize(charts.size());
    all.rotation_deg.resize(charts.size());
    all.scaled_down.resize(charts.size());
    for (size_t c = 0; c < charts.size(); ++c) {
        const int32_t s = slot[place[c]];
        all.uv[c] = packed.uv[s];
        all.page[c] = packed.page[s];
        all.rotation_deg[c] = packed.rotation_deg[s];
        all.scaled_down[c] = packed.scaled_down[s];
    }
    return all;
}

// A page must keep room for a chart inside its margin: refused before any work is done. At a
// resolution, the square must keep a texel for a chart inside the padding on both of its sides
// and a texel that its conservative raster may touch on each (pack_charts's density bound).
void check_page_settings(const Settings& settings) {
    if (settings.atlas_texels_per_unit <= 0 && !settings.atlas_whole_texels) {
        const int64_t resolution = settings.atlas_resolution, padding = settings.atlas_padding;
        if (resolution - 2 * padding - 2 < 1) {
            throw Error(ErrorCode::kInvalidArgument,
                        "an atlas of " + std::to_string(resolution) + " x " +
                            std::to_string(resolution) + " texels with a padding of " +
                            std::to_string(padding) +
                            " texels on each side of a chart leaves no texel for the chart: "
                            "raise RAPS_PARAM_ATLAS_RESOLUTION or lower RAPS_PARAM_ATLAS_PADDING");
        }
        return;
    }
    const PageSettings pages = page_settings(settings);
    const int32_t block = pages.block_align ? 4 : 1;
    const int32_t margin = (pages.margin + block - 1) / block * block;
    const int32_t inner = std::min(pages.max_width, pages.max_height) - 2 * margin;
    if (inner < block || inner <= pages.padding) {
        throw Error(ErrorCode::kInvalidArgument,
                    "a page of at most " + std::to_string(pages.max_width) + " x " +
                        std::to_string(pages.max_height) + " texels leaves " +
                        std::to_string(std::max(inner, 0)) + " texels inside its margin of " +
                        std::to_string(margin) + ", no more than the padding of " +
                        std::to_string(pages.padding) + ": no chart fits");
    }
}

// The charts and where each input triangle's corners come from, with each chart's part.
struct ChartSet {
    std::vector<AtlasChart> charts;
    CornerSources sources;
    std::vector<int32_t> part;  // per chart
    // Mapped charts: what their corner sources are found from (corner_sources_of).
    std::vector<int32_t> welded;
    AtlasSurface surface;       // only its maps to the input: mapped_charts empties the rest
    LongChartCuts cuts_to_try;  // charts that may pack better cut (long_chart_split.h)
};

// Steps 2-4: the surface, grown into charts, each cut to a disk and mapped (their corner
// sources are found in the packing phase: corner_sources_of).
ChartSet mapped_charts(const TriangleMesh& mesh, const AtlasParts& parts, const Settings& settings,
                       const Progress& progress, PhaseTimes& times, ThreadPool& pool) {
    ChartSet set;
    PhaseTimer topology_timer(Phase::kTopology, progress, times);
    set.welded = weld_parts(mesh, parts, settings.weld_tolerance, topology_timer.span(0.0, 0.2));
    const UserSeams seams(mesh, settings.atlas_keep_input_seams);
    set.surface = build_atlas_surface(mesh, set.welded, seams, pool, topology_timer.span(0.2, 1.0));
    topology_timer.finish();
    const AtlasSurface& surface = set.surface;

    PhaseTimer segment_timer(Phase::kSegment, progress, times);
    SegmentationSettings segmentation;
    // Charts do not grow across creases sharper than 60 degrees (CAD edges): growing across
    // them leaves charts that wrap around corners and must be split again; merging may still
    // join the pieces later where the union maps well (fandisk: 24 -> 6 charts). Creases are
    // forced seams only when the caller's hard-edge angle says so.
    segmentation.hard_edge_angle_deg = std::min(settings.hard_edge_angle_deg, 60.0);
    segmentation.max_normal_deviation_deg = 90.0;
    std::vector<int32_t> chart_of_surface =
        segment_charts(surface, segmentation, pool, segment_timer.span(0.0, 0.95));
    const std::vector<char> seam =
        hard_edge_seams(surface, settings.hard_edge_angle_deg, segment_timer.span(0.95, 1.0));
    segment_timer.finish();

    PhaseTimer chart_timer(Phase::kInitialMap, progress, times);
    ChartLimits limits;
    limits.target_stretch_l2 = settings.atlas_target_l2;
    limits.max_stretch_linf = settings.atlas_max_linf;
    set.charts =
        build_charts(surface, std::move(chart_of_surface), seam, settings, limits, progress, pool);
    set.cuts_to_try = split_long_charts(surface, settings, set.charts, chart_timer.span(1.0, 1.0));
    chart_timer.finish();
    // The charts hold their own meshes now: what is left to do (corner sources, packing,
    // output) reads only the surface's maps back to the input, so its mesh, twins and angles
    // (over 60 bytes per triangle) go before the output's arrays are made.
    set.surface.mesh = TriangleMesh();
    std::vector<int32_t>().swap(set.surface.twin);
    std::vector<double>().swap(set.surface.corner_angle);
    std::vector<char>().swap(set.surface.polygon_inner);
    return set;
}

// The mapped charts' corner sources and parts; with stacking, an instance (a mesh or a piece of
// one repeated, instanced_parts.h) takes copies of its source's charts, without which it could
// share none of their texels.
void corner_sources_of(const TriangleMesh& mesh, const AtlasParts& parts, const Settings& settings,
                       ChartSet& set, const ProgressSpan& progress) {
    const AtlasSurface& surface = set.surface;
    set.sources = corner_sources(mesh, parts, set.welded, surface, set.charts, progress);
    for (const AtlasChart& chart : set.charts) {
        const int32_t first = surface.input_triangle[chart.disk.surface_triangle[0]];
        set.part.push_back(parts.part_of_triangle(first));
    }
    if (settings.atlas_stack == ChartStacking::kNone) return;
    const Instances instances = find_instances(
        mesh, parts, set.welded, set.sources, set.charts.size(), settings.atlas_stack_tolerance,
        settings.atlas_stack == ChartStacking::kMirrored, !settings.atlas_mesh_per_page);
    if (instances.any())
        copy_instance_charts(mesh, parts, surface, instances, set.charts, set.sources, set.part);
}

// Repacking: the input's own uv islands are the charts, as they are (uv_repack.h).
ChartSet repacked_charts(const TriangleMesh& mesh, const AtlasParts& parts,
                         const Settings& settings, const Progress& progress, PhaseTimes& times) {
    PhaseTimer topology_timer(Phase::kTopology, progress, times);
    const std::vector<int32_t> welded =
        weld_parts(mesh, parts, settings.weld_tolerance, topology_timer.span());
    topology_timer.finish();
    PhaseTimer segment_timer(Phase::kSegment, progress, times);
    RepackedCharts repacked = repack_charts(mesh, parts, welded);
    ChartSet set;
    set.charts = std::move(repacked.charts);
    set.sources.chart = std::move(repacked.chart_of);
    set.sources.vertex = std::move(repacked.corner_vertex);
    set.sources.point_chart_part = std::move(repacked.point_chart_part);
    set.part.assign(set.charts.size(), 0);
    for (int32_t t = mesh.triangle_count() - 1; t >= 0; --t) {
        const int32_t c = set.sources.chart[t];
        if (c < static_cast<int32_t>(set.part.size())) set.part[c] = parts.part_of_triangle(t);
    }
    segment_timer.finish();
    return set;
}

// A chart set packed: each chart's place (stacking, chart_places) and the layout.
struct PackedCharts {
    std::vector<int32_t> place;
    PackResult layout;
};

PackedCharts pack_chart_set(const TriangleMesh& mesh, const AtlasParts& parts,
                            const Settings& settings, ChartSet& set, ThreadPool& pool,
                            const ProgressSpan& progress) {
    if (!settings.atlas_repack)
        corner_sources_of(mesh, parts, settings, set, progress.part(0.0, 1.0 / 7.0));
    PackedCharts packed;
    packed.place = chart_places(set.charts, set.part, settings);
    packed.layout = pack_places(set.charts, set.part, packed.place, settings, pool,
                                progress.part(1.0 / 7.0, 1.0));
    return packed;
}

// The set packed as it is and, where some charts may pack better cut, with them cut: the denser
// of the two (`set` becomes the cut one when that is kept).
PackedCharts pack_whole_or_cut(const TriangleMesh& mesh, const AtlasParts& parts,
                               const Settings& settings, ChartSet& set, ThreadPool& pool,
                               const ProgressSpan& progress) {
    if (set.cuts_to_try.pieces.empty())
        return pack_chart_set(mesh, parts, settings, set, pool, progress);
    // Before corner_sources_of: what the cut set needs is its charts and the maps to the input.
    ChartSet cut;
    cut.charts = with_cuts(set.charts, set.cuts_to_try);
    cut.welded = set.welded;
    cut.surface = set.surface;
    set.cuts_to_try = LongChartCuts();
    PackedCharts whole = pack_chart_set(mesh, parts, settings, set, pool, progress.part(0.0, 0.5));
    PackedCharts pieces = pack_chart_set(mesh, parts, settings, cut, pool, progress.part(0.5, 1.0));
    if (!(pieces.layout.texels_per_unit > kCutPacksDenser * whole.layout.texels_per_unit))
        return whole;
    set = std::move(cut);
    return pieces;
}

}  // namespace

int32_t AtlasParts::part_of_triangle(int32_t triangle) const {
    return static_cast<int32_t>(
        std::upper_bound(first_triangle.begin(), first_triangle.end(), triangle) -
        first_triangle.begin() - 1);
}

AtlasParts single_part(const TriangleMesh& mesh) {
    AtlasParts parts;
    parts.first_vertex = {0, mesh.vertex_count()};
    parts.first_triangle = {0, mesh.triangle_count()};
    return parts;
}

AtlasOutput build_atlas(const TriangleMesh& mesh, const AtlasParts& parts, const Settings& settings,
                        const Progress& progress, PhaseTimes& times, ThreadPool& pool) {
    {
        PhaseTimer timer(Phase::kValidate, progress, times);
        check_page_settings(settings);
        check_indices_in_range(mesh, timer.span());  // everything else an atlas takes as it comes
        check_user_seams(mesh, "");
        if (settings.atlas_repack) check_corner_uvs(mesh, "");
        timer.finish();
    }
    ChartSet set = settings.atlas_repack
                       ? repacked_charts(mesh, parts, settings, progress, times)
                       : mapped_charts(mesh, parts, settings, progress, times, pool);

    PhaseTimer pack_timer(Phase::kPack, progress, times);
    // Progress: where each corner comes from and the packing, the output's vertices and records.
    const PackedCharts packed_set =
        pack_whole_or_cut(mesh, parts, settings, set, pool, pack_timer.span(0.0, 0.7));
    const std::vector<int32_t>& place = packed_set.place;
    const PackResult& packed = packed_set.layout;
    refuse_collapsed_atlas(mesh, settings.weld_tolerance, set.charts, packed);

    AtlasOutput out;
    out.width = packed.width;
    out.height = packed.height;
    out.page_count = packed.page_count;
    out.texels_per_unit = packed.texels_per_unit;
    for (const AtlasChart& chart : set.charts) out.adaptive_solves += chart.map.adaptive_solves;
    emit_output(mesh, parts, set.charts, set.sources, packed, out, pack_timer.span(0.7, 0.9));
    record_charts(mesh, parts, set.charts, set.sources, packed, place, out,
                  pack_timer.span(0.9, 1.0));
    pack_timer.finish();
    return out;
}

}  // namespace raps
