#include "atlas/chart_box.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "atlas/chart_raster.h"
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
    const Eigen::Vector2d extent = turned_box(uv, box.rotation).extent;
    const double box_area = extent.x() * extent.y();
    box.fill = box_area > 0 ? std::min(1.0, uv_area(uv, triangles) / box_area) : 1.0;
    return box;
}

TurnedBox turned_box(const std::vector<Eigen::Vector2d>& uv, const Eigen::Vector2d& rotation) {
    Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
    for (const Eigen::Vector2d& p : uv) {
        lo = lo.cwiseMin(turned(rotation, p));
        hi = hi.cwiseMax(turned(rotation, p));
    }
    return {lo, hi - lo};
}

double uv_area(const std::vector<Eigen::Vector2d>& uv, const std::vector<Triangle>& triangles) {
    double area = 0;
    for (const Triangle& t : triangles) {
        const Eigen::Vector2d a = uv[t[1]] - uv[t[0]], b = uv[t[2]] - uv[t[0]];
        area += 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
    }
    return area;
}

}  // namespace raps
