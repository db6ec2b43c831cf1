#include "mesh/mesh_topology.h"

#include <algorithm>
#include <numeric>
#include <string>

#include "core/error.h"
#include "core/fill_in_runs.h"

namespace raps {
namespace {

std::string edge_name(int32_t a, int32_t b) {
    return "(" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

bool same_vertex_set(const Triangle& a, const Triangle& b) {
    Triangle x = a, y = b;
    std::sort(x.begin(), x.end());
    std::sort(y.begin(), y.end());
    return x == y;
}

// Half-edges grouped by origin vertex (counting sort), so that finding the half-edges between two
// vertices costs a scan of one vertex's star instead of a global sort.
struct OutgoingHalfedges {
    std::vector<int32_t> offsets;
    std::vector<int32_t> halfedges;
};

OutgoingHalfedges group_by_origin(const TriangleMesh& mesh, const ProgressSpan& progress) {
    OutgoingHalfedges out;
    const int32_t halfedge_count = 3 * mesh.triangle_count();
    out.offsets.assign(mesh.positions.size() + 1, 0);
    progress.in_runs(halfedge_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t h = static_cast<int32_t>(run_begin); h < run_end; ++h) {
            ++out.offsets[halfedge_origin(mesh, h) + 1];
        }
    });
    std::partial_sum(out.offsets.begin(), out.offsets.end(), out.offsets.begin());
    assign_in_runs(out.halfedges, halfedge_count, 0, progress.part(0.5, 0.5));
    std::vector<int32_t> fill(out.offsets.begin(), out.offsets.end() - 1);
    for (int32_t h = 0; h < halfedge_count; ++h) {
        progress.at(halfedge_count + h, 2 * static_cast<int64_t>(halfedge_count));
        out.halfedges[fill[halfedge_origin(mesh, h)]++] = h;
    }
    return out;
}

}  // namespace

Halfedges build_halfedges(const TriangleMesh& mesh, const ProgressSpan& progress) {
    const OutgoingHalfedges out = group_by_origin(mesh, progress.part(0.0, 0.15));
    const int32_t halfedge_count = 3 * mesh.triangle_count();
    std::vector<int32_t> target = filled_in_runs(halfedge_count, 0, progress.part(0.15, 0.15));
    progress.part(0.15, 0.2).in_runs(halfedge_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t h = static_cast<int32_t>(run_begin); h < run_end; ++h) {
            target[h] = halfedge_target(mesh, h);
        }
    });
    Halfedges result;
    assign_in_runs(result.twin, halfedge_count, -1, progress.part(0.2, 0.2));
    const ProgressSpan pairing = progress.part(0.2, 1.0);
    pairing.in_runs(halfedge_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t h = static_cast<int32_t>(run_begin); h < run_end; ++h) {
            const int32_t a = halfedge_origin(mesh, h), b = target[h];
            int32_t same_direction = -1, opposite = -1, opposite_count = 0;
            for (int32_t i = out.offsets[a]; i < out.offsets[a + 1]; ++i) {
                const int32_t g = out.halfedges[i];
                if (g != h && target[g] == b) same_direction = g;
            }
            for (int32_t i = out.offsets[b]; i < out.offsets[b + 1]; ++i) {
                const int32_t g = out.halfedges[i];
                if (target[g] == a) {
                    opposite = g;
                    ++opposite_count;
                }
            }
            if (same_direction >= 0 || opposite_count > 1) {
                const int32_t other = same_direction >= 0 ? same_direction : opposite;
                if (same_vertex_set(mesh.triangles[h / 3], mesh.triangles[other / 3])) {
                    throw Error(ErrorCode::kNonManifoldEdge,
                                "triangles " + std::to_string(h / 3) + " and " +
                                    std::to_string(other / 3) +
                                    " are duplicates (same three vertices), so edge " +
                                    edge_name(a, b) + " has more than two triangles");
                }
                if (same_direction >= 0 && opposite < 0) {
                    throw Error(ErrorCode::kInconsistentOrientation,
                                "triangles " + std::to_string(h / 3) + " and " +
                                    std::to_string(same_direction / 3) + " both traverse edge " +
                                    edge_name(a, b) +
                                    " in the same direction (their winding is inconsistent)");
                }
                throw Error(ErrorCode::kNonManifoldEdge,
                            "edge " + edge_name(a, b) + " is shared by more than two triangles (" +
                                std::to_string(h / 3) + ", " + std::to_string(other / 3) +
                                " and more)");
            }
            result.twin[h] = opposite;
        }
    });
    return result;
}

void check_manifold_vertices(const TriangleMesh& mesh, const Halfedges& halfedges,
                             const ProgressSpan& progress) {
    // Rotating around the origin v of an outgoing half-edge h: twin(prev(h)) is the next
    // outgoing half-edge (or -1 at a boundary), next(twin(h)) the previous one. The outgoing
    // half-edges of a manifold vertex form one such orbit (one fan).
    const auto& twin = halfedges.twin;
    const int32_t halfedge_count = static_cast<int32_t>(twin.size());
    std::vector<char> visited(halfedge_count, 0);
    std::vector<int32_t> fan_start(mesh.positions.size(), -1);
    progress.in_runs(halfedge_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t h0 = static_cast<int32_t>(run_begin); h0 < run_end; ++h0) {
            if (visited[h0]) continue;
            const int32_t v = halfedge_origin(mesh, h0);
            if (fan_start[v] >= 0) {
                throw Error(ErrorCode::kNonManifoldVertex,
                            "vertex " + std::to_string(v) +
                                " joins separate fans of triangles (e.g. triangles " +
                                std::to_string(fan_start[v] / 3) + " and " +
                                std::to_string(h0 / 3) + " meet only at this vertex)");
            }
            fan_start[v] = h0;
            // Walk backwards to the fan's first half-edge (or all the way round), then forwards.
            int32_t h = h0;
            while (twin[h] >= 0 && Halfedges::next(twin[h]) != h0) h = Halfedges::next(twin[h]);
            if (twin[h] >= 0) h = h0;  // closed fan: start anywhere
            const int32_t start = h;
            do {
                visited[h] = 1;
                const int32_t p = twin[Halfedges::prev(h)];
                h = p;
            } while (h >= 0 && h != start);
        }
    });
}

std::vector<int32_t> piece_representatives(const TriangleMesh& mesh, const Halfedges& halfedges,
                                           const ProgressSpan& progress) {
    std::vector<int32_t> piece(mesh.triangles.size(), -1), representatives, stack;
    int64_t reached = 0;
    for (int32_t seed = 0; seed < mesh.triangle_count(); ++seed) {
        if (piece[seed] >= 0) continue;
        const int32_t id = static_cast<int32_t>(representatives.size());
        representatives.push_back(seed);
        piece[seed] = id;
        stack.push_back(seed);
        while (!stack.empty()) {
            const int32_t t = stack.back();
            stack.pop_back();
            progress.at(++reached, mesh.triangle_count());
            for (int k = 0; k < 3; ++k) {
                const int32_t o = halfedges.twin[3 * t + k];
                if (o >= 0 && piece[o / 3] < 0) {
                    piece[o / 3] = id;
                    stack.push_back(o / 3);
                }
            }
        }
    }
    return representatives;
}

std::vector<std::vector<int32_t>> boundary_loops(const TriangleMesh& mesh,
                                                 const Halfedges& halfedges,
                                                 const ProgressSpan& progress) {
    // With manifold vertices every boundary vertex starts exactly one boundary half-edge.
    std::vector<int32_t> boundary_out(mesh.positions.size(), -1);
    progress.part(0.0, 0.7).in_runs(
        static_cast<int64_t>(halfedges.twin.size()), [&](int64_t begin, int64_t end) {
            for (int32_t h = static_cast<int32_t>(begin); h < end; ++h) {
                if (halfedges.twin[h] < 0) boundary_out[halfedge_origin(mesh, h)] = h;
            }
        });
    std::vector<std::vector<int32_t>> loops;
    std::vector<char> done(mesh.positions.size(), 0);
    for (int32_t v0 = 0; v0 < mesh.vertex_count(); ++v0) {
        progress.at(v0, mesh.vertex_count(), 0.7, 1.0);
        if (boundary_out[v0] < 0 || done[v0]) continue;
        std::vector<int32_t> loop;
        for (int32_t v = v0; !done[v]; v = halfedge_target(mesh, boundary_out[v])) {
            done[v] = 1;
            loop.push_back(v);
        }
        loops.push_back(std::move(loop));
    }
    return loops;
}

int64_t edge_count(const Halfedges& halfedges) {
    int64_t count = 0;
    for (int32_t h = 0; h < static_cast<int32_t>(halfedges.twin.size()); ++h) {
        if (halfedges.twin[h] < h) ++count;  // boundary (-1) or the first of a twin pair
    }
    return count;
}

namespace {

void check_one_piece(const TriangleMesh& mesh, const Halfedges& halfedges, const char* shape,
                     const ProgressSpan& progress) {
    const std::vector<int32_t> pieces = piece_representatives(mesh, halfedges, progress);
    if (pieces.size() > 1) {
        throw Error(ErrorCode::kMultipleComponents,
                    "the mesh has " + std::to_string(pieces.size()) +
                        " separate pieces (triangles " + std::to_string(pieces[0]) + " and " +
                        std::to_string(pieces[1]) + " are not connected through edges); " + shape +
                        " is one piece");
    }
}

// "3, 17, 92": the first vertex of each of (at most 8 of) the loops, for messages.
std::string loop_starts(const std::vector<std::vector<int32_t>>& loops) {
    std::string starts;
    for (size_t i = 0; i < loops.size() && i < 8; ++i) {
        starts += (i ? ", " : "") + std::to_string(loops[i][0]);
    }
    return starts;
}

int64_t euler_characteristic(const TriangleMesh& mesh, const Halfedges& halfedges) {
    return static_cast<int64_t>(mesh.vertex_count()) - edge_count(halfedges) +
           mesh.triangle_count();
}

}  // namespace

std::vector<int32_t> disk_boundary_loop(const TriangleMesh& mesh, const Halfedges& halfedges,
                                        const ProgressSpan& progress) {
    check_manifold_vertices(mesh, halfedges, progress.part(0.0, 0.4));
    check_one_piece(mesh, halfedges, "a disk", progress.part(0.4, 0.8));
    std::vector<std::vector<int32_t>> loops =
        boundary_loops(mesh, halfedges, progress.part(0.8, 0.95));
    if (loops.empty()) {
        throw Error(ErrorCode::kNoBoundary,
                    "the mesh is closed (it has no boundary loop); a disk has exactly one");
    }
    if (loops.size() > 1) {
        const std::string starts = loop_starts(loops);
        throw Error(ErrorCode::kMultipleBoundaries,
                    "the mesh has " + std::to_string(loops.size()) +
                        " boundary loops (holes), through vertices " + starts +
                        "; a disk has exactly one");
    }
    progress.report(0.95);  // the Euler characteristic: one pass over the half-edges
    const int64_t euler = euler_characteristic(mesh, halfedges);
    if (euler != 1) {
        throw Error(ErrorCode::kNonzeroGenus,
                    "the mesh has handles: genus " + std::to_string((1 - euler) / 2) +
                        " (V - E + F = " + std::to_string(euler) +
                        " with one boundary loop; a disk has V - E + F = 1)");
    }
    return std::move(loops[0]);
}

void check_closed_genus_zero(const TriangleMesh& mesh, const Halfedges& halfedges,
                             const ProgressSpan& progress) {
    check_manifold_vertices(mesh, halfedges, progress.part(0.0, 0.4));
    check_one_piece(mesh, halfedges, "a sphere", progress.part(0.4, 0.8));
    const std::vector<std::vector<int32_t>> loops =
        boundary_loops(mesh, halfedges, progress.part(0.8, 0.95));
    if (!loops.empty()) {
        const std::string starts = loop_starts(loops);
        throw Error(ErrorCode::kOpenMesh, "the sphere domain needs a closed mesh: it has " +
                                              std::to_string(loops.size()) + " boundary loop" +
                                              (loops.size() > 1 ? "s" : "") +
                                              " (through vertices " + starts + ")");
    }
    progress.report(0.95);  // the Euler characteristic: one pass over the half-edges
    const int64_t euler = euler_characteristic(mesh, halfedges);
    if (euler != 2) {
        throw Error(ErrorCode::kNonzeroGenus, "the mesh has handles: genus " +
                                                  std::to_string((2 - euler) / 2) +
                                                  " (V - E + F = " + std::to_string(euler) +
                                                  "; a closed genus-0 mesh has V - E + F = 2)");
    }
}

std::vector<int32_t> vertex_ring(const TriangleMesh& mesh, const Halfedges& halfedges, int32_t v) {
    int32_t start = -1;
    for (int32_t h = 0; h < static_cast<int32_t>(halfedges.twin.size()) && start < 0; ++h) {
        if (halfedge_origin(mesh, h) == v) start = h;
    }
    return vertex_ring_from(mesh, halfedges, start);
}

std::vector<int32_t> vertex_ring_from(const TriangleMesh& mesh, const Halfedges& halfedges,
                                      int32_t start) {
    std::vector<int32_t> ring;
    if (start < 0) return ring;
    int32_t h = start;
    do {
        ring.push_back(halfedge_target(mesh, h));
        h = halfedges.twin[Halfedges::prev(h)];  // the next triangle around v
    } while (h >= 0 && h != start);
    return ring;
}

std::vector<int32_t> first_outgoing_halfedges(const TriangleMesh& mesh, const Halfedges& halfedges,
                                              const ProgressSpan& progress) {
    std::vector<int32_t> first(mesh.positions.size(), -1);
    progress.in_runs(static_cast<int64_t>(halfedges.twin.size()), [&](int64_t begin, int64_t end) {
        for (int32_t h = static_cast<int32_t>(begin); h < end; ++h) {
            int32_t& out = first[halfedge_origin(mesh, h)];
            if (out < 0) out = h;
        }
    });
    return first;
}

VertexTriangles build_vertex_triangles(const TriangleMesh& mesh, const ProgressSpan& progress) {
    VertexTriangles stars;
    // The counts and the arrays' first touches report too: at 5.65M triangles the three arrays
    // filled in one go were 145-330 ms without a progress call.
    const ProgressSpan start = progress.part(0.0, 0.0);
    stars.offsets.assign(mesh.positions.size() + 1, 0);
    start.in_runs(mesh.triangle_count(), [&](int64_t run_begin, int64_t run_end) {
        for (int64_t f = run_begin; f < run_end; ++f) {
            for (int32_t v : mesh.triangles[f]) ++stars.offsets[v + 1];
        }
    });
    std::partial_sum(stars.offsets.begin(), stars.offsets.end(), stars.offsets.begin());
    const size_t entries = static_cast<size_t>(stars.offsets.back());
    assign_in_runs(stars.first, entries, 0, start);
    assign_in_runs(stars.second, entries, 0, start);
    assign_in_runs(stars.triangle, entries, 0, start);
    std::vector<int32_t> fill(stars.offsets.begin(), stars.offsets.end() - 1);
    progress.in_runs(mesh.triangle_count(), [&](int64_t run_begin, int64_t run_end) {
        for (int32_t f = static_cast<int32_t>(run_begin); f < run_end; ++f) {
            const Triangle& t = mesh.triangles[f];
            for (int k = 0; k < 3; ++k) {
                const int32_t e = fill[t[k]]++;
                stars.first[e] = t[(k + 1) % 3];
                stars.second[e] = t[(k + 2) % 3];
                stars.triangle[e] = f;
            }
        }
    });
    return stars;
}

VertexAdjacency build_vertex_adjacency(const TriangleMesh& mesh, const Halfedges& halfedges,
                                       const ProgressSpan& progress) {
    VertexAdjacency adjacency;
    const int32_t halfedge_count = static_cast<int32_t>(halfedges.twin.size());
    adjacency.offsets.assign(mesh.positions.size() + 1, 0);
    // Each undirected edge once: boundary half-edges, and the smaller of each twin pair.
    progress.part(0.0, 0.2).in_runs(halfedge_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t h = static_cast<int32_t>(run_begin); h < run_end; ++h) {
            if (halfedges.twin[h] > h) continue;
            ++adjacency.offsets[halfedge_origin(mesh, h) + 1];
            ++adjacency.offsets[halfedge_target(mesh, h) + 1];
        }
    });
    std::partial_sum(adjacency.offsets.begin(), adjacency.offsets.end(), adjacency.offsets.begin());
    // Each entry carries its edge's half-edge h and direction (2h: in the row of h's origin,
    // 2h + 1: of its target) through the sort, so the slots come out of the sort itself: binary
    // searches for them afterwards were most of this function.
    std::vector<std::pair<int32_t, int32_t>> entries = filled_in_runs(
        adjacency.offsets.back(), std::pair<int32_t, int32_t>(), progress.part(0.2, 0.2));
    std::vector<int32_t> fill(adjacency.offsets.begin(), adjacency.offsets.end() - 1);
    progress.part(0.2, 0.4).in_runs(halfedge_count, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t h = static_cast<int32_t>(run_begin); h < run_end; ++h) {
            if (halfedges.twin[h] > h) continue;
            const int32_t a = halfedge_origin(mesh, h), b = halfedge_target(mesh, h);
            entries[fill[a]++] = {b, 2 * h};
            entries[fill[b]++] = {a, 2 * h + 1};
        }
    });
    const ProgressSpan sorting = progress.part(0.4, 0.9);
    assign_in_runs(adjacency.neighbors, entries.size(), 0, progress.part(0.4, 0.4));
    assign_in_runs(adjacency.forward_slot, halfedge_count, 0, progress.part(0.4, 0.4));
    assign_in_runs(adjacency.backward_slot, halfedge_count, 0, progress.part(0.4, 0.4));
    sorting.in_runs(mesh.vertex_count(), [&](int64_t run_begin, int64_t run_end) {
        for (int32_t v = static_cast<int32_t>(run_begin); v < run_end; ++v) {
            // Insertion sort by neighbour: a vertex has about six.
            const int32_t first = adjacency.offsets[v], last = adjacency.offsets[v + 1];
            for (int32_t i = first + 1; i < last; ++i) {
                const std::pair<int32_t, int32_t> entry = entries[i];
                int32_t j = i;
                for (; j > first && entries[j - 1].first > entry.first; --j)
                    entries[j] = entries[j - 1];
                entries[j] = entry;
            }
            // A neighbour listed twice (two edges between the same vertices, in degenerate input)
            // has its first slot, the one a search would find.
            int32_t run = first;
            for (int32_t slot = first; slot < last; ++slot) {
                const auto [neighbor, tag] = entries[slot];
                if (neighbor != entries[run].first) run = slot;
                adjacency.neighbors[slot] = neighbor;
                (tag % 2 ? adjacency.backward_slot : adjacency.forward_slot)[tag / 2] = run;
            }
        }
    });
    for (int32_t h = 0; h < halfedge_count; ++h) {  // the larger twin, g, runs the other way
        progress.at(h, halfedge_count, 0.9, 1.0);
        const int32_t g = halfedges.twin[h];
        if (g < h) continue;
        adjacency.forward_slot[h] = adjacency.backward_slot[g];
        adjacency.backward_slot[h] = adjacency.forward_slot[g];
    }
    return adjacency;
}

std::vector<int32_t> corner_vertex_classes(const std::vector<int32_t>& twin,
                                           const ProgressSpan& progress) {
    std::vector<int32_t> classes(twin.size(), -1);
    label_corner_classes(
        twin, [&](int32_t c) -> int32_t& { return classes[c]; }, progress);
    return classes;
}

}  // namespace raps
