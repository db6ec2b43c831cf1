// The input's polygons in the atlas (raps_mesh_set_triangle_polygons): a quad or n-gon that was
// triangulated for raps is one unit, so that its corners get one uv each. The surface marks the
// half-edges that join two triangles of one polygon (AtlasSurface::polygon_inner); charts grow
// over whole polygons (chart_segmentation.h), are cut open across other edges only
// (chart_disk.h), and are split between polygons here. A chart that is one polygon is not split.
#pragma once

#include <cstdint>
#include <vector>

#include "atlas/atlas_surface.h"
#include "core/triangle_mesh.h"

namespace raps {

// Whether `triangles` (a chart, whose polygons are whole) are one polygon, or one triangle.
bool is_one_polygon(const AtlasSurface& surface, const std::vector<int32_t>& triangles);

// The chart functions below work on a chart's own triangles: `triangles` (surface ids), side[i]
// per triangles[i], neighbour[3i+k] the chart triangle across side k of triangle i or -1
// (atlas_charts.cpp's chart_neighbours; a polygon's own edges are never seams).

// Every polygon takes the side of its first triangle in `triangles`.
void keep_polygons_together(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
                            const std::vector<int32_t>& neighbour, std::vector<int32_t>& side);

// Halves `triangles` by polygons in their order (side 0, then 1) where no distance could; a
// single polygon by triangles (the only way left to split it).
void halve_by_polygons(const AtlasSurface& surface, const std::vector<int32_t>& triangles,
                       const std::vector<int32_t>& neighbour, std::vector<int32_t>& side);

// Per triangles[i], whether it is part of a polygon of several triangles (it moves only with
// its polygon); empty when the mesh has no polygons.
std::vector<char> polygon_triangles(const AtlasSurface& surface,
                                    const std::vector<int32_t>& triangles);

// Per triangle set aside as degenerate (surface.aside_triangles; a zero-area part of an n-gon
// with collinear corners), the chart of a triangle of its polygon that shares an edge with it
// (chart_of_input: per input triangle), or -1: its corners then come from its polygon's chart.
std::vector<int32_t> aside_polygon_charts(const TriangleMesh& mesh,
                                          const std::vector<int32_t>& welded,
                                          const AtlasSurface& surface,
                                          const std::vector<int32_t>& chart_of_input);

}  // namespace raps
