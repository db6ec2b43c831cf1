// The atlas domain: any triangle mesh in, a texture atlas out (issue "Atlas for any mesh"):
// weld -> surface (manifold, oriented) -> segment into charts -> cut each to a disk and map it
// (free boundary, then the r-adaptive step) -> pack -> output vertices, one per distinct
// (input vertex, chart vertex) pair, so seams duplicate vertices and every output vertex keeps
// the attributes of exactly one input vertex.
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

struct AtlasOutput {
    std::vector<Eigen::Vector2d> uv;  // per output vertex, in [0,1]^2 (per-axis normalised)
    std::vector<uint32_t> remap;      // per output vertex: its input vertex
    std::vector<uint32_t> indices;    // per input triangle, in input order: 3 output vertices
    std::vector<uint32_t> chart_of;   // per triangle
    int64_t chart_count = 0;
    int64_t adaptive_solves = 0;    // behind the charts' maps
    int32_t width = 0, height = 0;  // atlas size in texels
};

// Every parallel step runs on `pool`; the output is the same for any pool size.
AtlasOutput build_atlas(const TriangleMesh& mesh, const Settings& settings,
                        const Progress& progress, PhaseTimes& times, ThreadPool& pool);

}  // namespace raps
