#include "planar/convex_boundary.h"

#include <algorithm>
#include <cmath>

#include "core/portable_math.h"

namespace raps {
namespace {

// Point at arc parameter s in [0, 4) along the unit square's perimeter, counter-clockwise from
// (0, 0).
Eigen::Vector2d square_point(double s) {
    const int side = std::min(3, static_cast<int>(s));
    const double t = s - side;
    switch (side) {
        case 0:
            return {t, 0.0};
        case 1:
            return {1.0, t};
        case 2:
            return {1.0 - t, 1.0};
        default:
            return {0.0, 1.0 - t};
    }
}

}  // namespace

std::vector<Eigen::Vector2d> convex_boundary(const TriangleMesh& mesh,
                                             const std::vector<int32_t>& loop,
                                             BoundaryShape shape) {
    const size_t n = loop.size();
    // cumulative[i]: chord length from loop[0] to loop[i]; cumulative[n]: the whole loop.
    std::vector<double> cumulative(n + 1, 0.0);
    for (size_t i = 0; i < n; ++i) {
        cumulative[i + 1] =
            cumulative[i] + (mesh.positions[loop[(i + 1) % n]] - mesh.positions[loop[i]]).norm();
    }
    const double total = cumulative[n];
    std::vector<Eigen::Vector2d> uv(n);
    if (shape == BoundaryShape::kCircle || n < 4) {
        for (size_t i = 0; i < n; ++i) {
            const double t = cumulative[i] / total;
            uv[i] = shape == BoundaryShape::kCircle
                        ? Eigen::Vector2d(0.5 + 0.5 * portable::cos(2 * M_PI * t),
                                          0.5 + 0.5 * portable::sin(2 * M_PI * t))
                        : square_point(4.0 * t);
        }
        return uv;
    }
    // Corners at the vertices nearest to each quarter, kept strictly increasing so that every
    // side receives at least its two end vertices; chord length in between.
    size_t corner[5] = {0, 0, 0, 0, n};
    for (int c = 1; c < 4; ++c) {
        const double target = total * c / 4.0;
        const auto it = std::lower_bound(cumulative.begin(), cumulative.begin() + n, target);
        size_t i = static_cast<size_t>(it - cumulative.begin());
        if (i > 0 && target - cumulative[i - 1] < cumulative[i] - target) --i;
        corner[c] = std::clamp(i, corner[c - 1] + 1, n - 4 + c);
    }
    for (int side = 0; side < 4; ++side) {
        const double begin = cumulative[corner[side]],
                     length = cumulative[corner[side + 1]] - begin;
        for (size_t i = corner[side]; i < corner[side + 1]; ++i) {
            uv[i] = square_point(side + (cumulative[i] - begin) / length);
        }
    }
    return uv;
}

}  // namespace raps
