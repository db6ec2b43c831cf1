// Step 3b: a chart as a mesh of its own, cut open into a topological disk. Hard edges inside the
// chart become seams; a chart that is still not a disk (holes, handles) is cut along the edges
// that a spanning tree of its triangles does not cross, pruned of dangling branches (the cut
// graph of Erickson & Har-Peled 2002; Gu, Gortler & Hoppe 2002, geometry images): what remains
// joins every hole to the outer boundary and opens every handle.
#pragma once

#include <cstdint>
#include <vector>

#include "atlas/atlas_surface.h"
#include "mesh/mesh_topology.h"

namespace raps {

struct ChartDisk {
    TriangleMesh mesh;                      // the chart's own vertices and triangles
    std::vector<int32_t> surface_triangle;  // per chart triangle
    std::vector<int32_t> surface_vertex;    // per chart vertex
    // The two below serve the chart's maps only: map_chart empties them once it has mapped.
    std::vector<double> angle_sum;       // per vertex of `mesh`: its corners' angles, radians
    VertexAdjacency adjacency;           // of `mesh`, built once for every map of the chart
    std::vector<int32_t> boundary_loop;  // the disk's boundary, mesh on its left
    // A fill-reducing order of the vertices, shared by the chart's sparse systems (the
    // free-boundary map's and the adaptive step's): ordered once instead of once per system.
    std::vector<int32_t> vertex_order;
};

// The chart made of `triangles` (surface triangle ids). seam[h] marks half-edges of the surface
// that must not be crossed even inside the chart (hard edges). Returns false when the chart
// could not be made a disk (it is then split by the caller).
bool make_chart_disk(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
                     const std::vector<char>& seam, ChartDisk& disk,
                     const ProgressSpan& progress = {});

// The same for the union of two charts `a` and `b` (triangles: theirs together), whose vertex
// order is made from theirs instead of ordering the union again.
bool make_union_chart_disk(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
                           const std::vector<char>& seam, const ChartDisk& a, const ChartDisk& b,
                           ChartDisk& disk, const ProgressSpan& progress = {});

}  // namespace raps
