// A colouring of the vertex graph: no two neighbours share a colour. Gauss-Seidel relaxation
// over one colour at a time moves only vertices that do not see each other, so the vertices of a
// colour can be updated by any number of threads in any order with the same result, and a
// vertex's check that it folds none of its triangles stays valid while the others move (each
// triangle has three different colours).
#pragma once

#include <cstdint>
#include <vector>

#include "core/progress.h"
#include "mesh/mesh_topology.h"

namespace raps {

// Greedy colouring in vertex order: each vertex takes the smallest colour none of its
// lower-numbered neighbours has. Deterministic; at most (max degree + 1) colours. Returns the
// vertices of each colour, ascending.
std::vector<std::vector<int32_t>> greedy_vertex_coloring(const VertexAdjacency& adjacency,
                                                         const ProgressSpan& progress = {});

}  // namespace raps
