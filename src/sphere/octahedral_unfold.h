// Texture coordinates from a spherical map: unfold the sphere onto the square through the
// octahedron (Praun and Hoppe, "Spherical parametrization and remeshing", 2003, whose spherical
// geometry images use this layout). The octahedral map sends the upper hemisphere to the
// diamond |u| + |v| <= 1 and folds each lower octant out onto the corner triangle beyond it; the
// south pole goes to the four corners, and the four half-meridians below the equator are the
// seams, each mapped to both halves of one side of the square.
//
// A mesh can only be cut along its edges, so:
//  1. The map is rotated so that a vertex (the root, near the south pole) is the south pole.
//  2. Four paths of edges run from the root to the vertices nearest the equator points of the
//     four seams (+x, +y, -x, -y): shortest paths by chord length, each kept inside the lune of
//     +-45 degrees around its own meridian, so the four are disjoint and leave the root in the
//     octahedron's order.
//  3. The vertices on the paths are duplicated, one copy per side (the root gets four): the cut
//     mesh is a disk. Its boundary goes onto the square's sides as the octahedral map puts the
//     seams: the root's copies on the corners, each path's vertices at the position their arc
//     length from the root gives along the meridian.
//  4. Every other vertex goes where the octahedral map sends its point - not directly (a vertex
//     near a seam but on the far side of the path of edges would land on the wrong side of the
//     square, and straight triangles across the fold lines can turn over) but through one sparse
//     solve: the Laplace system of paper eq. (1) with the cut boundary fixed on the square and
//     mean value weights computed from the octahedral positions themselves. Mean value
//     coordinates reproduce a planar configuration exactly, so wherever the octahedral map is a
//     valid triangulation the solve returns it; and since the weights are positive and the
//     boundary is convex, Tutte's and Floater's theorems make the result a bijection onto the
//     square: no uv triangle is flipped.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "core/progress.h"
#include "core/triangle_mesh.h"

namespace raps {

struct OctahedralUnfold {
    std::vector<Eigen::Vector2d> uv;     // per output vertex, in [0, 1]^2
    std::vector<uint32_t> vertex_remap;  // per output vertex: its input vertex (the first
                                         // vertex_count() output vertices are the input ones)
    std::vector<uint32_t> indices;       // per input triangle, its three output vertices
};

// `points`: one unit vector per vertex of `mesh`, a bijective map (det > 0 for every triangle).
// `progress` receives the fraction done (it may throw to cancel).
OctahedralUnfold octahedral_unfold(const TriangleMesh& mesh,
                                   const std::vector<Eigen::Vector3d>& points,
                                   const ProgressSpan& progress = {});

}  // namespace raps
