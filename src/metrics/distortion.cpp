#include "metrics/distortion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/fill_in_runs.h"
#include "core/portable_math.h"

namespace raps {
namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
}

// |uv angle - 3D angle| at a corner from the sine and cosine of each (both scaled by the side
// lengths, which atan2 ignores): one atan2 of the difference instead of two angles. The uv angle
// is taken unsigned, as the reference metrics do.
double angle_difference(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double sine_uv,
                        double cosine_uv) {
    const double sine_3d = a.cross(b).norm(), cosine_3d = a.dot(b);
    sine_uv = std::abs(sine_uv);
    return std::abs(portable::atan2(sine_uv * cosine_3d - cosine_uv * sine_3d,
                                    cosine_uv * cosine_3d + sine_uv * sine_3d));
}

// Singular values (largest, smallest) of the Jacobian of uv over an orthonormal frame of the
// 3D triangle, in closed form (no squaring, so no cancellation near an isometry).
std::pair<double, double> uv_singular_values(const Eigen::Vector3d& e1, const Eigen::Vector3d& e2,
                                             double area, const Eigen::Vector2d& d1,
                                             const Eigen::Vector2d& d2) {
    const double length = e1.norm();
    const double p2x = e2.dot(e1) / length, p2y = 2.0 * area / length;
    const double j00 = d1.x() / length, j10 = d1.y() / length;
    const double j01 = (d2.x() - d1.x() * p2x / length) / p2y;
    const double j11 = (d2.y() - d1.y() * p2x / length) / p2y;
    const double q = 0.5 * std::sqrt((j00 + j11) * (j00 + j11) + (j10 - j01) * (j10 - j01));
    const double s = 0.5 * std::sqrt((j00 - j11) * (j00 - j11) + (j10 + j01) * (j10 + j01));
    return {q + s, std::abs(q - s)};
}

}  // namespace

Stretch measure_stretch(const std::vector<Eigen::Vector3d>& positions,
                        const std::vector<Eigen::Vector2d>& uv,
                        const std::vector<Triangle>& triangles, const ProgressSpan& progress) {
    double total_3d = 0, total_uv = 0;
    const int64_t count = static_cast<int64_t>(triangles.size());
    std::vector<double> area(triangles.size());
    for (size_t t = 0; t < triangles.size(); ++t) {
        progress.at(static_cast<int64_t>(t), count, 0.0, 0.5);
        const Triangle& v = triangles[t];
        area[t] =
            0.5 *
            (positions[v[1]] - positions[v[0]]).cross(positions[v[2]] - positions[v[0]]).norm();
        total_3d += area[t];
        total_uv += 0.5 * std::abs(cross2(uv[v[1]] - uv[v[0]], uv[v[2]] - uv[v[0]]));
    }
    Stretch stretch;
    if (!(total_3d > 0) || !(total_uv > 0)) return stretch;
    const double scale = std::sqrt(total_3d / total_uv);
    const double degenerate = 1e-12 * total_3d / static_cast<double>(triangles.size());
    double sum = 0;
    stretch.linf = 0;
    for (size_t t = 0; t < triangles.size(); ++t) {
        progress.at(static_cast<int64_t>(t), count, 0.5, 1.0);
        if (!(area[t] >= degenerate && area[t] > 0)) continue;
        const Triangle& v = triangles[t];
        const auto [big, small] =
            uv_singular_values(positions[v[1]] - positions[v[0]], positions[v[2]] - positions[v[0]],
                               area[t], uv[v[1]] - uv[v[0]], uv[v[2]] - uv[v[0]]);
        const double stretch_max = 1.0 / (scale * small), stretch_min = 1.0 / (scale * big);
        sum += area[t] / total_3d * 0.5 * (stretch_max * stretch_max + stretch_min * stretch_min);
        stretch.linf = std::max(stretch.linf, stretch_max);
    }
    stretch.l2 = std::sqrt(sum);
    return stretch;
}

namespace {

// Sums and extremes over a range of triangles, combined in block order (parallel_sum).
struct Totals {
    double area_3d = 0, area_uv = 0;
    int64_t used = 0;
    Totals& operator+=(const Totals& o) {
        area_3d += o.area_3d;
        area_uv += o.area_uv;
        used += o.used;
        return *this;
    }
};
struct Figures {
    int64_t flipped = 0, zero_area = 0;
    double area_log = 0, area_max = 1, angle_sum = 0, angle_max = 0, stretch_sum = 0,
           stretch_max = 0;
    Figures& operator+=(const Figures& o) {
        flipped += o.flipped;
        zero_area += o.zero_area;
        area_log += o.area_log;
        area_max = std::max(area_max, o.area_max);
        angle_sum += o.angle_sum;
        angle_max = std::max(angle_max, o.angle_max);
        stretch_sum += o.stretch_sum;
        stretch_max = std::max(stretch_max, o.stretch_max);
        return *this;
    }
};

}  // namespace

DistortionStats measure_distortion(const std::vector<Eigen::Vector3d>& positions,
                                   const MapGeometry& map, const std::vector<Triangle>& triangles,
                                   ThreadPool& pool, const ProgressSpan& progress) {
    // Progress: the per-triangle arrays' fills (in runs: 2 x 46 MB of fresh pages at 5.8M
    // triangles were 40 ms of CPU without a call), then three passes, each block of a pass
    // reporting as it starts (whichever thread takes it); the last pass is most of the work.
    const ProgressSpan fills = progress.part(0.0, 0.03), areas = progress.part(0.03, 0.15),
                       sums = progress.part(0.15, 0.2), figures_span = progress.part(0.2, 1.0);
    const int64_t count = static_cast<int64_t>(triangles.size());
    std::vector<double> area = filled_in_runs(count, 0.0, fills.part(0.0, 0.5));
    std::vector<double> uv_signed_area = filled_in_runs(count, 0.0, fills.part(0.5, 1.0));
    const double area_sum = parallel_sum<double>(pool, count, [&](int64_t begin, int64_t end) {
        areas.at(begin, count);
        double sum = 0;
        for (int64_t t = begin; t < end; ++t) {
            const Triangle& v = triangles[t];
            area[t] =
                0.5 *
                (positions[v[1]] - positions[v[0]]).cross(positions[v[2]] - positions[v[0]]).norm();
            uv_signed_area[t] = map.area(v[0], v[1], v[2]);
            sum += area[t];
        }
        return sum;
    });
    const double degenerate_3d = 1e-12 * area_sum / static_cast<double>(count);
    auto used = [&](int64_t t) {
        return area[t] >= degenerate_3d && area[t] > 0 && std::isfinite(uv_signed_area[t]);
    };
    const Totals totals = parallel_sum<Totals>(pool, count, [&](int64_t begin, int64_t end) {
        sums.at(begin, count);
        Totals sum;
        for (int64_t t = begin; t < end; ++t) {
            if (!used(t)) continue;
            ++sum.used;
            sum.area_3d += area[t];
            sum.area_uv += std::abs(uv_signed_area[t]);
        }
        return sum;
    });
    DistortionStats stats;
    if (totals.used == 0) return stats;
    const double total_3d = totals.area_3d, total_uv = totals.area_uv;
    const double zero_uv = 1e-14 * total_uv / static_cast<double>(totals.used);
    const double infinity = std::numeric_limits<double>::infinity();
    // A map that collapses every triangle (total uv area 0) has infinite distortion, not 0/0:
    // r_t is 0 and, at scale 1, every singular value is 0.
    const double scale = total_uv > 0 ? std::sqrt(total_3d / total_uv) : 1.0;
    const Figures figures = parallel_sum<Figures>(pool, count, [&](int64_t begin, int64_t end) {
        figures_span.at(begin, count);
        Figures sum;
        for (int64_t t = begin; t < end; ++t) {
            if (!used(t)) continue;
            const Triangle& v = triangles[t];
            const double a = uv_signed_area[t];
            if (a < -zero_uv) ++sum.flipped;
            if (std::abs(a) <= zero_uv) ++sum.zero_area;
            const double weight = area[t] / total_3d;
            const double r = total_uv > 0 ? (std::abs(a) / total_uv) / weight : 0.0;
            sum.area_log += weight * std::abs(portable::log(r));
            sum.area_max = std::max(sum.area_max, r > 0 ? std::max(r, 1 / r) : infinity);
            for (int k = 0; k < 3; ++k) {
                const int32_t i = v[k], j = v[(k + 1) % 3], l = v[(k + 2) % 3];
                double sine, cosine;
                map.angle(i, j, l, &sine, &cosine);
                const double degrees = angle_difference(positions[j] - positions[i],
                                                        positions[l] - positions[i], sine, cosine) *
                                       180.0 / M_PI;
                sum.angle_sum += degrees;
                sum.angle_max = std::max(sum.angle_max, degrees);
            }
            Eigen::Vector2d d1, d2;
            map.edges(v[0], v[1], v[2], &d1, &d2);
            const auto [uv_big, uv_small] =
                uv_singular_values(positions[v[1]] - positions[v[0]],
                                   positions[v[2]] - positions[v[0]], area[t], d1, d2);
            const double big = scale * uv_big, small = scale * uv_small;
            const double stretch_max = 1.0 / small, stretch_min = 1.0 / big;
            sum.stretch_sum +=
                weight * 0.5 * (stretch_max * stretch_max + stretch_min * stretch_min);
            sum.stretch_max = std::max(sum.stretch_max, stretch_max);
        }
        return sum;
    });
    stats.flipped_triangles = figures.flipped;
    stats.zero_area_triangles = figures.zero_area;
    stats.area_log_mean = figures.area_log;
    stats.area_max = figures.area_max;
    stats.angle_mean_deg = figures.angle_sum / (3.0 * static_cast<double>(totals.used));
    stats.angle_max_deg = figures.angle_max;
    stats.stretch_l2 = std::sqrt(figures.stretch_sum);
    stats.stretch_linf = figures.stretch_max;
    return stats;
}

}  // namespace raps
