// The atlas domain: any triangle mesh in, a texture atlas out (issue "Atlas for any mesh"):
// weld -> surface (manifold, oriented) -> segment into charts -> cut each to a disk and map it
// (free boundary, then the r-adaptive step) -> pack -> output vertices, one per distinct
// (input vertex, chart vertex) pair, so seams duplicate vertices and every output vertex keeps
// the attributes of exactly one input vertex.
// A scene (several meshes in one atlas) comes in as one mesh made of its parts, each part's
// vertices and triangles contiguous and in the scene's order: no chart crosses from one part to
// another (parts are welded apart), and each part's output vertices and triangles come out
// contiguous too.
// With RAPS_PARAM_ATLAS_REPACK the input's own uv islands replace steps 2-4 (uv_repack.h): weld
// -> islands -> pack -> output.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/phase_timer.h"
#include "core/progress.h"
#include "core/settings.h"
#include "core/triangle_mesh.h"
#include "parallel/thread_pool.h"

namespace raps {

// Where each part of the input lies: part p owns vertices first_vertex[p] ..
// first_vertex[p + 1] - 1 and triangles first_triangle[p] .. first_triangle[p + 1] - 1. A
// single mesh is one part.
struct AtlasParts {
    std::vector<int32_t> first_vertex, first_triangle;  // part count + 1 entries each
    int32_t count() const { return static_cast<int32_t>(first_vertex.size()) - 1; }
    int32_t part_of_triangle(int32_t triangle) const;
};
AtlasParts single_part(const TriangleMesh& mesh);

// What the packer did with one chart (chart_packing.h, page_packing.h), and what it holds.
struct AtlasChartRecord {
    int32_t part = 0, page = 0;
    int32_t x = 0, y = 0, width = 0, height = 0;  // texels its uv triangles touch, on its page
    double rotation_deg = 0;                      // counter-clockwise turn given to the chart's map
    int64_t triangle_count = 0;
    double area_3d = 0, area_texels = 0;
    double stretch_l2 = 0;     // Sander's L2 stretch of the chart's map; 0 for degenerate triangles
    bool scaled_down = false;  // shrunk below the atlas's density to fit a page
    int64_t stacked_on = 0;  // the chart whose texels it shares (chart_stacking.h); itself if none
};

struct AtlasOutput {
    std::vector<Eigen::Vector2d> uv;  // per output vertex, in [0,1]^2 of its page (per axis)
    std::vector<uint32_t> remap;      // per output vertex: its input vertex
    std::vector<uint32_t> indices;    // per input triangle, in input order: 3 output vertices
    std::vector<uint32_t> chart_of;   // per triangle
    std::vector<AtlasChartRecord> charts;
    std::vector<int64_t> first_output_vertex;  // per part, and the total last
    int64_t adaptive_solves = 0;               // behind the charts' maps
    int32_t width = 0, height = 0;             // every page's size in texels
    int32_t page_count = 1;
    double texels_per_unit = 0;  // the atlas's density (charts scaled down to fit excepted)
    int64_t chart_count() const { return static_cast<int64_t>(charts.size()); }
};

// Every parallel step runs on `pool`; the output is the same for any pool size.
AtlasOutput build_atlas(const TriangleMesh& mesh, const AtlasParts& parts, const Settings& settings,
                        const Progress& progress, PhaseTimes& times, ThreadPool& pool);

}  // namespace raps
