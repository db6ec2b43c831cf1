// Repacking the input's own uvs (RAPS_PARAM_ATLAS_REPACK; what xatlas's AddUvMesh and Blender's
// Pack Islands do): no new map. The charts are the input's uv islands: triangles that share an
// edge (the same two vertices, welded by position within a part) whose corner uvs are equal at
// both ends are in one chart, unless a triangle group boundary or a seam edge lies between
// them (user_seams.h). Each chart's uvs are scaled uniformly so that its uv area equals
// its 3D area (the packer's unit, chart_packing.h); the packer then only turns them (as the
// rotation policy allows), scales them to the atlas's one density and moves them, so every chart
// keeps its shape. Flipped or overlapping triangles inside a chart are kept as given.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "atlas/atlas_charts.h"
#include "atlas/atlas_pipeline.h"
#include "core/triangle_mesh.h"

namespace raps {

// Refuses a mesh whose corner uvs are not one per triangle corner (kUvCount); `name` ("mesh 2",
// or "" for the one mesh) leads the message.
void check_corner_uvs(const TriangleMesh& mesh, const std::string& name);

struct RepackedCharts {
    // Per chart: disk.mesh holds its own vertices (one per distinct input vertex and uv) and
    // triangles, map.uv its uvs scaled to its 3D area, map.stretch_l2 the stretch of that map,
    // box its smallest bounding box. Charts in order of their first triangle.
    std::vector<AtlasChart> charts;
    // Per input triangle: its chart, or charts.size() + k for point chart k (islands without 3D
    // area, which get no texels: their uvs all become one point, as the atlas does with
    // degenerate triangles).
    std::vector<int32_t> chart_of;
    std::vector<std::array<int32_t, 3>> corner_vertex;  // per input triangle: chart vertices
    std::vector<int32_t> point_chart_part;              // per point chart: its part
};

// The uv islands of `mesh` (its corner uvs checked by check_corner_uvs). welded[v]: input vertex
// v's representative, welded within its part. Throws kDegenerateUvChart for an island with 3D
// area but no uv area (it has no shape to keep), naming its mesh and first triangle.
RepackedCharts repack_charts(const TriangleMesh& mesh, const AtlasParts& parts,
                             const std::vector<int32_t>& welded);

}  // namespace raps
