#include "sphere/cylinder_initial_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>
#include <utility>

#include "core/fill_in_runs.h"
#include "core/portable_math.h"
#include "core/release_in_runs.h"
#include "core/sort_in_runs.h"
#include "mesh/mesh_topology.h"
#include "planar/laplace_system.h"
#include "sphere/mobius_centring.h"
#include "sphere/sphere_initial_map.h"
#include "sphere/sphere_map_check.h"
#include "weights/laplacian_weights.h"

namespace raps {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

// The equal-area map counts every triangle as at least this share of the mean triangle area. A
// sliver gets the sphere's share of its 3D area, nearly none, and a band of slivers as wide as
// its ring is then too flat to keep its orientation (folds once the band's height is below about
// dtheta^2 / 8). Measured on the dumbbell of neck 0.02, whose tips are flat disks of nearly
// coincident rings: without the floor its equal-area map folded 120 to 672 triangles at every
// blend and the area monitor reached 15 %; with 0.01, 0.03 and 0.1: 53.1 -> 0.030, 0.039 and
// 0.088, with 0.1 in the fewest sweeps (312 against 730; docs/sphere-status.md).
constexpr double kAreaFloor = 0.1;

// Dijkstra over 3D edge lengths from `from`; returns the farthest vertex (the lowest index among
// equals).
int32_t farthest_vertex(const SphereProblem& problem, int32_t from, const ProgressSpan& beat) {
    const VertexAdjacency& adjacency = problem.adjacency;
    const std::vector<Eigen::Vector3d>& p = problem.mesh.positions;
    std::vector<double> distance(p.size(), std::numeric_limits<double>::infinity());
    using Entry = std::pair<double, int32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    distance[from] = 0.0;
    queue.push({0.0, from});
    for (int64_t popped = 0; !queue.empty(); ++popped) {
        beat.at(popped, static_cast<int64_t>(p.size()));
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > distance[v]) continue;
        for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s) {
            const int32_t w = adjacency.neighbors[s];
            const double through = d + (p[w] - p[v]).norm();
            if (through < distance[w]) {
                distance[w] = through;
                queue.push({through, w});
            }
        }
    }
    int32_t best = from;
    for (int32_t v = 0; v < static_cast<int32_t>(p.size()); ++v) {
        if (distance[v] > distance[best]) best = v;
    }
    return best;
}

// A path with the fewest edges from a to b (so no two of its vertices but consecutive ones share
// an edge), a first.
std::vector<int32_t> fewest_edges_path(const VertexAdjacency& adjacency, int32_t a, int32_t b,
                                       const ProgressSpan& beat) {
    const int32_t n = static_cast<int32_t>(adjacency.offsets.size()) - 1;
    std::vector<int32_t> hops(n, -1);
    std::vector<int32_t> queue{a};
    hops[a] = 0;
    for (size_t k = 0; k < queue.size() && hops[b] < 0; ++k) {
        beat.at(static_cast<int64_t>(k), n);
        const int32_t v = queue[k];
        for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s) {
            const int32_t w = adjacency.neighbors[s];
            if (hops[w] < 0) {
                hops[w] = hops[v] + 1;
                queue.push_back(w);
            }
        }
    }
    std::vector<int32_t> path{b};
    while (path.back() != a) {
        const int32_t v = path.back();
        for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s) {
            if (hops[adjacency.neighbors[s]] == hops[v] - 1) {
                path.push_back(adjacency.neighbors[s]);
                break;
            }
        }
    }
    std::reverse(path.begin(), path.end());
    return path;
}

// The ring of v (its first half-edge out: first_out[v]) turned so that it starts at `first`.
std::vector<int32_t> ring_from(const SphereProblem& problem, const std::vector<int32_t>& first_out,
                               int32_t v, int32_t first) {
    std::vector<int32_t> ring = vertex_ring_from(problem.mesh, problem.halfedges, first_out[v]);
    std::rotate(ring.begin(), std::find(ring.begin(), ring.end(), first), ring.end());
    return ring;
}

int32_t slot_of(const VertexAdjacency& adjacency, int32_t v, int32_t w) {
    const auto begin = adjacency.neighbors.begin() + adjacency.offsets[v];
    const auto end = adjacency.neighbors.begin() + adjacency.offsets[v + 1];
    return static_cast<int32_t>(std::lower_bound(begin, end, w) - adjacency.neighbors.begin());
}

// The cut: theta jumps by 2 pi across `path` (A, its ring, ..., B's ring, B). At each inner
// path vertex its ring splits into the neighbours between the next and the previous path vertex
// and those between the previous and the next; `shift` gets, per adjacency slot v -> w, what
// theta(w) - theta(v) on the cylinder's cover exceeds the stored values' difference by: -2 pi
// from a path vertex to a neighbour on the side of the cut whose stored angles are near 2 pi,
// +2 pi back. That side is the one holding the last vertex of A's ring (A's ring starts at the
// path's second vertex, at angle 0). Returns +1 or -1 for the side of B's ring's second vertex
// (+1: the same side, so B's ring runs the other way round the cylinder), 0 if the sides
// do not come out consistent (then no cylinder map).
int cut_shifts(const SphereProblem& problem, const std::vector<int32_t>& first_out,
               const std::vector<int32_t>& path, const std::vector<int32_t>& ring_a,
               const std::vector<int32_t>& ring_b, std::vector<double>& shift,
               const ProgressSpan& beat) {
    const VertexAdjacency& adjacency = problem.adjacency;
    // One per adjacency slot: 270 MB of fresh pages at 5.65M triangles, filled in runs.
    assign_in_runs(shift, adjacency.neighbors.size(), 0.0, beat);
    bool after_next = false;  // whether the high side runs from next to previous in ring order
    int b_side = 0;
    for (size_t m = 1; m + 1 < path.size(); ++m) {
        const std::vector<int32_t> ring =
            vertex_ring_from(problem.mesh, problem.halfedges, first_out[path[m]]);
        const int32_t k = static_cast<int32_t>(ring.size());
        const int32_t previous =
            static_cast<int32_t>(std::find(ring.begin(), ring.end(), path[m - 1]) - ring.begin());
        const int32_t next =
            static_cast<int32_t>(std::find(ring.begin(), ring.end(), path[m + 1]) - ring.begin());
        const auto on_high_side = [&](int32_t index) {
            // Strictly between next and previous (cyclically, in ring order) or the reverse.
            const int32_t from = after_next ? next : previous, to = after_next ? previous : next;
            const int32_t offset = (index - from + k) % k, span = (to - from + k) % k;
            return offset > 0 && offset < span;
        };
        if (m == 1) {
            const int32_t last_a = static_cast<int32_t>(
                std::find(ring.begin(), ring.end(), ring_a.back()) - ring.begin());
            if (last_a == k) return 0;
            after_next = true;
            if (!on_high_side(last_a)) {
                after_next = false;
                if (!on_high_side(last_a)) return 0;
            }
        }
        if (m + 2 == path.size()) {
            const auto index = [&](int32_t v) {
                return static_cast<int32_t>(std::find(ring.begin(), ring.end(), v) - ring.begin());
            };
            const bool second = on_high_side(index(ring_b[1]));
            const bool last = on_high_side(index(ring_b.back()));
            if (second == last) return 0;
            b_side = second ? 1 : -1;
        }
        for (int32_t index = 0; index < k; ++index) {
            if (!on_high_side(index)) continue;
            const int32_t w = ring[index];
            shift[slot_of(adjacency, path[m], w)] = -kTwoPi;
            shift[slot_of(adjacency, w, path[m])] = kTwoPi;
        }
    }
    return b_side;
}

double tanh_of(double x) {
    const double e = portable::exp(-2.0 * std::abs(x));
    return std::copysign((1.0 - e) / (1.0 + e), x);
}

}  // namespace

std::optional<CylinderCoordinates> cylinder_coordinates(const SphereProblem& problem,
                                                        WeightScheme weights,
                                                        const ProgressSpan& progress) {
    const TriangleMesh& mesh = problem.mesh;
    const VertexAdjacency& adjacency = problem.adjacency;
    const int32_t n = mesh.vertex_count();
    // The passes around the solves report to `beat` as they go: at 446K triangles they were
    // 320 ms without a progress call.
    const ProgressSpan beat = progress.part(0.0, 0.0);
    const int32_t a = farthest_vertex(problem, farthest_vertex(problem, 0, beat), beat);
    const int32_t b = farthest_vertex(problem, a, beat);
    const std::vector<int32_t> path = fewest_edges_path(adjacency, a, b, beat);
    if (path.size() < 5) return std::nullopt;
    // Each ring from its vertex's first half-edge, found for all in one pass: vertex_ring's own
    // search, a pass over the mesh for every vertex of the path, was 170 ms at 446K triangles.
    const std::vector<int32_t> first_out = first_outgoing_halfedges(mesh, problem.halfedges, beat);
    const std::vector<int32_t> ring_a = ring_from(problem, first_out, a, path[1]);
    const std::vector<int32_t> ring_b = ring_from(problem, first_out, b, path[path.size() - 2]);
    std::vector<double> shift;
    const int b_side = cut_shifts(problem, first_out, path, ring_a, ring_b, shift, beat);
    if (b_side == 0) return std::nullopt;

    // Height in x, angle in y; the rings fixed (B's twist is added below, as tau h).
    std::vector<char> fixed = filled_in_runs(static_cast<size_t>(n), char{0}, beat);
    std::vector<Eigen::Vector2d> plane =
        filled_in_runs(static_cast<size_t>(n), Eigen::Vector2d::Zero().eval(), beat);
    fixed[a] = fixed[b] = 1;
    const std::vector<double> angle_a = pole_ring_angles(mesh, a, ring_a);
    const std::vector<double> angle_b = pole_ring_angles(mesh, b, ring_b);
    for (size_t m = 0; m < ring_a.size(); ++m) {
        fixed[ring_a[m]] = 1;
        plane[ring_a[m]] = Eigen::Vector2d(0.0, angle_a[m]);
    }
    for (size_t m = 0; m < ring_b.size(); ++m) {
        fixed[ring_b[m]] = 1;
        const double theta = b_side > 0 && m > 0 ? kTwoPi - angle_b[m] : angle_b[m];
        plane[ring_b[m]] = Eigen::Vector2d(1.0, theta);
    }
    const WeightScheme positive =
        weights == WeightScheme::kCotangent ? WeightScheme::kMeanValue : weights;
    std::vector<double> w = laplacian_weights(mesh, adjacency, positive, progress.part(0.0, 0.05));
    {
        LaplaceSystem system(mesh, adjacency, fixed, {}, progress.part(0.05, 0.4));
        system.solve(w, plane, progress.part(0.4, 0.8));
        // The cut's jumps, by superposition: the same system with their terms as right-hand side.
        const std::vector<int32_t>& vertex_of = system.vertex_of_unknown();
        const int32_t unknowns = system.unknown_count();
        std::vector<double> rhs = filled_in_runs(2 * static_cast<size_t>(unknowns), 0.0, beat);
        for (int32_t row = 0; row < unknowns; ++row) {
            beat.at(row, unknowns);
            const int32_t v = vertex_of[row];
            double sum = 0.0, jump = 0.0;
            for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s) {
                sum += w[s];
                jump += w[s] * shift[s];
            }
            rhs[unknowns + row] = jump / sum;
        }
        system.solver().solve_more(rhs.data(), 2, progress.part(0.8, 1.0));
        for (int32_t row = 0; row < unknowns; ++row) {
            beat.at(row, unknowns);
            plane[vertex_of[row]].y() += rhs[unknowns + row];
        }
        // Given back in runs: the factorization's memory freed in one go was 131 ms at 5.65M
        // triangles without a progress call.
        release_in_runs(rhs, beat);
        system.release(beat);
    }
    release_in_runs(fixed, beat);

    // The twist of least energy (theta + tau h), then the modulus H; sums over the annulus.
    double hh = 0.0, th = 0.0, tt = 0.0;
    const ProgressSpan end = progress.part(1.0, 1.0);
    for (int32_t v = 0; v < n; ++v) {
        end.at(v, n);
        if (v == a || v == b) continue;
        for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s) {
            const int32_t u = adjacency.neighbors[s];
            if (u == a || u == b) continue;
            const double dh = plane[u].x() - plane[v].x();
            const double dt = plane[u].y() + shift[s] - plane[v].y();
            hh += w[s] * dh * dh;
            th += w[s] * dt * dh;
            tt += w[s] * dt * dt;
        }
    }
    if (!(hh > 0.0)) return std::nullopt;
    CylinderCoordinates cylinder;
    cylinder.south = a;
    cylinder.north = b;
    cylinder.modulus = std::sqrt(std::max(tt - th * th / hh, 0.0) / hh);
    if (!(cylinder.modulus > 0.0) || !std::isfinite(cylinder.modulus)) return std::nullopt;
    const double tau = -th / hh;
    assign_in_runs(cylinder.height, static_cast<size_t>(n), 0.0, end);
    assign_in_runs(cylinder.cosine, static_cast<size_t>(n), 0.0, end);
    assign_in_runs(cylinder.sine, static_cast<size_t>(n), 0.0, end);
    for (int32_t v = 0; v < n; ++v) {
        end.at(v, n);
        const double theta = plane[v].y() + tau * plane[v].x();
        cylinder.height[v] = plane[v].x();
        cylinder.cosine[v] = portable::cos(theta);
        cylinder.sine[v] = portable::sin(theta);
    }
    release_in_runs(w, end);
    release_in_runs(shift, end);
    release_in_runs(plane, end);
    return cylinder;
}

namespace {

// Which way round theta runs was not decided: a reflection if most triangles came out
// clockwise.
void orient(const TriangleMesh& mesh, std::vector<Eigen::Vector3d>& points,
            const ProgressSpan& beat) {
    if (2 * count_folds(mesh, points, beat).folded > mesh.triangle_count()) {
        for (Eigen::Vector3d& p : points) p.y() = -p.y();
    }
}

// The shift c of the height that balances the centre of mass of the conformal lift along the
// axis: its height component sum mass tanh(H (h - c)) falls as c grows (bisection).
double axial_balance(const SphereProblem& problem, const CylinderCoordinates& cylinder,
                     const ProgressSpan& beat) {
    const int32_t n = problem.mesh.vertex_count();
    double low = -1.0, high = 2.0;
    for (int k = 0; k < 80; ++k) {
        const double c = 0.5 * (low + high);
        double balance = 0.0;
        for (int32_t v = 0; v < n; ++v) {
            beat.at(v, n);
            balance +=
                problem.mass[v] * (v == cylinder.south ? -1.0
                                   : v == cylinder.north
                                       ? 1.0
                                       : tanh_of(cylinder.modulus * (cylinder.height[v] - c)));
        }
        (balance > 0.0 ? low : high) = c;
    }
    return 0.5 * (low + high);
}

}  // namespace

std::vector<Eigen::Vector3d> conformal_cylinder_map(const SphereProblem& problem,
                                                    const CylinderCoordinates& cylinder,
                                                    const ProgressSpan& beat) {
    const int32_t n = problem.mesh.vertex_count();
    const double height = cylinder.modulus;
    const auto is_pole = [&](int32_t v) { return v == cylinder.south || v == cylinder.north; };
    const double c = axial_balance(problem, cylinder, beat);
    std::vector<Eigen::Vector3d> points(n);
    for (int32_t v = 0; v < n; ++v) {
        beat.at(v, n);
        if (is_pole(v)) {
            points[v] = Eigen::Vector3d(0.0, 0.0, v == cylinder.south ? -1.0 : 1.0);
            continue;
        }
        const double x = height * (cylinder.height[v] - c);
        const double r = portable::exp(-std::abs(x));
        const double d = 1.0 + r * r;
        points[v] =
            Eigen::Vector3d(2.0 * r * cylinder.cosine[v] / d, 2.0 * r * cylinder.sine[v] / d,
                            std::copysign((1.0 - r * r) / d, x));
    }
    orient(problem.mesh, points, beat);
    return points;
}

std::vector<Eigen::Vector3d> equal_area_cylinder_map(const SphereProblem& problem,
                                                     const CylinderCoordinates& cylinder,
                                                     double share, const ProgressSpan& beat) {
    const TriangleMesh& mesh = problem.mesh;
    const int32_t n = mesh.vertex_count();
    const auto is_pole = [&](int32_t v) { return v == cylinder.south || v == cylinder.north; };
    // The 3D area below each height, F(h): each triangle's area spread evenly over its own range
    // of heights, so that F is piecewise linear with a slope that changes only at vertices and
    // varies on the scale of the triangles (a step per vertex or per bin made F steep inside
    // one ring of a capsule and folded its triangles). The poles' stars are steps at 0 and 1.
    // The arrays are filled, and given back, in runs: 90 MB of fresh pages at 5.65M triangles.
    std::vector<double> slope_change = filled_in_runs(static_cast<size_t>(n), 0.0, beat);
    std::vector<double> step = filled_in_runs(static_cast<size_t>(n), 0.0, beat);
    double total = 0.0, start = 0.0;
    std::vector<double> areas = filled_in_runs(mesh.triangles.size(), 0.0, beat);
    double sum = 0.0;
    const int64_t triangle_count = mesh.triangle_count();
    for (size_t k = 0; k < mesh.triangles.size(); ++k) {
        beat.at(static_cast<int64_t>(k), triangle_count);
        const Triangle& t = mesh.triangles[k];
        areas[k] = 0.5 * (mesh.positions[t[1]] - mesh.positions[t[0]])
                             .cross(mesh.positions[t[2]] - mesh.positions[t[0]])
                             .norm();
        sum += areas[k];
    }
    const double floor = kAreaFloor * sum / static_cast<double>(mesh.triangles.size());
    for (size_t f = 0; f < mesh.triangles.size(); ++f) {
        beat.at(static_cast<int64_t>(f), triangle_count);
        const Triangle& t = mesh.triangles[f];
        const double area = std::max(areas[f], floor);
        total += area;
        if (is_pole(t[0]) || is_pole(t[1]) || is_pole(t[2])) {
            if (t[0] == cylinder.south || t[1] == cylinder.south || t[2] == cylinder.south)
                start += area;
            continue;
        }
        int32_t low = t[0], high = t[0];
        for (int k = 1; k < 3; ++k) {
            if (cylinder.height[t[k]] < cylinder.height[low]) low = t[k];
            if (cylinder.height[t[k]] > cylinder.height[high]) high = t[k];
        }
        const double span = cylinder.height[high] - cylinder.height[low];
        if (span > 0.0) {
            slope_change[low] += area / span;
            slope_change[high] -= area / span;
        } else {
            step[low] += area;
        }
    }
    std::vector<int32_t> order;
    order.reserve(n);
    for (int32_t v = 0; v < n; ++v) {
        if (!is_pole(v)) order.push_back(v);
    }
    sort_in_runs(
        order,
        [&](int32_t x, int32_t y) {
            return cylinder.height[x] < cylinder.height[y] ||
                   (cylinder.height[x] == cylinder.height[y] && x < y);
        },
        beat);
    release_in_runs(areas, beat);
    std::vector<Eigen::Vector3d> points =
        filled_in_runs(static_cast<size_t>(n), Eigen::Vector3d::Zero().eval(), beat);
    points[cylinder.south] = Eigen::Vector3d(0.0, 0.0, -1.0);
    points[cylinder.north] = Eigen::Vector3d(0.0, 0.0, 1.0);
    const double c = axial_balance(problem, cylinder, beat);
    double below = start, slope = 0.0, previous = 0.0;
    for (size_t k = 0; k < order.size(); ++k) {
        beat.at(static_cast<int64_t>(k), n);
        const int32_t v = order[k];
        below += slope * (cylinder.height[v] - previous);
        previous = cylinder.height[v];
        slope += slope_change[v];
        // The blend is of Mercator latitudes, log(g / q) for the sphere's shares g below and
        // q above the point: 2 H (h - c) for the conformal lift, the 3D shares' for the
        // equal-area one. (A blend of the shares themselves is the equal-area map's near the
        // poles, whatever the share.)
        const double g = below / total, q = (total - below) / total;
        const double key = (1.0 - share) * 2.0 * cylinder.modulus * (cylinder.height[v] - c) +
                           share * (portable::log(g) - portable::log(q));
        below += step[v];
        const double t = portable::exp(-0.5 * std::abs(key));
        const double d = 1.0 + t * t;
        points[v] =
            Eigen::Vector3d(2.0 * t * cylinder.cosine[v] / d, 2.0 * t * cylinder.sine[v] / d,
                            std::copysign((1.0 - t * t) / d, key));
    }
    release_in_runs(slope_change, beat);
    release_in_runs(step, beat);
    release_in_runs(order, beat);
    orient(mesh, points, beat);
    return points;
}

}  // namespace raps
