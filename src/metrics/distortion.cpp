#include "metrics/distortion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

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
    return std::abs(std::atan2(sine_uv * cosine_3d - cosine_uv * sine_3d,
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
                        const std::vector<Triangle>& triangles) {
    double total_3d = 0, total_uv = 0;
    std::vector<double> area(triangles.size());
    for (size_t t = 0; t < triangles.size(); ++t) {
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

DistortionStats measure_distortion(const std::vector<Eigen::Vector3d>& positions,
                                   const MapGeometry& map, const std::vector<Triangle>& triangles) {
    const size_t count = triangles.size();
    std::vector<double> area(count), uv_signed_area(count);
    double area_sum = 0;
    for (size_t t = 0; t < count; ++t) {
        const Triangle& v = triangles[t];
        area[t] =
            0.5 *
            (positions[v[1]] - positions[v[0]]).cross(positions[v[2]] - positions[v[0]]).norm();
        uv_signed_area[t] = map.area(v[0], v[1], v[2]);
        area_sum += area[t];
    }
    const double degenerate_3d = 1e-12 * area_sum / static_cast<double>(count);
    std::vector<size_t> used;
    used.reserve(count);
    double total_3d = 0, total_uv = 0;
    for (size_t t = 0; t < count; ++t) {
        if (area[t] >= degenerate_3d && area[t] > 0 && std::isfinite(uv_signed_area[t])) {
            used.push_back(t);
            total_3d += area[t];
            total_uv += std::abs(uv_signed_area[t]);
        }
    }
    DistortionStats stats;
    if (used.empty()) return stats;
    const double zero_uv = 1e-14 * total_uv / static_cast<double>(used.size());
    const double infinity = std::numeric_limits<double>::infinity();
    // A map that collapses every triangle (total uv area 0) has infinite distortion, not 0/0:
    // r_t is 0 and, at scale 1, every singular value is 0.
    const double scale = total_uv > 0 ? std::sqrt(total_3d / total_uv) : 1.0;
    double angle_sum = 0, stretch_sum = 0;
    stats.area_max = 1;
    stats.stretch_linf = 0;
    for (size_t t : used) {
        const Triangle& v = triangles[t];
        const double a = uv_signed_area[t];
        if (a < -zero_uv) ++stats.flipped_triangles;
        if (std::abs(a) <= zero_uv) ++stats.zero_area_triangles;
        const double weight = area[t] / total_3d;
        const double r = total_uv > 0 ? (std::abs(a) / total_uv) / weight : 0.0;
        stats.area_log_mean += weight * std::abs(std::log(r));
        stats.area_max = std::max(stats.area_max, r > 0 ? std::max(r, 1 / r) : infinity);
        for (int k = 0; k < 3; ++k) {
            const int32_t i = v[k], j = v[(k + 1) % 3], l = v[(k + 2) % 3];
            double sine, cosine;
            map.angle(i, j, l, &sine, &cosine);
            const double degrees = angle_difference(positions[j] - positions[i],
                                                    positions[l] - positions[i], sine, cosine) *
                                   180.0 / M_PI;
            angle_sum += degrees;
            stats.angle_max_deg = std::max(stats.angle_max_deg, degrees);
        }
        Eigen::Vector2d d1, d2;
        map.edges(v[0], v[1], v[2], &d1, &d2);
        const auto [uv_big, uv_small] = uv_singular_values(
            positions[v[1]] - positions[v[0]], positions[v[2]] - positions[v[0]], area[t], d1, d2);
        const double big = scale * uv_big, small = scale * uv_small;
        const double stretch_max = 1.0 / small, stretch_min = 1.0 / big;
        stretch_sum += weight * 0.5 * (stretch_max * stretch_max + stretch_min * stretch_min);
        stats.stretch_linf = std::max(stats.stretch_linf, stretch_max);
    }
    stats.angle_mean_deg = angle_sum / (3.0 * static_cast<double>(used.size()));
    stats.stretch_l2 = std::sqrt(stretch_sum);
    return stats;
}

}  // namespace raps
