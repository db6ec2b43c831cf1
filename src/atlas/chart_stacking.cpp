#include "atlas/chart_stacking.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

#include "core/hash_mix.h"

namespace raps {
namespace {

// The frame of three of `points` (indices chosen on the first chart and reused on the second,
// whose vertices correspond one to one): an origin and orthonormal axes. Empty when the
// points are (numerically) one point or on one line: no frame to compare in.
template <int N>
struct Frame {
    using Point = Eigen::Matrix<double, N, 1>;
    Point origin;
    Eigen::Matrix<double, N, N> axes;  // rows
    bool valid = false;
};

// Indices of the frame's vertices on the first chart: the first vertex, the farthest from it,
// the farthest from the line through both.
template <int N>
std::array<int32_t, 3> frame_vertices(const std::vector<Eigen::Matrix<double, N, 1>>& p) {
    std::array<int32_t, 3> id = {0, 0, 0};
    double far = -1;
    for (size_t v = 0; v < p.size(); ++v) {
        const double d = (p[v] - p[0]).squaredNorm();
        if (d > far) {
            far = d;
            id[1] = static_cast<int32_t>(v);
        }
    }
    const Eigen::Matrix<double, N, 1> axis = p[id[1]] - p[0];
    far = -1;
    for (size_t v = 0; v < p.size(); ++v) {
        const Eigen::Matrix<double, N, 1> w = p[v] - p[0];
        const double along = w.dot(axis);
        const double d = w.squaredNorm() * axis.squaredNorm() - along * along;
        if (d > far) {
            far = d;
            id[2] = static_cast<int32_t>(v);
        }
    }
    return id;
}

// A 3D frame: x along a->b, y towards c, z their cross product (which a mirror negates).
Frame<3> frame(const std::vector<Eigen::Vector3d>& p, const std::array<int32_t, 3>& id) {
    Frame<3> f;
    const Eigen::Vector3d x = p[id[1]] - p[id[0]];
    const Eigen::Vector3d w = p[id[2]] - p[id[0]];
    const Eigen::Vector3d z = x.cross(w);
    if (!(x.norm() > 0) || !(z.norm() > 1e-12 * x.squaredNorm())) return f;
    const Eigen::Vector3d ex = x.normalized(), ez = z.normalized();
    f.origin = p[id[0]];
    f.axes.row(0) = ex.transpose();
    f.axes.row(1) = ez.cross(ex).transpose();
    f.axes.row(2) = ez.transpose();
    f.valid = true;
    return f;
}

// A 2D frame: x along a->b, y its left perpendicular (which a mirror negates).
Frame<2> frame(const std::vector<Eigen::Vector2d>& p, const std::array<int32_t, 3>& id) {
    Frame<2> f;
    const Eigen::Vector2d x = p[id[1]] - p[id[0]];
    if (!(x.norm() > 0)) return f;
    const Eigen::Vector2d ex = x.normalized();
    f.origin = p[id[0]];
    f.axes.row(0) = ex.transpose();
    f.axes.row(1) = Eigen::Vector2d(-ex.y(), ex.x()).transpose();
    f.valid = true;
    return f;
}

// Whether b's points are a's moved rigidly, or mirrored, within tolerance times a's extent.
template <int N>
PointMatch compare(const std::vector<Eigen::Matrix<double, N, 1>>& a,
                   const std::vector<Eigen::Matrix<double, N, 1>>& b, double tolerance) {
    const std::array<int32_t, 3> id = frame_vertices<N>(a);
    const Frame<N> fa = frame(a, id), fb = frame(b, id);
    if (!fa.valid || !fb.valid) return PointMatch::kNone;
    const double limit = tolerance * (a[id[1]] - a[id[0]]).norm();
    bool rigid = true, mirror = true;
    for (size_t v = 0; v < a.size() && (rigid || mirror); ++v) {
        const Eigen::Matrix<double, N, 1> pa = fa.axes * (a[v] - fa.origin);
        const Eigen::Matrix<double, N, 1> pb = fb.axes * (b[v] - fb.origin);
        for (int k = 0; k < N; ++k) {
            const bool last = k == N - 1;
            rigid = rigid && std::abs(pa[k] - pb[k]) <= limit;
            mirror = mirror && std::abs(pa[k] - (last ? -pb[k] : pb[k])) <= limit;
        }
    }
    return rigid ? PointMatch::kRigid : mirror ? PointMatch::kMirror : PointMatch::kNone;
}

bool congruent(const AtlasChart& a, const AtlasChart& b, const StackSettings& settings) {
    if (a.disk.mesh.triangles != b.disk.mesh.triangles) return false;
    const PointMatch shape =
        compare<3>(a.disk.mesh.positions, b.disk.mesh.positions, settings.tolerance);
    if (shape == PointMatch::kNone) return false;
    bool mirrored = shape == PointMatch::kMirror;
    if (settings.compare_uvs) {
        const PointMatch uv = compare<2>(a.map.uv, b.map.uv, settings.tolerance);
        if (uv == PointMatch::kNone) return false;
        mirrored = mirrored != (uv == PointMatch::kMirror);
    }
    return !mirrored || settings.allow_mirror;
}

// Charts that may stack: the same counts and the same triangles (hashed), and the same part
// when stacking stays within one.
using StackKey = std::tuple<int32_t, size_t, size_t, uint64_t>;

StackKey key_of(const AtlasChart& chart, int32_t part) {
    uint64_t hash = 0;
    for (const Triangle& t : chart.disk.mesh.triangles) {
        for (int32_t v : t) hash = mix_bits(hash ^ static_cast<uint32_t>(v));
    }
    return {part, chart.disk.mesh.positions.size(), chart.disk.mesh.triangles.size(), hash};
}

}  // namespace

PointMatch match_points(const std::vector<Eigen::Vector3d>& a,
                        const std::vector<Eigen::Vector3d>& b, double tolerance) {
    return a.size() == b.size() && !a.empty() ? compare<3>(a, b, tolerance) : PointMatch::kNone;
}

std::vector<int32_t> stack_charts(const std::vector<AtlasChart>& charts,
                                  const std::vector<int32_t>& part, const StackSettings& settings) {
    std::vector<int32_t> place(charts.size());
    std::map<StackKey, std::vector<int32_t>> places;  // per key, the charts that hold a place
    for (size_t c = 0; c < charts.size(); ++c) {
        place[c] = static_cast<int32_t>(c);
        std::vector<int32_t>& candidates =
            places[key_of(charts[c], settings.within_part ? part[c] : 0)];
        for (int32_t other : candidates) {
            if (congruent(charts[other], charts[c], settings)) {
                place[c] = other;
                break;
            }
        }
        if (place[c] == static_cast<int32_t>(c)) candidates.push_back(static_cast<int32_t>(c));
    }
    return place;
}

}  // namespace raps
