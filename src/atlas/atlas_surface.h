// Step 2 of the atlas pipeline: turn any triangle soup into a manifold, consistently oriented
// surface that charts can be grown on. Vertices are welded by position; edges shared by more
// than two triangles (save between two triangles of one input polygon), or traversed twice in
// the same direction, become cuts, and so do the artist's seams (user_seams.h); each vertex is
// split into one surface vertex per fan of triangles around it. Triangles that cannot take part
// (repeated welded vertex, zero area, an exact duplicate of another) are kept aside: they still
// get uvs, on the chart of a neighbour.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "atlas/user_seams.h"
#include "core/progress.h"
#include "core/triangle_mesh.h"
#include "parallel/thread_pool.h"

namespace raps {

struct AtlasSurface {
    TriangleMesh mesh;                    // surface vertices and the triangles charts are made of
    std::vector<int32_t> twin;            // per half-edge 3t+k (as in mesh_topology.h); -1: cut
    std::vector<int32_t> input_triangle;  // per surface triangle
    std::vector<int32_t> welded_vertex;   // per surface vertex: its welded input vertex
    // Per corner 3t+k: the triangle's angle there, in radians. Every chart and every union
    // tried while merging sums them (each triangle is mapped several times): measured once.
    std::vector<double> corner_angle;
    // Input triangles that are not surface triangles, each with the surface triangle whose uvs
    // it shares (duplicates) or -1 (degenerate: placed by the atlas on a neighbouring chart).
    std::vector<int32_t> aside_triangles;
    std::vector<int32_t> aside_primary;
    // Per half-edge: whether it joins two triangles of one input polygon (the input's
    // triangle_polygon), which charts keep together (atlas/polygon_units.h); empty without
    // polygons.
    std::vector<char> polygon_inner;
};

// Whether half-edge h of the surface joins two triangles of one input polygon.
inline bool joins_polygon(const AtlasSurface& surface, int32_t h) {
    return !surface.polygon_inner.empty() && surface.polygon_inner[h];
}

// `welded[v]`: the representative of input vertex v (vertex_welding.h); `seams` of `input`.
// Corner angles are measured on `pool`.
AtlasSurface build_atlas_surface(const TriangleMesh& input, const std::vector<int32_t>& welded,
                                 const UserSeams& seams, ThreadPool& pool,
                                 const ProgressSpan& progress = {});

}  // namespace raps
