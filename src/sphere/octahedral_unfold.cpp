#include "sphere/octahedral_unfold.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <string>

#include <Eigen/Geometry>

#include "core/error.h"
#include "core/portable_rotation.h"
#include "mesh/mesh_topology.h"
#include "planar/laplace_system.h"
#include "sphere/spherical_geometry.h"
#include "weights/laplacian_weights.h"

namespace raps {
namespace {

// Seam k runs along the meridian at longitude k * 90 degrees: +x, +y, -x, -y.
constexpr int kSeams = 4;

// The rotation that takes unit vector `from` to the south pole.
Eigen::Matrix3d rotation_to_south(const Eigen::Vector3d& from) {
    const Eigen::Vector3d south = -Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d axis = from.cross(south);
    const double sine = axis.norm(), cosine = from.dot(south);
    if (sine > 1e-15) {
        return portable::rotation(portable::atan2(sine, cosine), axis / sine);
    }
    return cosine > 0.0 ? Eigen::Matrix3d::Identity()
                        : portable::rotation(M_PI, Eigen::Vector3d::UnitX());
}

// Angular distance of longitude `angle` from seam k's meridian, in [0, pi].
double off_meridian(double angle, int k) {
    const double d = std::remainder(angle - k * M_PI / 2.0, 2.0 * M_PI);
    return std::abs(d);
}

// The octahedral map of a unit vector onto [-1, 1]^2 (Praun and Hoppe 2003).
Eigen::Vector2d octahedral(const Eigen::Vector3d& q) {
    const double l1 = std::abs(q.x()) + std::abs(q.y()) + std::abs(q.z());
    const double x = q.x() / l1, y = q.y() / l1;
    if (q.z() >= 0.0) return {x, y};
    const double sx = x >= 0.0 ? 1.0 : -1.0, sy = y >= 0.0 ? 1.0 : -1.0;
    return {sx * (1.0 - std::abs(y)), sy * (1.0 - std::abs(x))};
}

struct Cut {
    int32_t root = -1;
    Eigen::Matrix3d rotation;
    std::vector<std::vector<int32_t>> paths;  // per seam: root, ..., the vertex at the equator
};

// Shortest path by chord length from the root to the vertex nearest seam k's equator point,
// over the vertices within `width` of the seam's meridian that no other path uses.
std::vector<int32_t> seam_path(const VertexAdjacency& adjacency,
                               const std::vector<Eigen::Vector3d>& q, int32_t root, int k,
                               double width, const std::vector<char>& taken) {
    const int32_t n = static_cast<int32_t>(q.size());
    const Eigen::Vector3d equator(portable::cos(k * M_PI / 2.0), portable::sin(k * M_PI / 2.0),
                                  0.0);
    auto allowed = [&](int32_t v) {
        return v == root ||
               (!taken[v] && off_meridian(portable::atan2(q[v].y(), q[v].x()), k) < width);
    };
    std::vector<double> distance(n, std::numeric_limits<double>::infinity());
    std::vector<int32_t> parent(n, -1);
    using Entry = std::pair<double, int32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    distance[root] = 0.0;
    queue.push({0.0, root});
    int32_t best = -1;
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > distance[v]) continue;
        if (v != root && (best < 0 || q[v].dot(equator) > q[best].dot(equator))) best = v;
        for (int32_t s = adjacency.offsets[v]; s < adjacency.offsets[v + 1]; ++s) {
            const int32_t w = adjacency.neighbors[s];
            if (!allowed(w)) continue;
            const double next = d + (q[w] - q[v]).norm();
            if (next < distance[w]) {
                distance[w] = next;
                parent[w] = v;
                queue.push({next, w});
            }
        }
    }
    std::vector<int32_t> path;
    for (int32_t v = best; v >= 0; v = parent[v]) path.push_back(v);
    std::reverse(path.begin(), path.end());
    return path;  // empty when no vertex is reachable
}

// Whether the first vertices of the four paths appear around the root in the order the
// octahedron has (one cyclic direction or the other).
bool paths_in_order(const std::vector<int32_t>& ring,
                    const std::vector<std::vector<int32_t>>& paths) {
    int position[kSeams];
    for (int k = 0; k < kSeams; ++k) {
        const auto it = std::find(ring.begin(), ring.end(), paths[k][1]);
        if (it == ring.end()) return false;
        position[k] = static_cast<int>(it - ring.begin());
    }
    int rises = 0;
    for (int k = 0; k < kSeams; ++k) rises += position[(k + 1) % kSeams] > position[k];
    return rises == 1 || rises == kSeams - 1;  // cyclically monotone
}

Cut choose_cut(const TriangleMesh& mesh, const Halfedges& halfedges,
               const VertexAdjacency& adjacency, const std::vector<Eigen::Vector3d>& points) {
    // Roots to try: the vertices nearest the south pole of the map, nearest first.
    std::vector<int32_t> candidates(mesh.positions.size());
    for (size_t v = 0; v < candidates.size(); ++v) candidates[v] = static_cast<int32_t>(v);
    const size_t tries = std::min<size_t>(16, candidates.size());
    std::partial_sort(candidates.begin(), candidates.begin() + tries, candidates.end(),
                      [&](int32_t a, int32_t b) {
                          return points[a].z() < points[b].z() ||
                                 (points[a].z() == points[b].z() && a < b);
                      });
    for (double width : {M_PI / 4.0, M_PI / 3.0, 0.45 * M_PI}) {
        for (size_t c = 0; c < tries; ++c) {
            Cut cut;
            cut.root = candidates[c];
            cut.rotation = rotation_to_south(points[cut.root]);
            std::vector<Eigen::Vector3d> q(points.size());
            for (size_t v = 0; v < q.size(); ++v) q[v] = cut.rotation * points[v];
            q[cut.root] = -Eigen::Vector3d::UnitZ();
            std::vector<char> taken(points.size(), 0);
            bool ok = true;
            for (int k = 0; k < kSeams && ok; ++k) {
                std::vector<int32_t> path = seam_path(adjacency, q, cut.root, k, width, taken);
                ok = path.size() >= 2;
                for (size_t j = 1; j < path.size(); ++j) taken[path[j]] = 1;
                cut.paths.push_back(std::move(path));
            }
            if (ok && paths_in_order(vertex_ring(mesh, halfedges, cut.root), cut.paths)) {
                return cut;
            }
        }
    }
    throw Error(ErrorCode::kInternal,
                "octahedral unfold: found no four disjoint cut paths from a vertex near the "
                "south pole to the equator");
}

}  // namespace

OctahedralUnfold octahedral_unfold(const TriangleMesh& mesh,
                                   const std::vector<Eigen::Vector3d>& points,
                                   const ProgressSpan& progress) {
    // Progress: the mesh's and the cut mesh's structures and weights, then the system's
    // ordering, analysis and solve (most of it).
    const int32_t n = mesh.vertex_count();
    const Halfedges halfedges = build_halfedges(mesh, progress.part(0.0, 0.05));
    const VertexAdjacency adjacency =
        build_vertex_adjacency(mesh, halfedges, progress.part(0.05, 0.1));
    const Cut cut = choose_cut(mesh, halfedges, adjacency, points);
    progress.report(0.15);
    std::vector<Eigen::Vector3d> q(points.size());
    for (int32_t v = 0; v < n; ++v) q[v] = cut.rotation * points[v];

    // Cut half-edges, both directions of each path edge.
    const int32_t halfedge_count = 3 * mesh.triangle_count();
    std::vector<int32_t> seam_of_vertex(n, -1), step_of_vertex(n, -1);
    for (int k = 0; k < kSeams; ++k) {
        for (size_t j = 1; j < cut.paths[k].size(); ++j) {
            seam_of_vertex[cut.paths[k][j]] = k;
            step_of_vertex[cut.paths[k][j]] = static_cast<int32_t>(j);
        }
    }
    auto on_path = [&](int32_t v) { return v == cut.root || seam_of_vertex[v] >= 0; };
    std::vector<char> is_cut(halfedge_count, 0);
    for (int32_t h = 0; h < halfedge_count; ++h) {
        const int32_t a = halfedge_origin(mesh, h), b = halfedge_target(mesh, h);
        if (!on_path(a) || !on_path(b)) continue;
        // Consecutive on one path (paths are shortcut-free and share only the root).
        const int32_t ka = a == cut.root ? seam_of_vertex[b] : seam_of_vertex[a];
        const int32_t kb = b == cut.root ? seam_of_vertex[a] : seam_of_vertex[b];
        const int32_t ja = a == cut.root ? 0 : step_of_vertex[a];
        const int32_t jb = b == cut.root ? 0 : step_of_vertex[b];
        if (ka == kb && std::abs(ja - jb) == 1) is_cut[h] = 1;
    }

    // Copies: walking around a vertex on the cut, each cut edge starts a new sector; sector 0
    // keeps the input index, the others are appended.
    OctahedralUnfold out;
    out.vertex_remap.resize(n);
    for (int32_t v = 0; v < n; ++v) out.vertex_remap[v] = static_cast<uint32_t>(v);
    std::vector<int32_t> corner(3 * static_cast<size_t>(mesh.triangle_count()));
    for (int32_t h = 0; h < halfedge_count; ++h) corner[h] = halfedge_origin(mesh, h);
    std::vector<int32_t> first_out(n, -1);  // some outgoing half-edge per vertex
    for (int32_t h = 0; h < halfedge_count; ++h) first_out[halfedge_origin(mesh, h)] = h;
    // Per output vertex: its position on the square (the boundary's are fixed) and whether it
    // is on the boundary.
    std::vector<Eigen::Vector2d> target(n, Eigen::Vector2d::Zero());
    std::vector<char> boundary(n, 0);
    auto new_vertex = [&](int32_t input) {
        out.vertex_remap.push_back(static_cast<uint32_t>(input));
        target.emplace_back(Eigen::Vector2d::Zero());
        boundary.push_back(0);
        return static_cast<int32_t>(out.vertex_remap.size()) - 1;
    };
    // The side of seam k that lies to the left of the path walked outwards from the root is the
    // one of decreasing longitude: -y, +x, +y, -x for seams +x, +y, -x, -y.
    const double left_sign[kSeams] = {-1.0, 1.0, 1.0, -1.0};
    // Arc-length parameter along each path: tau in [0, 1] is where the octahedral map puts the
    // point of the meridian at colatitude theta (from the south pole), tan(theta) / (1 +
    // tan(theta)), with theta scaled so that the path's end is the equator.
    std::vector<std::vector<double>> tau(kSeams);
    for (int k = 0; k < kSeams; ++k) {
        const std::vector<int32_t>& path = cut.paths[k];
        std::vector<double> length(path.size(), 0.0);
        for (size_t j = 1; j < path.size(); ++j) {
            length[j] = length[j - 1] + arc_length(points[path[j - 1]], points[path[j]]);
        }
        tau[k].resize(path.size());
        for (size_t j = 0; j < path.size(); ++j) {
            const double theta = 0.5 * M_PI * length[j] / length.back();
            tau[k][j] =
                j + 1 == path.size() ? 1.0 : portable::tan(theta) / (1.0 + portable::tan(theta));
        }
    }
    auto seam_point = [&](int k, double t, double side) -> Eigen::Vector2d {
        const double along = side * (1.0 - t);
        switch (k) {
            case 0:
                return {1.0, along};
            case 1:
                return {along, 1.0};
            case 2:
                return {-1.0, along};
            default:
                return {along, -1.0};
        }
    };
    for (int32_t v = 0; v < n; ++v) {
        if (!on_path(v)) continue;
        // Start the walk at a cut half-edge leaving v (every vertex on a path has one).
        int32_t start = first_out[v];
        while (!is_cut[start]) start = halfedges.twin[Halfedges::prev(start)];
        int32_t copy = -1;
        int32_t h = start;
        do {
            if (is_cut[h]) {
                // A new sector: the triangles from the one left of cut edge h onwards.
                copy = copy < 0 ? v : new_vertex(v);
                boundary[copy] = 1;
                const int32_t w = halfedge_target(mesh, h);
                if (v == cut.root) {
                    const int k = seam_of_vertex[w];
                    target[copy] = seam_point(k, 0.0, left_sign[k]);
                } else {
                    const int k = seam_of_vertex[v];
                    const bool outwards = w != cut.root && step_of_vertex[w] > step_of_vertex[v];
                    target[copy] = seam_point(k, tau[k][step_of_vertex[v]],
                                              outwards ? left_sign[k] : -left_sign[k]);
                }
            }
            corner[h] = copy;
            h = halfedges.twin[Halfedges::prev(h)];
        } while (h != start);
    }
    // Interior vertices: the octahedral map of their point.
    for (int32_t v = 0; v < n; ++v) {
        if (!on_path(v)) target[v] = octahedral(q[v]);
    }

    // The cut mesh, its boundary on the square, its interior by one solve with mean value
    // weights of the octahedral positions (rows whose weights are not finite, from a degenerate
    // configuration, take the weights of the sphere's chord triangles instead).
    const int32_t out_count = static_cast<int32_t>(out.vertex_remap.size());
    TriangleMesh plane, chords;
    plane.positions.resize(out_count);
    chords.positions.resize(out_count);
    for (int32_t o = 0; o < out_count; ++o) {
        plane.positions[o] = Eigen::Vector3d(target[o].x(), target[o].y(), 0.0);
        chords.positions[o] = points[out.vertex_remap[o]];
    }
    plane.triangles.resize(mesh.triangles.size());
    out.indices.resize(3 * mesh.triangles.size());
    for (int32_t t = 0; t < mesh.triangle_count(); ++t) {
        for (int k = 0; k < 3; ++k) {
            plane.triangles[t][k] = corner[3 * t + k];
            out.indices[3 * t + k] = static_cast<uint32_t>(corner[3 * t + k]);
        }
    }
    chords.triangles = plane.triangles;
    const Halfedges cut_halfedges = build_halfedges(plane, progress.part(0.15, 0.2));
    const VertexAdjacency cut_adjacency =
        build_vertex_adjacency(plane, cut_halfedges, progress.part(0.2, 0.25));
    std::vector<double> weights =
        laplacian_weights(plane, cut_adjacency, WeightScheme::kMeanValue, progress.part(0.25, 0.3));
    const std::vector<double> fallback = laplacian_weights(
        chords, cut_adjacency, WeightScheme::kMeanValue, progress.part(0.3, 0.35));
    for (int32_t o = 0; o < out_count; ++o) {
        const int32_t begin = cut_adjacency.offsets[o], end = cut_adjacency.offsets[o + 1];
        double sum = 0.0;
        bool finite = true;
        for (int32_t s = begin; s < end; ++s) {
            finite = finite && std::isfinite(weights[s]) && weights[s] >= 0.0;
            sum += weights[s];
        }
        if (!finite || !(sum > 0.0) || !std::isfinite(sum)) {
            std::copy(fallback.begin() + begin, fallback.begin() + end, weights.begin() + begin);
        }
    }
    LaplaceSystem system(plane, cut_adjacency, boundary, {}, progress.part(0.35, 0.6));
    system.solve(weights, target, progress.part(0.6, 1.0));
    out.uv.resize(out_count);
    for (int32_t o = 0; o < out_count; ++o) out.uv[o] = 0.5 * (target[o] + Eigen::Vector2d::Ones());
    return out;
}

}  // namespace raps
