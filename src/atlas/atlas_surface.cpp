#include "atlas/atlas_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include "atlas/huge_pages.h"
#include "core/fill_in_runs.h"
#include "core/hash_mix.h"
#include "core/portable_math.h"
#include "mesh/mesh_topology.h"

namespace raps {

namespace {

// Edges with more half-edges than this stay cut: pairing them looks at every two (a hostile
// mesh can stack any number of triangles on one edge).
constexpr std::ptrdiff_t kMostSheetsPaired = 64;
// A triangle's back: on the same edge, the other way round, facing away within about 25
// degrees (the back of a quad split along its other diagonal is not the same triangles).
constexpr double kBackAlignment = 0.9;

Eigen::Vector3d unit_normal(const std::vector<Eigen::Vector3d>& positions, const Triangle& v) {
    const Eigen::Vector3d n =
        (positions[v[1]] - positions[v[0]]).cross(positions[v[2]] - positions[v[0]]);
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

    // Areas, for the zero-area test (same threshold as the metrics: 1e-12 of the mean), summed
    // in input order and measured again where tested: an array of them was a fresh 8 bytes per
    // triangle, and a page touched for the first time costs more than the arithmetic.
    auto area_of = [&](int32_t t) {
        const Triangle& v = input.triangles[t];
        return 0.5 * (input.positions[v[1]] - input.positions[v[0]])
                         .cross(input.positions[v[2]] - input.positions[v[0]])
                         .norm();
    };
    double total = 0;
    progress.part(0.0, 0.05).in_runs(input_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) total += area_of(t);
    });
    const double zero_area = 1e-12 * total / std::max(input_count, 1);

    // Exact duplicates (same welded vertices in the same rotation) follow their first copy.
    // A copy wound the other way is the back of a two-sided surface and keeps its own chart, and
    // so does a copy in another group (it belongs to another material or region).
    // Found with a hash table of the rotated vertex triples, triangles in input order (linear,
    // where sorting the triples was a quarter of fandisk's topology phase); a triple is rotated
    // again when a probe compares it, rarer than a stored copy of every triple was costly.
    auto rotated = [&](int32_t t) {
        const Triangle& v = input.triangles[t];
        std::array<int32_t, 3> w = {welded[v[0]], welded[v[1]], welded[v[2]]};
        std::rotate(w.begin(), std::min_element(w.begin(), w.end()), w.end());
        return w;
    };
    // Per input triangle: kKept, kDegenerate, or the first copy it duplicates.
    constexpr int32_t kKept = -1, kDegenerate = -2;
    std::vector<int32_t> primary_of;
    reserve_huge_pages(primary_of, input_count);
    assign_in_runs(primary_of, static_cast<size_t>(input_count), kKept, progress.part(0.05, 0.06));
    std::vector<int32_t> slot = filled_in_runs(hash_table_size(static_cast<size_t>(input_count)),
                                               -1, progress.part(0.06, 0.08));
    const size_t capacity = slot.size();
    progress.part(0.08, 0.2).in_runs(input_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            const Triangle& v = input.triangles[t];
            const int32_t a = welded[v[0]], b = welded[v[1]], c = welded[v[2]];
            if (a == b || b == c || c == a || !(area_of(t) > zero_area)) {
                surface.aside_triangles.push_back(t);
                surface.aside_primary.push_back(-1);
                primary_of[t] = kDegenerate;
                continue;
            }
            const std::array<int32_t, 3> w = rotated(t);
            const uint64_t hash =
                mix_bits(mix_bits(static_cast<uint64_t>(w[0]) << 32 | static_cast<uint32_t>(w[1])) ^
                         static_cast<uint32_t>(w[2]));
            size_t i = hash & (capacity - 1);
            while (slot[i] >= 0 &&
                   (seams.group(slot[i]) != seams.group(t) || rotated(slot[i]) != w))
                i = (i + 1) & (capacity - 1);
            if (slot[i] < 0) {
                slot[i] = t;
            } else {
                primary_of[t] = slot[i];
            }
        }
    });
    std::vector<int32_t>().swap(slot);
    std::vector<int32_t> kept;              // input triangles that become surface triangles
    reserve_huge_pages(kept, input_count);  // nearly all of them: no doubling's slack kept
    progress.part(0.2, 0.25).in_runs(input_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t t = static_cast<int32_t>(run_begin); t < run_end; ++t) {
            if (primary_of[t] == kKept) kept.push_back(t);
        }
    });
    for (int32_t t = 0; t < input_count; ++t) {
        if (primary_of[t] >= 0) {  // a first copy is kept: its surface triangle by its rank
            surface.aside_triangles.push_back(t);
            surface.aside_primary.push_back(static_cast<int32_t>(
                std::lower_bound(kept.begin(), kept.end(), primary_of[t]) - kept.begin()));
        }
    }
    std::vector<int32_t>().swap(primary_of);

    // Half-edges over welded vertices; an edge is an interior edge of the surface only when it
    // has exactly one half-edge in each direction.
    const int32_t count = static_cast<int32_t>(kept.size());
    // The kept triangles over welded vertices, held (as ~vertex, below 0) in the surface's own
    // triangles, which their corners' classes overwrite below: no array of their own.
    // Large arrays are filled as they are written, or else in runs (fill_in_runs.h): filled
    // in one go, each was a gap of 120 to 270 ms without a progress call at 3.3M triangles.
    reserve_huge_pages(surface.mesh.triangles, count);
    progress.part(0.25, 0.3).in_runs(count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t s = static_cast<int32_t>(run_begin); s < run_end; ++s) {
            const Triangle& v = input.triangles[kept[s]];
            surface.mesh.triangles.push_back({~welded[v[0]], ~welded[v[1]], ~welded[v[2]]});
        }
    });
    auto origin = [&](int32_t h) { return ~surface.mesh.triangles[h / 3][h % 3]; };
    auto target = [&](int32_t h) { return ~surface.mesh.triangles[h / 3][(h % 3 + 1) % 3]; };
    // Half-edges bucketed by their smaller vertex (a counting sort), each bucket sorted by the
    // larger vertex: the groups of one undirected edge in linear time, where one comparison sort
    // of all half-edges by their vertex pair was most of the atlas's topology phase.
    const int32_t halfedge_count = 3 * count;
    std::vector<int32_t> bucket_offset(input.positions.size() + 1, 0);
    progress.part(0.3, 0.35).in_runs(halfedge_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t h = static_cast<int32_t>(run_begin); h < run_end; ++h) {
            const int32_t a = origin(h), b = target(h);
            ++bucket_offset[std::min(a, b) + 1];
        }
    });
    std::partial_sum(bucket_offset.begin(), bucket_offset.end(), bucket_offset.begin());
    std::vector<std::pair<int32_t, int32_t>> by_edge;  // (larger vertex, h)
    reserve_huge_pages(by_edge, halfedge_count);
    assign_in_runs(by_edge, halfedge_count, {0, 0}, progress.part(0.35, 0.38));
    {
        std::vector<int32_t> cursor(bucket_offset.begin(), bucket_offset.end() - 1);
        progress.part(0.38, 0.45).in_runs(halfedge_count, [&](int64_t run_begin, int64_t run_end) {
            for (int32_t h = static_cast<int32_t>(run_begin); h < run_end; ++h) {
                const int32_t a = origin(h), b = target(h);
                by_edge[cursor[std::min(a, b)]++] = {std::max(a, b), h};
            }
        });
    }
    reserve_huge_pages(surface.twin, halfedge_count);
    assign_in_runs(surface.twin, halfedge_count, -1, progress.part(0.45, 0.47));
    // Half-edges h and g of one edge become twins when they run opposite ways and no seam cuts
    // them.
    auto join = [&](int32_t h, int32_t g) {
        if (origin(h) == target(g) &&
            !(seams.any() && seams.cuts(kept[h / 3], h % 3, kept[g / 3], g % 3))) {
            surface.twin[h] = g;
            surface.twin[g] = h;
        }
    };
    // A non-manifold edge (more than two half-edges): first two triangles of one polygon stay
    // joined (a quad folded onto its neighbour, as on Suzanne). Then, where every triangle on
    // the edge has its back there too (a triangle the other way round facing away: a two-sided
    // surface, as leaves, cards and cloth are modelled), the half-edges are paired opposite ways,
    // the most nearly coplanar pairs first, so that the front and the back each stay one sheet
    // instead of one chart per triangle (a two-sided 10 x 10 grid: 364 charts). Other
    // non-manifold edges stay cut: pairing fins and touching sheets too changed charts on meshes
    // that have such edges (cow: 61 -> 55) and, through a scene's shared stretch budget, every
    // mesh packed with them.
    auto welded_corners = [&](int32_t s) {
        const Triangle& v = surface.mesh.triangles[s];
        return Triangle{~v[0], ~v[1], ~v[2]};
    };
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
        auto normal = [&](int32_t h) {
            return unit_normal(input.positions, welded_corners(h / 3));
        };
        for (auto p = begin; p != end; ++p) {
            const bool has_back = std::any_of(begin, end, [&](const auto& q) {
                return origin(q.second) == target(p->second) &&
                       normal(q.second).dot(normal(p->second)) <= -kBackAlignment;
            });
            if (!has_back) return;
        }
        std::vector<std::pair<double, std::pair<int32_t, int32_t>>> pairs;
        for (auto p = begin; p != end; ++p) {
            for (auto q = p + 1; q != end; ++q) {
                const int32_t h = p->second, g = q->second;
                if (surface.twin[h] >= 0 || surface.twin[g] >= 0 || origin(h) != target(g))
                    continue;
                const double alignment = normal(h).dot(normal(g));
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
    progress.part(0.47, 0.65).in_runs(bucket_count, [&](int64_t run_begin, int64_t run_end) {
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

    // Surface vertices: corners joined across interior edges, one class per fan, numbered in
    // the order of their first corners, each corner's class written over its welded vertex.
    const std::vector<int32_t> first_value = label_corner_classes(
        surface.twin, [&](int32_t c) -> int32_t& { return surface.mesh.triangles[c / 3][c % 3]; },
        progress.part(0.65, 0.8));
    const size_t vertex_count = first_value.size();
    reserve_huge_pages(surface.welded_vertex, vertex_count);  // exact: no doubling's slack
    reserve_huge_pages(surface.mesh.positions, vertex_count);
    progress.part(0.8, 0.83).in_runs(static_cast<int64_t>(vertex_count),
                                     [&](int64_t run_begin, int64_t run_end) {
                                         for (int64_t v = run_begin; v < run_end; ++v) {
                                             const int32_t w = ~first_value[v];
                                             surface.welded_vertex.push_back(w);
                                             surface.mesh.positions.push_back(input.positions[w]);
                                         }
                                     });
    reserve_huge_pages(surface.corner_angle, 3 * static_cast<size_t>(count));
    assign_in_runs(surface.corner_angle, 3 * static_cast<size_t>(count), 0.0,
                   progress.part(0.83, 0.86));
    parallel_for(pool, 3 * static_cast<int64_t>(count), [&](int64_t begin, int64_t end) {
        progress.at(begin, 3 * static_cast<int64_t>(count), 0.86, 1.0);
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
