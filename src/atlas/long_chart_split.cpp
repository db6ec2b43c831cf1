#include "atlas/long_chart_split.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "atlas/chart_box.h"
#include "atlas/chart_raster.h"
#include "atlas/local_index.h"
#include "atlas/polygon_units.h"
#include "metrics/distortion.h"

namespace raps {
namespace {

// The share of the square the charts' area is expected to fill, and how many times longer than
// the square's side a chart must be at the density this allows to be cut. A chart longer than
// the side lowers every chart's density by as much, and the square's cover by its square.
// - A chart that holds most of the charts' area is cut only past twice the side, where the
//   charts would cover under a quarter of what they could (below 0.18 of the square): a 4:1
//   strip or a half cylinder of 3:1 is one chart covering a quarter or a third of the square,
//   and a seam across it would cost more than the texels it saves.
// - A chart that holds less is cut past 1.25 times the side, where it alone would hold the
//   cover under 0.45 of the square and the other charts, most of the area, lose density for it:
//   one long mesh in a scene of compact ones (alligator among the 19 shared meshes: 1.45 times
//   the side, a quarter of the area, the square 0.33 covered). Between the side and 1.25 times
//   it, either may pack better, so both are packed (LongChartCuts): beetle's largest chart (1.17
//   times the side, 0.47 of the area, placed across the square) cut in two covered 0.590 of it
//   instead of 0.606; teapot stretched 6 times along x among three stretched meshes (1.23
//   times, 0.49 of the area) cut covered 0.622 instead of 0.454.
constexpr double kExpectedFill = 0.7;
constexpr double kTooLong = 2.0;
constexpr double kTooLongBesideOthers = 1.25;
constexpr double kMayBeTooLong = 1.0;
constexpr double kMostOfTheArea = 0.5;
// Each piece at most this share of the square's side long at that density, so that pieces lie
// side by side with room to spare.
constexpr double kPieceLength = 0.8;

// The chart's box in the frame its smallest box turns it to.
TurnedBox box_of(const AtlasChart& chart) {
    return turned_box(chart.map.uv, chart.box.rotation);
}

// Every input polygon in the piece of its first triangle (polygon_units.h): polygons stay whole.
void keep_polygons_whole(const AtlasSurface& surface, const AtlasChart& chart,
                         std::vector<int32_t>& piece) {
    if (surface.polygon_inner.empty()) return;
    const std::vector<int32_t>& triangles = chart.disk.surface_triangle;
    const LocalIndex local(triangles, surface.input_triangle.size());
    std::vector<int32_t> neighbour(3 * triangles.size(), -1);
    for (size_t i = 0; i < triangles.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            const int32_t twin = surface.twin[3 * triangles[i] + k];
            if (twin >= 0) neighbour[3 * i + k] = local(twin / 3);
        }
    }
    keep_polygons_together(surface, triangles, neighbour, piece);
}

// The chart's triangles in `pieces` pieces by where they lie along the chart's longer side (in
// its smallest box), each polygon with its first triangle, each piece a chart of its own.
std::vector<AtlasChart> cut_across(const AtlasSurface& surface, const AtlasChart& chart, int pieces,
                                   const ProgressSpan& beat) {
    const std::vector<Triangle>& triangles = chart.disk.mesh.triangles;
    const TurnedBox box = box_of(chart);
    const Eigen::Vector2d &low = box.origin, &size = box.extent;
    const int axis = size.x() >= size.y() ? 0 : 1;
    const int64_t count = static_cast<int64_t>(triangles.size());
    std::vector<int32_t> piece_of(triangles.size());
    for (size_t t = 0; t < triangles.size(); ++t) {
        beat.at(static_cast<int64_t>(t), count);
        const Triangle& v = triangles[t];
        const Eigen::Vector2d centre =
            (chart.map.uv[v[0]] + chart.map.uv[v[1]] + chart.map.uv[v[2]]) / 3.0;
        const double along =
            (turned(chart.box.rotation, centre)[axis] - low[axis]) / std::max(size[axis], 1e-300);
        piece_of[t] = std::clamp(static_cast<int32_t>(along * pieces), 0, pieces - 1);
    }
    keep_polygons_whole(surface, chart, piece_of);
    beat.report(0.0);
    std::vector<std::vector<int32_t>> members(pieces);  // each piece's triangles, ascending
    for (size_t t = 0; t < triangles.size(); ++t)
        members[piece_of[t]].push_back(static_cast<int32_t>(t));
    beat.report(0.0);
    std::vector<AtlasChart> out;
    std::vector<int32_t> vertex_of(chart.map.uv.size(), -1);
    for (const std::vector<int32_t>& piece : members) {
        if (piece.empty()) continue;
        AtlasChart part;
        for (int32_t t : piece) {
            beat.at(t, count);
            Triangle local;
            for (int k = 0; k < 3; ++k) {
                int32_t& v = vertex_of[triangles[t][k]];
                if (v < 0) {
                    v = static_cast<int32_t>(part.map.uv.size());
                    part.map.uv.push_back(chart.map.uv[triangles[t][k]]);
                    part.disk.mesh.positions.push_back(chart.disk.mesh.positions[triangles[t][k]]);
                    part.disk.surface_vertex.push_back(chart.disk.surface_vertex[triangles[t][k]]);
                }
                local[k] = v;
            }
            part.disk.mesh.triangles.push_back(local);
            part.disk.surface_triangle.push_back(chart.disk.surface_triangle[t]);
        }
        for (int32_t t : piece) {  // reset for the next piece, touching only what was set
            for (int32_t v : triangles[t]) vertex_of[v] = -1;
        }
        const Stretch stretch =
            measure_stretch(part.disk.mesh.positions, part.map.uv, part.disk.mesh.triangles, beat);
        part.map.stretch_l2 = stretch.l2;
        part.map.stretch_linf = stretch.linf;
        part.map.method = chart.map.method;
        part.map.injective = chart.map.injective;
        part.map.adaptive_solves = out.empty() ? chart.map.adaptive_solves : 0;
        std::vector<int32_t> every(part.map.uv.size());
        std::iota(every.begin(), every.end(), 0);
        part.box = smallest_bounding_box(part.map.uv, part.disk.mesh.triangles, every);
        beat.report(0.0);
        out.push_back(std::move(part));
    }
    return out;
}

// Pieces at most kPieceLength of the side long, never more than the chart's triangles.
int pieces_of(double longest, double side, const AtlasChart& chart) {
    return static_cast<int>(std::min(std::ceil(longest / (kPieceLength * side)),
                                     static_cast<double>(chart.disk.mesh.triangles.size())));
}

}  // namespace

LongChartCuts split_long_charts(const AtlasSurface& surface, const Settings& settings,
                                std::vector<AtlasChart>& charts, const ProgressSpan& beat) {
    LongChartCuts to_try;
    if (settings.atlas_texels_per_unit > 0 || settings.atlas_repack || charts.empty())
        return to_try;
    double area = 0;
    for (const AtlasChart& chart : charts) {
        area += uv_area(chart.map.uv, chart.disk.mesh.triangles);
        beat.report(0.0);
    }
    if (!(area > 0)) return to_try;
    const double side = settings.atlas_resolution;
    const double density = std::sqrt(kExpectedFill * side * side / area);  // texels per unit
    std::vector<AtlasChart> out;
    out.reserve(charts.size());
    for (AtlasChart& chart : charts) {
        const double longest = box_of(chart).extent.maxCoeff() * density;  // texels
        const double share = uv_area(chart.map.uv, chart.disk.mesh.triangles) / area;
        beat.report(0.0);
        const bool most = share >= kMostOfTheArea;
        const double too_long = most ? kTooLong : kTooLongBesideOthers;
        if (longest > too_long * side) {
            for (AtlasChart& part :
                 cut_across(surface, chart, pieces_of(longest, side, chart), beat))
                out.push_back(std::move(part));
            continue;
        }
        if (!most && longest > kMayBeTooLong * side)
            to_try.pieces.emplace_back(
                out.size(), cut_across(surface, chart, pieces_of(longest, side, chart), beat));
        out.push_back(std::move(chart));
    }
    charts = std::move(out);
    return to_try;
}

std::vector<AtlasChart> with_cuts(const std::vector<AtlasChart>& charts,
                                  const LongChartCuts& cuts) {
    std::vector<AtlasChart> out;
    out.reserve(charts.size() + cuts.pieces.size());
    size_t next = 0;
    for (size_t c = 0; c < charts.size(); ++c) {
        if (next < cuts.pieces.size() && cuts.pieces[next].first == c) {
            for (const AtlasChart& part : cuts.pieces[next++].second) out.push_back(part);
            continue;
        }
        out.push_back(charts[c]);
    }
    return out;
}

}  // namespace raps
