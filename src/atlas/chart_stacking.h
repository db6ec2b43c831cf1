// Stacking congruent charts (RAPS_PARAM_ATLAS_STACK): charts of duplicated or instanced
// geometry share one place in the atlas, so the copies cost no texels. Two charts stack when
// they are the same triangles over the same chart vertices (as copies of one mesh, or of one
// part of it, come out of the pipeline) and their 3D vertices agree, vertex for vertex, up to a
// rigid motion within a tolerance: each chart's vertices are written in a frame built from three
// of its vertices (the first, the one farthest from it, the one farthest from the line through
// both), where a rigid motion changes no coordinate and a mirror negates the third one. A
// mirrored copy stacks only when mirroring is allowed. With repacked uvs the charts' own uvs
// must agree the same way in 2D (a uv island laid out mirrored is a mirror too), since a
// stacked chart takes its place's uvs.
#pragma once

#include <cstdint>
#include <vector>

#include "atlas/atlas_charts.h"

namespace raps {

struct StackSettings {
    bool allow_mirror = false;
    double tolerance = 1e-4;   // of the chart's extent (its first vertex to its farthest)
    bool within_part = false;  // only charts of one mesh of a scene (one page per mesh)
    bool compare_uvs = false;  // the charts' uvs are the user's (repacking): they must agree
};

// How `b`'s points lie on `a`'s, vertex for vertex: moved rigidly, only mirrored, or neither,
// within tolerance times a's extent (the frame test above). Points on one line never match.
enum class PointMatch { kNone, kRigid, kMirror };
PointMatch match_points(const std::vector<Eigen::Vector3d>& a,
                        const std::vector<Eigen::Vector3d>& b, double tolerance);

// Per chart, the chart whose place it shares: an earlier chart, or itself when none.
std::vector<int32_t> stack_charts(const std::vector<AtlasChart>& charts,
                                  const std::vector<int32_t>& part, const StackSettings& settings);

}  // namespace raps
