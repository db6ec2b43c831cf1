#include "atlas/map_validity.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace raps {
namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() * b.y() - a.y() * b.x();
}

// Segments p-q and r-s intersect (including touching and collinear overlap).
bool segments_intersect(const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                        const Eigen::Vector2d& r, const Eigen::Vector2d& s) {
    const double d1 = cross(q - p, r - p), d2 = cross(q - p, s - p);
    const double d3 = cross(s - r, p - r), d4 = cross(s - r, q - r);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
        return true;
    }
    auto on_segment = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                         const Eigen::Vector2d& c) {
        return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
               std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
    };
    return (d1 == 0 && on_segment(p, q, r)) || (d2 == 0 && on_segment(p, q, s)) ||
           (d3 == 0 && on_segment(r, s, p)) || (d4 == 0 && on_segment(r, s, q));
}

}  // namespace

int64_t count_flipped_or_degenerate(const TriangleMesh& mesh,
                                    const std::vector<Eigen::Vector2d>& uv,
                                    const ProgressSpan& progress) {
    std::vector<double> area(mesh.triangles.size());
    double total = 0;
    for (size_t t = 0; t < area.size(); ++t) {
        progress.at(static_cast<int64_t>(t), static_cast<int64_t>(area.size()));
        const Triangle& v = mesh.triangles[t];
        area[t] = 0.5 * cross(uv[v[1]] - uv[v[0]], uv[v[2]] - uv[v[0]]);
        total += std::abs(area[t]);
    }
    const double threshold = 1e-14 * total / std::max<size_t>(area.size(), 1);
    int64_t bad = 0;
    for (double a : area) bad += !(a > threshold);
    return bad;
}

bool boundary_self_intersects(const std::vector<Eigen::Vector2d>& uv,
                              const std::vector<int32_t>& loop) {
    const size_t n = loop.size();
    if (n < 4) return false;
    double length = 0;
    Eigen::Vector2d low = uv[loop[0]], high = uv[loop[0]];
    for (size_t k = 0; k < n; ++k) {
        length += (uv[loop[(k + 1) % n]] - uv[loop[k]]).norm();
        low = low.cwiseMin(uv[loop[k]]);
        high = high.cwiseMax(uv[loop[k]]);
    }
    const double cell = std::max(2.0 * length / static_cast<double>(n), 1e-300);
    // Cells keyed by their integer coordinates; a segment goes into every cell its box touches.
    std::unordered_map<int64_t, std::vector<int32_t>> cells;
    auto key = [&](int64_t x, int64_t y) { return x * 2654435761LL + y; };
    auto cell_range = [&](size_t k, int64_t& x0, int64_t& y0, int64_t& x1, int64_t& y1) {
        const Eigen::Vector2d a = uv[loop[k]], b = uv[loop[(k + 1) % n]];
        x0 = static_cast<int64_t>(std::floor((std::min(a.x(), b.x()) - low.x()) / cell));
        y0 = static_cast<int64_t>(std::floor((std::min(a.y(), b.y()) - low.y()) / cell));
        x1 = static_cast<int64_t>(std::floor((std::max(a.x(), b.x()) - low.x()) / cell));
        y1 = static_cast<int64_t>(std::floor((std::max(a.y(), b.y()) - low.y()) / cell));
    };
    for (size_t k = 0; k < n; ++k) {
        int64_t x0, y0, x1, y1;
        cell_range(k, x0, y0, x1, y1);
        for (int64_t x = x0; x <= x1; ++x) {
            for (int64_t y = y0; y <= y1; ++y) cells[key(x, y)].push_back(static_cast<int32_t>(k));
        }
    }
    for (const auto& entry : cells) {
        const std::vector<int32_t>& segments = entry.second;
        for (size_t i = 0; i < segments.size(); ++i) {
            for (size_t j = i + 1; j < segments.size(); ++j) {
                const size_t a = segments[i], b = segments[j];
                // Neighbouring segments share an end point by construction.
                if ((a + 1) % n == b || (b + 1) % n == a) continue;
                if (segments_intersect(uv[loop[a]], uv[loop[(a + 1) % n]], uv[loop[b]],
                                       uv[loop[(b + 1) % n]])) {
                    return true;
                }
            }
        }
    }
    return false;
}

}  // namespace raps
