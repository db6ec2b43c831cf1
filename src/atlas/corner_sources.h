// Where each input triangle's corners come from in an atlas: the record the output is written
// from (atlas_pipeline.cpp), shared with the steps that make charts without mapping them.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "atlas/atlas_pipeline.h"
#include "atlas/atlas_surface.h"
#include "atlas/chart_mapping.h"
#include "core/progress.h"
#include "core/triangle_mesh.h"

namespace raps {

// A chart per input triangle (its index; the point charts of degenerate triangles with no chart
// beside them follow the real ones, one per part that has such triangles) and, per corner, the
// chart vertex.
struct CornerSources {
    std::vector<int32_t> chart;                  // per input triangle
    std::vector<std::array<int32_t, 3>> vertex;  // per input triangle, per corner
    std::vector<int32_t> point_chart_part;       // per point chart: its part
    // Per input triangle: 1 for an exact copy of another (the same welded corners, so the same
    // uvs); its texels are its original's and count once. Empty: no copies.
    std::vector<char> copy;
};

// The corner sources of mapped charts: each triangle a chart holds takes its chart vertices;
// each triangle the surface set aside (atlas_surface.h) takes its primary's corners (an exact
// copy), or goes on the chart of its polygon, or of one of its vertices, or else on a point
// chart of its part. `welded`: the welded vertex of each input vertex.
CornerSources corner_sources(const TriangleMesh& mesh, const AtlasParts& parts,
                             const std::vector<int32_t>& welded, const AtlasSurface& surface,
                             const std::vector<AtlasChart>& charts, const ProgressSpan& progress);

}  // namespace raps
