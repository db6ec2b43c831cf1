#include "atlas/chart_packing.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

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

// The rotation (as cos, sin) that aligns the smallest-area bounding box (or, for a single
// chart, the smallest square) with the axes: one of the hull's edge directions.
Eigen::Vector2d best_rotation(const std::vector<Eigen::Vector2d>& uv, bool square) {
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
        const double score =
            square ? std::max(hi_x - lo_x, hi_y - lo_y) : (hi_x - lo_x) * (hi_y - lo_y);
        if (score < best_score - 1e-12 * std::abs(best_score)) {
            best_score = score;
            best = edge;
        }
    }
    return best;
}

// A chart rasterised at the current scale: its cells, in a frame with `padding` texels of
// margin on every side.
struct Raster {
    int32_t width = 0, height = 0;
    std::vector<uint8_t> cells;  // row-major, 1 where a triangle touches the texel
    uint8_t at(int32_t x, int32_t y) const { return cells[static_cast<size_t>(y) * width + x]; }
};

// Marks every texel that a triangle touches (conservative): per row band, the x-range of the
// triangle clipped to the band.
void rasterise(const std::vector<Eigen::Vector2d>& points, const std::vector<Triangle>& triangles,
               Raster& raster) {
    for (const Triangle& t : triangles) {
        const Eigen::Vector2d p[3] = {points[t[0]], points[t[1]], points[t[2]]};
        const double y_lo = std::min({p[0].y(), p[1].y(), p[2].y()});
        const double y_hi = std::max({p[0].y(), p[1].y(), p[2].y()});
        const int32_t row_lo = std::max(0, static_cast<int32_t>(std::floor(y_lo)));
        const int32_t row_hi = std::min(raster.height - 1, static_cast<int32_t>(std::floor(y_hi)));
        for (int32_t row = row_lo; row <= row_hi; ++row) {
            const double band_lo = row, band_hi = row + 1.0;
            double x_lo = 1e300, x_hi = -1e300;
            for (int e = 0; e < 3; ++e) {
                const Eigen::Vector2d& a = p[e];
                const Eigen::Vector2d& b = p[(e + 1) % 3];
                if (a.y() >= band_lo && a.y() <= band_hi) {
                    x_lo = std::min(x_lo, a.x());
                    x_hi = std::max(x_hi, a.x());
                }
                for (double y : {band_lo, band_hi}) {
                    if ((a.y() - y) * (b.y() - y) < 0) {
                        const double x = a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
                        x_lo = std::min(x_lo, x);
                        x_hi = std::max(x_hi, x);
                    }
                }
            }
            if (x_lo > x_hi) continue;
            const int32_t c_lo = std::max(0, static_cast<int32_t>(std::floor(x_lo)));
            const int32_t c_hi = std::min(raster.width - 1, static_cast<int32_t>(std::floor(x_hi)));
            for (int32_t c = c_lo; c <= c_hi; ++c)
                raster.cells[static_cast<size_t>(row) * raster.width + c] = 1;
        }
    }
}

// Per column of a (rotated) raster: the lowest cell of the padded footprint and the highest cell
// of the chart itself, relative to the frame.
struct Profile {
    int32_t width = 0, height = 0;
    std::vector<int32_t> bottom;        // lowest padded row, or height if the column is empty
    std::vector<int32_t> top;           // highest chart row, or -1
    std::vector<int32_t> chart_bottom;  // lowest chart row, or height
};

struct PreparedChart {
    Eigen::Vector2d rotation;  // cos, sin
    Eigen::Vector2d origin;    // lower corner of the rotated chart's box, in 3D units
    Profile profiles[4];       // the four quarter turns
};

Profile make_profile(const Raster& raster, int32_t padding, int quarter) {
    // Rotate the raster by quarter turns: (x, y) -> per turn (h-1-y, x).
    const int32_t w = raster.width, h = raster.height;
    Profile profile;
    profile.width = quarter % 2 ? h : w;
    profile.height = quarter % 2 ? w : h;
    profile.bottom.assign(profile.width, profile.height);
    profile.top.assign(profile.width, -1);
    profile.chart_bottom.assign(profile.width, profile.height);
    for (int32_t y = 0; y < h; ++y) {
        for (int32_t x = 0; x < w; ++x) {
            if (!raster.at(x, y)) continue;
            int32_t rx = x, ry = y;
            for (int q = 0; q < quarter; ++q) {
                const int32_t cur_h = q % 2 ? w : h;
                const int32_t nx = cur_h - 1 - ry, ny = rx;
                rx = nx;
                ry = ny;
            }
            profile.top[rx] = std::max(profile.top[rx], ry);
            profile.chart_bottom[rx] = std::min(profile.chart_bottom[rx], ry);
            // The padded footprint reaches `padding` texels further in every direction.
            for (int32_t c = std::max(0, rx - padding);
                 c <= std::min(profile.width - 1, rx + padding); ++c) {
                profile.bottom[c] = std::min(profile.bottom[c], std::max(0, ry - padding));
            }
        }
    }
    return profile;
}

// Places the charts (in `order`) into a strip `strip` texels wide: each lands, in its best
// quarter turn, as low as the skyline lets it, then as far left. x is searched with a step of
// an eighth of the chart's width and refined around the best step, which keeps the search
// linear in the strip width. Returns false if a chart is wider than the strip in every turn.
bool pack_strip(const std::vector<PreparedChart>& prepared, const std::vector<size_t>& order,
                int32_t strip, bool count_waste, std::vector<Eigen::Vector2i>& at,
                std::vector<int>& quarter, int32_t& width, int32_t& height) {
    std::vector<int32_t> skyline(static_cast<size_t>(strip), 0);
    width = height = 0;
    auto rest_height = [&](const Profile& p, int32_t x) {
        int32_t y = 0;
        for (int32_t i = 0; i < p.width; ++i) {
            if (p.bottom[i] < p.height) y = std::max(y, skyline[x + i] - p.bottom[i]);
        }
        return y;
    };
    // Lowest top first; or, with count_waste, the texels left empty under the chart plus the
    // area up to its top, which favours placements that fit the skyline's dips.
    auto score_of = [&](const Profile& p, int32_t x, int32_t y) -> int64_t {
        const int64_t top = static_cast<int64_t>(y) + p.height;
        if (!count_waste) return top * (int64_t(strip) + 1) + x;
        int64_t waste = 0;
        for (int32_t i = 0; i < p.width; ++i) {
            if (p.bottom[i] < p.height) waste += y + p.bottom[i] - skyline[x + i];
        }
        return (waste + top * p.width) * (int64_t(strip) + 1) + x;
    };
    for (size_t c : order) {
        int64_t best_score = std::numeric_limits<int64_t>::max();
        int32_t best_x = -1, best_y = 0;
        int best_q = 0;
        for (int q = 0; q < 4; ++q) {
            const Profile& p = prepared[c].profiles[q];
            if (p.width > strip) continue;
            const int32_t last = strip - p.width, step = std::max(1, p.width / 8);
            auto consider = [&](int32_t x) {
                const int32_t y = rest_height(p, x);
                const int64_t score = score_of(p, x, y);
                if (score < best_score) {
                    best_score = score;
                    best_x = x;
                    best_y = y;
                    best_q = q;
                }
            };
            int32_t coarse_best = 0;
            int64_t coarse_score = std::numeric_limits<int64_t>::max();
            for (int32_t x = 0; x <= last; x += step) {
                const int64_t score = score_of(p, x, rest_height(p, x));
                if (score < coarse_score) {
                    coarse_score = score;
                    coarse_best = x;
                }
            }
            for (int32_t x = std::max(0, coarse_best - step + 1);
                 x <= std::min(last, coarse_best + step - 1); ++x) {
                consider(x);
            }
            consider(last);
        }
        if (best_x < 0) return false;
        const Profile& p = prepared[c].profiles[best_q];
        for (int32_t i = 0; i < p.width; ++i) {
            if (p.top[i] >= 0)
                skyline[best_x + i] = std::max(skyline[best_x + i], best_y + p.top[i] + 1);
        }
        at[c] = Eigen::Vector2i(best_x, best_y);
        quarter[c] = best_q;
        width = std::max(width, best_x + p.width);
        height = std::max(height, best_y + p.height);
    }
    return true;
}

}  // namespace

PackResult pack_charts(const std::vector<PackInput>& charts, const PackSettings& settings) {
    PackResult result;
    const size_t count = charts.size();
    result.uv.resize(count);
    if (count == 0) return result;
    const int32_t padding = std::max(0, settings.padding);
    const double resolution = std::max(1, settings.resolution);

    // Rotate every chart to its best box.
    std::vector<PreparedChart> prepared(count);
    std::vector<Eigen::Vector2d> extent(count);
    double total_area = 0;
    for (size_t c = 0; c < count; ++c) {
        const std::vector<Eigen::Vector2d>& uv = *charts[c].uv;
        prepared[c].rotation = best_rotation(uv, false);
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
    // Largest charts first (by the longer side of their box), ties by index.
    std::vector<size_t> order(count);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return std::max(extent[a].x(), extent[a].y()) > std::max(extent[b].x(), extent[b].y());
    });

    // Pack at a trial density, then raise it by the room left and pack again, so the final
    // layout is packed at (nearly) its final texel size and the padding is not inflated.
    double scale = std::sqrt(0.45 * resolution * resolution / std::max(total_area, 1e-300));
    // No chart may be longer than the atlas.
    double longest = 0;
    for (const Eigen::Vector2d& e : extent) longest = std::max({longest, e.x(), e.y()});
    scale = std::min(scale, (resolution - 2.0 * padding - 2.0) / std::max(longest, 1e-300));
    std::vector<Eigen::Vector2i> placed(count);
    std::vector<int> turn(count);
    int32_t used_width = 0, used_height = 0;
    double last_good_scale = scale;
    bool packed_once = false;
    for (int attempt = 0; attempt < 64; ++attempt) {
        int32_t widest = 1;
        for (size_t c = 0; c < count; ++c) {
            Raster raster;
            raster.width = static_cast<int32_t>(std::ceil(extent[c].x() * scale)) + 1 + 2 * padding;
            raster.height =
                static_cast<int32_t>(std::ceil(extent[c].y() * scale)) + 1 + 2 * padding;
            raster.cells.assign(static_cast<size_t>(raster.width) * raster.height, 0);
            const Eigen::Vector2d r = prepared[c].rotation;
            std::vector<Eigen::Vector2d> points(charts[c].uv->size());
            for (size_t v = 0; v < points.size(); ++v) {
                const Eigen::Vector2d& p = (*charts[c].uv)[v];
                const Eigen::Vector2d q(r.x() * p.x() + r.y() * p.y(),
                                        -r.y() * p.x() + r.x() * p.y());
                points[v] = (q - prepared[c].origin) * scale + Eigen::Vector2d(padding, padding);
            }
            rasterise(points, *charts[c].triangles, raster);
            for (int q = 0; q < 4; ++q) prepared[c].profiles[q] = make_profile(raster, padding, q);
            widest = std::max(widest, std::min(raster.width, raster.height));
        }
        // Strip widths from the widest chart's narrow side up to the resolution.
        const int32_t limit = static_cast<int32_t>(resolution);
        double area_cells = 0;
        for (size_t c = 0; c < count; ++c) {
            area_cells +=
                static_cast<double>(prepared[c].profiles[0].width) * prepared[c].profiles[0].height;
        }
        std::vector<int32_t> widths;
        const int32_t square = static_cast<int32_t>(std::sqrt(area_cells));
        // Twelve strip widths, geometrically spaced from 0.7 to 1.8 times the square's side.
        for (int k = 0; k < 12; ++k) {
            const double f = 0.7 * std::pow(1.8 / 0.7, k / 11.0);
            widths.push_back(std::clamp(static_cast<int32_t>(square * f), widest, limit));
        }
        if (count == 1)
            widths = {std::max(prepared[0].profiles[0].width, prepared[0].profiles[0].height)};
        std::sort(widths.begin(), widths.end());
        widths.erase(std::unique(widths.begin(), widths.end()), widths.end());
        double best_area = std::numeric_limits<double>::max();
        for (int trial = 0; trial < 2 * static_cast<int>(widths.size()); ++trial) {
            const int32_t strip = widths[trial / 2];
            std::vector<Eigen::Vector2i> at(count);
            std::vector<int> quarter(count);
            int32_t width = 0, height = 0;
            if (!pack_strip(prepared, order, strip, trial % 2 == 1, at, quarter, width, height))
                continue;
            const double area = static_cast<double>(width) * height;
            if (std::max(width, height) <= limit && area < best_area) {
                best_area = area;
                placed = at;
                turn = quarter;
                used_width = width;
                used_height = height;
            }
        }
        if (best_area == std::numeric_limits<double>::max()) {
            if (packed_once) {  // the previous, smaller density fitted: go back to it
                scale = last_good_scale;
                continue;
            }
            scale *= 0.85;  // nothing fitted yet: lower the density
            continue;
        }
        const bool refit = packed_once && scale == last_good_scale;
        packed_once = true;
        last_good_scale = scale;
        const double room = resolution / std::max(used_width, used_height);
        if (refit || room < 1.03 || attempt >= 6) break;
        scale *= std::min(room, 1.5) * 0.995;
    }

    // The padding matters between charts, not at the atlas's border: crop the layout to the
    // texels the charts themselves touch.
    int32_t low_x = std::numeric_limits<int32_t>::max(), low_y = low_x, high_x = 0, high_y = 0;
    for (size_t c = 0; c < count; ++c) {
        const Profile& p = prepared[c].profiles[turn[c]];
        for (int32_t i = 0; i < p.width; ++i) {
            if (p.top[i] < 0) continue;
            low_x = std::min(low_x, placed[c].x() + i);
            high_x = std::max(high_x, placed[c].x() + i + 1);
            low_y = std::min(low_y, placed[c].y() + p.chart_bottom[i]);
            high_y = std::max(high_y, placed[c].y() + p.top[i] + 1);
        }
    }
    if (low_x > high_x) low_x = low_y = 0;  // no texel at all (empty charts)
    used_width = std::max(1, high_x - low_x);
    used_height = std::max(1, high_y - low_y);
    for (Eigen::Vector2i& at : placed) at -= Eigen::Vector2i(low_x, low_y);
    // Final coordinates: the layout is stretched uniformly until its longer side is the
    // resolution (a factor >= 1, which only widens the gaps between charts), then normalised per
    // axis to [0, 1].
    const double grow = resolution / std::max(std::max(used_width, used_height), 1);
    result.width = std::max(1, static_cast<int32_t>(std::ceil(used_width * grow - 1e-9)));
    result.height = std::max(1, static_cast<int32_t>(std::ceil(used_height * grow - 1e-9)));
    result.texels_per_unit = scale * grow;
    const double to_u = grow / result.width, to_v = grow / result.height;
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
            result.uv[c][v] =
                Eigen::Vector2d((placed[c].x() + x) * to_u, (placed[c].y() + y) * to_v);
        }
    }
    return result;
}

}  // namespace raps
