#include "atlas/chart_packing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "atlas/skyline_packing.h"
#include "core/error.h"
#include "core/portable_math.h"

namespace raps {
namespace {

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Andrew's monotone chain.
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points) {
    std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
        return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
    });
    if (points.size() < 3) return points;
    std::vector<Eigen::Vector2d> hull(2 * points.size());
    size_t k = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
        hull[k++] = points[i];
    }
    for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
        hull[k++] = points[i];
    }
    hull.resize(k - 1);
    return hull;
}

// The rotation (as cos, sin) that aligns the smallest-area bounding box with the axes: one of
// the hull's edge directions.
Eigen::Vector2d best_rotation(const std::vector<Eigen::Vector2d>& uv) {
    const std::vector<Eigen::Vector2d> hull = convex_hull(uv);
    Eigen::Vector2d best(1, 0);
    double best_score = std::numeric_limits<double>::max();
    for (size_t i = 0; i < hull.size(); ++i) {
        Eigen::Vector2d edge = hull[(i + 1) % hull.size()] - hull[i];
        if (edge.norm() == 0) continue;
        edge.normalize();
        double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
        for (const Eigen::Vector2d& p : hull) {
            const double x = edge.x() * p.x() + edge.y() * p.y();
            const double y = -edge.y() * p.x() + edge.x() * p.y();
            lo_x = std::min(lo_x, x);
            hi_x = std::max(hi_x, x);
            lo_y = std::min(lo_y, y);
            hi_y = std::max(hi_y, y);
        }
        const double score = (hi_x - lo_x) * (hi_y - lo_y);
        if (score < best_score - 1e-12 * std::abs(best_score)) {
            best_score = score;
            best = edge;
        }
    }
    return best;
}

// Atlases of up to this many charts get the thorough search of layouts (pack_charts).
constexpr size_t kFewCharts = 100;

// Up to this many charts, the best layout's chart order is then improved by swaps: each round
// packs the order with every pair of charts swapped (same strip width and rule) and keeps the
// smallest layout, until a round finds none smaller or after kSwapRounds. A few large charts
// fill the square worst, and their order matters most. Measured against 7db2b6e, 2 threads:
// halftunnel (7 charts) coverage 0.623 -> 0.662, pack 7.4 -> 12.4 ms; face (12) 0.711 ->
// 0.745, 13.2 -> 20.9 ms; 3holes (11) and fandisk (4) unchanged, beetle (9) 0.628 -> 0.629.
// Four rounds found nothing more on these five; 8 rounds of 8 random swaps instead ranged
// 0.653 to 0.683 on halftunnel with the seed (7 seeds tried).
constexpr size_t kSwappedCharts = 16;
constexpr int kSwapRounds = 2;

}  // namespace

double turn_degrees(const Eigen::Vector2d& rotation, int quarters) {
    double degrees = 90.0 * quarters - portable::atan2(rotation.y(), rotation.x()) * (180.0 / M_PI);
    // A box along the axes turns by a multiple of 90 degrees, which rounding leaves a hair off.
    const double quarter = std::round(degrees / 90.0) * 90.0;
    if (std::abs(degrees - quarter) < 1e-9) degrees = quarter;
    degrees = std::fmod(degrees, 360.0);
    return degrees < 0 ? degrees + 360.0 : degrees + 0.0;  // + 0.0: never -0
}

ChartBox smallest_bounding_box(const std::vector<Eigen::Vector2d>& uv,
                               const std::vector<Triangle>& triangles,
                               const std::vector<int32_t>& boundary) {
    std::vector<Eigen::Vector2d> outline(boundary.size());
    for (size_t i = 0; i < boundary.size(); ++i) outline[i] = uv[boundary[i]];
    ChartBox box;
    box.rotation = best_rotation(outline);
    const Eigen::Vector2d r = box.rotation;
    Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
    for (const Eigen::Vector2d& p : uv) {
        const Eigen::Vector2d q(r.x() * p.x() + r.y() * p.y(), -r.y() * p.x() + r.x() * p.y());
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
    }
    double area = 0;
    for (const Triangle& t : triangles) {
        const Eigen::Vector2d a = uv[t[1]] - uv[t[0]], b = uv[t[2]] - uv[t[0]];
        area += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
    }
    const double box_area = (hi.x() - lo.x()) * (hi.y() - lo.y());
    box.fill = box_area > 0 ? std::min(1.0, area / box_area) : 1.0;
    return box;
}

PackResult pack_charts(const std::vector<PackInput>& charts, const PackSettings& settings,
                       ThreadPool& pool, const ProgressSpan& progress) {
    // Progress: a report at the start of every chart's raster and every trial layout, on
    // whichever thread runs it (the fraction stays where the phase is: the trials' number is
    // not known in advance).
    const ProgressSpan beat = progress.part(0.0, 0.0);
    PackResult result;
    const size_t count = charts.size();
    result.uv.resize(count);
    result.page.assign(count, 0);
    result.scaled_down.assign(count, 0);
    result.rotation_deg.resize(count);
    if (count == 0) return result;
    const int32_t padding = std::max(0, settings.padding);
    const double resolution = std::max(1, settings.resolution);

    // Turn every chart to its smallest box.
    std::vector<PreparedChart> prepared(count);
    std::vector<Eigen::Vector2d> extent(count);
    double total_area = 0;
    for (size_t c = 0; c < count; ++c) {
        const std::vector<Eigen::Vector2d>& uv = *charts[c].uv;
        prepared[c].rotation =
            settings.rotation == ChartRotation::kAny ? charts[c].rotation : Eigen::Vector2d(1, 0);
        prepared[c].turns = settings.rotation == ChartRotation::kNone ? 1 : 4;
        const Eigen::Vector2d r = prepared[c].rotation;
        Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
        for (const Eigen::Vector2d& p : uv) {
            const Eigen::Vector2d q(r.x() * p.x() + r.y() * p.y(), -r.y() * p.x() + r.x() * p.y());
            lo = lo.cwiseMin(q);
            hi = hi.cwiseMax(q);
        }
        prepared[c].origin = lo;
        extent[c] = hi - lo;
        for (const Triangle& t : *charts[c].triangles) {
            const Eigen::Vector2d a = uv[t[1]] - uv[t[0]], b = uv[t[2]] - uv[t[0]];
            total_area += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
        }
    }
    // Three orders to place the charts in, largest first by the longer side of their box, by
    // its area and by its shorter side (ties by index): which packs best varies from mesh to
    // mesh (measured: lion, suzanne and teapot each best in a different one).
    auto largest_first = [&](auto size_of) {
        std::vector<size_t> order(count);
        std::iota(order.begin(), order.end(), 0);
        std::stable_sort(order.begin(), order.end(),
                         [&](size_t a, size_t b) { return size_of(a) > size_of(b); });
        return order;
    };
    std::vector<std::vector<size_t>> orders = {
        largest_first([&](size_t c) { return std::max(extent[c].x(), extent[c].y()); }),
        largest_first([&](size_t c) { return extent[c].x() * extent[c].y(); }),
        largest_first([&](size_t c) { return std::min(extent[c].x(), extent[c].y()); })};
    // Charts of one size (thousands of equal quads) come in the same order every way.
    for (size_t k = orders.size(); k-- > 1;) {
        if (std::find(orders.begin(), orders.begin() + k, orders[k]) != orders.begin() + k)
            orders.erase(orders.begin() + k);
    }
    const std::vector<size_t>& order = orders[0];

    // Pack at a trial density, then raise it by the room left and pack again, so the final
    // layout is packed at (nearly) its final texel size and the padding is not inflated.
    double scale = std::sqrt(0.45 * resolution * resolution / std::max(total_area, 1e-300));
    // No chart may be longer than the atlas.
    double longest = 0;
    for (const Eigen::Vector2d& e : extent) longest = std::max({longest, e.x(), e.y()});
    scale = std::min(scale, (resolution - 2.0 * padding - 2.0) / std::max(longest, 1e-300));
    const int32_t limit = static_cast<int32_t>(resolution);
    // Charts, strip widths and layouts are independent: each runs on its own thread and writes
    // only its own slot, so the result does not depend on the thread count.
    auto rasterise_all = [&](double at_scale, int32_t& widest) {
        std::vector<int32_t> narrow_side(count);
        parallel_for_each(pool, count, [&](size_t c) {
            beat.report(0.0);
            BitImage raster;
            raster.resize(
                static_cast<int32_t>(std::ceil(extent[c].x() * at_scale)) + 1 + 2 * padding,
                static_cast<int32_t>(std::ceil(extent[c].y() * at_scale)) + 1 + 2 * padding);
            const Eigen::Vector2d r = prepared[c].rotation;
            std::vector<Eigen::Vector2d> points(charts[c].uv->size());
            for (size_t v = 0; v < points.size(); ++v) {
                const Eigen::Vector2d& p = (*charts[c].uv)[v];
                const Eigen::Vector2d q(r.x() * p.x() + r.y() * p.y(),
                                        -r.y() * p.x() + r.x() * p.y());
                points[v] = (q - prepared[c].origin) * at_scale + Eigen::Vector2d(padding, padding);
            }
            rasterise(points, *charts[c].triangles, raster);
            for (int q = 0; q < 4; ++q) {
                prepared[c].profiles[q] = make_profile(raster, padding);
                if (q < 3) raster = rotate_quarter(raster);
            }
            // A chart that may not turn needs a strip as wide as it is.
            narrow_side[c] = prepared[c].turns == 1 ? prepared[c].profiles[0].width
                                                    : std::min(raster.width, raster.height);
        });
        widest = std::max(1, *std::max_element(narrow_side.begin(), narrow_side.end()));
    };
    struct Packed {
        std::vector<Eigen::Vector2i> at;
        std::vector<int> quarter;
        int32_t width = 0, height = 0;
        double area() const { return static_cast<double>(width) * height; }
    };
    // Every order, strip width and scoring rule, each packed with holes filled, or on the
    // skyline alone where filling holes overflows the atlas; the smallest rectangle wins (ties:
    // the earlier trial). `density_strip` is among the widths: its skyline packing is the one
    // the density was fitted to, so some trial always fits.
    // The side of the square as large as the charts' padded boxes together, in cells.
    auto square_side = [&] {
        double area_cells = 0;
        for (size_t c = 0; c < count; ++c) {
            area_cells +=
                static_cast<double>(prepared[c].profiles[0].width) * prepared[c].profiles[0].height;
        }
        return static_cast<int32_t>(std::sqrt(area_cells));
    };
    auto best_layout = [&](int32_t widest, int32_t density_strip) {
        std::vector<int32_t> widths = {density_strip};
        const int32_t square = square_side();
        // Strip widths geometrically spaced from 0.83 to 1.8 times the square's side (k = 2 ..
        // 11 of a series from 0.7). The density is fitted to the square strip, so narrower
        // strips grow too tall: 0.7 and 0.76 fitted none of the 16 shared meshes.
        for (int k = 2; k < 12 && count > 1; ++k) {
            const double f = 0.7 * portable::pow(1.8 / 0.7, k / 11.0);
            widths.push_back(std::clamp(static_cast<int32_t>(square * f), widest, limit));
        }
        std::sort(widths.begin(), widths.end());
        widths.erase(std::unique(widths.begin(), widths.end()), widths.end());
        // Up to kFewCharts charts, where each chart's place matters and a packing is cheap,
        // every order is tried and every trial fills holes (on the skyline alone where that
        // overflows the atlas). With more, one order on the skyline alone, and holes filled in
        // the two best layouts: for 2,000 separate triangles the rest took three times as long
        // and found no better layout.
        const bool few = count <= kFewCharts;
        const size_t per_order = 2 * widths.size();
        const size_t trials = (few ? orders.size() : 1) * per_order;
        std::vector<Packed> packed(trials);
        std::vector<char> fits(trials, 0);
        auto pack_order = [&](const std::vector<size_t>& chart_order, int32_t width,
                              bool count_waste, bool holes, Packed& p) {
            p.at.resize(count);
            p.quarter.resize(count);
            return pack_strip(prepared, chart_order, width, count_waste, holes, limit, p.at,
                              p.quarter, p.width, p.height);
        };
        auto pack_trial = [&](size_t trial, bool holes, Packed& p) {
            return pack_order(orders[trial / per_order], widths[trial % per_order / 2],
                              trial % 2 == 1, holes, p);
        };
        parallel_for_each(pool, trials, [&](size_t trial) {
            beat.report(0.0);
            fits[trial] = (few && pack_trial(trial, true, packed[trial])) ||
                          pack_trial(trial, false, packed[trial]);
        });
        if (!few) {
            std::vector<size_t> ranked;
            for (size_t trial = 0; trial < trials; ++trial) {
                if (fits[trial]) ranked.push_back(trial);
            }
            std::stable_sort(ranked.begin(), ranked.end(), [&](size_t a, size_t b) {
                return packed[a].area() < packed[b].area();
            });
            ranked.resize(std::min<size_t>(ranked.size(), 2));
            std::vector<Packed> with_holes(ranked.size());
            std::vector<char> holes_fit(ranked.size(), 0);
            parallel_for_each(pool, ranked.size(), [&](size_t k) {
                beat.report(0.0);
                holes_fit[k] = pack_trial(ranked[k], true, with_holes[k]);
            });
            for (size_t k = 0; k < ranked.size(); ++k) {
                if (holes_fit[k]) packed[ranked[k]] = std::move(with_holes[k]);
            }
        }
        size_t best = trials;
        for (size_t trial = 0; trial < trials; ++trial) {
            if (fits[trial] && (best == trials || packed[trial].area() < packed[best].area()))
                best = trial;
        }
        if (best == trials) throw Error(ErrorCode::kInternal, "no chart layout fits the atlas");
        Packed layout = std::move(packed[best]);
        if (count < 2 || count > kSwappedCharts) return layout;
        std::vector<size_t> kept_order = orders[best / per_order];
        const int32_t width = widths[best % per_order / 2];
        const bool count_waste = best % 2 == 1;
        for (int round = 0; round < kSwapRounds; ++round) {
            std::vector<std::vector<size_t>> variants;
            for (size_t i = 0; i < count; ++i) {
                for (size_t j = i + 1; j < count; ++j) {
                    variants.push_back(kept_order);
                    std::swap(variants.back()[i], variants.back()[j]);
                }
            }
            std::vector<Packed> tried(variants.size());
            std::vector<char> tried_fits(variants.size(), 0);
            parallel_for_each(pool, variants.size(), [&](size_t k) {
                beat.report(0.0);
                tried_fits[k] = pack_order(variants[k], width, count_waste, true, tried[k]);
            });
            bool improved = false;
            for (size_t k = 0; k < variants.size(); ++k) {
                if (tried_fits[k] && tried[k].area() < layout.area()) {
                    layout = std::move(tried[k]);
                    kept_order = variants[k];
                    improved = true;
                }
            }
            if (!improved) break;
        }
        return layout;
    };

    // The strip the density is fitted in: as wide as the square of the charts' box areas (a
    // single chart: its longer side).
    auto density_strip = [&](int32_t widest) {
        if (count == 1)
            return std::max(prepared[0].profiles[0].width, prepared[0].profiles[0].height);
        return std::clamp(square_side(), widest, limit);
    };
    // The density: the largest for which a skyline packing into a strip of the square's width
    // fits, found in a few steps (each scales by the room the last layout left). Only then are
    // all orders, strip widths and rules tried, at that density.
    double fitted_scale = -1;
    int32_t widest = 1;
    for (int attempt = 0; attempt < 24; ++attempt) {
        rasterise_all(scale, widest);
        const int32_t strip = density_strip(widest);
        std::vector<Eigen::Vector2i> at(count);
        std::vector<int> quarter(count);
        int32_t width = 0, height = 0;
        const bool fits =
            pack_strip(prepared, order, strip, false, false, limit, at, quarter, width, height);
        if (!fits) {
            if (fitted_scale > 0) break;
            scale *= 0.85;  // nothing fitted yet: lower the density
            continue;
        }
        fitted_scale = scale;
        const double room = resolution / std::max(std::max(width, height), 1);
        if (room < 1.02 || attempt >= 3) break;
        scale *= std::min(room, 1.5) * 0.995;
    }
    if (fitted_scale != scale) rasterise_all(fitted_scale, widest);
    scale = fitted_scale;
    const Packed best = best_layout(widest, density_strip(widest));
    const std::vector<Eigen::Vector2i>& placed = best.at;
    const std::vector<int>& turn = best.quarter;

    // Positions in the layout, in cells (continuous).
    Eigen::Vector2d low(1e300, 1e300), high(-1e300, -1e300);
    for (size_t c = 0; c < count; ++c) {
        const Eigen::Vector2d r = prepared[c].rotation;
        const Profile& p = prepared[c].profiles[turn[c]];
        const int32_t w0 = turn[c] % 2 ? p.height : p.width;  // the unrotated raster's size
        const int32_t h0 = turn[c] % 2 ? p.width : p.height;
        result.uv[c].resize(charts[c].uv->size());
        for (size_t v = 0; v < result.uv[c].size(); ++v) {
            const Eigen::Vector2d& src = (*charts[c].uv)[v];
            const Eigen::Vector2d q(r.x() * src.x() + r.y() * src.y(),
                                    -r.y() * src.x() + r.x() * src.y());
            // Position in the unrotated padded raster frame (texel units, continuous); the
            // quarter turns map the cell (x, y) to (h - 1 - y, x), i.e. the point (x, y) to
            // (h - y, x) for continuous coordinates.
            double x = (q.x() - prepared[c].origin.x()) * scale + padding;
            double y = (q.y() - prepared[c].origin.y()) * scale + padding;
            int32_t cur_w = w0, cur_h = h0;
            for (int k = 0; k < turn[c]; ++k) {
                const double nx = cur_h - y, ny = x;
                x = nx;
                y = ny;
                std::swap(cur_w, cur_h);
            }
            const Eigen::Vector2d at(placed[c].x() + x, placed[c].y() + y);
            result.uv[c][v] = at;
            low = low.cwiseMin(at);
            high = high.cwiseMax(at);
        }
    }
    // The padding matters between charts, not at the atlas's border: the layout is cropped to
    // the charts themselves. It is stretched uniformly until its longer side is the resolution
    // (a factor >= 1, which only widens the gaps between charts), then normalised per axis to
    // the atlas's texels: texel space stays isotropic, and the charts span [0, 1] on one axis
    // and all but a fraction of a texel on the other.
    const double span_x = std::max(high.x() - low.x(), 0.0);
    const double span_y = std::max(high.y() - low.y(), 0.0);
    const double span = std::max(span_x, span_y);
    auto texels = [](double length) {
        return std::max(1, static_cast<int32_t>(std::ceil(length - 1e-9)));
    };
    double grow = span > 0 ? resolution / span : 1.0;
    // The shorter side loses up to a texel to rounding up (0.5% of alligator's 180): shrinking
    // the layout until that side is a whole number of texels loses less of the longer one.
    const double shorter = std::min(span_x, span_y);
    if (shorter > 0) {
        const double exact = std::floor(shorter * grow) / shorter;
        auto fill = [&](double g) {
            return span_x * g / texels(span_x * g) * (span_y * g / texels(span_y * g));
        };
        if (exact >= 1.0 && fill(exact) > fill(grow)) grow = exact;
    }
    result.width = texels(span_x * grow);
    result.height = texels(span_y * grow);
    result.texels_per_unit = scale * grow;
    for (size_t c = 0; c < count; ++c)
        result.rotation_deg[c] = turn_degrees(prepared[c].rotation, turn[c]);
    const double to_u = grow / result.width, to_v = grow / result.height;
    for (std::vector<Eigen::Vector2d>& chart_uv : result.uv) {
        for (Eigen::Vector2d& at : chart_uv) {
            at = Eigen::Vector2d(std::min(1.0, (at.x() - low.x()) * to_u),
                                 std::min(1.0, (at.y() - low.y()) * to_v));
        }
    }
    return result;
}

}  // namespace raps
