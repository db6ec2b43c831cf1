// The one entry point behind the C API: runs the pipeline of the requested domain and measures
// the result. Data flows one way: mesh in -> validate -> topology -> initial map -> adapt ->
// metrics -> output.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "atlas/atlas_pipeline.h"
#include "core/phase_timer.h"
#include "core/progress.h"
#include "core/settings.h"
#include "core/triangle_mesh.h"
#include "metrics/distortion.h"

namespace raps {

// One input mesh's share of the output: its output vertices and indices (which index its own
// output vertices, from 0). raps_parameterize's one mesh owns all of it.
struct OutputRange {
    int64_t first_vertex = 0, vertex_count = 0, first_index = 0, index_count = 0;
};

struct Parameterization {
    std::vector<uint32_t> vertex_remap;  // per output vertex: the input vertex it comes from
    std::vector<uint32_t> indices;       // output triangles, 3 per triangle
    std::vector<Eigen::Vector2d> uv;     // per output vertex; empty when the map has no uvs
    std::vector<Eigen::Vector3d> sphere_points;  // per output vertex; empty for the disk
    DistortionStats distortion;
    int64_t negative_weights = 0;
    int64_t adaptive_solves = 0;
    int64_t relaxation_sweeps = 0;
    // Atlas domain.
    std::vector<uint32_t> chart_ids;  // per output triangle
    int64_t chart_count = 1;          // the disk and sphere domains: one chart
    int32_t atlas_width = 0, atlas_height = 0;
    double utilization = 0;  // uv area over the unit square (per page)
    std::vector<AtlasChartRecord> charts;
    int32_t page_count = 1;
    double texels_per_unit = 0;
    std::vector<OutputRange> ranges;  // per input mesh
    // The most threads any step of the run computed on (ThreadPool::threads_used), the caller's
    // included: describes the run, not the map.
    int threads_used = 1;
    PhaseTimes phase_ms{};
};

// Throws raps::Error (or std::bad_alloc) on failure.
Parameterization parameterize(const TriangleMesh& mesh, const Settings& settings,
                              const Progress& progress);

// One mesh of a scene, placed in world units by a 3x4 transform (row-major, [A | t]).
struct ScenePart {
    const TriangleMesh* mesh = nullptr;
    Eigen::Matrix<double, 3, 4> transform = Eigen::Matrix<double, 3, 4>::Identity();
};

// Several meshes in one atlas (settings.domain must be the atlas): the output holds each mesh's
// output in turn (ranges), its remap giving each mesh's own input vertices and its indices each
// mesh's own output vertices.
Parameterization parameterize_scene(const std::vector<ScenePart>& parts, const Settings& settings,
                                    const Progress& progress);

}  // namespace raps
