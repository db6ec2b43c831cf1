#include "atlas/atlas_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "core/hash_mix.h"
#include "core/portable_math.h"
#include "mesh/mesh_topology.h"

namespace raps {

namespace {

// Edges with more half-edges than this stay cut: pairing them looks at every two (a hostile
// mesh can stack any number of triangles on one edge).
constexpr std::ptrdiff_t kMostSheetsPaired = 64;

Eigen::Vector3d unit_normal(const TriangleMesh& mesh, int32_t t) {
    const Triangle& v = mesh.triangles[t];
    const Eigen::Vector3d n = (mesh.positions[v[1]] - mesh.positions[v[0]])
                                  .cross(mesh.positions[v[2]] - mesh.positions[v[0]]);
    const double length = n.norm();
    return length > 0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

}  // namespace

AtlasSurface build_atlas_surface(const TriangleMesh& input, const std::vector<int32_t>& welded,
                                 const UserSeams& seams, ThreadPool& pool,
                                 const ProgressSpan& progress) {
    // Progress: each pass over the triangles, half-edges or corners reports every
    // kItemsPerReport items within its share.
    AtlasSurface surface;
    const int32_t input_count = input.triangle_count();

    // Areas, for the zero-area test (same threshold as the metrics: 1e-12 of the mean).
    std::vector<double> area(input_count);
    double total = 0;
    progress.part(0.0, 0.05).in_runs(input_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            const Triangle& v = input.triangles[t];
            area[t] = 0.5 * (input.positions[v[1]] - input.positions[v[0]])
                                .cross(input.positions[v[2]] - input.positions[v[0]])
                                .norm();
            total += area[t];
        }
    });
    const double zero_area = 1e-12 * total / std::max(input_count, 1);

    // Exact duplicates (same welded vertices in the same rotation) follow their first copy.
    // A copy wound the other way is the back of a two-sided surface and keeps its own chart, and
    // so does a copy in another group (it belongs to another material or region).
    // Found with a hash table of the rotated vertex triples, triangles in input order (linear,
    // where sorting the triples was a quarter of fandisk's topology phase).
    std::vector<std::array<int32_t, 3>> rotated(input_count);
    std::vector<int32_t> primary_of(input_count, -1);
    const size_t capacity = hash_table_size(static_cast<size_t>(input_count));
    std::vector<int32_t> slot(capacity, -1);
    progress.part(0.05, 0.2).in_runs(input_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            const Triangle& v = input.triangles[t];
            std::array<int32_t, 3>& w = rotated[t];
            w = {welded[v[0]], welded[v[1]], welded[v[2]]};
            if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0] || !(area[t] > zero_area)) {
                surface.aside_triangles.push_back(t);
                surface.aside_primary.push_back(-1);
                continue;
            }
            std::rotate(w.begin(), std::min_element(w.begin(), w.end()), w.end());
            const uint64_t hash =
                mix_bits(mix_bits(static_cast<uint64_t>(w[0]) << 32 | static_cast<uint32_t>(w[1])) ^
                         static_cast<uint32_t>(w[2]));
            size_t i = hash & (capacity - 1);
            while (slot[i] >= 0 &&
                   (rotated[slot[i]] != w || seams.group(slot[i]) != seams.group(t)))
                i = (i + 1) & (capacity - 1);
            if (slot[i] < 0) {
                slot[i] = t;
            } else {
                primary_of[t] = slot[i];
            }
        }
    });
    std::vector<int32_t> kept;  // input triangles that become surface triangles
    kept.reserve(input_count);  // nearly all of them: no doubling's slack kept to the end
    std::vector<int32_t> surface_of_input(input_count, -1);
    progress.part(0.2, 0.25).in_runs(input_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            const Triangle& v = input.triangles[t];
            if (welded[v[0]] == welded[v[1]] || welded[v[1]] == welded[v[2]] ||
                welded[v[2]] == welded[v[0]] || !(area[t] > zero_area)) {
                continue;
            }
            if (primary_of[t] >= 0) continue;
            surface_of_input[t] = static_cast<int32_t>(kept.size());
            kept.push_back(t);
        }
    });
    for (int32_t t = 0; t < input_count; ++t) {
        if (primary_of[t] >= 0) {
            surface.aside_triangles.push_back(t);
            surface.aside_primary.push_back(surface_of_input[primary_of[t]]);
        }
    }

    // Half-edges over welded vertices; an edge is an interior edge of the surface only when it
    // has exactly one half-edge in each direction.
    const int32_t count = static_cast<int32_t>(kept.size());
    TriangleMesh welded_mesh;
    welded_mesh.positions = input.positions;
    welded_mesh.triangles.resize(count);
    progress.part(0.25, 0.3).in_runs(count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t s = static_cast<int32_t>(run_begin); s < run_end; ++s) {
            const Triangle& v = input.triangles[kept[s]];
            welded_mesh.triangles[s] = {welded[v[0]], welded[v[1]], welded[v[2]]};
        }
    });
    // Half-edges bucketed by their smaller vertex (a counting sort), each bucket sorted by the
    // larger vertex: the groups of one undirected edge in linear time, where one comparison sort
    // of all half-edges by their vertex pair was most of the atlas's topology phase.
    const int32_t halfedge_count = 3 * count;
    std::vector<int32_t> bucket_offset(input.positions.size() + 1, 0);
    progress.part(0.3, 0.35).in_runs(halfedge_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t h = static_cast<int32_t>(run_begin); h < run_end; ++h) {
            const int32_t a = halfedge_origin(welded_mesh, h), b = halfedge_target(welded_mesh, h);
            ++bucket_offset[std::min(a, b) + 1];
        }
    });
    std::partial_sum(bucket_offset.begin(), bucket_offset.end(), bucket_offset.begin());
    std::vector<std::pair<int32_t, int32_t>> by_edge(halfedge_count);  // (larger vertex, h)
    {
        std::vector<int32_t> cursor(bucket_offset.begin(), bucket_offset.end() - 1);
        progress.part(0.35, 0.45).in_runs(halfedge_count, [&](int64_t run_begin, int64_t run_end) {
            for (int32_t h = static_cast<int32_t>(run_begin); h < run_end; ++h) {
                const int32_t a = halfedge_origin(welded_mesh, h),
                              b = halfedge_target(welded_mesh, h);
                by_edge[cursor[std::min(a, b)]++] = {std::max(a, b), h};
            }
        });
    }
    surface.twin.assign(halfedge_count, -1);
    // Half-edges h and g of one edge become twins when they run opposite ways and no seam cuts
    // them.
    auto join = [&](int32_t h, int32_t g) {
        if (halfedge_origin(welded_mesh, h) == halfedge_target(welded_mesh, g) &&
            !(seams.any() && seams.cuts(kept[h / 3], h % 3, kept[g / 3], g % 3))) {
            surface.twin[h] = g;
            surface.twin[g] = h;
        }
    };
    // A non-manifold edge (more than two half-edges): first two triangles of one polygon stay
    // joined (a quad folded onto its neighbour, as on Suzanne); then the remaining half-edges
    // are paired opposite ways, the most nearly coplanar pairs first, so that sheets touching
    // along the edge each continue across it: the back of a two-sided surface (every face
    // repeated, wound the other way) is one sheet beside the front instead of one chart per
    // triangle (a two-sided 10 x 10 grid: 364 charts). What no pair takes stays cut.
    auto join_sheets = [&](auto begin, auto end) {
        if (!input.triangle_polygon.empty()) {
            for (auto p = begin; p != end; ++p) {
                for (auto q = p + 1; q != end; ++q) {
                    if (surface.twin[p->second] < 0 && surface.twin[q->second] < 0 &&
                        input.triangle_polygon[kept[p->second / 3]] ==
                            input.triangle_polygon[kept[q->second / 3]])
                        join(p->second, q->second);
                }
            }
        }
        std::vector<std::pair<double, std::pair<int32_t, int32_t>>> pairs;
        for (auto p = begin; p != end; ++p) {
            for (auto q = p + 1; q != end; ++q) {
                const int32_t h = p->second, g = q->second;
                if (surface.twin[h] >= 0 || surface.twin[g] >= 0 ||
                    halfedge_origin(welded_mesh, h) != halfedge_target(welded_mesh, g))
                    continue;
                const double alignment = unit_normal(welded_mesh, h / 3)
                                             .dot(unit_normal(welded_mesh, g / 3));
                pairs.push_back({-alignment, {std::min(h, g), std::max(h, g)}});
            }
        }
        std::sort(pairs.begin(), pairs.end());
        for (const auto& pair : pairs) {
            const auto [h, g] = pair.second;
            if (surface.twin[h] < 0 && surface.twin[g] < 0) join(h, g);
        }
    };
    const int64_t bucket_count = static_cast<int64_t>(bucket_offset.size()) - 1;
    progress.part(0.45, 0.65).in_runs(bucket_count, [&](int64_t run_begin, int64_t run_end) {
        for (int64_t v = static_cast<int64_t>(run_begin); v < run_end; ++v) {
            const auto begin = by_edge.begin() + bucket_offset[v],
                       end = by_edge.begin() + bucket_offset[v + 1];
            std::sort(begin, end);
            for (auto i = begin; i != end;) {
                auto j = i;
                while (j != end && j->first == i->first) ++j;
                if (j - i == 2) {
                    join(i->second, (i + 1)->second);
                } else if (j - i > 2 && j - i <= kMostSheetsPaired) {
                    join_sheets(i, j);
                }
                i = j;
            }
        }
    });

    // Surface vertices: corners joined across interior edges, one class per fan.
    const std::vector<int32_t> classes =
        corner_vertex_classes(surface.twin, progress.part(0.65, 0.8));
    surface.mesh.triangles.resize(count);
    // Classes are numbered in order of first sight: the largest is the vertex count less one.
    // Reserved exactly, these arrays keep no doubling's slack through the whole atlas.
    const size_t vertex_count =
        classes.empty()
            ? 0
            : static_cast<size_t>(*std::max_element(classes.begin(), classes.end())) + 1;
    surface.welded_vertex.reserve(vertex_count);
    surface.mesh.positions.reserve(vertex_count);
    progress.part(0.8, 0.85).in_runs(3 * count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t c = static_cast<int32_t>(run_begin); c < run_end; ++c) {
            if (classes[c] == static_cast<int32_t>(surface.welded_vertex.size())) {  // a new vertex
                const int32_t w = welded_mesh.triangles[c / 3][c % 3];
                surface.welded_vertex.push_back(w);
                surface.mesh.positions.push_back(input.positions[w]);
            }
            surface.mesh.triangles[c / 3][c % 3] = classes[c];
        }
    });
    surface.corner_angle.resize(3 * static_cast<size_t>(count));
    parallel_for(pool, 3 * static_cast<int64_t>(count), [&](int64_t begin, int64_t end) {
        progress.at(begin, 3 * static_cast<int64_t>(count), 0.85, 1.0);
        for (int64_t c = begin; c < end; ++c) {
            const Triangle& t = surface.mesh.triangles[c / 3];
            const Eigen::Vector3d& at = surface.mesh.positions[t[c % 3]];
            const Eigen::Vector3d a = surface.mesh.positions[t[(c + 1) % 3]] - at;
            const Eigen::Vector3d b = surface.mesh.positions[t[(c + 2) % 3]] - at;
            surface.corner_angle[c] = portable::atan2(a.cross(b).norm(), a.dot(b));
        }
    });
    surface.input_triangle = std::move(kept);
    if (!input.triangle_polygon.empty()) {
        surface.polygon_inner.assign(surface.twin.size(), 0);
        for (size_t h = 0; h < surface.twin.size(); ++h) {
            const int32_t o = surface.twin[h];
            surface.polygon_inner[h] =
                o >= 0 && input.triangle_polygon[surface.input_triangle[h / 3]] ==
                              input.triangle_polygon[surface.input_triangle[o / 3]];
        }
    }
    return surface;
}

}  // namespace raps
