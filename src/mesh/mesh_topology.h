// Combinatorial structure of a triangle mesh: half-edges with their twins, manifold and
// orientation checks, boundary loops, pieces, and the vertex adjacency the Laplace systems use.
// Knows nothing of positions or maps.
#pragma once

#include <cstdint>
#include <vector>

#include "core/progress.h"
#include "core/triangle_mesh.h"

namespace raps {

// Half-edge h = 3 * t + k runs from triangles[t][k] to triangles[t][(k + 1) % 3], so the
// triangle lies on its left. twin[h] is the opposite half-edge, or -1 on the boundary.
struct Halfedges {
    std::vector<int32_t> twin;

    static int32_t next(int32_t h) { return h - h % 3 + (h % 3 + 1) % 3; }
    static int32_t prev(int32_t h) { return h - h % 3 + (h % 3 + 2) % 3; }
};

inline int32_t halfedge_origin(const TriangleMesh& mesh, int32_t h) {
    return mesh.triangles[h / 3][h % 3];
}
inline int32_t halfedge_target(const TriangleMesh& mesh, int32_t h) {
    return mesh.triangles[h / 3][(h % 3 + 1) % 3];
}

// Pairs every half-edge with its twin. Throws NON_MANIFOLD_EDGE when an edge has more than two
// triangles (or a duplicate triangle), INCONSISTENT_ORIENTATION when two triangles traverse an
// edge in the same direction.
Halfedges build_halfedges(const TriangleMesh& mesh, const ProgressSpan& progress = {});

// The vertices that twins imply: corners (3 t + k, the corner where half-edge 3 t + k starts)
// joined across every paired edge (twin[h] < 0 on a boundary or a cut), so that the corners of
// one fan of triangles around a vertex form one class. Returns each corner's class, classes
// numbered in the order of their first corner.
std::vector<int32_t> corner_vertex_classes(const std::vector<int32_t>& twin,
                                           const ProgressSpan& progress = {});

// The same classes written in place: corner(c) is an int32_t& holding a negative value on entry,
// overwritten with c's class. Returns the entry value of each class's first corner, in class
// order (what a caller keeps there, such as ~vertex, to name each class).
//
// Corner h is joined to next(twin[h]) (the same vertex's corner in the triangle across h) and to
// twin[prev(h)] (across the edge that ends at h's vertex): each corner has at most one of each,
// so a class is a path or a cycle of corners round its vertex, walked both ways from its first
// corner. Corners visited in index order number the classes in the order of their first
// corners, as a union-find over all pairs did, without its parent and root arrays (24 bytes per
// triangle) or its scattered root searches.
template <typename Corner>
std::vector<int32_t> label_corner_classes(const std::vector<int32_t>& twin, Corner&& corner,
                                          const ProgressSpan& progress = {}) {
    const int32_t corners = static_cast<int32_t>(twin.size());
    std::vector<int32_t> first_value;
    progress.in_runs(corners, [&](int64_t run_begin, int64_t run_end) {
        for (int32_t c = static_cast<int32_t>(run_begin); c < run_end; ++c) {
            if (corner(c) >= 0) continue;
            const int32_t cls = static_cast<int32_t>(first_value.size());
            first_value.push_back(corner(c));
            corner(c) = cls;
            // Each step names a new corner or stops (on a boundary, or back at c round a closed
            // fan), so even twins that are not an involution end the walk.
            for (int32_t h = c, g = twin[h]; g >= 0; g = twin[h]) {
                h = Halfedges::next(g);
                if (corner(h) >= 0) break;
                corner(h) = cls;
            }
            for (int32_t h = c, g = twin[Halfedges::prev(h)]; g >= 0;
                 g = twin[Halfedges::prev(h)]) {
                h = g;
                if (corner(h) >= 0) break;
                corner(h) = cls;
            }
        }
    });
    return first_value;
}

// Throws NON_MANIFOLD_VERTEX when the triangles around a vertex form more than one fan.
void check_manifold_vertices(const TriangleMesh& mesh, const Halfedges& halfedges,
                             const ProgressSpan& progress = {});

// Number of edge-connected pieces, and one triangle of each.
std::vector<int32_t> piece_representatives(const TriangleMesh& mesh, const Halfedges& halfedges,
                                           const ProgressSpan& progress = {});

// Boundary loops as vertex sequences, each traversed with the mesh on its left (so a disk's loop
// runs counter-clockwise around it), starting at its smallest vertex index; loops sorted by that
// vertex. Needs manifold vertices.
std::vector<std::vector<int32_t>> boundary_loops(const TriangleMesh& mesh,
                                                 const Halfedges& halfedges,
                                                 const ProgressSpan& progress = {});

// Undirected edge count: interior edges once, boundary edges once.
int64_t edge_count(const Halfedges& halfedges);

// Checks everything a topological disk needs (manifold, oriented, one piece, one boundary loop,
// Euler characteristic 1) and returns its boundary loop.
std::vector<int32_t> disk_boundary_loop(const TriangleMesh& mesh, const Halfedges& halfedges,
                                        const ProgressSpan& progress = {});

// Checks everything the sphere domain needs (manifold, oriented, one piece, no boundary loop,
// Euler characteristic 2). Throws OPEN_MESH when the mesh has boundary loops, NONZERO_GENUS when
// it has handles.
void check_closed_genus_zero(const TriangleMesh& mesh, const Halfedges& halfedges,
                             const ProgressSpan& progress = {});

// The neighbours of vertex v of a closed mesh in the order of its triangles: (v, ring[m],
// ring[m + 1]) is a triangle for every m (cyclically). Needs manifold vertices and no boundary
// at v.
std::vector<int32_t> vertex_ring(const TriangleMesh& mesh, const Halfedges& halfedges, int32_t v);

// The same from the half-edge `start` (from v), without vertex_ring's search for one (a pass over
// the mesh): for the rings of many vertices, with starts from first_outgoing_halfedges.
std::vector<int32_t> vertex_ring_from(const TriangleMesh& mesh, const Halfedges& halfedges,
                                      int32_t start);

// Per vertex, the first half-edge (the lowest index) that starts there, or -1: the start that
// vertex_ring finds.
std::vector<int32_t> first_outgoing_halfedges(const TriangleMesh& mesh, const Halfedges& halfedges,
                                              const ProgressSpan& progress = {});

// The triangles around each vertex, as the two other vertices in the triangle's order: for the
// entries e in [offsets[v], offsets[v + 1]), (v, first[e], second[e]) is triangle triangle[e] of
// the mesh with its orientation. Used to check that moving v folds none of its triangles.
struct VertexTriangles {
    std::vector<int32_t> offsets;
    std::vector<int32_t> first, second, triangle;
};

VertexTriangles build_vertex_triangles(const TriangleMesh& mesh, const ProgressSpan& progress = {});

// Symmetric vertex adjacency in compressed rows: the neighbours of v are
// neighbors[offsets[v] .. offsets[v + 1]), sorted ascending. A "slot" is a position in neighbors,
// i.e. one directed edge v -> neighbors[slot].
struct VertexAdjacency {
    std::vector<int32_t> offsets;
    std::vector<int32_t> neighbors;
    // For half-edge h (a -> b): the slot of b in a's row and the slot of a in b's row.
    std::vector<int32_t> forward_slot;
    std::vector<int32_t> backward_slot;
};

VertexAdjacency build_vertex_adjacency(const TriangleMesh& mesh, const Halfedges& halfedges,
                                       const ProgressSpan& progress = {});

}  // namespace raps
